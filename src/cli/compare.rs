//! `legacy-rt compare SCENE|REFERENCE STUDENT`: the verdict (exit 0 match, 1 differ, 2
//! error, as ImageMagick's `compare`), where the images differ and on which objects, the
//! worst pixels with the `trace` command that explains each, and with `--diagnose` the
//! student's likely mistake.

use super::render::write_image;
use super::{Failure, HowArgs, output_file, size, threads};
use legacy_rt::compare::read::{Content, content};
use legacy_rt::compare::{self, Report, Settings, Tolerance, Verdict};
use legacy_rt::render::{DEFAULT_MAX_DIST, Stage, Variant};
use legacy_rt::shapes::kernel::KernelChoice;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Examples for `compare --help`.
pub const EXAMPLES: &str = "\
Examples:
  legacy-rt compare scene.txt mine.ppm              render the reference at mine.ppm's size
  legacy-rt compare reference.ppm mine.png          two images (no scene: no explanation)
  legacy-rt compare --stage shadows scene.txt mine.ppm    against the shadows assignment
  legacy-rt compare --diagnose scene.txt mine.ppm   and name the mistake that explains it
  legacy-rt compare --diff diff.png scene.txt mine.ppm    a picture of where they differ
  legacy-rt compare --json scene.txt mine.ppm       the report for scripts

  for f in submissions/*.ppm; do                    grading a class
    legacy-rt compare scene.txt \"$f\" > \"${f%.ppm}.txt\"; echo \"$f $?\"
  done

The first file is a scene or an image, told apart by its content. Images are PPM (P6 or
P3, 8 bits) or PNG. Exit status: 0 when the images match within the tolerance, 1 when
they differ, 2 on an error (an unreadable, truncated, grey or 16-bit image, images of two
sizes, a scene that does not load). The diff image shows the reference in grey where the
pixels match, and differing pixels in blue (1-3 levels), yellow (4-31) or red (32-255).";

/// The comparison's arguments.
#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// The scene file, or a reference image (PPM or PNG)
    #[arg(value_name = "SCENE|REFERENCE")]
    reference: PathBuf,

    /// The student's image: PPM (P6 or P3) or PNG
    #[arg(value_name = "STUDENT")]
    student: PathBuf,

    /// The largest per-channel difference, in byte levels (0-255), that counts as equal
    #[arg(long, value_name = "N", default_value_t = Tolerance::default().levels)]
    tolerance: u8,

    /// The share of pixels, in percent, that may differ beyond the tolerance while the
    /// images still match [default: 0.5]
    #[arg(long, value_name = "PCT", value_parser = percent)]
    allow: Option<f64>,

    /// Print the report as JSON (keys: verdict, width, height, differing_pixels,
    /// differing_fraction, max_channel_difference, groups, worst, diagnosis, ...)
    #[arg(long)]
    json: bool,

    /// Also write a diff image to FILE (PNG, or PPM for .ppm): the reference in grey,
    /// differing pixels blue (1-3 levels), yellow (4-31) or red (32 or more)
    #[arg(long, value_name = "FILE")]
    diff: Option<PathBuf>,

    /// Try every variant of spec §7.3 (the students' common mistakes) and report those
    /// that explain the student's image better than the reference, best first
    #[arg(long)]
    diagnose: bool,

    /// How many of the most different pixels to list
    #[arg(long, value_name = "N", default_value_t = 10)]
    worst: usize,

    /// Render on N threads, at most 256; 0 (the default) means one per core
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = threads)]
    threads: usize,

    /// How the reference is computed (with a scene).
    #[command(flatten)]
    how: HowArgs,
}

/// Parses `--allow`, a percentage.
fn percent(text: &str) -> Result<f64, String> {
    match text.trim_end_matches('%').parse::<f64>() {
        Ok(p) if (0.0..=100.0).contains(&p) => Ok(p),
        _ => Err("expected a percentage from 0 to 100, such as 0.5".to_string()),
    }
}

/// The largest file read.
const MAX_FILE: u64 = 256 << 20;

/// A file's bytes, at most `MAX_FILE`.
fn read_file(path: &Path) -> Result<Vec<u8>, Failure> {
    let shown = path.display();
    let cannot = |error: std::io::Error| Failure(format!("error: cannot read {shown}: {error}"), 2);
    if path.is_dir() {
        return Err(Failure(
            format!("error: {shown} is a folder, not a file"),
            2,
        ));
    }
    let mut bytes = Vec::new();
    let file = std::fs::File::open(path).map_err(cannot)?;
    file.take(MAX_FILE + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_FILE {
        let mib = MAX_FILE >> 20;
        return Err(Failure(
            format!("error: {shown} is larger than {mib} MiB"),
            2,
        ));
    }
    Ok(bytes)
}

/// An image file, or exit 2 naming it and what is wrong.
fn read_image(path: &Path, role: &str) -> Result<legacy_rt::Image, Failure> {
    let bytes = read_file(path)?;
    let shown = path.display();
    if content(&bytes) == Content::Text && role == "student's image" {
        let hint = match bytes.first() {
            Some(b'0'..=b'9' | b'-' | b'+' | b'.') => {
                ": it looks like a scene file; the scene comes first, the image second"
            }
            _ => "",
        };
        return Err(Failure(
            format!("error: {shown} (the {role}) is not a PPM or PNG image{hint}"),
            2,
        ));
    }
    compare::read_image(&bytes)
        .map_err(|error| Failure(format!("error: {shown} (the {role}): {error}"), 2))
}

/// Compares; `Ok(true)` when the images match.
pub fn run(args: &CompareArgs) -> Result<bool, Failure> {
    // Every failure of `compare` is exit 2, whatever it would be for rendering.
    run_inner(args).map_err(|Failure(message, _)| Failure(message, 2))
}

fn run_inner(args: &CompareArgs) -> Result<bool, Failure> {
    if let Some(diff) = &args.diff {
        // `--diff mine.ppm` would replace the image being graded with its diff.
        let same = |other: &Path| match (diff.canonicalize(), other.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        };
        if same(&args.student) || same(&args.reference) {
            return Err(Failure(
                format!(
                    "error: --diff {} names a file being compared; give the diff image \
                     another name",
                    diff.display()
                ),
                2,
            ));
        }
    }
    let diff = output_file(args.diff.as_deref())?;
    args.how.check()?;
    let first = read_file(&args.reference)?;
    let student = read_image(&args.student, "student's image")?;
    let settings = Settings {
        tolerance: Tolerance {
            levels: args.tolerance,
            allow: args.allow.unwrap_or(Tolerance::default().allow * 100.0) / 100.0,
        },
        worst: args.worst,
        diagnose: args.diagnose,
    };
    let shown = args.reference.display().to_string();
    let (reference, scene, options) = match content(&first) {
        Content::Text => {
            let text = String::from_utf8_lossy(&first);
            let scene =
                legacy_rt::load(&text).map_err(|error| Failure(format!("{shown}: {error}"), 2))?;
            let given = (Some(student.width as u64), Some(student.height as u64));
            let (w, h) = size(given, &scene)?;
            let options = legacy_rt::Options {
                threads: args.threads,
                ..args.how.options(w, h)?
            };
            let reference = compare::reference(&scene, &options, &student);
            (reference, Some(scene), Some(options))
        }
        _ => {
            if args.diagnose {
                return Err(Failure(
                    "error: --diagnose needs the scene: give the scene file first, not an \
                     image"
                        .to_string(),
                    2,
                ));
            }
            (read_image(&args.reference, "reference image")?, None, None)
        }
    };
    let with_scene = scene.as_ref().zip(options.as_ref());
    let mut report = compare::report(&reference, &student, with_scene, &settings)
        .map_err(|error| Failure(format!("error: {error}"), 2))?;
    if let Some(options) = &options {
        for worst in &mut report.worst {
            worst.trace = Some(trace_command(&args.how, options, &shown, worst.x, worst.y));
        }
    }
    if let Some(diff) = diff {
        let image = compare::diff_image(&reference, &student, args.tolerance)
            .map_err(|error| Failure(format!("error: {error}"), 2))?;
        write_image(&image, diff.format, Some(diff))?;
    }
    let out = match args.json {
        true => {
            let json = serde_json::to_string_pretty(&report)
                .map_err(|error| Failure(format!("error: {error}"), 2))?;
            json + "\n"
        }
        false => text(
            &report,
            &shown,
            &args.student.display().to_string(),
            options.as_ref(),
            &args.how,
        ),
    };
    super::io::emit_to_stdout(out.as_bytes())?;
    Ok(report.verdict == Verdict::Match)
}

/// `path` as a shell word: as it is when it needs no quoting.
fn shell_word(path: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./-+,:=@%".contains(c);
    if !path.is_empty() && path.chars().all(plain) {
        return path.to_string();
    }
    format!("'{}'", path.replace('\'', r"'\''"))
}

/// The options that made the reference, as command-line flags.
fn flags(how: &HowArgs, options: &legacy_rt::Options) -> String {
    let mut flags = String::new();
    if how.max_dist != DEFAULT_MAX_DIST {
        flags += &format!(" --max-dist {}", how.max_dist);
    }
    if how.kernel != KernelChoice::Accurate {
        flags += &format!(" --kernel {}", how.kernel.name());
    }
    if let Some(show) = options.show {
        flags += &format!(" --show {}", show.name());
    } else if options.stage != Stage::Full {
        flags += &format!(" --stage {}", options.stage.name());
    }
    if !how.variant.is_empty() {
        let ids: Vec<_> = how.variant.iter().map(|v| v.id()).collect();
        flags += &format!(" --variant {}", ids.join(","));
    }
    flags
}

/// The `trace` command that explains the reference's pixel (x, y).
fn trace_command(
    how: &HowArgs,
    options: &legacy_rt::Options,
    scene: &str,
    x: usize,
    y: usize,
) -> String {
    let (w, h) = (options.width, options.height);
    let flags = flags(how, options);
    format!(
        "legacy-rt trace {x} {y} {w} {h}{flags} < {}",
        shell_word(scene)
    )
}

/// 1234567 as "1,234,567".
fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// A share (0 to 1) as a percentage with enough decimals to tell small ones apart.
fn percent_of(share: f64) -> String {
    let p = share * 100.0;
    match p {
        _ if p == 0.0 || p >= 10.0 => format!("{p:.0} %"),
        _ if p >= 1.0 => format!("{p:.1} %"),
        _ => format!("{p:.2} %"),
    }
}

/// How many groups the text report lists; `--json` has them all.
const GROUPS_SHOWN: usize = 8;

/// "1 pixel differs", "1,204 pixels differ".
fn pixels_differ(n: usize) -> String {
    match n {
        1 => "1 pixel differs".to_string(),
        n => format!("{} pixels differ", thousands(n)),
    }
}

/// An agreement (0 to 1) in percent, rounded down to two decimals so that only a full
/// agreement shows as 100.00 %.
fn agreement(share: f64) -> String {
    format!("{:.2} %", (share * 10_000.0).floor() / 100.0)
}

/// The plain-text report.
fn text(
    report: &Report,
    reference: &str,
    student: &str,
    options: Option<&legacy_rt::Options>,
    how: &HowArgs,
) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let mut line = |text: String| {
        let _ = writeln!(out, "{text}");
    };
    let (w, h) = (report.width, report.height);
    match options {
        Some(options) => {
            let flags = flags(how, options);
            let how = match flags.is_empty() {
                true => String::new(),
                false => format!(" with{flags}"),
            };
            line(format!("reference: {reference}, rendered at {w}x{h}{how}"));
        }
        None => line(format!("reference: {reference}")),
    }
    line(format!("student:   {student}"));
    line(format!(
        "size: {w}x{h}, {} pixels compared",
        thousands(report.pixels)
    ));
    line(format!(
        "beyond the tolerance of {} levels: {} pixels ({}); {} may be",
        report.tolerance,
        thousands(report.differing_pixels),
        percent_of(report.differing_fraction),
        percent_of(report.allow)
    ));
    line(format!(
        "largest channel difference: {}",
        report.max_channel_difference
    ));
    line(format!(
        "mean absolute error: {:.3} levels per channel",
        report.mean_absolute_error
    ));
    let verdict = match report.verdict {
        Verdict::Match => "match",
        Verdict::Differ => "differ",
    };
    line(format!("verdict: {verdict}"));
    if !report.groups.is_empty() {
        line(String::new());
        line("differing pixels by what the reference ray hits first:".to_string());
        for group in report.groups.iter().take(GROUPS_SHOWN) {
            let name = match group.line {
                Some(at) => format!("{} (line {at})", group.object),
                None => group.object.clone(),
            };
            line(format!(
                "  {name}: {}, {} of the differences",
                pixels_differ(group.pixels),
                percent_of(group.share)
            ));
        }
        let rest = &report.groups[report.groups.len().min(GROUPS_SHOWN)..];
        if !rest.is_empty() {
            let pixels = rest.iter().map(|g| g.pixels).sum();
            let share = rest.iter().map(|g| g.share).sum();
            line(format!(
                "  {} more objects: {}, {} of the differences (--json lists them all)",
                rest.len(),
                pixels_differ(pixels),
                percent_of(share)
            ));
        }
    }
    if !report.worst.is_empty() {
        line(String::new());
        line("worst pixels, (0, 0) at the lower left: reference -> student".to_string());
        for worst in &report.worst {
            let [r, g, b] = worst.reference;
            let [sr, sg, sb] = worst.student;
            let at = format!("({}, {})", worst.x, worst.y);
            let mut text = format!(
                "  {at:<12} {r:3} {g:3} {b:3} -> {sr:3} {sg:3} {sb:3}  (by {:3})",
                worst.difference
            );
            if let Some(trace) = &worst.trace {
                text += &format!("  {trace}");
            }
            line(text);
        }
    }
    if let Some(diagnosis) = &report.diagnosis {
        line(String::new());
        if diagnosis.is_empty() {
            line(
                match report.differing_pixels {
                    0 => "diagnosis: nothing to explain, every pixel is within the tolerance",
                    _ => "diagnosis: no variant explains the differences better than the reference",
                }
                .to_string(),
            );
        } else {
            let before = diagnosis[0].agreement_before;
            line(format!(
                "diagnosis: the reference agrees with {} of the student's pixels; rendered as \
                 if with",
                agreement(before)
            ));
            for found in diagnosis {
                let ids = found.variants.join(",");
                let about: Vec<String> = (found.variants.iter())
                    .filter_map(|id| Variant::parse(id).ok())
                    .map(Variant::describe)
                    .collect();
                line(format!(
                    "  --variant {ids}: {} ({})",
                    agreement(found.agreement_after),
                    about.join("; ")
                ));
            }
        }
    }
    out
}
