//! `legacy-rt grade SCENES SUBMISSIONS -o REPORT`: every student's image of every scene,
//! graded as `compare --diagnose` grades one pair, each reference rendered once and
//! shared, the pairs on all cores; the grades as CSV and JSON, a page to look over, and
//! Gradescope's `results.json`.
//!
//! [`class`] finds the scenes, the students and their files; [`write`] writes the
//! report's files; [`html`] is its page; [`scheme`] reads `--scheme`.

mod class;
mod html;
mod scheme;
mod write;

use super::compare::{Closeness, add_trace_commands, max_pixels, read_image};
use super::{Failure, HowArgs, pixels, threads, usage};
use class::{Class, Pair, Submitted};
use legacy_rt::compare::read::DEFAULT_MAX_PIXELS;
use legacy_rt::compare::{self, Reference, Settings, Verdict};
use legacy_rt::error::escaped;
use legacy_rt::{Options, Scene};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

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

/// One graded pair: a row of grades.csv, and of grades.json with the compare report.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Row {
    /// The student: their folder's name.
    pub student: String,
    /// The scene: its file's name without `.txt`.
    pub scene: String,
    /// match, differ, wrong-size, missing or unreadable.
    pub verdict: String,
    /// Pixels beyond the tolerance (none when nothing was compared).
    pub differing_pixels: Option<usize>,
    /// The ids of the causes compare's report states, in order, joined by commas (as
    /// `--variant` takes them where they are the catalogue's); empty when none.
    pub diagnosis: String,
    /// The points given.
    pub points: f64,
    /// The points the scene is worth.
    pub max_points: f64,
    /// The student image's size.
    pub width: Option<usize>,
    /// See `width`.
    pub height: Option<usize>,
    /// The student's file, under SUBMISSIONS; none when missing.
    pub file: Option<String>,
    /// Why the file could not be graded (unreadable), or what was expected (missing).
    pub message: Option<String>,
    /// What the grader should look at although the pair was graded: other images of the
    /// scene in the folder, not graded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warning: Option<String>,
    /// The diagnosis in words, as compare's report ends (with --diagnose).
    #[serde(deserialize_with = "at_most::<_, 10_000>")]
    pub explanation: Vec<String>,
    /// compare's text report of the pair.
    pub text: Option<String>,
    /// The images under REPORT/: the reference, the student's and the diff.
    pub images: Option<Images>,
    /// `compare --diagnose --json` of the pair, as its text: read back from a part's
    /// grades.json it costs its size, whatever it holds.
    pub compare: Option<Box<serde_json::value::RawValue>>,
}

/// A list of at most `N` items, read lazily: a crafted file's list of millions of empty
/// strings is refused before it takes memory 8 times its size.
fn at_most<'de, D, const N: usize>(deserializer: D) -> Result<Vec<String>, D::Error>
where
    D: serde::Deserializer<'de>,
{
    struct Bounded<const N: usize>;
    impl<'de, const N: usize> serde::de::Visitor<'de> for Bounded<N> {
        type Value = Vec<String>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "a list of at most {N} strings")
        }
        fn visit_seq<A: serde::de::SeqAccess<'de>>(
            self,
            mut seq: A,
        ) -> Result<Vec<String>, A::Error> {
            let mut out = Vec::new();
            while let Some(item) = seq.next_element()? {
                if out.len() == N {
                    return Err(serde::de::Error::custom(format!("more than {N} items")));
                }
                out.push(item);
            }
            Ok(out)
        }
    }
    deserializer.deserialize_seq(Bounded::<N>)
}

/// A pair's images in the report folder, relative to it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Images {
    /// The reference (none for wrong-size: no reference was rendered).
    pub reference: Option<String>,
    /// The student's image.
    pub student: String,
    /// The diff (none for wrong-size).
    pub diff: Option<String>,
}

/// What grades.json holds.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Grades {
    /// The scenes, in order.
    #[serde(deserialize_with = "at_most::<_, 100_000>")]
    pub scenes: Vec<String>,
    /// The students, in order.
    #[serde(deserialize_with = "at_most::<_, 1_000_000>")]
    pub students: Vec<String>,
    /// The options every pair was graded with, as compare's flags.
    pub options: String,
    /// The part graded (`K/N`), when not all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<String>,
    /// Files in SUBMISSIONS that are no scene's image.
    #[serde(deserialize_with = "at_most::<_, 1_000_000>")]
    pub unexpected: Vec<String>,
    /// Every pair, student by student, scene by scene.
    pub rows: Vec<Row>,
}

