fn main() {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format_timestamp(None)
        .init();
    if let Err(e) = opengl3d::cli::run() {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
