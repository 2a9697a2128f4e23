//! The report folder and its files: each written whole (to a new hidden file beside it,
//! then renamed over), so that a failure leaves no half file and a symbolic or hard link
//! planted in the folder is replaced, not written through.

use super::{GradeError, Grades, Images, Row, html};
use crate::compare::{self, Reference};
use crate::error::escaped;
use crate::files;
use crate::files::{MAX_INPUT, read_file};
use crate::image_output::file::Temporary;
use crate::{Image, image_output};
use std::collections::HashSet;
use std::fs;
use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;

/// The largest side of the report's small images; larger images are scaled down.
const THUMBNAIL: (u32, u32) = (240, 180);

/// The report folder, checked before anything is graded.
pub struct Folder {
    root: PathBuf,
    /// Images already copied by `--merge` (a reference is shared by many rows).
    copied: Mutex<HashSet<String>>,
    /// Hears of each temporary file written.
    temporary: fn(&Path, Temporary),
}

/// A failure to write under the report folder.
fn cannot_write(path: &Path, error: impl std::fmt::Display) -> GradeError {
    GradeError::Failed(format!("cannot write {}: {error}", files::shown(path)))
}

/// Writes `bytes` to `path` whole ([`image_output::file::replace`]), `temporary` told of
/// the temporary file it goes through.
fn put(path: &Path, bytes: &[u8], temporary: fn(&Path, Temporary)) -> Result<(), GradeError> {
    image_output::file::replace(path, bytes, temporary).map_err(|error| cannot_write(path, error))
}

/// `path` made absolute and resolved as far as it exists.
fn resolved(path: &Path) -> PathBuf {
    if let Ok(path) = fs::canonicalize(path) {
        return path;
    }
    match (path.parent(), path.file_name()) {
        (Some(parent), Some(name)) => {
            let parent = match parent.as_os_str().is_empty() {
                true => Path::new("."),
                false => parent,
            };
            resolved(parent).join(name)
        }
        _ => path.to_path_buf(),
    }
}

/// A name as one safe path component: letters, digits, `-` and `_` as they are, every
/// other byte as `~XX`, so that two names never share a file and none climbs out.
fn component(name: &str) -> String {
    let mut out = String::new();
    for byte in name.bytes() {
        match byte {
            b'a'..=b'z' | b'A'..=b'Z' | b'0'..=b'9' | b'-' | b'_' => out.push(byte as char),
            _ => out.push_str(&format!("~{byte:02X}")),
        }
    }
    out
}

/// The image as a PNG no larger than [`THUMBNAIL`].
fn thumbnail(image: &Image) -> Result<Vec<u8>, String> {
    let (w, h) = (image.width as u32, image.height as u32);
    let scale = f64::min(
        1.0,
        f64::min(
            f64::from(THUMBNAIL.0) / f64::from(w),
            f64::from(THUMBNAIL.1) / f64::from(h),
        ),
    );
    let small = match scale < 1.0 {
        true => {
            let flat: Vec<u8> = image.pixels.iter().flatten().copied().collect();
            let full = image::RgbImage::from_raw(w, h, flat).ok_or("the image's size")?;
            let (tw, th) = (
                ((f64::from(w) * scale) as u32).max(1),
                ((f64::from(h) * scale) as u32).max(1),
            );
            let small = image::imageops::thumbnail(&full, tw, th);
            Image {
                width: tw as usize,
                height: th as usize,
                pixels: small.pixels().map(|p| p.0).collect(),
            }
        }
        false => image.clone(),
    };
    image_output::png(&small).map_err(|error| error.to_string())
}

/// Fails unless `path` can be written as a file: the Gradescope file's path, checked
/// before grading.
pub fn check_file(path: &Path) -> Result<PathBuf, GradeError> {
    let shown = files::shown(path);
    if path.is_dir() {
        return Err(GradeError::Failed(format!(
            "{shown} is a folder, not a file"
        )));
    }
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    if parent.is_some_and(|p| !p.is_dir()) {
        return Err(GradeError::Failed(format!(
            "cannot write {shown}: its folder does not exist"
        )));
    }
    Ok(path.to_path_buf())
}

