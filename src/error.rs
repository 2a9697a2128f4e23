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

/// The most characters of the offending line an error shows: a 10 MB line is shown as
/// the part around the column, with `...` where it was cut.
const SHOWN_LINE: usize = 100;

/// The most characters of a token quoted in a message.
const SHOWN_TOKEN: usize = 40;

/// How a character is shown in an error: as itself, or as an escape such as `\u{1b}`
/// when it is a control character (ESC, BEL: they would act on the terminal) or an
/// invisible one (a byte-order mark, zero-width spaces, direction marks). Tabs stay tabs.
fn visible(c: char) -> Option<String> {
    let invisible = matches!(c, '\u{200b}'..='\u{200f}' | '\u{2028}'..='\u{202e}'
        | '\u{2060}'..='\u{2064}' | '\u{feff}');
    ((c.is_control() && c != '\t') || invisible).then(|| c.escape_unicode().to_string())
}

/// A token as quoted in a message: escaped as [`visible`] does, and cut after
/// `SHOWN_TOKEN` characters.
pub(crate) fn quoted(token: &str) -> String {
    let mut shown = String::new();
    for (i, c) in token.chars().enumerate() {
        if i == SHOWN_TOKEN {
            shown.push_str("...");
            break;
        }
        match visible(c) {
            Some(escape) => shown.push_str(&escape),
            None => shown.push(c),
        }
    }
    shown
}

/// A name (a file's, as the user gave it) as a message shows it: every control and
/// invisible character escaped as `\u{1b}`, tabs and newlines included, so that
/// a name cannot start a line of its own or move the terminal's cursor.
pub fn escaped(name: &str) -> String {
    let mut shown = String::new();
    for c in name.chars() {
        match visible(c) {
            Some(escape) => shown.push_str(&escape),
            None if c == '\t' => shown.push_str(&c.escape_unicode().to_string()),
            None => shown.push(c),
        }
    }
    shown
}