impl Grades {
    /// Each verdict given and how many pairs got it, in the order first given.
    pub fn verdicts(&self) -> Vec<(&str, usize)> {
        let mut counts: Vec<(&str, usize)> = Vec::new();
        let mut at: HashMap<&str, usize> = HashMap::new();
        for row in &self.rows {
            match at.get(row.verdict.as_str()) {
                Some(&k) => counts[k].1 += 1,
                None => {
                    at.insert(&row.verdict, counts.len());
                    counts.push((&row.verdict, 1));
                }
            }
        }
        counts
    }
}

/// Grades the class, or joins parts with `--merge`.
pub fn run(args: &GradeArgs) -> Result<(), Failure> {
    args.how.check()?;
    // An interrupt removes the report's files being written (`.NAME.PID-N.partial`).
    super::interrupt::remove_partial_file_on_interrupt();
    if args.merge {
        return merge(args);
    }
    let [scenes, submissions] = args.paths.as_slice() else {
        return Err(usage(format!(
            "grade takes two folders, SCENES and SUBMISSIONS (or, with --merge, the parts' \
             reports); {} given",
            args.paths.len()
        )));
    };
    let report = write::Folder::check(&args.output, &[scenes, submissions])?;
    let scheme = match &args.scheme {
        Some(path) => scheme::read(path)?,
        None => scheme::Scheme::default(),
    };
    let class = class::find(scenes, submissions)?;
    scheme.check(&class.scenes)?;
    if args.gradescope.is_some() && class.students.len() != 1 {
        return Err(usage(format!(
            "--gradescope writes one student's results, and {} holds {} students' folders",
            escaped(&submissions.display().to_string()),
            class.students.len()
        )));
    }
    let gradescope = args
        .gradescope
        .as_deref()
        .map(write::check_file)
        .transpose()?;
    let loaded = load_scenes(&class)?;
    report.create()?;
    let mut pairs = class.pairs();
    if let Some((k, n)) = args.shard {
        pairs = pairs.into_iter().skip(k - 1).step_by(n).collect();
    }
    let grader = Grader {
        args,
        class: &class,
        scheme: &scheme,
        scenes: &loaded,
        references: Mutex::new(HashMap::new()),
        folder: &report,
    };
    let rows = grader.grade_all(&pairs)?;
    let grades = Grades {
        scenes: class.scenes.iter().map(|s| s.name.clone()).collect(),
        students: class.students.iter().map(|s| s.name.clone()).collect(),
        options: options_text(args),
        shard: args.shard.map(|(k, n)| format!("{k}/{n}")),
        unexpected: class.unexpected.clone(),
        rows,
    };
    report.write_grades(&grades)?;
    if let Some(file) = gradescope {
        write::gradescope(&grades, &file)?;
    }
    summary(&grades, &args.output);
    Ok(())
}

/// The flags that every pair's `compare` takes, as grades.json records them.
fn options_text(args: &GradeArgs) -> String {
    let mut flags = format!("--diagnose --tolerance {}", args.close.tolerance);
    if let Some(allow) = args.close.allow {
        flags += &format!(" --allow {allow}");
    }
    if let Some(precision) = args.close.precision {
        flags += &format!(" --precision {precision:e}");
    }
    if let Some(&[w, h]) = args.size.as_deref() {
        flags += &format!(" --size {w} {h}");
    }
    flags + &args.how.choices().flags()
}

/// The scenes, loaded; exit 2 naming the first that does not load.
fn load_scenes(class: &Class) -> Result<Vec<Scene>, Failure> {
    class
        .scenes
        .iter()
        .map(|scene| {
            let shown = escaped(&scene.path.display().to_string());
            let file = super::io::open_regular(&scene.path)?;
            let bytes = super::io::read_all(file, &scene.path, super::io::MAX_INPUT)?;
            legacy_rt::load(&super::io::text_of(bytes))
                .map_err(|error| Failure(format!("{shown}: {error}"), 2))
        })
        .collect()
}

/// A reference for one (scene, size), rendered by the first pair that needs it.
type Shared = Arc<OnceLock<Result<(Reference, Options), String>>>;

/// What grading shares between the pairs.
struct Grader<'a> {
    args: &'a GradeArgs,
    class: &'a Class,
    scheme: &'a scheme::Scheme,
    scenes: &'a [Scene],
    references: Mutex<HashMap<(usize, usize, usize), Shared>>,
    folder: &'a write::Folder,
}