impl Folder {
    /// Checks the report folder `root`: new, empty, or an earlier report
    /// (it holds grades.json), and neither inside nor around the folders read (`inputs`),
    /// whose files it would otherwise be graded with or write over.
    pub fn check(
        root: &Path,
        inputs: &[&Path],
        temporary: fn(&Path, Temporary),
    ) -> Result<Folder, GradeError> {
        let shown = files::shown(root);
        let refuse = |why: String| GradeError::Failed(format!("-o {shown}: {why}"));
        let at = resolved(root);
        for input in inputs {
            let input_at = resolved(input);
            if at.starts_with(&input_at) || input_at.starts_with(&at) {
                return Err(refuse(format!(
                    "the report folder must be outside {} and not hold it",
                    files::shown(input)
                )));
            }
        }
        match fs::metadata(root) {
            Ok(m) if !m.is_dir() => return Err(refuse("it is not a folder".into())),
            Ok(_) => {
                let empty = fs::read_dir(root)
                    .map_err(|error| refuse(error.to_string()))?
                    .next()
                    .is_none();
                if !empty && !root.join("grades.json").is_file() {
                    return Err(refuse(
                        "it holds files and no grades.json of an earlier report; give a new \
                         or empty folder"
                            .into(),
                    ));
                }
            }
            Err(_) => {}
        }
        Ok(Folder {
            root: root.to_path_buf(),
            copied: Mutex::new(HashSet::new()),
            temporary,
        })
    }

    /// Creates the folder and its images/, once what is graded has been read: a run
    /// that fails before leaves nothing behind.
    pub fn create(&self) -> Result<(), GradeError> {
        let images = self.root.join("images");
        fs::create_dir_all(&images).map_err(|error| cannot_write(&images, error))
    }

    /// The reference's image path under the folder, for scene `name` at its size.
    fn reference_path(name: &str, width: usize, height: usize) -> String {
        format!("images/reference/{}-{width}x{height}.png", component(name))
    }

    /// Writes the small image of the reference of scene `name`.
    pub fn reference_image(&self, name: &str, image: &Image) -> Result<(), GradeError> {
        let relative = Self::reference_path(name, image.width, image.height);
        self.put_image(&relative, image)
    }

    fn put_image(&self, relative: &str, image: &Image) -> Result<(), GradeError> {
        let path = self.root.join(relative);
        if let Some(parent) = path.parent() {
            fs::create_dir_all(parent).map_err(|error| cannot_write(parent, error))?;
        }
        let png = thumbnail(image).map_err(|error| cannot_write(&path, error))?;
        put(&path, &png, self.temporary)
    }

    /// Writes a pair's small images, the student's and (with a reference) the diff, and
    /// says where they and the reference's are.
    pub fn pair_images(
        &self,
        student: &str,
        scene: &str,
        image: &Image,
        reference: Option<&Reference>,
        levels: u8,
    ) -> Result<Images, GradeError> {
        let folder = format!("images/{}", component(student));
        let own = format!("{folder}/{}.png", component(scene));
        self.put_image(&own, image)?;
        let mut images = Images {
            reference: None,
            student: own,
            diff: None,
        };
        if let Some(reference) = reference {
            let diff = format!("{folder}/{}-diff.png", component(scene));
            let drawn = compare::diff_image(reference, image, levels)
                .map_err(|error| GradeError::Failed(format!("{error}")))?;
            self.put_image(&diff, &drawn)?;
            images.diff = Some(diff);
            let (w, h) = (reference.image.width, reference.image.height);
            images.reference = Some(Self::reference_path(scene, w, h));
        }
        Ok(images)
    }

    /// grades.csv, grades.json and index.html.
    pub fn write_grades(&self, grades: &Grades) -> Result<(), GradeError> {
        let csv_path = self.root.join("grades.csv");
        let table = csv(grades).map_err(|e| cannot_write(&csv_path, e))?;
        put(&csv_path, &table, self.temporary)?;
        let json_path = self.root.join("grades.json");
        let json = serde_json::to_vec_pretty(grades).map_err(|e| cannot_write(&json_path, e))?;
        put(&json_path, &json, self.temporary)?;
        let page = html::page(grades);
        put(
            &self.root.join("index.html"),
            page.as_bytes(),
            self.temporary,
        )
    }

