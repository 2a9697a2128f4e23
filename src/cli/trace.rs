//! `legacy-rt trace X Y [W H]`: the trace of one pixel, readable or in the course's
//! format, and with `-o` the image with that pixel marked.

use super::io::{MAX_INPUT, emit_to_stdout, open_regular, read_all, read_scene, text_of};
use super::render::{render_with_progress, write_image};
use super::{Failure, HowArgs, check_stdout, output_file, pixels, size, usage};
use std::path::PathBuf;

/// Examples for `trace --help`.
pub const EXAMPLES: &str = "\
Examples:
  legacy-rt trace 320 240 < scene.txt                 pixel (320, 240) of the 640-wide image
  legacy-rt trace 5 3 800 600 < scene.txt             pixel (5, 3) of an 800x600 image
  legacy-rt trace 320 240 --format course < s.txt     the course's PIX/WRL/FND/HIT/AMB lines
  legacy-rt trace 320 240 --stage diffuse < s.txt     as the no-shadows assignment computes it
  legacy-rt trace 320 240 -o traced.png < s.txt       and the image, the pixel marked green
  legacy-rt trace 320 240 --against dbg.txt < s.txt   your program's DBG_ trace read against
                                                      the reference: the first number that
                                                      differs, by object, light and line

(0, 0) is the lower-left pixel, as in the course (spec §4.1). The trace goes to standard
output; its last line is `bytes: R G B`, the pixel's bytes in the image.

With --against FILE: FILE is what the course program printed on standard error when built
with its DBG_ flags, for this pixel or a whole image (docs/trace.md says how to make it).
Exit 0 when it agrees with the reference, 1 at a difference, 2 when FILE cannot be read
or holds no trace of this pixel of this scene.";

/// The trace's arguments.
#[derive(clap::Args, Debug)]
pub struct TraceArgs {
    /// The pixel's column, 0 at the left
    #[arg(value_name = "X")]
    x: u64,

    /// The pixel's row, 0 at the bottom
    #[arg(value_name = "Y")]
    y: u64,

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
    /// flags, against the reference's trace of the pixel: the first number that differs
    #[arg(long, value_name = "FILE")]
    against: Option<PathBuf>,

    /// With --against: the comparisons as JSON (every value compared, the first
    /// difference)
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

/// Traces the pixel of the scene on standard input.
pub fn run(args: &TraceArgs) -> Result<(), Failure> {
    check_stdout()?;
    let output = output_file(args.output.as_deref())?;
    args.how.check()?;
    let text = read_scene()?;
    let scene = legacy_rt::load(&text).map_err(|error| Failure(error.to_string(), 1))?;
    let (width, height) = size((args.width, args.height), &scene)?;
    if args.x >= width || args.y >= height {
        return Err(usage(format!(
            "pixel ({}, {}) is outside the {width}x{height} image: X must be below {width} \
             and Y below {height}, with (0, 0) at the lower left",
            args.x, args.y
        )));
    }
    let options = args.how.options(&scene, width, height)?;
    let (x, y) = (args.x as usize, args.y as usize);
    // The student's trace is read before anything is rendered: an unreadable FILE fails
    // at once.
    let student = match &args.against {
        Some(path) => Some((
            path,
            text_of(read_all(open_regular(path)?, path, MAX_INPUT)?),
        )),
        None => None,
    };
    let trace = legacy_rt::render::trace(&scene, &options, x, y).expect("the pixel is inside");
    let (text, differs) = match &student {
        Some((path, student)) => against(&scene, &trace, path, student, args.json)?,
        None => match args.format.as_str() {
            "course" => (trace.course(&scene), false),
            _ => (trace.readable(&scene), false),
        },
    };
    if let Some(output) = output {
        let mut image = render_with_progress(&scene, &options);
        let at = options.row_of(y) * width as usize + x;
        image.pixels[at] = MARK;
        write_image(&image, output.format, Some(output))?;
    }
    emit_to_stdout(text.as_bytes())?;
    match differs {
        true => Err(Failure(String::new(), 1)),
        false => Ok(()),
    }
}

/// The student's trace read against the reference's: the report, and whether they differ.
fn against(
    scene: &legacy_rt::Scene,
    trace: &legacy_rt::render::Trace,
    path: &std::path::Path,
    student: &str,
    json: bool,
) -> Result<(String, bool), Failure> {
    let shown = legacy_rt::error::escaped(&path.display().to_string());
    let report = legacy_rt::against::against(scene, trace, student)
        .map_err(|unreadable| Failure(format!("error: {}", unreadable.about(&shown)), 2))?;
    let differs = report.first_difference().is_some();
    let text = match json {
        true => {
            let file = path.display().to_string();
            let summary = report.summary(trace, &file);
            serde_json::to_string_pretty(&summary).expect("the report is plain data") + "\n"
        }
        false => report.text(scene, trace, &shown, student),
    };
    Ok((text, differs))
}
