//! Rebuilds the crate when a message file changes: rust-i18n reads `locales/*.yml` at compile time
//! through a macro, which cargo does not see as an input of the crate.

fn main() {
    println!("cargo:rerun-if-changed=locales");
}
