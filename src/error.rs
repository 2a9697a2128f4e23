//! Errors a scene file can produce (spec §2.4), and how they are shown to a student.
//!
//! A [`SceneError`] always knows where it happened: a 1-based line and column and the text
//! of that line. Its `Display` prints the message, the location, the offending line and a
//! caret under the column, in plain text so that snapshots of it stay stable.
//!
//! Syntax errors (text that is not the format) and meaning errors (well-formed numbers that
//! describe no valid object) are separate enums, [`SyntaxError`] and [`MeaningError`].

use std::fmt;
use thiserror::Error;

/// A place in the scene text: 1-based line and column (in characters), plus the line itself.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// 1-based line number.
    pub line: usize,
    /// 1-based column, counted in characters (a tab counts as one).
    pub column: usize,
    /// The text of that line, without its line ending.
    pub line_text: String,
}

impl Location {
    /// The location of byte `offset` in `text` (clamped to the text's end).
    pub fn of_offset(text: &str, offset: usize) -> Location {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
        let line_text = text[line_start..line_end].trim_end_matches('\r');
        Location {
            line: text[..line_start].matches('\n').count() + 1,
            column: text[line_start..offset].chars().count() + 1,
            line_text: line_text.to_string(),
        }
    }
}

/// What stood in the text where something else was expected.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Found {
    /// The input ended.
    EndOfInput,
    /// The line ended (only where the format needs more on the same line).
    EndOfLine,
    /// A token: the characters up to the next whitespace.
    Token(String),
}

impl fmt::Display for Found {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Found::EndOfInput => write!(f, "the end of the input"),
            Found::EndOfLine => write!(f, "the end of the line"),
            Found::Token(token) => write!(f, "`{token}`"),
        }
    }
}

/// The text is not the scene format: a bad or missing token (spec §2).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SyntaxError {
    /// Something else stood where a number, a type code or a file name was expected.
    #[error("expected {expected}, found {found}")]
    Expected {
        /// What the format needs here, e.g. "number 2 of 3 on the sphere's diffuse line".
        expected: String,
        /// What was there instead.
        found: Found,
    },
    /// `nan`, `inf`, or a number too large for a double (Decision of spec §2.2).
    #[error("expected {expected}, found `{text}`, which is not a finite number")]
    NonFinite {
        /// What the format needs here.
        expected: String,
        /// The offending token.
        text: String,
    },
    /// A type code that the course never defined (spec §3.2).
    #[error(
        "unknown type code {code}: the codes are 10, 11, 13-17 and 19-24, or the keyword QUADRIC"
    )]
    UnknownTypeCode {
        /// The code as written.
        code: String,
    },
    /// A type code that exists in other variants of the course, but not in this format.
    #[error("type {code} ({name}) is not supported{hint}")]
    Unsupported {
        /// The code.
        code: u32,
        /// What the code stood for.
        name: &'static str,
        /// A pointer to what the writer probably meant.
        hint: &'static str,
    },
    /// A `QUADRIC` line that ends before its ten coefficients (spec §3.3).
    #[error(
        "the QUADRIC line needs its 10 coefficients A B C D E F G H I J on the same line, \
         found {count} before {found}"
    )]
    QuadricLineShort {
        /// How many coefficients the line had.
        count: usize,
        /// What ended it.
        found: Found,
    },
}

