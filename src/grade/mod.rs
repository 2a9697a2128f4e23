//! Grading a class: every student's image of every scene, graded as `compare --diagnose`
//! grades one pair, each reference rendered once and shared, the pairs on all cores; the
//! grades as CSV and JSON, a page to look over, and Gradescope's `results.json`. The
//! command line's `legacy-rt grade` is a thin layer over [`grade`] and [`merge`].
//!
//! `class` finds the scenes, the students and their files; `write` writes the
//! report's files; `html` is its page; `scheme` reads `--scheme`.

mod class;
mod html;
mod scheme;
mod write;

use crate::compare::{self, Reference, Settings, Tolerance, Verdict};
use crate::error::escaped;
use crate::files::{self, FileError, MAX_INPUT};
use crate::image_output::file::Temporary;
use crate::render::Choices;
use crate::{Options, Scene};
use class::{Class, Pair, Submitted};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};
use thiserror::Error;

/// Why a class cannot be graded (or parts merged). None of the messages starts with
/// `error: `, which the command line adds.
#[derive(Debug, Error)]
pub enum GradeError {
    /// The folders or options given do not go together: the command line points at
    /// `--help`.
    #[error("{0}")]
    Usage(String),
    /// A file or folder the user named cannot be read.
    #[error(transparent)]
    File(#[from] FileError),
    /// A scene does not load: its file and the error of spec §2.4.
    #[error("{file}: {error}")]
    Scene {
        /// The scene file, escaped.
        file: String,
        /// Why it does not load (boxed: it holds the line).
        error: Box<crate::SceneError>,
    },
    /// Anything else that stops the grading: the report folder, a scheme, a part.
    #[error("{0}")]
    Failed(String),
}

/// How close each student's image must be: `--tolerance`, `--allow` (a percentage) and
/// `--precision`, each `None` where not given.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Closeness {
    /// The largest per-channel difference that counts as equal, in byte levels.
    pub levels: Option<u8>,
    /// The share of pixels, in percent, that may differ on pixels the reference is sure of.
    pub allow: Option<f64>,
    /// The arithmetic a correct tracer is granted, as a relative precision.
    pub precision: Option<f64>,
}

impl Closeness {
    /// The tolerance, with a scene's `levels` (a scheme's) before the given ones.
    pub fn tolerance(&self, levels: Option<u8>) -> Tolerance {
        let default = Tolerance::default();
        Tolerance {
            levels: levels.or(self.levels).unwrap_or(default.levels),
            allow: self.allow.unwrap_or(default.allow * 100.0) / 100.0,
            precision: self.precision.unwrap_or(default.precision),
        }
    }
}

/// What every pair is graded with: `grade`'s options.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// How close each image must be.
    pub closeness: Closeness,
    /// The size every image must have (another is wrong-size); `None` renders each
    /// reference at its student image's size.
    pub size: Option<[u64; 2]>,
    /// How the references are computed.
    pub choices: Choices,
    /// Pairs graded at a time; 0 for one per core.
    pub threads: usize,
    /// How many of the most different pixels each pair's report lists.
    pub worst: usize,
    /// The most pixels a student's image may have.
    pub max_pixels: u64,
    /// Only the K-th of N parts of the pairs (K from 1).
    pub shard: Option<(usize, usize)>,
}

/// What grading tells its caller as it goes.
pub struct Hooks<'a> {
    /// Hears of each temporary file the report is written through (the command line
    /// removes them on an interrupt).
    pub temporary: fn(&Path, Temporary),
    /// Hears how many pairs there are, then of each one graded.
    pub progress: &'a (dyn Fn(Progress) + Sync),
}

/// How far the grading is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress {
    /// This many pairs are to be graded.
    Pairs(usize),
    /// One more pair is graded.
    Graded,
    /// Every pair is graded.
    Done,
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

