fn main() {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format_timestamp(None)
        .init();
    if let Err(e) = opengl3d::cli::run() {
        eprintln!("{}{e:#}", opengl3d::i18n::error_prefix());
        std::process::exit(1);
    }
    // A closed pipe (`| head`) keeps the status; output lost otherwise (a full disk) does not.
    if opengl3d::io::stdout::failed() {
        std::process::exit(1);
    }
}
