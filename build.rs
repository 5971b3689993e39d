//! Rebuilds the crate when a message file or a file of `Res/` changes: rust-i18n reads
//! `locales/*.yml` and `include_dir!` reads `Res/` at compile time through macros, which cargo does
//! not see as inputs of the crate.

fn main() {
    println!("cargo:rerun-if-changed=locales");
    println!("cargo:rerun-if-changed=Res");
}
