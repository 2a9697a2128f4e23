//! The `legacy-rt` command: parse flags, call the library, print the error.

use clap::Parser;
use legacy_rt::image_output::file::OutputFile;
use legacy_rt::image_output::{self, Format};
use legacy_rt::render::{self, DEFAULT_MAX_DIST};
use legacy_rt::shapes::kernel::KernelChoice;
use std::io::{IsTerminal, Read, Write};
use std::path::PathBuf;
use std::process::ExitCode;

/// The largest scene text accepted on standard input.
const MAX_INPUT: u64 = 256 << 20;

/// The largest image, in pixels (16384 x 16384), so that an absurd size is an error and
/// not an allocation failure.
const MAX_PIXELS: u64 = 1 << 28;

const EXAMPLES: &str = "\
Examples:
  legacy-rt < scene.txt > image.ppm            640 wide, height from the world window
  legacy-rt 800 600 < scene.txt > image.ppm    as the course's program was called
  legacy-rt -o image.png < scene.txt           PNG (by the file's extension)
  legacy-rt --max-dist 64 < scene.txt > image.ppm
  legacy-rt --dump < scene.txt                 the typed scene, with precomputed values
  legacy-rt --kernel textbook < s.txt > t.ppm  as a tracer using the notes' root formula
  legacy-rt --threads 0 < scene.txt > image.ppm  on every core, same bytes

The scene is read from standard input; the image goes to standard output (or -o FILE);
errors go to standard error with the line and column to fix, and then nothing at all is
written to standard output. Texture file names in a scene are relative to the current
folder. -o never leaves half an image: a new or regular file is replaced whole (keeping
its permissions), a device or pipe is written in place, a read-only file is refused.

Limits: a scene of at most 256 MiB and 1,000,000 records (lights and objects together);
textures of at most 2^28 texels; images of at most 2^28 pixels (16384 x 16384); at most
256 threads. Mirror bounces stop when the path is longer than --max-dist, so two mirrors
facing each other a hair apart can take minutes: the progress bar shows it.

Exit status: 0 when the image was written, 1 when the scene cannot be loaded or gives
no image, 2 for a bad command line or an output that cannot be written.";

/// Renders a scene file of the ray-tracing course exactly as the course's program did.
///
/// The scene format and the rendering rules are documented in docs/ and README.md.
#[derive(Parser, Debug)]
#[command(version, about, after_help = EXAMPLES)]
struct Args {
    /// Image width in pixels [default: 640]
    #[arg(value_name = "W", value_parser = pixels)]
    width: Option<u64>,

    /// Image height in pixels [default: W times the world window's height / width, rounded]
    #[arg(value_name = "H", value_parser = pixels)]
    height: Option<u64>,

    /// Write the image to FILE instead of standard output: PNG if FILE ends in .png, PPM
    /// if it ends in .ppm or .pnm or has no extension
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,

    /// Paths of rays longer than D (eye to hit, summed over mirror bounces) are black
    #[arg(long, value_name = "D", default_value_t = DEFAULT_MAX_DIST)]
    max_dist: f64,

    /// Print the typed scene (every object with the values computed at load) instead of
    /// rendering it
    #[arg(long)]
    dump: bool,

    /// How hit distances are computed: accurate (within 4 ulps of the exact root),
    /// stable (the notes' coefficients, cancellation-free roots), textbook (the notes'
    /// (-b ± sqrt(b² - 4ac)) / 2a, as most students' tracers do), textbook-f32 (the same
    /// in single precision). Render with textbook to see where a tracer's speckles and
    /// missing pixels come from; see docs/speed-vs-error.md
    #[arg(long, value_name = "KERNEL", default_value = "accurate", value_parser = kernel)]
    kernel: KernelChoice,

    /// Render on N threads, at most 256; 0 means one per core. The image is the same bytes
    /// for every N (1, the default, is the course program's single thread)
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = threads)]
    threads: usize,
}

/// Parses W or H, and recognises the usual slip of naming the scene file there.
fn pixels(text: &str) -> Result<u64, String> {
    text.parse().map_err(|_| {
        if std::path::Path::new(text).is_file() || text.ends_with(".txt") {
            format!(
                "the scene is read from standard input, not named: \
                 legacy-rt < {text} > image.ppm"
            )
        } else {
            "expected a whole number of pixels, such as 640".to_string()
        }
    })
}

/// Parses `--threads`, which is bounded so that a typo cannot start a thread storm.
fn threads(text: &str) -> Result<usize, String> {
    let limit = render::MAX_THREADS;
    match text.parse::<usize>() {
        Ok(n) if n <= limit => Ok(n),
        Ok(_) => Err(format!(
            "at most {limit} threads (0 means one per core: {} here)",
            std::thread::available_parallelism().map_or(1, |n| n.get())
        )),
        Err(_) => Err("expected a whole number of threads, such as 4".to_string()),
    }
}

/// Parses a `--kernel` name.
fn kernel(name: &str) -> Result<KernelChoice, String> {
    KernelChoice::from_name(name).ok_or_else(|| {
        let names: Vec<_> = KernelChoice::ALL.iter().map(|k| k.name()).collect();
        format!("expected one of: {}", names.join(", "))
    })
}

/// An error of the command line or of the output, with its exit status.
struct Failure(String, u8);

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(message, code)) => {
            say(&message);
            ExitCode::from(code)
        }
    }
}

/// Writes a line to standard error. A closed standard error (`2>&1 | head`) is no reason
/// to fail, and `eprintln!` would panic there.
fn say(message: &str) {
    if !message.is_empty() {
        let _ = writeln!(std::io::stderr().lock(), "{message}");
    }
}

