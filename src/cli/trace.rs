//! `legacy-rt trace X Y [W H]`: the trace of one pixel, readable or in the course's
//! format, and with `-o` the image with that pixel marked.

use super::io::{emit_to_stdout, read_scene, stdin_name};
use super::render::{render_with_progress, write_image};
use super::{Failure, HowArgs, output_file, pixels, size};
use legacy_rt::files;
use legacy_rt::files::open_regular;
use std::path::{Path, PathBuf};

/// Examples for `trace --help`.
pub const EXAMPLES: &str = "\
Examples:
  legacy-rt trace 320 240 < scene.txt                 pixel (320, 240) of the 640-wide image
  legacy-rt trace 5 3 800 600 < scene.txt             pixel (5, 3) of an 800x600 image
  legacy-rt trace 320 240 --format course < s.txt     the course's PIX/WRL/FND/HIT/AMB lines
  legacy-rt trace 320 240 --stage diffuse < s.txt     as the no-shadows assignment computes it
  legacy-rt trace 320 240 -o traced.png < s.txt       and the image, the pixel marked green
  legacy-rt trace --against dbg.txt 64 48 < s.txt     your program's whole DBG_ trace of a
                                                      64x48 image read against the reference:
                                                      how many pixels agree, and the first
                                                      difference of the others, grouped
  legacy-rt trace 5 3 64 48 --against dbg.txt < s.txt one pixel of it: the first number that
                                                      differs, by object, light and line

(0, 0) is the lower-left pixel, as in the course (spec §4.1). The trace goes to standard
output; its last line is `bytes: R G B`, the pixel's bytes in the image.

With --against FILE: FILE is what the course program printed on standard error when built
with its DBG_ flags (docs/trace.md says how to make it): `ray 64 48 < scene.txt 2> dbg.txt`.
With two numbers they are the image's size W H, as the program was run; with four, X Y W
H: one pixel. Only a difference that changes an outcome (a hit or a miss, the closest
object, a blocked light, the bytes) counts. Exit 0 when every pixel read agrees with the
reference, 1 at a difference, 2 when FILE cannot be read or is not of this scene and size.";

/// The trace's arguments.
#[derive(clap::Args, Debug)]
pub struct TraceArgs {
    /// The pixel's column, 0 at the left (with --against and no W H: the image's width)
    #[arg(value_name = "X")]
    x: Option<u64>,

    /// The pixel's row, 0 at the bottom (with --against and no W H: the image's height)
    #[arg(value_name = "Y")]
    y: Option<u64>,

    /// Image width in pixels [default: 640]
    #[arg(value_name = "W", value_parser = pixels)]
    width: Option<u64>,

    /// Image height in pixels [default: from the world window, as for rendering]
    #[arg(value_name = "H", value_parser = pixels)]
    height: Option<u64>,

    /// readable (an indented tree of every step) or course (the course program's debug
    /// lines, with its object ids: lights and objects numbered together from 0)
    #[arg(long, value_name = "FORMAT", default_value = "readable", value_parser = ["readable", "course"])]
    format: String,

    /// Read FILE, the standard error of a student's program built with the course's DBG_
    /// flags, against the reference's traces: every pixel it holds (no X Y), or pixel X Y;
    /// the first difference that changes an outcome
    #[arg(long, value_name = "FILE")]
    against: Option<PathBuf>,

    /// With --against: the report as JSON (one pixel: every value compared and the first
    /// difference; a whole file: the counts and the groups of differing pixels)
    #[arg(long, requires = "against")]
    json: bool,

    /// Also write the image to FILE with the traced pixel painted green
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,

    /// What the image is computed with.
    #[command(flatten)]
    how: HowArgs,
}

/// The colour of the marked pixel (the UCR course painted the traced pixel green).
const MARK: [u8; 3] = [0, 255, 0];