impl Grader<'_> {
    /// Every pair, on `--threads` threads, with a progress bar on a terminal; the rows in
    /// the pairs' order.
    fn grade_all(&self, pairs: &[Pair]) -> Result<Vec<Row>, Failure> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.args.threads)
            .build()
            .map_err(|error| Failure(format!("error: cannot start the threads: {error}"), 2))?;
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = indicatif::ProgressBar::new(pairs.len() as u64);
            bar.set_style(
                indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} pairs, {eta} left")
                    .expect("the template is valid"),
            );
            bar
        });
        let rows = pool.install(|| {
            pairs
                .par_iter()
                .map(|pair| {
                    let row = self.grade(pair);
                    if let Some(bar) = &bar {
                        bar.inc(1);
                    }
                    row
                })
                .collect::<Result<Vec<Row>, Failure>>()
        });
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
        rows
    }

    /// One pair's row; its images written under REPORT/images/.
    fn grade(&self, pair: &Pair) -> Result<Row, Failure> {
        let student = &self.class.students[pair.student];
        let scene = &self.class.scenes[pair.scene];
        let plan = self.scheme.scene(&scene.name);
        let settings = Settings {
            tolerance: self.args.close.tolerance(plan.tolerance),
            worst: self.args.worst,
            diagnose: true,
        };
        let mut row = Row {
            student: student.name.clone(),
            scene: scene.name.clone(),
            verdict: String::new(),
            differing_pixels: None,
            diagnosis: String::new(),
            points: 0.0,
            max_points: plan.points,
            width: None,
            height: None,
            file: None,
            message: None,
            warning: None,
            explanation: Vec::new(),
            text: None,
            images: None,
            compare: None,
        };
        let path = match &student.files[pair.scene] {
            Submitted::Missing => {
                row.verdict = "missing".into();
                row.message = Some(format!(
                    "no {0}.ppm or {0}.png in the student's folder",
                    scene.name
                ));
                return Ok(row);
            }
            Submitted::Link(path) => {
                row.verdict = "unreadable".into();
                row.file = Some(path.display().to_string());
                let target = std::fs::read_link(path).map_or(String::new(), |to| {
                    format!(" to {}", escaped(&to.display().to_string()))
                });
                row.message = Some(format!(
                    "{} is a symbolic link{target}, not followed: a student's file must be the \
                     file itself",
                    escaped(&path.display().to_string())
                ));
                return Ok(row);
            }
            Submitted::File(path, others) => {
                if !others.is_empty() {
                    let name = path
                        .file_name()
                        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
                    row.warning = Some(format!(
                        "also handed in: {} (not graded: {name} is, the first of .ppm, .png, .pnm)",
                        others.join(", ")
                    ));
                }
                path
            }
        };
        row.file = Some(path.display().to_string());
        let image = match read_image(path, "student's image", self.args.max_pixels) {
            Ok(image) => image,
            Err(Failure(message, _)) => {
                row.verdict = "unreadable".into();
                row.message = Some(message.trim_start_matches("error: ").to_string());
                return Ok(row);
            }
        };
        (row.width, row.height) = (Some(image.width), Some(image.height));
        let required = plan
            .size
            .or(self.args.size.as_deref().map(|s| [s[0], s[1]]));
        let scene_shown = scene.path.display().to_string();
        let student_shown = escaped(&path.display().to_string());
        let choices = self.args.how.choices();
        let shared;
        let (report, reference) = match required {
            Some([w, h]) if (image.width as u64, image.height as u64) != (w, h) => {
                let expected = (w as usize, h as usize);
                (compare::wrong_size(&image, expected, &settings), None)
            }
            _ => {
                shared = self.reference(pair.scene, image.width, image.height);
                let rendered = shared.get().expect("rendered by `reference`");
                let (reference, options) = rendered.as_ref().map_err(|message| {
                    Failure(format!("error: {}: {message}", escaped(&scene_shown)), 2)
                })?;
                let scene_data = &self.scenes[pair.scene];
                let mut report =
                    compare::report(reference, &image, Some((scene_data, options)), &settings)
                        .map_err(|error| Failure(format!("error: {error}"), 2))?;
                add_trace_commands(&mut report, &choices, options, &scene_shown);
                (report, Some(reference))
            }
        };
        row.verdict = report.verdict.name().into();
        if report.verdict != Verdict::WrongSize {
            row.differing_pixels = Some(report.differing_pixels);
        }
        if report.verdict == Verdict::Match {
            row.points = plan.points;
        }
        let causes = report.causes.iter().flatten();
        row.diagnosis = causes.map(|c| c.id.as_str()).collect::<Vec<_>>().join(",");
        row.explanation = compare::text::diagnosis(&report);
        let text_choices = Some(&choices).filter(|_| reference.is_some());
        let shown = escaped(&scene_shown);
        row.text = Some(compare::text::text(
            &report,
            &shown,
            &student_shown,
            text_choices,
        ));
        row.images = Some(self.folder.pair_images(
            &student.name,
            &scene.name,
            &image,
            reference,
            settings.tolerance.levels,
        )?);
        row.compare = Some(
            serde_json::value::to_raw_value(&report)
                .map_err(|error| Failure(format!("error: {error}"), 2))?,
        );
        Ok(row)
    }

    /// The reference of scene `index` at `width` x `height`, rendered once (by the first
    /// pair that asks; the others wait for it) and shared by every student.
    fn reference(&self, index: usize, width: usize, height: usize) -> Shared {
        let cell = {
            let mut references = self.references.lock().expect("no thread panics holding it");
            Arc::clone(references.entry((index, width, height)).or_default())
        };
        cell.get_or_init(|| {
            let scene = &self.scenes[index];
            let options = self
                .args
                .how
                .options(scene, width as u64, height as u64)
                .map_err(|Failure(message, _)| message)?;
            // One thread: the pool's other threads grade other pairs meanwhile.
            let options = Options {
                threads: 1,
                ..options
            };
            let precision = self.args.close.tolerance(None).precision;
            let reference = compare::reference_at(scene, &options, precision, true);
            if let Err(error) = self
                .folder
                .reference_image(&self.class.scenes[index].name, &reference.image)
            {
                return Err(error.0);
            }
            Ok((reference, options))
        });
        cell
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
        escaped(&folder.join("index.html").display().to_string())
    ));
}