/// Well-formed numbers that describe no valid scene object (spec §2.4).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeaningError {
    /// A direction given as (0, 0, 0).
    #[error("the {record}'s {what} is the zero vector, so it has no direction")]
    ZeroVector {
        /// Record name, e.g. "plane".
        record: &'static str,
        /// Which vector, e.g. "normal".
        what: &'static str,
    },
    /// A spotlight whose aim point is its location.
    #[error("the spotlight's aim point equals its location, so the beam has no direction")]
    AimAtLocation,
    /// The x direction of a plane frame lies along the plane's normal.
    #[error(
        "the {record}'s x direction is parallel to its normal, so it gives no direction in the plane"
    )]
    XdirParallel {
        /// Record name.
        record: &'static str,
    },
    /// A size that must be positive is not.
    #[error("the {record}'s {what} must be greater than zero, found {value}")]
    NotPositive {
        /// Record name.
        record: &'static str,
        /// Which quantity, e.g. "radius".
        what: &'static str,
        /// The value found.
        value: f64,
    },
    /// A hyperboloid waist radius below zero.
    #[error("the hyperboloid's waist radius must not be negative, found {value}")]
    NegativeWaist {
        /// The value found.
        value: f64,
    },
    /// A spotlight half-angle outside (0, 180) degrees.
    #[error(
        "the spotlight's half-angle must lie strictly between 0 and 180 degrees, found {value}"
    )]
    SpotAngle {
        /// The value found.
        value: f64,
    },
    /// A procedural shader index other than 0 or 1 (spec §5.5).
    #[error("the {record}'s shader index must be 0 (stripes) or 1 (colour wheel), found {value}")]
    UnknownShader {
        /// Record name.
        record: &'static str,
        /// The value found.
        value: f64,
    },
    /// A texture mode other than 1 or 2 (spec §5.8).
    #[error("the textured plane's mode must be 1 (fit) or 2 (tile), found {value}")]
    TextureMode {
        /// The value found.
        value: f64,
    },
    /// The texture file could not be opened or is not a binary P6 PPM.
    #[error("cannot read the texture file `{path}`: {reason}")]
    Texture {
        /// The path as written in the scene.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// A `QUADRIC` whose ten coefficients are all zero.
    #[error("all ten coefficients of the QUADRIC are zero, so it describes no surface")]
    ZeroQuadric,
    /// More records than this program accepts.
    #[error("the scene has more than {limit} lights and objects; this program stops there")]
    TooManyRecords {
        /// The limit.
        limit: usize,
    },
}

/// Either kind of scene error.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SceneErrorKind {
    /// The text is not the format.
    #[error(transparent)]
    Syntax(#[from] SyntaxError),
    /// The numbers describe no valid object.
    #[error(transparent)]
    Meaning(#[from] MeaningError),
}

/// A scene that cannot be loaded, with the place to fix.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// What is wrong.
    pub kind: SceneErrorKind,
    /// Where.
    pub at: Location,
    /// Extra context, e.g. the line on which the record started.
    pub notes: Vec<String>,
}

impl std::error::Error for SceneError {}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Location {
            line,
            column,
            line_text,
        } = &self.at;
        let gutter = " ".repeat(line.to_string().len());
        // The caret line repeats the tabs of the source line so that it lines up.
        let pad: String = line_text
            .chars()
            .take(column - 1)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        writeln!(f, "error: {}", self.kind)?;
        writeln!(f, "{gutter}--> line {line}, column {column}")?;
        writeln!(f, "{gutter} |")?;
        writeln!(f, "{line} | {line_text}")?;
        write!(f, "{gutter} | {pad}^")?;
        for note in &self.notes {
            write!(f, "\n{gutter} = note: {note}")?;
        }
        Ok(())
    }
}

/// An error found before the text's lines are known to the caller: a byte offset, the
/// kind, and optionally a note. [`Pending::locate`] turns it into a [`SceneError`].
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Pending {
    pub at: usize,
    pub kind: SceneErrorKind,
    pub notes: Vec<String>,
}

impl Pending {
    pub(crate) fn new(at: usize, kind: impl Into<SceneErrorKind>) -> Pending {
        Pending {
            at,
            kind: kind.into(),
            notes: Vec::new(),
        }
    }

    pub(crate) fn with_note(mut self, note: String) -> Pending {
        self.notes.push(note);
        self
    }

    /// Attaches line, column and line text from the scene text.
    pub(crate) fn locate(self, text: &str) -> SceneError {
        SceneError {
            kind: self.kind,
            at: Location::of_offset(text, self.at),
            notes: self.notes,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn location_counts_lines_and_characters() {
        let text = "8 6\n0 0 3\n13\té x\n";
        let at = Location::of_offset(text, text.find('x').unwrap());
        assert_eq!(at.line, 3);
        assert_eq!(at.column, 6);
        assert_eq!(at.line_text, "13\té x");
    }

    #[test]
    fn location_at_end_of_text_is_after_the_last_character() {
        let text = "8 6\n0 0";
        let at = Location::of_offset(text, text.len());
        assert_eq!((at.line, at.column), (2, 4));
    }

    #[test]
    fn caret_lines_up_under_tabs() {
        let error = SceneError {
            kind: MeaningError::ZeroQuadric.into(),
            at: Location {
                line: 7,
                column: 3,
                line_text: "\tx y".into(),
            },
            notes: vec![],
        };
        let shown = error.to_string();
        assert!(shown.ends_with("7 | \tx y\n  | \t ^"), "{shown}");
    }
}
