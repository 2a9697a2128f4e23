//! Standard input and output: the scene text in, the image or the text out.

use super::Failure;
use std::io::{IsTerminal, Read};

/// The largest scene text accepted on standard input.
const MAX_INPUT: u64 = 256 << 20;

/// The scene text from standard input, at most `MAX_INPUT` bytes.
pub fn read_scene() -> Result<String, Failure> {
    let stdin = std::io::stdin();
    if stdin.is_terminal() {
        super::say(
            "legacy-rt: reading the scene from the terminal; end it with Ctrl-D, \
             or run: legacy-rt < scene.txt > image.ppm",
        );
    }
    let mut text = Vec::new();
    if let Err(error) = stdin.take(MAX_INPUT + 1).read_to_end(&mut text) {
        return Err(Failure(
            format!("error: cannot read standard input: {error}"),
            2,
        ));
    }
    if text.len() as u64 > MAX_INPUT {
        let mib = MAX_INPUT >> 20;
        return Err(super::scene_failure(format!(
            "the scene is larger than {mib} MiB, the most this program reads"
        )));
    }
    // Valid UTF-8 (nearly every scene) becomes the String without a copy.
    Ok(String::from_utf8(text)
        .unwrap_or_else(|invalid| String::from_utf8_lossy(invalid.as_bytes()).into_owned()))
}

/// Writes `bytes` to standard output.
pub fn emit_to_stdout(bytes: &[u8]) -> Result<(), Failure> {
    match legacy_rt::image_output::write(&mut std::io::stdout().lock(), bytes) {
        Ok(()) => Ok(()),
        // The reader went away (`| head`): end quietly.
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(error) => Err(Failure(
            format!("error: cannot write the image: {error}"),
            2,
        )),
    }
}
