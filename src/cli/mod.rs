//! The command line: its arguments, and the commands that run the library for them.

pub mod compare;
pub mod grade;
pub mod interrupt;
pub mod io;
pub mod render;
pub mod trace;

use clap::{Parser, Subcommand};
use legacy_rt::compare::{F32, F64, Tolerance};
use legacy_rt::image_output::file::OutputFile;
use legacy_rt::render::{
    Choices, DEFAULT_MAX_DIST, MAX_THREADS, Show, Stage, VARIANTS, Variant, by_name, size_problem,
};
use legacy_rt::shapes::kernel::KernelChoice;
use std::io::Write;
use std::path::PathBuf;

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
  legacy-rt --stage diffuse < s.txt > d.ppm    the reference of the no-shadows assignment
  legacy-rt --show normals < s.txt > n.ppm     normals as colours (also: objects, depth)
  legacy-rt --variant no-shadows < s.txt > v.ppm  as if with a student's mistake
  legacy-rt trace 320 240 < scene.txt          why pixel (320, 240) is what it is
  legacy-rt trace 320 240 --format course < scene.txt   as the course's DBG_ output
  legacy-rt compare --diagnose scene.txt mine.ppm   why a student's image differs
  legacy-rt grade scenes/ submissions/ -o report/   a whole class, with a report

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
#[command(version, about, after_help = EXAMPLES, args_conflicts_with_subcommands = true)]
pub struct Args {
    /// Another command than rendering.
    #[command(subcommand)]
    pub command: Option<Command>,

    /// The render's arguments.
    #[command(flatten)]
    pub render: RenderArgs,
}

/// The commands besides rendering.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Print everything the renderer computes for one pixel, in order: the ray, every
    /// object tested (by kind and line), the hit, the material, each light with its
    /// shadow ray, the division by the distance, each mirror bounce, and last the
    /// pixel's bytes
    #[command(after_help = trace::EXAMPLES)]
    Trace(trace::TraceArgs),

    /// Compare a student's image with the reference rendered from the scene (or with a
    /// reference image): the verdict as the exit status (0 match, 1 differ, 2 error),
    /// where and on which objects they differ, the worst pixels with the trace command
    /// for each, and with --diagnose the mistake that explains the difference
    #[command(after_help = compare::EXAMPLES)]
    Compare(compare::CompareArgs),

    /// Grade a class: every student's image of every scene, each pair as `compare
    /// --diagnose` grades it, each reference rendered once; the grades as CSV and JSON, a
    /// page to look over (REPORT/index.html) and, if asked, Gradescope's results.json
    #[command(after_help = grade::EXAMPLES)]
    Grade(grade::GradeArgs),
}

/// What rendering takes.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// Image width in pixels [default: 640]
    #[arg(value_name = "W", value_parser = pixels)]
    pub width: Option<u64>,

    /// Image height in pixels [default: W times the world window's height / width, rounded]
    #[arg(value_name = "H", value_parser = pixels)]
    pub height: Option<u64>,

    /// Write the image to FILE instead of standard output: PNG if FILE ends in .png, PPM
    /// if it ends in .ppm or .pnm or has no extension
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,

    /// Print the typed scene (every object with the values computed at load) instead of
    /// rendering it
    #[arg(long)]
    pub dump: bool,

    /// Render on N threads, at most 256; 0 means one per core; a scene of a megabyte or
    /// more is read on them too. The image, or the error, is the same for every N (1, the
    /// default, is the course program's single thread)
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = threads)]
    pub threads: usize,

    /// What the image is computed with.
    #[command(flatten)]
    pub how: HowArgs,
}

/// The options that rendering, `trace` and `compare` share.
#[derive(clap::Args, Debug, Clone)]
pub struct HowArgs {
    /// Paths of rays longer than D (eye to hit, summed over mirror bounces) are black
    #[arg(long, value_name = "D", default_value_t = DEFAULT_MAX_DIST)]
    pub max_dist: f64,

    /// How hit distances are computed: accurate (within 4 ulps of the exact root),
    /// stable (the notes' coefficients, cancellation-free roots), textbook (the notes'
    /// (-b ± sqrt(b² - 4ac)) / 2a, as most students' tracers do), textbook-f32 (the same
    /// in single precision). Render with textbook to see where a tracer's speckles and
    /// missing pixels come from; see docs/speed-vs-error.md
    #[arg(long, value_name = "KERNEL", default_value = "accurate", value_parser = kernel)]
    pub kernel: KernelChoice,

    /// The course's assignment to render the reference of: ambient (ambient only),
    /// diffuse (ambient and diffuse, no shadow rays), shadows (with shadow rays, no
    /// mirrors), full (the finished image)
    #[arg(long, value_name = "STAGE", default_value = "full", value_parser = stage)]
    pub stage: Stage,

