//! The `legacy-rt` command: parse flags, call the library, print the error.

use clap::Parser;
use legacy_rt::image_output::{self, Format};
use legacy_rt::render::{self, DEFAULT_MAX_DIST};
use legacy_rt::shapes::kernel::KernelChoice;
use std::io::{IsTerminal, Read};
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
folder.";

/// Renders a scene file of the ray-tracing course exactly as the course's program did.
///
/// The scene format and the rendering rules are documented in docs/ and README.md.
#[derive(Parser, Debug)]
#[command(version, about, after_help = EXAMPLES)]
struct Args {
    /// Image width in pixels [default: 640]
    #[arg(value_name = "W")]
    width: Option<u64>,

    /// Image height in pixels [default: W times the world window's height / width, rounded]
    #[arg(value_name = "H")]
    height: Option<u64>,

    /// Write the image to FILE instead of standard output: PNG if FILE ends in .png, else PPM
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

    /// Render on N threads; 0 means one per core. The image is the same bytes for every N
    /// (1, the default, is the course program's single thread)
    #[arg(long, value_name = "N", default_value_t = 1)]
    threads: usize,
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
            if !message.is_empty() {
                eprintln!("{message}");
            }
            ExitCode::from(code)
        }
    }
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
    let mut text = Vec::new();
    if let Err(error) = std::io::stdin().take(MAX_INPUT + 1).read_to_end(&mut text) {
        return Err(Failure(
            format!("error: cannot read standard input: {error}"),
            2,
        ));
    }
    if text.len() as u64 > MAX_INPUT {
        let mib = MAX_INPUT >> 20;
        return Err(Failure(
            format!("error: the scene is larger than {mib} MiB"),
            2,
        ));
    }
    let text = String::from_utf8_lossy(&text);
    let scene = legacy_rt::load(&text).map_err(|error| Failure(error.to_string(), 1))?;
    if args.dump {
        return emit(args, legacy_rt::dump(&scene).as_bytes());
    }

    let (width, height) = match (args.width, args.height) {
        (None, _) => scene.default_size(),
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => {
            let h = (w as f64 * scene.window.y / scene.window.x).round();
            (w, h.min(u64::MAX as f64) as u64)
        }
    };
    if width < 2 || height < 2 {
        return Err(usage(format!(
            "the image must be at least 2x2 pixels (the projection divides by W-1 and H-1), \
             not {width}x{height}"
        )));
    }
    if width.saturating_mul(height) > MAX_PIXELS {
        return Err(usage(format!(
            "{width}x{height} is more than the {MAX_PIXELS} pixels this program renders"
        )));
    }
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
    let format = args
        .output
        .as_deref()
        .map_or(Format::Ppm, Format::from_path);
    let bytes = image_output::encode(&image, format)
        .map_err(|error| Failure(format!("error: cannot encode the image: {error}"), 2))?;
    emit(args, &bytes)
}

/// Writes `bytes` to the output file (whole, or not at all) or to standard output.
fn emit(args: &Args, bytes: &[u8]) -> Result<(), Failure> {
    match &args.output {
        Some(path) if !args.dump => {
            // Write beside the target and rename, so a failure leaves no partial image.
            let mut partial = path.clone().into_os_string();
            partial.push(".partial");
            let partial = PathBuf::from(partial);
            std::fs::write(&partial, bytes)
                .and_then(|()| std::fs::rename(&partial, path))
                .map_err(|error| {
                    let _ = std::fs::remove_file(&partial);
                    Failure(
                        format!("error: cannot write {}: {error}", path.display()),
                        2,
                    )
                })
        }
        _ => match image_output::write(&mut std::io::stdout().lock(), bytes) {
            Ok(()) => Ok(()),
            // The reader went away (`| head`): end quietly.
            Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
            Err(error) => Err(Failure(
                format!("error: cannot write the image: {error}"),
                2,
            )),
        },
    }
}
