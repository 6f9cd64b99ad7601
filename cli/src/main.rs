//! The `strahl` command line, a thin front end over the `strahl` library.

fn main() -> std::process::ExitCode {
    strahl_cli::main()
}