/// A failure caused by the scene: exit status 1, as for a scene that cannot be loaded.
fn scene_failure(message: String) -> Failure {
    Failure(format!("error: {message}"), 1)
}

fn usage(message: String) -> Failure {
    Failure(
        format!("error: {message}\n\nFor more information, try '--help'."),
        2,
    )
}

fn run(args: &Args) -> Result<(), Failure> {
    if args.max_dist.is_nan() || args.max_dist <= 0.0 {
        return Err(usage(format!(
            "--max-dist must be greater than 0, found {}",
            args.max_dist
        )));
    }
    let writing_to_terminal = args.output.is_none() && std::io::stdout().is_terminal();
    if writing_to_terminal && !args.dump {
        return Err(usage(
            "standard output is a terminal; redirect it to a file (> image.ppm) or use -o FILE"
                .into(),
        ));
    }
    // Checked before the render, so that a bad name costs nothing and destroys nothing.
    let output = match &args.output {
        Some(path) if !args.dump => {
            Some(OutputFile::check(path).map_err(|error| Failure(format!("error: {error}"), 2))?)
        }
        _ => None,
    };
    if output.is_some() {
        interrupt::remove_partial_file_on_interrupt();
    }
    let text = read_scene()?;
    let scene = legacy_rt::load(&text).map_err(|error| Failure(error.to_string(), 1))?;
    if args.dump {
        return emit_to_stdout(legacy_rt::dump(&scene).as_bytes());
    }

    let (width, height) = size(args, &scene)?;
    let options = legacy_rt::Options {
        max_dist: args.max_dist,
        kernel: args.kernel,
        threads: args.threads,
        ..legacy_rt::Options::new(width as usize, height as usize)
    };
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(height);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} rows, {eta} left")
                .expect("the template is valid"),
        );
        bar
    });
    let (image, _) = render::render(&scene, &options, |rows| {
        if let Some(bar) = &bar {
            bar.set_position(rows as u64);
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let format = output.as_ref().map_or(Format::Ppm, |o| o.format);
    let bytes = image_output::encode(&image, format)
        .map_err(|error| Failure(format!("error: cannot encode the image: {error}"), 2))?;
    match output {
        Some(output) => output
            .write(&bytes, interrupt::partial_file)
            .map_err(|error| Failure(format!("error: {error}"), 2)),
        None => emit_to_stdout(&bytes),
    }
}

/// The scene text from standard input, at most `MAX_INPUT` bytes.
fn read_scene() -> Result<String, Failure> {
    let stdin = std::io::stdin();
    if stdin.is_terminal() {
        say(
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
        return Err(scene_failure(format!(
            "the scene is larger than {mib} MiB, the most this program reads"
        )));
    }
    Ok(String::from_utf8_lossy(&text).into_owned())
}

/// The image size: W and H as given, or derived from the world window (spec §1). A bad
/// size the user typed is a command-line error (2); one derived from the scene is the
/// scene's (1), and the message says how to give a size instead.
fn size(args: &Args, scene: &legacy_rt::Scene) -> Result<(u64, u64), Failure> {
    let (width, height) = match (args.width, args.height) {
        (None, _) => scene.default_size(),
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => {
            let h = (w as f64 * scene.window.y / scene.window.x).round();
            (w, h.min(u64::MAX as f64) as u64)
        }
    };
    let problem = if width < 2 || height < 2 {
        format!(
            "the image must be at least 2x2 pixels (the projection divides by W-1 and H-1), \
             not {width}x{height}"
        )
    } else if width.saturating_mul(height) > MAX_PIXELS {
        format!("{width}x{height} is more than the {MAX_PIXELS} pixels this program renders")
    } else {
        return Ok((width, height));
    };
    if args.height.is_some() {
        return Err(usage(problem));
    }
    let (ww, wh) = (scene.window.x, scene.window.y);
    Err(scene_failure(format!(
        "{problem}: that size follows from the scene's world window, {ww} x {wh}; \
         give both W and H on the command line, e.g. legacy-rt 640 480 < scene.txt"
    )))
}

/// Writes `bytes` to standard output.
fn emit_to_stdout(bytes: &[u8]) -> Result<(), Failure> {
    match image_output::write(&mut std::io::stdout().lock(), bytes) {
        Ok(()) => Ok(()),
        // The reader went away (`| head`): end quietly.
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(error) => Err(Failure(
            format!("error: cannot write the image: {error}"),
            2,
        )),
    }
}

/// Removing the temporary file of `-o` when the program is interrupted while writing it.
mod interrupt {
    use std::path::{Path, PathBuf};
    use std::sync::Mutex;

    /// The temporary file being written, if any.
    static PARTIAL: Mutex<Option<PathBuf>> = Mutex::new(None);

    /// Records the temporary file being written (`None` once it is renamed or removed).
    pub fn partial_file(path: Option<&Path>) {
        if let Ok(mut partial) = PARTIAL.lock() {
            *partial = path.map(Path::to_path_buf);
        }
    }

    /// On SIGINT, SIGTERM or SIGHUP: remove the temporary file, then exit with 128 plus
    /// the signal's number, as the default action's status reads in a shell.
    #[cfg(unix)]
    pub fn remove_partial_file_on_interrupt() {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            return;
        };
        std::thread::spawn(move || {
            if let Some(signal) = signals.forever().next() {
                if let Ok(mut partial) = PARTIAL.lock()
                    && let Some(path) = partial.take()
                {
                    let _ = std::fs::remove_file(path);
                }
                std::process::exit(128 + signal);
            }
        });
    }

    /// Without Unix signals, an interrupt ends the program as it always does.
    #[cfg(not(unix))]
    pub fn remove_partial_file_on_interrupt() {}
}
