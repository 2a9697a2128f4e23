//! `grade --scheme FILE`: the points each scene is worth, and optionally the size its
//! images must have and its tolerance, in TOML:
//!
//! ```toml
//! points = 1            # what a scene not listed is worth (default 1)
//! [scenes.spec1]
//! points = 2
//! size = [640, 480]
//! tolerance = 1
//! ```

use super::GradeError;
use super::class::SceneFile;
use crate::error::escaped;
use crate::files;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// The largest scheme file read: a few lines per scene.
const MAX_SCHEME: u64 = 1 << 20;

/// The scheme file.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scheme {
    /// What a scene not listed is worth.
    points: Option<f64>,
    /// Per scene name (the file's name without `.txt`).
    #[serde(default)]
    scenes: BTreeMap<String, Entry>,
    /// The file as named and its text, for the lines the messages name.
    #[serde(skip)]
    source: Option<(String, String)>,
}

/// One scene's entry.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct Entry {
    points: Option<f64>,
    size: Option<[u64; 2]>,
    tolerance: Option<u8>,
}

/// How one scene is graded.
#[derive(Debug, Clone, Copy)]
pub struct Plan {
    /// The points a match gives.
    pub points: f64,
    /// The size its images must have, if fixed.
    pub size: Option<[u64; 2]>,
    /// Its tolerance in byte levels, if not --tolerance.
    pub tolerance: Option<u8>,
}

impl Scheme {
    /// The plan for the scene `name`.
    pub fn scene(&self, name: &str) -> Plan {
        let entry = self.scenes.get(name).copied().unwrap_or_default();
        Plan {
            points: entry.points.or(self.points).unwrap_or(1.0),
            size: entry.size,
            tolerance: entry.tolerance,
        }
    }

    /// Fails on a scene the scheme names that SCENES does not hold (a typo would give
    /// its scene the default silently), on negative points and on an empty size.
    pub fn check(&self, scenes: &[SceneFile]) -> Result<(), GradeError> {
        // The file and the line of the first line that holds each of `needles`.
        let bad = |needles: &[&str], message: String| {
            let (file, line) = match &self.source {
                Some((shown, text)) => {
                    let line = text
                        .lines()
                        .position(|l| needles.iter().all(|n| l.contains(n)));
                    let line = line.map_or(String::new(), |k| format!(" (line {})", k + 1));
                    (format!(" {shown}"), line)
                }
                None => (String::new(), String::new()),
            };
            GradeError::Failed(format!("--scheme{file}{line}: {message}"))
        };
        for (name, entry) in &self.scenes {
            let key = format!("scenes.{name}");
            if !scenes.iter().any(|s| &s.name == name) {
                let names: Vec<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
                return Err(bad(
                    &[&key],
                    format!(
                        "[scenes.{}] is no scene of SCENES, whose scenes are {}",
                        escaped(name),
                        names.join(", ")
                    ),
                ));
            }
            if entry.size.is_some_and(|[w, h]| w == 0 || h == 0) {
                return Err(bad(
                    &["size", "0"],
                    format!("[scenes.{}]: a size is two positive numbers", escaped(name)),
                ));
            }
        }
        let points = self
            .scenes
            .values()
            .filter_map(|e| e.points)
            .chain(self.points);
        if let Some(p) = points.into_iter().find(|p| !(p.is_finite() && *p >= 0.0)) {
            return Err(bad(
                &["points", "-"],
                format!("points are a number from 0 up, not {p}"),
            ));
        }
        Ok(())
    }
}

/// Reads the scheme file at `path`.
pub fn read(path: &Path) -> Result<Scheme, GradeError> {
    let shown = files::shown(path);
    let bytes = crate::files::read_file(path, MAX_SCHEME)?;
    let text = String::from_utf8(bytes)
        .map_err(|_| GradeError::Failed(format!("--scheme {shown} is not UTF-8 text")))?;
    let scheme: Result<Scheme, _> = toml::from_str(&text);
    let mut scheme = scheme.map_err(|error| {
        let at = error
            .span()
            .and_then(|span| text.get(..span.start))
            .map(|before| format!(" (line {})", before.matches('\n').count() + 1))
            .unwrap_or_default();
        GradeError::Failed(format!("--scheme {shown}{at}: {}", error.message()))
    })?;
    scheme.source = Some((shown, text));
    Ok(scheme)
}