/// Traces the pixel of the scene on standard input, or reads a student's trace.
pub fn run(args: &TraceArgs) -> Result<(), Failure> {
    let numbers: Vec<u64> = [args.x, args.y, args.width, args.height]
        .into_iter()
        .flatten()
        .collect();
    let (pixel, given) = match (numbers.as_slice(), &args.against) {
        ([], Some(_)) => (None, (None, None)),
        ([w, h], Some(_)) => (None, (Some(*w), Some(*h))),
        ([x, y], _) => (Some((*x, *y)), (None, None)),
        ([x, y, w], _) => (Some((*x, *y)), (Some(*w), None)),
        ([x, y, w, h], _) => (Some((*x, *y)), (Some(*w), Some(*h))),
        _ => {
            return Err(Failure::usage(
                "trace takes X Y [W H] (a pixel), or with --against FILE, [W H] (every pixel \
                 of the file) or X Y W H",
            ));
        }
    };
    if let (None, (Some(w), Some(h))) = (pixel, given) {
        super::pixels(&w.to_string()).map_err(Failure::usage)?;
        super::pixels(&h.to_string()).map_err(Failure::usage)?;
    }
    let output = output_file(args.output.as_deref())?;
    if pixel.is_none() && output.is_some() {
        return Err(Failure::usage("-o marks one pixel: give X Y W H with it"));
    }
    args.how.check()?;
    // The student's file is opened before the scene is read: an unreadable FILE fails at
    // once. It is read as a stream, one pixel's block at a time.
    let student = match &args.against {
        Some(path) => Some((path, open_regular(path)?)),
        None => None,
    };
    let text = read_scene()?;
    let scene = legacy_rt::load(&text).map_err(|error| Failure::load(None, error, 1))?;
    let (width, height) = size(given, &scene)?;
    let options = args.how.options(&scene, width, height)?;
    let Some((x, y)) = pixel else {
        let (path, file) = student.expect("no pixel only with --against");
        return whole(&scene, &options, &args.how.choices(), path, file, args.json);
    };
    if x >= width || y >= height {
        return Err(Failure::usage(format!(
            "pixel ({x}, {y}) is outside the {width}x{height} image: X must be below {width} \
             and Y below {height}, with (0, 0) at the lower left"
        )));
    }
    let (x, y) = (x as usize, y as usize);
    let (text, differs) = match student {
        Some((path, file)) => against(&scene, &options, (x, y), path, file, args.json)?,
        None => {
            let trace =
                legacy_rt::render::trace(&scene, &options, x, y).expect("the pixel is inside");
            match args.format.as_str() {
                "course" => (trace.course(&scene), false),
                _ => (trace.readable(&scene), false),
            }
        }
    };
    if let Some(output) = output {
        let mut image = render_with_progress(&scene, &options);
        let at = options.row_of(y) * width as usize + x;
        image.pixels[at] = MARK;
        write_image(&image, output.format, Some(output))?;
    }
    emit_to_stdout(text.as_bytes())?;
    match differs {
        true => Err(Failure::quiet(1)),
        false => Ok(()),
    }
}

/// The student's file as a stream of lines, read once.
fn stream(file: std::fs::File) -> std::io::BufReader<std::fs::File> {
    std::io::BufReader::with_capacity(64 << 10, file)
}

/// The message of a file that cannot be read against the reference.
fn unreadable(path: &Path, unreadable: legacy_rt::against::Unreadable) -> Failure {
    let shown = files::shown(path);
    Failure::other(unreadable.about(&shown))
}

/// One pixel of the student's trace read against the reference's: the report, and
/// whether they differ.
fn against(
    scene: &legacy_rt::Scene,
    options: &legacy_rt::Options,
    pixel: (usize, usize),
    path: &Path,
    file: std::fs::File,
    json: bool,
) -> Result<(String, bool), Failure> {
    let shown = files::shown(path);
    legacy_rt::render::tracing(scene, options, |frame| {
        let (report, trace) = legacy_rt::against::against(scene, frame, pixel, stream(file))
            .map_err(|error| unreadable(path, error))?;
        let differs = report.first_difference().is_some();
        let text = match json {
            true => {
                let file = path.display().to_string();
                let summary = report.summary((options.width, options.height), &file);
                serde_json::to_string_pretty(&summary).expect("the report is plain data") + "\n"
            }
            false => report.text(scene, &trace, &shown),
        };
        Ok((text, differs))
    })
}

/// Every pixel of the student's trace read against the reference's.
fn whole(
    scene: &legacy_rt::Scene,
    options: &legacy_rt::Options,
    choices: &legacy_rt::render::Choices,
    path: &Path,
    file: std::fs::File,
    json: bool,
) -> Result<(), Failure> {
    let shown = files::shown(path);
    let report = legacy_rt::render::tracing(scene, options, |frame| {
        legacy_rt::against::whole(scene, frame, stream(file))
    })
    .map_err(|error| {
        let shown = files::shown(path);
        Failure::other(format!(
            "{} (with --against, two numbers are the image's size W H, here {}x{}; to read \
             one pixel, give X Y W H)",
            error.about(&shown),
            options.width,
            options.height
        ))
    })?;
    let (w, h) = (options.width, options.height);
    let flags = choices.flags();
    let word = legacy_rt::compare::text::shell_word(&path.display().to_string());
    let scene_word =
        legacy_rt::compare::text::shell_word(&stdin_name().unwrap_or("scene.txt".into()));
    let command = |x: usize, y: usize| {
        format!("legacy-rt trace {x} {y} {w} {h}{flags} --against {word} < {scene_word}")
    };
    let text = match json {
        true => {
            let mut value = serde_json::to_value(&report).expect("the report is plain data");
            value["file"] = path.display().to_string().into();
            value["agrees"] = report.agrees().into();
            for group in value["groups"].as_array_mut().into_iter().flatten() {
                let (x, y) = (group["pixel"][0].as_u64(), group["pixel"][1].as_u64());
                if let (Some(x), Some(y)) = (x, y) {
                    group["command"] = command(x as usize, y as usize).into();
                }
            }
            serde_json::to_string_pretty(&value).expect("the report is plain data") + "\n"
        }
        false => report.text(&shown, command),
    };
    emit_to_stdout(text.as_bytes())?;
    match report.agrees() {
        true => Ok(()),
        false => Err(Failure::quiet(1)),
    }
}
