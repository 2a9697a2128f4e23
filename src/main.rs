//! The `legacy-rt` command: parse flags, run the command, print the error.

mod cli;

use clap::Parser;
use cli::{Args, Command, say};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = Args::parse();
    let result = match &args.command {
        None => cli::render::run(&args.render).map(|()| true),
        Some(Command::Trace(trace)) => cli::trace::run(trace).map(|()| true),
        // 1 when the images differ, as ImageMagick's `compare`.
        Some(Command::Compare(compare)) => cli::compare::run(compare),
        // 0 whatever the verdicts: the class was graded.
        Some(Command::Grade(grade)) => cli::grade::run(grade).map(|()| true),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(failure) => {
            say(&failure.message());
            ExitCode::from(failure.code)
        }
    }
}