/// `grade --merge PART... -o REPORT`: the parts' grades.json joined, their images copied.
fn merge(args: &GradeArgs) -> Result<(), Failure> {
    let parts: Vec<&PathBuf> = args.paths.iter().collect();
    let report = write::Folder::check(&args.output, &parts)?;
    let read: Vec<Grades> = (args.paths.iter())
        .map(|part| write::read_grades(part))
        .collect::<Result<_, _>>()?;
    report.create()?;
    let mut merged: Option<Grades> = None;
    let mut seen = HashMap::new();
    for (part, grades) in args.paths.iter().zip(read) {
        let shown = escaped(&part.display().to_string());
        let whole = merged.get_or_insert_with(|| Grades {
            rows: Vec::new(),
            shard: None,
            unexpected: Vec::new(),
            ..grades.clone()
        });
        if (&whole.scenes, &whole.students, &whole.options)
            != (&grades.scenes, &grades.students, &grades.options)
        {
            return Err(Failure(
                format!(
                    "error: {shown} is a report of another class, scenes or options than the \
                     first part's: merge the parts of one grading"
                ),
                2,
            ));
        }
        for row in grades.rows {
            let key = (row.student.clone(), row.scene.clone());
            if let Some(first) = seen.insert(key, part.clone()) {
                return Err(Failure(
                    format!(
                        "error: {} and {shown} both grade {}'s {}: give each part once",
                        escaped(&first.display().to_string()),
                        escaped(&row.student),
                        escaped(&row.scene)
                    ),
                    2,
                ));
            }
            let row = report.copy_images(part, row)?;
            whole.rows.push(row);
        }
        for file in grades.unexpected {
            if !whole.unexpected.contains(&file) {
                whole.unexpected.push(file);
            }
        }
    }
    let mut grades = merged.expect("clap requires one path at least");
    let places = |names: &[String]| -> HashMap<String, usize> {
        names
            .iter()
            .enumerate()
            .map(|(k, n)| (n.clone(), k))
            .collect()
    };
    let (students, scenes) = (places(&grades.students), places(&grades.scenes));
    let mut rows = std::mem::take(&mut grades.rows);
    rows.sort_by_key(|row| {
        (
            students.get(&row.student).copied(),
            scenes.get(&row.scene).copied(),
        )
    });
    grades.rows = rows;
    grades.unexpected.sort();
    report.write_grades(&grades)?;
    summary(&grades, &args.output);
    Ok(())
}