/// The part of `line` an error shows around the 1-based `column`, escaped, and the
/// caret's padding under it (tabs repeated so that the caret lines up).
fn excerpt(line: &str, column: usize) -> (String, String) {
    let count = line.chars().count();
    let first = if count <= SHOWN_LINE {
        0
    } else {
        (column - 1)
            .saturating_sub(SHOWN_LINE / 2)
            .min(count - SHOWN_LINE)
    };
    let last = (first + SHOWN_LINE).min(count);
    let (mut shown, mut pad) = (String::new(), String::new());
    if first > 0 {
        shown.push_str("...");
        pad.push_str("   ");
    }
    for (i, c) in line.chars().enumerate().take(last).skip(first) {
        let piece = visible(c).unwrap_or_else(|| c.to_string());
        if i + 1 < column {
            pad.extend(piece.chars().map(|p| if p == '\t' { '\t' } else { ' ' }));
        }
        shown.push_str(&piece);
    }
    if last < count {
        shown.push_str("...");
    }
    (shown, pad)
}

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
            Found::Token(token) => write!(f, "`{}`", quoted(token)),
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
    #[error("expected {expected}, found `{}`, which is not a finite number", quoted(.text))]
    NonFinite {
        /// What the format needs here.
        expected: String,
        /// The offending token.
        text: String,
    },
    /// A type code that the course never defined (spec §3.2).
    #[error(
        "unknown type code {}: the codes are 10, 11, 13-17 and 19-24, or the keyword QUADRIC",
        quoted(.code)
    )]
    UnknownTypeCode {
        /// The code as written.
        code: String,
    },
    /// A type code that exists in other variants of the course, but not in this format.
    #[error("type {code} ({name}) is not supported{hint}")]
    Unsupported {
        /// The type code as written.
        code: u32,
        /// What the code stood for.
        name: &'static str,
        /// A pointer to what the writer probably meant.
        hint: &'static str,
    },
    /// More records than this program reads: a limit of the reader, so that a huge input
    /// is an error and not an exhausted memory.
    #[error(
        "the scene has more than {limit} records (lights and objects together), the most this \
         program reads"
    )]
    TooManyRecords {
        /// The most records a scene may hold.
        limit: usize,
    },
    /// The text starts with a UTF-8 byte-order mark, which some editors put first.
    #[error(
        "the file starts with an invisible byte-order mark (\\u{{feff}}), which the course's \
         program could not read either; save the file as plain text (\"UTF-8 without BOM\")"
    )]
    ByteOrderMark,
    /// A `QUADRIC` line that ends before its ten coefficients (spec §3.3).
    #[error(
        "the QUADRIC line needs its 10 coefficients A B C D E F G H I J on the same line, \
         found {count} before {found}"
    )]
    QuadricLineShort {
        /// How many coefficients the line had.
        count: usize,
        /// What came instead of the number: a word, or the end of the file.
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
        /// The record's name, as messages write it ("sphere").
        record: &'static str,
    },
    /// A size that must be positive is not.
    #[error("the {record}'s {what} must be greater than zero, found {value}")]
    NotPositive {
        /// The record's name, as messages write it ("sphere").
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
        /// The record's name, as messages write it ("sphere").
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
    #[error("cannot read the texture file `{}`: {reason}", quoted(.path))]
    Texture {
        /// The path as written in the scene.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// A record the builder reads differently from how the reader read it: a mistake in
    /// this program, reported instead of a crash.
    #[error(
        "internal error: the {record} record has no {label} line as this program reads it; \
         please report this, with the scene file"
    )]
    Internal {
        /// The record's name, as messages write it ("sphere").
        record: &'static str,
        /// The group the builder asked for.
        label: &'static str,
    },
    /// A `QUADRIC` whose ten coefficients are all zero.
    #[error("all ten coefficients of the QUADRIC are zero, so it describes no surface")]
    ZeroQuadric,
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
    /// What is wrong, as a syntax or a meaning error.
    pub kind: SceneErrorKind,
    /// The line and column to fix, and the line's text.
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
        let (shown, pad) = excerpt(line_text, *column);
        writeln!(f, "error: {}", self.kind)?;
        writeln!(f, "{gutter}--> line {line}, column {column}")?;
        writeln!(f, "{gutter} |")?;
        writeln!(f, "{line} | {shown}")?;
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

    #[test]
    fn control_and_invisible_characters_are_shown_as_escapes() {
        let error = SceneError {
            kind: SyntaxError::Expected {
                expected: "a number".into(),
                found: Found::Token("\u{1b}[31m1\u{7}".into()),
            }
            .into(),
            at: Location {
                line: 4,
                column: 2,
                line_text: "\u{feff}\u{1b}[31m1".into(),
            },
            notes: vec![],
        };
        let shown = error.to_string();
        assert!(!shown.contains(['\u{1b}', '\u{7}', '\u{feff}']), "{shown}");
        assert!(shown.contains("found `\\u{1b}[31m1\\u{7}`"), "{shown}");
        // The caret stands under the escape of the second character, ESC.
        assert!(
            shown.ends_with("4 | \\u{feff}\\u{1b}[31m1\n  |         ^"),
            "{shown}"
        );
    }

    #[test]
    fn a_long_line_is_shown_around_the_column_and_a_long_token_is_cut() {
        let line_text = format!("{}x{}", "1".repeat(5_000), "2".repeat(5_000));
        let token = "9".repeat(1_000_000);
        let error = SceneError {
            kind: SyntaxError::NonFinite {
                expected: "a number".into(),
                text: token,
            }
            .into(),
            at: Location {
                line: 1,
                column: 5_001,
                line_text,
            },
            notes: vec![],
        };
        let shown = error.to_string();
        assert!(shown.len() < 400, "{} bytes", shown.len());
        let expected_token = format!("`{}...`", "9".repeat(SHOWN_TOKEN));
        assert!(shown.contains(&expected_token), "{shown}");
        // 50 characters before the column, the column itself, 49 after, cut at both ends.
        let excerpt = format!("1 | ...{}x{}...", "1".repeat(50), "2".repeat(49));
        assert!(shown.contains(&excerpt), "{shown}");
        let caret = format!("  | {}^", " ".repeat(53));
        assert!(shown.ends_with(&caret), "{shown}");
    }
}
