fn main() -> std::process::ExitCode {
    strahl::cli::main()
}
