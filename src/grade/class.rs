//! The class on disk: the scene files, the students and the image each handed in for each
//! scene, and what else lies there.

use super::GradeError;
use crate::files;
use std::fs;
use std::path::{Path, PathBuf};

/// The image extensions a student's file may have, the first found graded.
const IMAGES: [&str; 3] = ["ppm", "png", "pnm"];

/// A scene file of SCENES.
#[derive(Debug)]
pub struct SceneFile {
    /// Its name without `.txt`: the name of the students' images of it.
    pub name: String,
    /// Its path, as SCENES was given joined with the file's name.
    pub path: PathBuf,
}

/// What a student handed in for one scene.
#[derive(Debug)]
pub enum Submitted {
    /// No file of that name.
    Missing,
    /// The file (whatever it holds: reading it is grading it), and the other images of
    /// the same scene in the folder, not graded (`studio.png` beside `studio.ppm`).
    File(PathBuf, Vec<String>),
    /// A symbolic link, in the student's folder or as the folder itself: never followed
    /// (it may point anywhere on the grader's machine), graded unreadable.
    Link(PathBuf),
}

/// A student: a folder of SUBMISSIONS, or SUBMISSIONS itself for one student.
#[derive(Debug)]
pub struct Student {
    /// The folder's name.
    pub name: String,
    /// Per scene (in the order of [`Class::scenes`]), the file handed in.
    pub files: Vec<Submitted>,
}

/// One student's image of one scene, by their indices.
#[derive(Debug, Clone, Copy)]
pub struct Pair {
    /// Index in [`Class::students`].
    pub student: usize,
    /// Index in [`Class::scenes`].
    pub scene: usize,
}

/// The class to grade.
#[derive(Debug)]
pub struct Class {
    /// The scenes, by name.
    pub scenes: Vec<SceneFile>,
    /// The students, by name.
    pub students: Vec<Student>,
    /// Files and folders of SUBMISSIONS that are no scene's image, as paths under it.
    pub unexpected: Vec<String>,
}

impl Class {
    /// Every pair, student by student, scene by scene.
    pub fn pairs(&self) -> Vec<Pair> {
        (0..self.students.len())
            .flat_map(|student| (0..self.scenes.len()).map(move |scene| Pair { student, scene }))
            .collect()
    }
}

/// One entry of a folder: its name, its path, and whether it is a symbolic link.
type Entry = (String, PathBuf, bool);

/// The entries of a folder, sorted by name, hidden ones (`.name`) left out; each with
/// whether it is a symbolic link (told without following it).
fn entries(folder: &Path, what: &str) -> Result<Vec<Entry>, GradeError> {
    let shown = files::shown(folder);
    let cannot =
        |error: std::io::Error| GradeError::Failed(format!("cannot read {what} {shown}: {error}"));
    let mut found = Vec::new();
    for entry in fs::read_dir(folder).map_err(cannot)? {
        let entry = entry.map_err(cannot)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        // The entry's own type: a link is a link, whatever it points at.
        let link = entry.file_type().is_ok_and(|t| t.is_symlink());
        if !name.starts_with('.') {
            found.push((name.clone(), folder.join(&name), link));
        }
    }
    found.sort();
    Ok(found)
}

/// `name` split as `stem.extension`, the extension in lower case.
fn split(name: &str) -> Option<(&str, String)> {
    let (stem, extension) = name.rsplit_once('.')?;
    Some((stem, extension.to_ascii_lowercase()))
}

/// Finds the class: the scene files of `scenes` and the students of `submissions`.
pub fn find(scenes: &Path, submissions: &Path) -> Result<Class, GradeError> {
    let mut scene_files = Vec::new();
    for (name, path, _) in entries(scenes, "the scenes' folder")? {
        if let Some((stem, extension)) = split(&name)
            && extension == "txt"
            && path.is_file()
        {
            scene_files.push(SceneFile {
                name: stem.to_string(),
                path,
            });
        }
    }
    if scene_files.is_empty() {
        return Err(GradeError::Failed(format!(
            "{} holds no scene file (NAME.txt)",
            files::shown(scenes)
        )));
    }
    let is_image_of_a_scene = |name: &str| {
        split(name).is_some_and(|(stem, extension)| {
            IMAGES.contains(&extension.as_str()) && scene_files.iter().any(|s| s.name == stem)
        })
    };
    let top = entries(submissions, "the submissions' folder")?;
    let mut unexpected = Vec::new();
    let mut students = Vec::new();
    if top.iter().any(|(name, _, _)| is_image_of_a_scene(name)) {
        // One student's images, as an autograder gives them.
        let name = fs::canonicalize(submissions)
            .ok()
            .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| "student".to_string());
        students.push(student(name, &top, &scene_files, "", &mut unexpected));
    } else {
        for (name, path, link) in &top {
            if *link {
                // Listed, each scene unreadable, and never followed.
                let files = scene_files
                    .iter()
                    .map(|_| Submitted::Link(path.clone()))
                    .collect();
                students.push(Student {
                    name: name.clone(),
                    files,
                });
            } else if path.is_dir() {
                let files = entries(path, "the student's folder")?;
                let prefix = format!("{name}/");
                let found = student(name.clone(), &files, &scene_files, &prefix, &mut unexpected);
                students.push(found);
            } else {
                unexpected.push(name.clone());
            }
        }
    }
    if students.is_empty() {
        return Err(GradeError::Failed(format!(
            "{} holds no student's folder and no image named after a scene",
            files::shown(submissions)
        )));
    }
    Ok(Class {
        scenes: scene_files,
        students,
        unexpected,
    })
}

/// A student's files among `files`, the others noted as unexpected under `prefix`.
fn student(
    name: String,
    files: &[Entry],
    scenes: &[SceneFile],
    prefix: &str,
    unexpected: &mut Vec<String>,
) -> Student {
    // Per scene, the file kept so far: its rank (the place of its extension in IMAGES,
    // a symbolic link after every file), its name and entry; and the other images of the
    // scene, passed over.
    let mut chosen: Vec<Option<(usize, &str, &Entry)>> = vec![None; scenes.len()];
    let mut others: Vec<Vec<String>> = vec![Vec::new(); scenes.len()];
    for entry in files {
        let (file, _, link) = entry;
        let matched = split(file).and_then(|(stem, extension)| {
            let rank = IMAGES.iter().position(|e| *e == extension)?;
            let rank = if *link { rank + IMAGES.len() } else { rank };
            Some((scenes.iter().position(|s| s.name == stem)?, rank))
        });
        let Some((scene, rank)) = matched else {
            unexpected.push(format!("{prefix}{file}"));
            continue;
        };
        let passed_over = match chosen[scene] {
            Some((kept_rank, _, _)) if kept_rank <= rank => file.as_str(),
            kept => {
                chosen[scene] = Some((rank, file, entry));
                match kept {
                    Some((_, kept_name, _)) => kept_name,
                    None => continue,
                }
            }
        };
        unexpected.push(format!("{prefix}{passed_over}"));
        others[scene].push(format!("{prefix}{passed_over}"));
    }
    let files = chosen
        .into_iter()
        .zip(others)
        .map(|(c, mut others)| match c {
            Some((_, _, (_, path, true))) => Submitted::Link(path.clone()),
            Some((_, _, (_, path, false))) => {
                others.sort();
                Submitted::File(path.clone(), others)
            }
            None => Submitted::Missing,
        })
        .collect();
    Student { name, files }
}