/// Grades every student of SUBMISSIONS on every scene of SCENES into the report folder
/// `report` (grades.csv, grades.json, index.html, images/), with the points of `scheme`
/// (a TOML file) and, for one student, Gradescope's results.json at `gradescope`.
pub fn grade(
    [scenes, submissions]: [&Path; 2],
    report_folder: &Path,
    scheme: Option<&Path>,
    gradescope: Option<&Path>,
    plan: &Plan,
    hooks: &Hooks,
) -> Result<Grades, GradeError> {
    let report = write::Folder::check(report_folder, &[scenes, submissions], hooks.temporary)?;
    let scheme = match scheme {
        Some(path) => scheme::read(path)?,
        None => scheme::Scheme::default(),
    };
    let class = class::find(scenes, submissions)?;
    scheme.check(&class.scenes)?;
    if gradescope.is_some() && class.students.len() != 1 {
        return Err(GradeError::Usage(format!(
            "--gradescope writes one student's results, and {} holds {} students' folders",
            files::shown(submissions),
            class.students.len()
        )));
    }
    let gradescope = gradescope.map(write::check_file).transpose()?;
    let loaded = load_scenes(&class)?;
    // The choices apply to every scene (a variant scoped to a line each has a record on)
    // before the report folder is made: a refusal leaves nothing behind.
    for (file, scene) in class.scenes.iter().zip(&loaded) {
        let shown = files::shown(&file.path);
        (plan.choices.options(scene, 2, 2))
            .map_err(|error| GradeError::Failed(format!("{shown}: {error}")))?;
    }
    report.create()?;
    let mut pairs = class.pairs();
    if let Some((k, n)) = plan.shard {
        pairs = pairs.into_iter().skip(k - 1).step_by(n).collect();
    }
    let grader = Grader {
        plan,
        class: &class,
        scheme: &scheme,
        scenes: &loaded,
        references: Mutex::new(HashMap::new()),
        folder: &report,
    };
    let rows = grader.grade_all(&pairs, hooks.progress)?;
    let grades = Grades {
        scenes: class.scenes.iter().map(|s| s.name.clone()).collect(),
        students: class.students.iter().map(|s| s.name.clone()).collect(),
        options: options_text(plan),
        shard: plan.shard.map(|(k, n)| format!("{k}/{n}")),
        unexpected: class.unexpected.clone(),
        rows,
    };
    report.write_grades(&grades)?;
    if let Some(file) = gradescope {
        write::gradescope(&grades, &file, hooks.temporary)?;
    }
    Ok(grades)
}

/// The flags that every pair's `compare` takes, as grades.json records them.
fn options_text(plan: &Plan) -> String {
    let close = &plan.closeness;
    let levels = close.levels.unwrap_or(Tolerance::default().levels);
    let mut flags = format!("--diagnose --tolerance {levels}");
    if let Some(allow) = close.allow {
        flags += &format!(" --allow {allow}");
    }
    if let Some(precision) = close.precision {
        flags += &format!(" --precision {precision:e}");
    }
    if let Some([w, h]) = plan.size {
        flags += &format!(" --size {w} {h}");
    }
    flags + &plan.choices.flags()
}

/// The scenes, loaded; an error naming the first that does not load.
fn load_scenes(class: &Class) -> Result<Vec<Scene>, GradeError> {
    class
        .scenes
        .iter()
        .map(|scene| {
            let bytes = files::read_file(&scene.path, MAX_INPUT)?;
            crate::load(&files::text_of(bytes)).map_err(|error| GradeError::Scene {
                file: files::shown(&scene.path),
                error: Box::new(error),
            })
        })
        .collect()
}

/// A reference for one (scene, size), rendered by the first pair that needs it.
type Shared = Arc<OnceLock<Result<(Reference, Options), String>>>;

/// What grading shares between the pairs.
struct Grader<'a> {
    plan: &'a Plan,
    class: &'a Class,
    scheme: &'a scheme::Scheme,
    scenes: &'a [Scene],
    references: Mutex<HashMap<(usize, usize, usize), Shared>>,
    folder: &'a write::Folder,
}

