//! The command line's step from arguments to options: the input is the argument list
//! (arguments separated by zero bytes), parsed as `strahl` parses it and checked as `render`
//! and `solve` check their arguments before loading a scene.

#![no_main]

use clap::Parser;
use strahl_cli as cli;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let args = data
        .split(|&b| b == 0)
        .map(|a| String::from_utf8_lossy(a).into_owned());
    let Ok(parsed) = cli::Cli::try_parse_from(std::iter::once("strahl".to_string()).chain(args))
    else {
        return;
    };
    let _ = match &parsed.command {
        cli::Command::Render(args) => args.check(),
        cli::Command::Solve(args) => args.check(),
        _ => Ok(()),
    };
});
