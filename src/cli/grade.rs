//! `legacy-rt grade SCENES SUBMISSIONS -o REPORT`: the command line of
//! [`legacy_rt::grade`], which grades every student's image of every scene as
//! `compare --diagnose` grades one pair; here are its flags, its progress bar, its
//! clean-up on an interrupt and its summary line.

use super::{Closeness, Failure, HowArgs, max_pixels, pixels, threads};
use legacy_rt::compare::read::DEFAULT_MAX_PIXELS;
use legacy_rt::error::escaped;
use legacy_rt::files;
use legacy_rt::grade::{self, Grades, Hooks, Plan, Progress};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Examples for `grade --help`.
pub const EXAMPLES: &str = "\
Examples:
  legacy-rt grade scenes/ submissions/ -o report/         every student, every scene
  legacy-rt grade --size 640 480 scenes/ submissions/ -o report/   other sizes: wrong-size
  legacy-rt grade --scheme points.toml scenes/ submissions/ -o report/
  legacy-rt grade --gradescope /autograder/results/results.json \\
      scenes/ /autograder/submission/ -o report/                  one student, Gradescope
  legacy-rt grade --shard 2/4 scenes/ submissions/ -o part2/      a quarter of the pairs
  legacy-rt grade --merge part1/ part2/ part3/ part4/ -o report/  the parts joined

SCENES holds the scene files, NAME.txt. SUBMISSIONS holds a folder per student, each with
NAME.ppm or NAME.png for every scene NAME; image files directly in SUBMISSIONS are one
student's (as an autograder runs it). Each (student, scene) pair is graded as
`legacy-rt compare --diagnose SCENES/NAME.txt STUDENT/NAME.ppm` grades it, with the same
options; its verdict is match, differ, wrong-size (with --size or a scheme's size),
missing or unreadable. Each reference (scene, size, options) is rendered once.

REPORT/ gets grades.csv (student, scene, verdict, differing_pixels, diagnosis, points,
max_points, width, height, file, message, warning), grades.json (the same and each pair's compare
report), index.html (a page that works offline: the class's table and, per pair, the
reference, the student's image and the diff with the diagnosis) and images/. REPORT must
be a new or empty folder, or an earlier report (its files are replaced).

Points (--scheme FILE, TOML; docs/grade.md):
  [scenes.spec1]
  points = 2            # default 1, all or nothing on the verdict
  size = [640, 480]     # optional: another size is wrong-size
  tolerance = 1         # optional: --tolerance for this scene

Exit status: 0 when the class was graded, whatever the verdicts; 2 when SCENES or
SUBMISSIONS cannot be read, a scene does not load (the message names it), or an option is
wrong.";

/// `grade`'s arguments.
#[derive(clap::Args, Debug)]
pub struct GradeArgs {
    /// SCENES (a folder of NAME.txt) and SUBMISSIONS (a folder per student, or one
    /// student's images); with --merge, the REPORT folders of the parts
    #[arg(value_name = "SCENES SUBMISSIONS", required = true)]
    paths: Vec<PathBuf>,

    /// The folder to write the report to: grades.csv, grades.json, index.html, images/
    #[arg(short, long, value_name = "REPORT")]
    output: PathBuf,

    /// How close each student's image must be.
    #[command(flatten)]
    close: Closeness,

    /// The size every student's image must have: another size is verdict wrong-size
    /// (without it, each reference is rendered at the student image's size)
    #[arg(long, value_names = ["W", "H"], num_args = 2, value_parser = pixels)]
    size: Option<Vec<u64>>,

    /// Points, sizes and tolerances per scene (TOML; see below and docs/grade.md)
    #[arg(long, value_name = "FILE")]
    scheme: Option<PathBuf>,

    /// Also write Gradescope's results.json to FILE (one student's SUBMISSIONS)
    #[arg(long, value_name = "FILE")]
    gradescope: Option<PathBuf>,

    /// Grade only the K-th of N parts of the pairs (K from 1), the same parts on every
    /// machine; `grade --merge` joins the parts' reports
    #[arg(long, value_name = "K/N", value_parser = shard)]
    shard: Option<(usize, usize)>,

    /// Join the reports of the parts (their REPORT folders, given instead of SCENES and
    /// SUBMISSIONS) into one
    #[arg(long)]
    merge: bool,

    /// Grade N pairs at a time, at most 256; 0 (the default) means one per core
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = threads)]
    threads: usize,

    /// How many of the most different pixels each pair's report lists
    #[arg(long, value_name = "N", default_value_t = 10)]
    worst: usize,

    /// The most pixels a student's image may have [default: 16777216, 4096x4096]
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_PIXELS, value_parser = max_pixels, hide_default_value = true)]
    max_pixels: u64,

    /// How the references are computed.
    #[command(flatten)]
    how: HowArgs,
}

