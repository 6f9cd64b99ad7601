//! The `strahl` command line, a thin front end over the `strahl` library.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
