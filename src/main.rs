//! The `legacy-rt` command: parse flags, run the command, print the error.

mod cli;

use clap::Parser;
use cli::{Args, Command, Failure, say};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = Args::parse();
    let result = match &args.command {
        None => cli::render::run(&args.render),
        Some(Command::Trace(trace)) => cli::trace::run(trace),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(message, code)) => {
            say(&message);
            ExitCode::from(code)
        }
    }
}
