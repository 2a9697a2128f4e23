//! `legacy-rt compare SCENE|REFERENCE STUDENT`: the verdict (exit 0 match, 1 differ, 2
//! error, as ImageMagick's `compare`), where the images differ and on which objects, the
//! worst pixels with the `trace` command that explains each, and with `--diagnose` the
//! student's likely mistake.

use super::io::emit_to_stdout;
use super::render::write_image;
use super::{Closeness, Failure, HowArgs, max_pixels, output_file, pixels, size, threads};
use legacy_rt::compare::read::{Content, DEFAULT_MAX_PIXELS, content};
use legacy_rt::compare::{self, Settings, Verdict};
use legacy_rt::files::{self, MAX_INPUT, open_regular, read_all, read_image, same_file, text_of};
use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::PathBuf;

/// Examples for `compare --help`.
pub const EXAMPLES: &str = "\
Examples:
  legacy-rt compare scene.txt mine.ppm              render the reference at mine.ppm's size
  legacy-rt compare reference.ppm mine.png          two images (no scene: no explanation)
  legacy-rt compare --stage shadows scene.txt mine.ppm    against the shadows assignment
  legacy-rt compare --diagnose scene.txt mine.ppm   and name the mistake that explains it
  legacy-rt compare --diff diff.png scene.txt mine.ppm    a picture of where they differ
  legacy-rt compare --json scene.txt mine.ppm       the report for scripts

  legacy-rt grade scenes/ submissions/ -o report/   a whole class (legacy-rt grade --help)

The first file is a scene or an image, told apart by its content. Images are PPM (P6 or
P3, 8 bits) or PNG, regular files of at most --max-pixels pixels (4096x4096 unless
raised). Exit status: 0 when the images match within the tolerance, 1 when they differ
(or, with --size, when the student's image has another size: verdict wrong-size), 2 on an
error (an unreadable, damaged, truncated, grey or 16-bit image, a pipe or device, images
of two sizes, a scene that does not load).

With a scene, the images match when every pixel the reference is sure of is equal (within
--tolerance). Where one of the reference's decisions came within --precision of going the
other way (a grazing ray, a shadow's edge, a tile's edge, a byte at a step) the pixel is
fragile: a correct tracer may get it otherwise, and a difference there is reported but
not counted. The diff image shows the reference in grey where the pixels match,
differences on fragile pixels in purple, and the others in blue (1-3 levels), yellow
(4-31) or red (32-255).";

/// The comparison's arguments.
#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// The scene file, or a reference image (PPM or PNG)
    #[arg(value_name = "SCENE|REFERENCE")]
    reference: PathBuf,

    /// The student's image: PPM (P6 or P3) or PNG
    #[arg(value_name = "STUDENT")]
    student: PathBuf,

    /// How close the student's image must be.
    #[command(flatten)]
    pub(super) close: Closeness,

    /// Print the report as JSON (keys: verdict, width, height, differing_pixels,
    /// fragile_pixels, differing_fragile_pixels, differing_fraction,
    /// max_channel_difference, groups, worst, diagnosis, ...)
    #[arg(long)]
    json: bool,

    /// Also write a diff image to FILE (PNG, or PPM for .ppm): the reference in grey,
    /// differing pixels blue (1-3 levels), yellow (4-31) or red (32 or more), purple
    /// where the reference's pixel is fragile (excused)
    #[arg(long, value_name = "FILE")]
    diff: Option<PathBuf>,

    /// Try every variant of spec §7.3 (the students' common mistakes), and the edits of
    /// one record of §7.4 (an object hidden, casting no shadow, unlit...; a light off...)
    /// on the objects and lights the differences involve, and report those that explain
    /// the student's image better than the reference, best first, with a pixel to trace
    #[arg(long)]
    diagnose: bool,

    /// How many of the most different pixels to list
    #[arg(long, value_name = "N", default_value_t = 10)]
    worst: usize,

    /// Render on N threads, at most 256; 0 (the default) means one per core
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = threads)]
    threads: usize,

    /// The size the student's image must have: another size is verdict wrong-size (exit
    /// 1) instead of a reference rendered at the student's size
    #[arg(long, value_names = ["W", "H"], num_args = 2, value_parser = pixels)]
    size: Option<Vec<u64>>,

    /// The most pixels an image may have; a larger one is refused from its header,
    /// before it is decoded [default: 16777216, 4096x4096]
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_PIXELS, value_parser = max_pixels, hide_default_value = true)]
    max_pixels: u64,

    /// How the reference is computed (with a scene).
    #[command(flatten)]
    how: HowArgs,
}

/// The first bytes of a file, enough to tell an image from a scene.
fn first_bytes(file: &mut File, shown: &str) -> Result<Vec<u8>, Failure> {
    let mut start = Vec::new();
    (&mut *file)
        .take(16)
        .read_to_end(&mut start)
        .and_then(|_| file.seek(SeekFrom::Start(0)))
        .map_err(|error| Failure::other(format!("cannot read {shown}: {error}")))?;
    Ok(start)
}