/// Parses `--shard K/N`.
fn shard(text: &str) -> Result<(usize, usize), String> {
    let parsed = text
        .split_once('/')
        .and_then(|(k, n)| Some((k.trim().parse().ok()?, n.trim().parse().ok()?)));
    match parsed {
        Some((k, n)) if 1 <= k && k <= n => Ok((k, n)),
        _ => Err("expected K/N with 1 <= K <= N, such as 2/4".to_string()),
    }
}

/// Grades the class, or joins parts with `--merge`.
pub fn run(args: &GradeArgs) -> Result<(), Failure> {
    args.how.check()?;
    // An interrupt removes the report's files being written (`.NAME.PID-N.partial`).
    super::interrupt::remove_partial_file_on_interrupt();
    let bar: Mutex<Option<indicatif::ProgressBar>> = Mutex::new(None);
    let progress = |step: Progress| {
        let Ok(mut bar) = bar.lock() else { return };
        match step {
            Progress::Pairs(count) if std::io::stderr().is_terminal() => {
                let shown = indicatif::ProgressBar::new(count as u64);
                shown.set_style(
                    indicatif::ProgressStyle::with_template(
                        "{bar:40} {pos}/{len} pairs, {eta} left",
                    )
                    .expect("the template is valid"),
                );
                *bar = Some(shown);
            }
            Progress::Graded => bar.iter().for_each(|shown| shown.inc(1)),
            Progress::Done => bar.take().iter().for_each(|shown| shown.finish_and_clear()),
            Progress::Pairs(_) => {}
        }
    };
    let hooks = Hooks {
        temporary: super::interrupt::partial_file,
        progress: &progress,
    };
    let grades = match args.paths.as_slice() {
        parts if args.merge => grade::merge(parts, &args.output, &hooks)?,
        [scenes, submissions] => grade::grade(
            [scenes, submissions],
            &args.output,
            args.scheme.as_deref(),
            args.gradescope.as_deref(),
            &plan(args),
            &hooks,
        )?,
        paths => {
            return Err(Failure::usage(format!(
                "grade takes two folders, SCENES and SUBMISSIONS (or, with --merge, the \
                 parts' reports); {} given",
                paths.len()
            )));
        }
    };
    summary(&grades, &args.output);
    Ok(())
}

/// What the flags ask of every pair.
fn plan(args: &GradeArgs) -> Plan {
    Plan {
        closeness: args.close.closeness(),
        size: args.size.as_deref().map(|s| [s[0], s[1]]),
        choices: args.how.choices(),
        threads: args.threads,
        worst: args.worst,
        max_pixels: args.max_pixels,
        shard: args.shard,
    }
}

/// The verdicts' counts on standard error, and where the report is.
fn summary(grades: &Grades, folder: &Path) {
    // A part's verdicts are its file's words: escaped, so that a crafted one cannot act on
    // the terminal.
    let counts: Vec<String> = (grades.verdicts().iter())
        .map(|(v, n)| format!("{n} {}", escaped(v)))
        .collect();
    super::say(&format!(
        "graded {} pairs ({} students x {} scenes{}): {}; report in {}",
        grades.rows.len(),
        grades.students.len(),
        grades.scenes.len(),
        grades
            .shard
            .as_ref()
            .map(|s| format!(", part {s}"))
            .unwrap_or_default(),
        counts.join(", "),
        files::shown(&folder.join("index.html"))
    ));
}