    /// A diagnostic image instead: normals (the normal at the first hit as a colour),
    /// objects (each object its own colour; the legend goes to standard error), depth
    /// (grey by the distance to the first hit; the mapping goes to standard error)
    #[arg(long, value_name = "IMAGE", value_parser = show, conflicts_with = "stage")]
    pub show: Option<Show>,

    #[arg(long, value_name = "ID", value_delimiter = ',', value_parser = variant, help = variant_help())]
    pub variant: Vec<Variant>,
}

impl HowArgs {
    /// The choices these options make.
    pub fn choices(&self) -> Choices {
        Choices {
            max_dist: self.max_dist,
            kernel: self.kernel,
            stage: self.stage,
            show: self.show,
            variants: self.variant.clone(),
        }
    }

    /// Fails on an option no render can take (before the scene is read).
    pub fn check(&self) -> Result<(), Failure> {
        self.choices().check().map_err(Failure::usage)
    }

    /// The library's options for a `width` x `height` image of `scene`.
    pub fn options(
        &self,
        scene: &legacy_rt::Scene,
        width: u64,
        height: u64,
    ) -> Result<legacy_rt::Options, Failure> {
        let choices = self.choices();
        (choices.options(scene, width as usize, height as usize)).map_err(Failure::usage)
    }
}

/// How close a student's image must be: what `compare` and `grade` share
/// ([`legacy_rt::grade::Closeness`] as flags).
#[derive(clap::Args, Debug)]
pub struct Closeness {
    /// The largest per-channel difference, in byte levels (0-255), that counts as equal
    #[arg(long, value_name = "N", default_value_t = Tolerance::default().levels)]
    pub tolerance: u8,

    /// The share of pixels, in percent, that may differ beyond the tolerance on pixels
    /// the reference is sure of while the images still match [default: 0]
    #[arg(long, value_name = "PCT", value_parser = percent)]
    pub allow: Option<f64>,

    /// The arithmetic a correct tracer is granted: f32 (the default, single precision),
    /// f64, or a relative precision such as 1e-6. Pixels whose decisions came closer than
    /// this to going the other way are fragile, and a difference there is excused
    #[arg(long, value_name = "f32|f64|NUMBER", value_parser = precision)]
    pub precision: Option<f64>,
}

impl Closeness {
    /// The flags as the library takes them.
    pub fn closeness(&self) -> legacy_rt::grade::Closeness {
        legacy_rt::grade::Closeness {
            levels: Some(self.tolerance),
            allow: self.allow,
            precision: self.precision,
        }
    }

    /// The tolerance, with `levels` instead of `--tolerance` if given.
    pub fn tolerance(&self, levels: Option<u8>) -> Tolerance {
        self.closeness().tolerance(levels)
    }
}

/// Parses `--allow`, a percentage.
fn percent(text: &str) -> Result<f64, String> {
    match text.trim_end_matches('%').parse::<f64>() {
        Ok(p) if (0.0..=100.0).contains(&p) => Ok(p),
        _ => Err("expected a percentage from 0 to 100, such as 0.5".to_string()),
    }
}

/// Parses `--precision`: f32, f64 or a relative precision from 0 to 0.01 (the reach of
/// the margins' recording).
fn precision(text: &str) -> Result<f64, String> {
    match text {
        "f32" => Ok(F32),
        "f64" => Ok(F64),
        _ => match text.parse::<f64>() {
            Ok(p) if (0.0..=legacy_rt::render::MAX_PRECISION).contains(&p) => Ok(p),
            _ => Err(
                "expected f32, f64 or a relative precision from 0 to 0.01, such as 1e-6"
                    .to_string(),
            ),
        },
    }
}

/// Parses `--max-pixels`, a positive count.
pub fn max_pixels(text: &str) -> Result<u64, String> {
    match text.replace('_', "").parse::<u64>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err("expected a whole number of pixels, such as 16777216 (4096x4096)".to_string()),
    }
}

/// Parses W or H, and recognises the usual slip of naming the scene file there.
pub fn pixels(text: &str) -> Result<u64, String> {
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
    let limit = MAX_THREADS;
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
    by_name(&KernelChoice::ALL, name, KernelChoice::name)
}

/// Parses a `--stage` name.
fn stage(name: &str) -> Result<Stage, String> {
    by_name(&Stage::ALL, name, Stage::name)
}

/// `--variant`'s help: the ids of the table of variants (spec §7.3, §7.4).
fn variant_help() -> String {
    let ids: Vec<String> = VARIANTS.iter().map(Variant::pattern).collect();
    format!(
        "Render as if with a student's mistake, or another term's rule (spec §7.3), for the \
         whole image or, with @LINE, for the one object or light whose record starts on \
         LINE (spec §7.4): {}. Repeat it, or separate ids with commas, for several; \
         docs/variants.md shows each",
        ids.join(", ")
    )
}