impl Grader<'_> {
    /// Every pair, on the plan's threads, `progress` told of each; the rows in the pairs'
    /// order.
    fn grade_all(
        &self,
        pairs: &[Pair],
        progress: &(dyn Fn(Progress) + Sync),
    ) -> Result<Vec<Row>, GradeError> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.plan.threads)
            .build()
            .map_err(|error| GradeError::Failed(format!("cannot start the threads: {error}")))?;
        progress(Progress::Pairs(pairs.len()));
        let rows = pool.install(|| {
            pairs
                .par_iter()
                .map(|pair| {
                    let row = self.grade(pair);
                    progress(Progress::Graded);
                    row
                })
                .collect::<Result<Vec<Row>, GradeError>>()
        });
        progress(Progress::Done);
        rows
    }

    /// One pair's row; its images written under REPORT/images/.
    fn grade(&self, pair: &Pair) -> Result<Row, GradeError> {
        let student = &self.class.students[pair.student];
        let scene = &self.class.scenes[pair.scene];
        let plan = self.scheme.scene(&scene.name);
        let settings = Settings {
            tolerance: self.plan.closeness.tolerance(plan.tolerance),
            worst: self.plan.worst,
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
                let target = std::fs::read_link(path)
                    .map_or(String::new(), |to| format!(" to {}", files::shown(&to)));
                row.message = Some(format!(
                    "{} is a symbolic link{target}, not followed: a student's file must be the \
                     file itself",
                    files::shown(path)
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
        let image = match files::read_image(path, "student's image", self.plan.max_pixels) {
            Ok(image) => image,
            Err(error) => {
                row.verdict = "unreadable".into();
                row.message = Some(error.to_string());
                return Ok(row);
            }
        };
        (row.width, row.height) = (Some(image.width), Some(image.height));
        let required = plan.size.or(self.plan.size);
        let scene_shown = scene.path.display().to_string();
        let student_shown = files::shown(path);
        let choices = &self.plan.choices;
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
                    GradeError::Failed(format!("{}: {message}", escaped(&scene_shown)))
                })?;
                let scene_data = &self.scenes[pair.scene];
                let mut report =
                    compare::report(reference, &image, Some((scene_data, options)), &settings)
                        .map_err(|error| GradeError::Failed(error.to_string()))?;
                report.add_trace_commands(|x, y, under| {
                    compare::text::trace_command(choices, options, &scene_shown, x, y, under)
                });
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
        let text_choices = Some(choices).filter(|_| reference.is_some());
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
                .map_err(|error| GradeError::Failed(format!("{error}")))?,
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
            let options = (self.plan.choices.options(scene, width, height))
                .map_err(|error| error.to_string())?;
            // One thread: the pool's other threads grade other pairs meanwhile.
            let options = Options {
                threads: 1,
                ..options
            };
            let precision = self.plan.closeness.tolerance(None).precision;
            let reference = compare::reference_at(scene, &options, precision, true);
            if let Err(error) = self
                .folder
                .reference_image(&self.class.scenes[index].name, &reference.image)
            {
                return Err(error.to_string());
            }
            Ok((reference, options))
        });
        cell
    }
}

