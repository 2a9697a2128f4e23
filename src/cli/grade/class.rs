//! The class on disk: the scene files, the students and the image each handed in for each
//! scene, and what else lies there.

use super::super::Failure;
use legacy_rt::error::escaped;
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
    /// The file (whatever it holds: reading it is grading it).
    File(PathBuf),
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

/// The entries of a folder, sorted by name, hidden ones (`.name`) left out.
fn entries(folder: &Path, what: &str) -> Result<Vec<(String, PathBuf)>, Failure> {
    let shown = escaped(&folder.display().to_string());
    let cannot =
        |error: std::io::Error| Failure(format!("error: cannot read {what} {shown}: {error}"), 2);
    let mut found = Vec::new();
    for entry in fs::read_dir(folder).map_err(cannot)? {
        let name = entry
            .map_err(cannot)?
            .file_name()
            .to_string_lossy()
            .into_owned();
        if !name.starts_with('.') {
            found.push((name.clone(), folder.join(&name)));
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
pub fn find(scenes: &Path, submissions: &Path) -> Result<Class, Failure> {
    let mut scene_files = Vec::new();
    for (name, path) in entries(scenes, "the scenes' folder")? {
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
        return Err(Failure(
            format!(
                "error: {} holds no scene file (NAME.txt)",
                escaped(&scenes.display().to_string())
            ),
            2,
        ));
    }
    let is_image_of_a_scene = |name: &str| {
        split(name).is_some_and(|(stem, extension)| {
            IMAGES.contains(&extension.as_str()) && scene_files.iter().any(|s| s.name == stem)
        })
    };
    let top = entries(submissions, "the submissions' folder")?;
    let mut unexpected = Vec::new();
    let mut students = Vec::new();
    if top.iter().any(|(name, _)| is_image_of_a_scene(name)) {
        // One student's images, as an autograder gives them.
        let name = fs::canonicalize(submissions)
            .ok()
            .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| "student".to_string());
        students.push(student(name, &top, &scene_files, "", &mut unexpected));
    } else {
        for (name, path) in &top {
            if path.is_dir() {
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
        return Err(Failure(
            format!(
                "error: {} holds no student's folder and no image named after a scene",
                escaped(&submissions.display().to_string())
            ),
            2,
        ));
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
    files: &[(String, PathBuf)],
    scenes: &[SceneFile],
    prefix: &str,
    unexpected: &mut Vec<String>,
) -> Student {
    // Per scene, the file kept so far: the rank of its extension in IMAGES, its name, path.
    let mut chosen: Vec<Option<(usize, &str, &PathBuf)>> = vec![None; scenes.len()];
    for (file, path) in files {
        let matched = split(file).and_then(|(stem, extension)| {
            let rank = IMAGES.iter().position(|e| *e == extension)?;
            Some((scenes.iter().position(|s| s.name == stem)?, rank))
        });
        let Some((scene, rank)) = matched else {
            unexpected.push(format!("{prefix}{file}"));
            continue;
        };
        match chosen[scene] {
            Some((kept_rank, _, _)) if kept_rank <= rank => {
                unexpected.push(format!("{prefix}{file}"));
            }
            kept => {
                if let Some((_, kept_name, _)) = kept {
                    unexpected.push(format!("{prefix}{kept_name}"));
                }
                chosen[scene] = Some((rank, file, path));
            }
        }
    }
    let files = chosen
        .into_iter()
        .map(|c| match c {
            Some((_, _, path)) => Submitted::File(path.clone()),
            None => Submitted::Missing,
        })
        .collect();
    Student { name, files }
}