/// Parses a `--variant` id.
fn variant(id: &str) -> Result<Variant, String> {
    Variant::parse(id)
}

/// Parses a `--show` name.
fn show(name: &str) -> Result<Show, String> {
    by_name(&Show::ALL, name, Show::name)
}

/// `-o FILE` checked before anything is read or rendered, so that a bad name costs
/// nothing and destroys nothing; an interrupt from then on removes the temporary file.
pub fn output_file(path: Option<&std::path::Path>) -> Result<Option<OutputFile>, Failure> {
    let Some(path) = path else {
        return Ok(None);
    };
    let output = OutputFile::check(path).map_err(Failure::other)?;
    interrupt::remove_partial_file_on_interrupt();
    Ok(Some(output))
}

/// Why a command failed, and its exit status. `main` says it: `error: ` and the
/// message, the pointer to `--help` after a bad command line, and a scene's load error as
/// the block of spec §2.4 (which says `error: ` itself).
#[derive(Debug)]
pub struct Failure {
    what: What,
    /// The exit status.
    pub code: u8,
}

/// What a [`Failure`] says.
#[derive(Debug)]
enum What {
    /// A bad command line.
    Usage(String),
    /// A sentence about the scene, a file or the output.
    Message(String),
    /// A scene that does not load, after its file's name where it was named.
    Load {
        file: Option<String>,
        error: Box<legacy_rt::SceneError>,
    },
    /// Nothing more to say: the report on standard output said it.
    Quiet,
}

impl Failure {
    /// A bad command line: exit status 2.
    pub fn usage(message: impl std::fmt::Display) -> Failure {
        Failure {
            what: What::Usage(message.to_string()),
            code: 2,
        }
    }

    /// A failure caused by the scene: exit status 1, as for a scene that cannot be
    /// loaded.
    pub fn scene(message: String) -> Failure {
        Failure {
            what: What::Message(message),
            code: 1,
        }
    }

    /// A file, the output or the machine failed: exit status 2.
    pub fn other(message: impl std::fmt::Display) -> Failure {
        Failure {
            what: What::Message(message.to_string()),
            code: 2,
        }
    }

    /// A scene that does not load (`file` names it where it was named): exit status
    /// `code`.
    pub fn load(file: Option<String>, error: legacy_rt::SceneError, code: u8) -> Failure {
        Failure {
            what: What::Load {
                file,
                error: Box::new(error),
            },
            code,
        }
    }

    /// Exit status `code`, with nothing to say.
    pub fn quiet(code: u8) -> Failure {
        Failure {
            what: What::Quiet,
            code,
        }
    }

    /// The same failure with exit status `code`.
    pub fn with_code(self, code: u8) -> Failure {
        Failure { code, ..self }
    }

    /// What standard error gets.
    pub fn message(&self) -> String {
        match &self.what {
            What::Usage(message) => {
                format!("error: {message}\n\nFor more information, try '--help'.")
            }
            What::Message(message) => format!("error: {message}"),
            What::Load {
                file: Some(file),
                error,
            } => format!("{file}: {error}"),
            What::Load { file: None, error } => error.to_string(),
            What::Quiet => String::new(),
        }
    }
}

impl From<legacy_rt::files::FileError> for Failure {
    fn from(error: legacy_rt::files::FileError) -> Failure {
        Failure::other(error)
    }
}

impl From<legacy_rt::grade::GradeError> for Failure {
    fn from(error: legacy_rt::grade::GradeError) -> Failure {
        use legacy_rt::grade::GradeError;
        match error {
            GradeError::Usage(message) => Failure::usage(message),
            GradeError::Scene { file, error } => Failure::load(Some(file), *error, 2),
            other => Failure::other(other),
        }
    }
}

/// Writes a line to standard error. A closed standard error (`2>&1 | head`) is no reason
/// to fail, and `eprintln!` would panic there.
pub fn say(message: &str) {
    if !message.is_empty() {
        let _ = writeln!(std::io::stderr().lock(), "{message}");
    }
}

/// The image size: W and H as given, or derived from the world window (spec §1). A bad
/// size the user typed is a command-line error (2); one derived from the scene is the
/// scene's (1), and the message says how to give a size instead.
pub fn size(
    given: (Option<u64>, Option<u64>),
    scene: &legacy_rt::Scene,
) -> Result<(u64, u64), Failure> {
    let (width, height) = match given {
        (None, _) => scene.default_size(),
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, scene.height_for(w)),
    };
    let Some(problem) = size_problem(width, height, MAX_PIXELS) else {
        return Ok((width, height));
    };
    if given.1.is_some() {
        return Err(Failure::usage(problem));
    }
    let (ww, wh) = (scene.window.x, scene.window.y);
    Err(Failure::scene(format!(
        "{problem}: that size follows from the scene's world window, {ww} x {wh}; \
         give both W and H on the command line, e.g. legacy-rt 640 480 < scene.txt"
    )))
}