/// Refuses a `--diff` path that is a symbolic link (dangling or not) or names something
/// other than a regular file (a FIFO would hang the write, a device take it): a grader
/// who writes the diff into a student's folder must not write through the student's
/// link, nor create the file it points at. `-o`, for the user's own files, follows links.
fn diff_target(path: &std::path::Path) -> Result<(), Failure> {
    let shown = files::shown(path);
    let refuse = |what: &str| {
        Err(Failure::other(format!(
            "--diff {shown} is {what}: the diff image is written only to a new or regular file"
        )))
    };
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => refuse("a symbolic link"),
        Ok(meta) if meta.is_dir() => refuse("a folder"),
        Ok(meta) if !meta.is_file() => refuse("not a regular file (a pipe, socket or device)"),
        _ => Ok(()),
    }
}

/// Compares; `Ok(true)` when the images match.
pub fn run(args: &CompareArgs) -> Result<bool, Failure> {
    // Every failure of `compare` is exit 2, whatever it would be for rendering.
    run_inner(args).map_err(|failure| failure.with_code(2))
}

fn run_inner(args: &CompareArgs) -> Result<bool, Failure> {
    if let Some(diff) = &args.diff
        && (same_file(diff, &args.student) || same_file(diff, &args.reference))
    {
        // `--diff mine.ppm`, or a hard link to it, would replace the image being graded.
        return Err(Failure::other(format!(
            "--diff {} names a file being compared; give the diff image another name",
            files::shown(diff)
        )));
    }
    if let Some(diff) = &args.diff {
        diff_target(diff)?;
    }
    let diff = output_file(args.diff.as_deref())?;
    args.how.check()?;
    let shown = files::shown(&args.reference);
    let student_shown = files::shown(&args.student);
    let mut first = open_regular(&args.reference)?;
    let is_scene = content(&first_bytes(&mut first, &shown)?) == Content::Text;
    let student = read_image(&args.student, "student's image", args.max_pixels)?;
    let settings = Settings {
        tolerance: args.close.tolerance(None),
        worst: args.worst,
        diagnose: args.diagnose,
    };
    let choices = args.how.choices();
    if let Some(&[w, h]) = args.size.as_deref()
        && (student.width as u64, student.height as u64) != (w, h)
    {
        let report = compare::wrong_size(&student, (w as usize, h as usize), &settings);
        let choices = is_scene.then_some(&choices);
        emit_report(args, &report, &shown, &student_shown, choices)?;
        return Ok(false);
    }
    let (reference, scene, options) = match is_scene {
        true => {
            let bytes = read_all(first, &args.reference, MAX_INPUT)?;
            let scene = legacy_rt::load(&text_of(bytes))
                .map_err(|error| Failure::load(Some(shown.clone()), error, 2))?;
            let given = (Some(student.width as u64), Some(student.height as u64));
            let (w, h) = size(given, &scene)?;
            let options = legacy_rt::Options {
                threads: args.threads,
                ..args.how.options(&scene, w, h)?
            };
            let precision = settings.tolerance.precision;
            let reference =
                compare::reference(&scene, &options, &student, precision, args.diagnose);
            (reference, Some(scene), Some(options))
        }
        false => {
            if args.diagnose {
                return Err(Failure::other(
                    "--diagnose needs the scene: give the scene file first, not an image",
                ));
            }
            drop(first);
            let reference = read_image(&args.reference, "reference image", args.max_pixels)?;
            (compare::Reference::image(reference), None, None)
        }
    };
    let with_scene = scene.as_ref().zip(options.as_ref());
    let mut report =
        compare::report(&reference, &student, with_scene, &settings).map_err(Failure::other)?;
    // The choices that made the reference, when it was rendered from the scene.
    let choices = options.is_some().then_some(choices);
    if let Some((options, choices)) = options.as_ref().zip(choices.as_ref()) {
        let scene = args.reference.display().to_string();
        add_trace_commands(&mut report, choices, options, &scene);
    }
    if let Some(diff) = diff {
        let image = compare::diff_image(&reference, &student, args.close.tolerance)
            .map_err(Failure::other)?;
        write_image(&image, diff.format, Some(diff))?;
    }
    emit_report(args, &report, &shown, &student_shown, choices.as_ref())?;
    Ok(report.verdict == Verdict::Match)
}

/// Gives the report's worst pixels and diagnoses the `trace` commands that explain them
/// in the reference rendered from the scene file `scene` with `choices` and `options`.
pub(super) fn add_trace_commands(
    report: &mut compare::Report,
    choices: &legacy_rt::render::Choices,
    options: &legacy_rt::Options,
    scene: &str,
) {
    report.add_trace_commands(|x, y, under| {
        compare::text::trace_command(choices, options, scene, x, y, under)
    });
}

/// Prints the report, as text or JSON, on standard output.
fn emit_report(
    args: &CompareArgs,
    report: &compare::Report,
    reference: &str,
    student: &str,
    choices: Option<&legacy_rt::render::Choices>,
) -> Result<(), Failure> {
    let out = match args.json {
        true => {
            let json = serde_json::to_string_pretty(report).map_err(Failure::other)?;
            json + "\n"
        }
        false => compare::text::text(report, reference, student, choices),
    };
    emit_to_stdout(out.as_bytes())
}