    /// A part's row with its images copied from the part's folder `part` into this one.
    pub fn copy_images(&self, part: &Path, row: Row) -> Result<Row, GradeError> {
        let Some(images) = &row.images else {
            return Ok(row);
        };
        let paths = [
            Some(&images.student),
            images.reference.as_ref(),
            images.diff.as_ref(),
        ];
        for relative in paths.into_iter().flatten() {
            let inside = Path::new(relative)
                .components()
                .all(|c| matches!(c, Component::Normal(_)));
            if !inside || !relative.starts_with("images/") {
                return Err(GradeError::Failed(format!(
                    "{} names an image outside its images/: {}",
                    files::shown(&part.join("grades.json")),
                    escaped(relative)
                )));
            }
            if !self
                .copied
                .lock()
                .expect("not poisoned")
                .insert(relative.clone())
            {
                continue;
            }
            let from = within(part, relative)?;
            let bytes = read_file(&from, MAX_INPUT)?;
            let to = self.root.join(relative);
            if let Some(parent) = to.parent() {
                fs::create_dir_all(parent).map_err(|error| cannot_write(parent, error))?;
            }
            put(&to, &bytes, self.temporary)?;
        }
        Ok(row)
    }
}

/// A text cell of grades.csv as a spreadsheet may show it: control characters escaped
/// (`\u{1b}`), and a cell that a spreadsheet would take for a formula (starting `=`, `+`,
/// `-`, `@`, a tab or a carriage return: a student's folder named `=HYPERLINK(...)`)
/// prefixed with `'`, as OWASP advises against CSV injection.
fn cell(text: &str) -> String {
    let shown = escaped(text);
    match text.starts_with(['=', '+', '-', '@', '\t', '\r']) {
        true => format!("'{shown}"),
        false => shown,
    }
}

/// grades.csv: a row per pair.
fn csv(grades: &Grades) -> Result<Vec<u8>, csv::Error> {
    let mut out = csv::Writer::from_writer(Vec::new());
    out.write_record([
        "student",
        "scene",
        "verdict",
        "differing_pixels",
        "diagnosis",
        "points",
        "max_points",
        "width",
        "height",
        "file",
        "message",
        "warning",
    ])?;
    let or_empty = |n: Option<usize>| n.map(|n| n.to_string()).unwrap_or_default();
    let text = |t: Option<&str>| cell(t.unwrap_or_default());
    for row in &grades.rows {
        out.write_record([
            cell(&row.student),
            cell(&row.scene),
            cell(&row.verdict),
            or_empty(row.differing_pixels),
            cell(&row.diagnosis),
            row.points.to_string(),
            row.max_points.to_string(),
            or_empty(row.width),
            or_empty(row.height),
            text(row.file.as_deref()),
            text(row.message.as_deref()),
            text(row.warning.as_deref()),
        ])?;
    }
    out.into_inner().map_err(|error| error.into_error().into())
}

/// `relative` under the part's folder `part`, where no component below the part is a
/// symbolic link: a part's files are read as themselves, never through a link out of
/// the part (an `images` linked to /etc would copy its files into the report).
fn within(part: &Path, relative: &str) -> Result<PathBuf, GradeError> {
    let mut path = part.to_path_buf();
    for component in Path::new(relative).components() {
        path.push(component);
        if fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_symlink()) {
            return Err(GradeError::Failed(format!(
                "{} is a symbolic link: a part's report is read only from its own \
                     files, never through a link",
                files::shown(&path)
            )));
        }
    }
    Ok(path)
}

/// A part's grades.json.
pub fn read_grades(part: &Path) -> Result<Grades, GradeError> {
    let path = within(part, "grades.json")?;
    let bytes = read_file(&path, MAX_INPUT)?;
    serde_json::from_slice(&bytes).map_err(|error| {
        GradeError::Failed(format!(
            "{} is not a report of legacy-rt grade: {error}",
            files::shown(&path)
        ))
    })
}

/// Gradescope's results.json for the one student of `grades`: a test per scene.
pub fn gradescope(
    grades: &Grades,
    path: &Path,
    temporary: fn(&Path, Temporary),
) -> Result<(), GradeError> {
    let tests: Vec<serde_json::Value> = grades
        .rows
        .iter()
        .map(|row| {
            let output = match (&row.text, &row.message) {
                (Some(text), _) => text.clone(),
                (None, Some(message)) => format!("{}: {message}\n", row.verdict),
                (None, None) => format!("{}\n", row.verdict),
            };
            serde_json::json!({
                "name": row.scene,
                "score": row.points,
                "max_score": row.max_points,
                "status": if row.verdict == "match" { "passed" } else { "failed" },
                "output": output,
            })
        })
        .collect();
    let score: f64 = grades.rows.iter().map(|row| row.points).sum();
    let results = serde_json::json!({
        "score": score,
        "output": format!("graded by legacy-rt grade {}", grades.options),
        "tests": tests,
    });
    let bytes = serde_json::to_vec_pretty(&results).map_err(|error| cannot_write(path, error))?;
    put(path, &bytes, temporary)
}
