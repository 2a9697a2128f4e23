//! The `legacy-rt` command: parse flags, call the library, print the error.

use clap::Parser;
use std::io::{Read, Write};
use std::process::ExitCode;

/// The largest scene text accepted on standard input.
const MAX_INPUT: u64 = 256 << 20;

/// Renders a scene file of the ray-tracing course as the course's program did.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Print the typed scene (every object with its precomputed values) instead of rendering.
    #[arg(long)]
    dump: bool,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let mut text = Vec::new();
    if let Err(error) = std::io::stdin().take(MAX_INPUT + 1).read_to_end(&mut text) {
        eprintln!("error: cannot read the scene from standard input: {error}");
        return ExitCode::from(2);
    }
    if text.len() as u64 > MAX_INPUT {
        eprintln!("error: the scene is larger than {} MiB", MAX_INPUT >> 20);
        return ExitCode::from(2);
    }
    let text = String::from_utf8_lossy(&text);
    let scene = match legacy_rt::load(&text) {
        Ok(scene) => scene,
        Err(error) => {
            eprintln!("{error}");
            return ExitCode::FAILURE;
        }
    };
    if args.dump {
        let _ = std::io::stdout().write_all(legacy_rt::dump(&scene).as_bytes());
    }
    ExitCode::SUCCESS
}