/// `grade --merge PART... -o REPORT`: the parts' grades.json joined into the report
/// folder `report_folder`, their images copied.
pub fn merge(paths: &[PathBuf], report_folder: &Path, hooks: &Hooks) -> Result<Grades, GradeError> {
    let parts: Vec<&Path> = paths.iter().map(PathBuf::as_path).collect();
    let report = write::Folder::check(report_folder, &parts, hooks.temporary)?;
    let read: Vec<Grades> = (paths.iter())
        .map(|part| write::read_grades(part))
        .collect::<Result<_, _>>()?;
    report.create()?;
    let mut merged: Option<Grades> = None;
    let mut seen = HashMap::new();
    for (part, grades) in paths.iter().zip(read) {
        let shown = files::shown(part);
        let whole = merged.get_or_insert_with(|| Grades {
            rows: Vec::new(),
            shard: None,
            unexpected: Vec::new(),
            ..grades.clone()
        });
        if (&whole.scenes, &whole.students, &whole.options)
            != (&grades.scenes, &grades.students, &grades.options)
        {
            return Err(GradeError::Failed(format!(
                "{shown} is a report of another class, scenes or options than the \
                     first part's: merge the parts of one grading"
            )));
        }
        for row in grades.rows {
            let key = (row.student.clone(), row.scene.clone());
            if let Some(first) = seen.insert(key, part.clone()) {
                return Err(GradeError::Failed(format!(
                    "{} and {shown} both grade {}'s {}: give each part once",
                    files::shown(&first),
                    escaped(&row.student),
                    escaped(&row.scene)
                )));
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
    let Some(mut grades) = merged else {
        return Err(GradeError::Usage(
            "--merge takes the parts' report folders".into(),
        ));
    };
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
    Ok(grades)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The library's grading without the command line: a class of one student who
    /// handed in the reference of one scene and another scene's image with one channel
    /// off, graded with the progress told pair by pair and the files written through the
    /// hook.
    #[test]
    fn a_class_is_graded_through_the_library_with_its_hooks_told() {
        let dir = std::env::temp_dir().join(format!("legacy-rt-grade-lib-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let (scenes, student) = (dir.join("scenes"), dir.join("subs/ada"));
        std::fs::create_dir_all(&scenes).unwrap();
        std::fs::create_dir_all(&student).unwrap();
        for (name, off) in [("mirrors", false), ("planes", true)] {
            let text = std::fs::read_to_string(format!("examples/{name}.txt")).unwrap();
            std::fs::write(scenes.join(format!("{name}.txt")), &text).unwrap();
            let scene = crate::load(&text).unwrap();
            let mut image = crate::render(&scene, &Options::new(40, 30), |_| {});
            if off {
                image.pixels[0][0] = image.pixels[0][0].wrapping_add(9);
            }
            let ppm = crate::image_output::ppm(&image);
            std::fs::write(student.join(format!("{name}.ppm")), ppm).unwrap();
        }
        let (pairs, graded, done) = (
            AtomicUsize::new(0),
            AtomicUsize::new(0),
            AtomicUsize::new(0),
        );
        let progress = |step: Progress| match step {
            Progress::Pairs(n) => pairs.store(n, Ordering::SeqCst),
            Progress::Graded => _ = graded.fetch_add(1, Ordering::SeqCst),
            Progress::Done => _ = done.fetch_add(1, Ordering::SeqCst),
        };
        let hooks = Hooks {
            temporary: |_, _| {},
            progress: &progress,
        };
        let plan = Plan {
            closeness: Closeness::default(),
            size: None,
            choices: Choices::default(),
            threads: 1,
            worst: 3,
            max_pixels: 1 << 20,
            shard: None,
        };
        let report = dir.join("report");
        let grades = grade(
            [&scenes, &dir.join("subs")],
            &report,
            None,
            None,
            &plan,
            &hooks,
        )
        .unwrap();
        let verdicts: Vec<(&str, &str)> = (grades.rows.iter())
            .map(|r| (r.scene.as_str(), r.verdict.as_str()))
            .collect();
        assert_eq!(verdicts, [("mirrors", "match"), ("planes", "differ")]);
        assert_eq!(grades.rows[1].differing_pixels, Some(1));
        assert_eq!(grades.rows[0].points, 1.0);
        assert_eq!(grades.rows[1].points, 0.0);
        assert_eq!(
            [&pairs, &graded, &done].map(|n| n.load(Ordering::SeqCst)),
            [2, 2, 1]
        );
        assert!(report.join("grades.csv").is_file() && report.join("index.html").is_file());
        // Grading again into a folder that is not a report is refused, typed.
        let refused = grade(
            [&scenes, &dir.join("subs")],
            &scenes,
            None,
            None,
            &plan,
            &hooks,
        );
        assert!(matches!(refused, Err(GradeError::Failed(_))), "{refused:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
