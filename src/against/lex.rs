//! One line of what a student's program printed with the course's `DBG_*` flags (spec §8)
//! → what it says: the tags (`PIX`, `WRL`, `FND`, `HIT`, `AMB`, ...) with their numbers,
//! and the diffuse block's labels with theirs. Every copy of the course program printed a
//! little differently, so nothing here insists on spacing, colons, precision or case of
//! the pixel label; a label's values may follow on later lines, blank lines between
//! (as the course's own copy prints them). What is neither (a model dump, matrices,
//! `byte:` lines) is passed over.
//!
//! [`Lexer`] reads a file as a stream, one line at a time, in time linear in its size
//! and in memory bounded by [`MAX_LINE`], whatever the file holds.

use std::collections::VecDeque;
use std::io::{self, BufRead};

/// The most bytes of one line that are read; the rest of a longer line is skipped
/// unread (a debug trace's line is under 200 bytes: a longer one is not the format).
pub const MAX_LINE: usize = 64 * 1024;

/// The most characters of a line kept to quote it in a report.
const QUOTED: usize = 160;

/// A number as printed: its value, and half a unit of its last printed digit (what the
/// printing may have rounded away).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num {
    /// The value; NaN for `nan` and `-nan`.
    pub value: f64,
    /// Half a unit of the last digit printed.
    pub half_unit: f64,
}

/// A label of the diffuse block (spec §8), followed by its value(s), on that line or on
/// the next ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Label {
    /// "hit object id was"
    HitObject,
    /// "hit point was"
    HitPoint,
    /// "normal at hitpoint"
    Normal,
    /// "light object id was"
    LightObject,
    /// "light center was"
    LightCenter,
    /// "unit vector to light is"
    ToLight,
    /// "distance to light is"
    Distance,
    /// "cos is", "cosine is", "theta is"
    Cos,
    /// "Emissivity of the light"
    Emissivity,
    /// "Diffuse reflectivity"
    Reflectivity,
    /// "Current ivec"
    Ivec,
    /// "hit object occluded by"
    OccludedBy,
    /// "distance was"
    DistanceWas,
}

impl Label {
    /// How many numbers follow the label.
    pub fn count(self) -> usize {
        match self {
            Label::HitPoint
            | Label::Normal
            | Label::LightCenter
            | Label::ToLight
            | Label::Emissivity
            | Label::Reflectivity
            | Label::Ivec => 3,
            _ => 1,
        }
    }

    /// Whether the label is one of a light's geometry, which the course's copies print
    /// before the shadow ray (the rest, from `Emissivity` or `occluded by` on, come after
    /// it).
    pub fn geometry(self) -> bool {
        matches!(
            self,
            Label::HitObject
                | Label::HitPoint
                | Label::Normal
                | Label::LightObject
                | Label::LightCenter
                | Label::ToLight
                | Label::Distance
                | Label::Cos
        )
    }
}

/// The labels' spellings, longest first where one contains another; matched in lower case.
const LABELS: [(&str, Label); 16] = [
    ("hit object occluded by", Label::OccludedBy),
    ("hit object id was", Label::HitObject),
    ("hit point was", Label::HitPoint),
    ("normal at hitpoint", Label::Normal),
    ("normal at hit point", Label::Normal),
    ("light object id was", Label::LightObject),
    ("light center was", Label::LightCenter),
    ("unit vector to light", Label::ToLight),
    ("distance to light", Label::Distance),
    ("distance was", Label::DistanceWas),
    ("cosine is", Label::Cos),
    ("cos is", Label::Cos),
    ("theta is", Label::Cos),
    ("emissivity of the light", Label::Emissivity),
    ("diffuse reflectivity", Label::Reflectivity),
    ("current ivec", Label::Ivec),
];

/// One thing the student's program printed.
#[derive(Debug, Clone, PartialEq)]
pub enum Said {
    /// `PIX a b`, `PIX: ROW = a COL = b`, `Pix: ROW = a COL = b`: two numbers, which
    /// copies print as x y, y x, or the image's size on every block ([`super::layout`]
    /// tells which from the file).
    Pix {
        /// The first number.
        a: i64,
        /// The second.
        b: i64,
        /// Whether the copy names them `ROW` and `COL`.
        row_col: bool,
    },
    /// `WRL (x, y)`, `world coordinates(x, y)`: the pixel's world point.
    World(Num, Num),
    /// `FND id: t`: one object tested by a ray.
    Found(i64, Num),
    /// The three-line `FND` form's `base X: .. Y: .. Z: ..`.
    FoundBase([Num; 3]),
    /// Its `dir X: .. Y: .. Z: ..`.
    FoundDir([Num; 3]),
    /// Its `hits: X: .. Y: .. Z: ..`.
    FoundHits([Num; 3]),
    /// `HIT id: t (x, y, z)`: the closest hit.
    Hit(i64, Num, [Num; 3]),
    /// `The total dist is d`, after `HIT` in one copy.
    TotalDist(Num),
    /// `AMB (r, g, b)`: the intensity divided by the path's length.
    Amb([Num; 3]),
    /// `DIFFUSE (r, g, b)`, printed by one copy; read, not compared.
    Diffuse([Num; 3]),
    /// A label of the diffuse block and its numbers.
    Labelled(Label, Vec<Num>),
}

impl Said {
    /// Whether this is a line only a traced ray prints (not a pixel's or a model dump's).
    pub fn traced(&self) -> bool {
        matches!(
            self,
            Said::Found(..) | Said::Hit(..) | Said::Amb(_) | Said::Labelled(..)
        )
    }
}

/// One [`Said`], the line of the file it starts on (from 1) and that line's text.
#[derive(Debug, Clone, PartialEq)]
pub struct Item {
    /// The line number, from 1.
    pub line: usize,
    /// What it said.
    pub said: Said,
    /// The line as printed (a label's with its value lines), trimmed, cut to 160
    /// characters: what a report quotes.
    pub text: String,
}

/// A label whose values are still to come on the next lines.
struct Pending {
    label: Label,
    values: Vec<Num>,
    line: usize,
    text: String,
}

/// The items of a student's file, read one line at a time.
pub struct Lexer<R> {
    input: R,
    /// The number of the line read last, from 1.
    line: usize,
    buffer: Vec<u8>,
    queue: VecDeque<Item>,
    pending: Option<Pending>,
    finished: bool,
}

impl<R: BufRead> Lexer<R> {
    /// The lexer of `input`.
    pub fn new(input: R) -> Lexer<R> {
        Lexer {
            input,
            line: 0,
            buffer: Vec::new(),
            queue: VecDeque::new(),
            pending: None,
            finished: false,
        }
    }

    /// The number of lines read so far.
    pub fn lines(&self) -> usize {
        self.line
    }

    /// The next item, or `None` at the end of the input.
    pub fn next_item(&mut self) -> io::Result<Option<Item>> {
        loop {
            if let Some(item) = self.queue.pop_front() {
                return Ok(Some(item));
            }
            if self.finished {
                return Ok(None);
            }
            if !self.read_line()? {
                self.finished = true;
                continue;
            }
            self.line += 1;
            let text = String::from_utf8_lossy(&self.buffer).into_owned();
            self.take(&text);
        }
    }

    /// Reads the next line into the buffer, at most [`MAX_LINE`] bytes of it; `false` at
    /// the end of the input.
    fn read_line(&mut self) -> io::Result<bool> {
        self.buffer.clear();
        let mut any = false;
        loop {
            let available = match self.input.fill_buf() {
                Ok(bytes) => bytes,
                Err(error) if error.kind() == io::ErrorKind::Interrupted => continue,
                Err(error) => return Err(error),
            };
            if available.is_empty() {
                return Ok(any);
            }
            any = true;
            let newline = available.iter().position(|&b| b == b'\n');
            let end = newline.unwrap_or(available.len());
            let room = MAX_LINE.saturating_sub(self.buffer.len());
            self.buffer.extend_from_slice(&available[..end.min(room)]);
            let used = newline.map_or(end, |n| n + 1);
            self.input.consume(used);
            if newline.is_some() {
                return Ok(true);
            }
        }
    }

    /// What one line says, queued.
    fn take(&mut self, text: &str) {
        let line = self.line;
        if let Some(mut pending) = self.pending.take() {
            if text.trim().is_empty() {
                self.pending = Some(pending);
                return;
            }
            if only_numbers(text) {
                pending.values.extend(numbers(text));
                pending.text = quoted(&format!("{} {}", pending.text, text.trim()));
                self.settle(pending);
                return;
            }
            // The label's values never came: it is passed over.
        }
        if let Some((label, rest)) = label(text) {
            let pending = Pending {
                label,
                values: numbers(rest),
                line,
                text: quoted(text.trim()),
            };
            self.settle(pending);
            return;
        }
        for (tag, rest) in tagged(text) {
            if let Some(said) = said(tag, rest) {
                self.queue.push_back(Item {
                    line,
                    said,
                    text: quoted(text.trim()),
                });
            }
        }
    }

    /// Queues a label that has its values, or keeps it pending.
    fn settle(&mut self, mut pending: Pending) {
        let count = pending.label.count();
        if pending.values.len() < count {
            self.pending = Some(pending);
            return;
        }
        pending.values.truncate(count);
        self.queue.push_back(Item {
            line: pending.line,
            said: Said::Labelled(pending.label, pending.values),
            text: pending.text,
        });
    }
}

/// Everything recognised in `text`, in order (for tests and small inputs).
pub fn read(text: &str) -> Vec<Item> {
    let mut lexer = Lexer::new(text.as_bytes());
    let mut out = Vec::new();
    while let Ok(Some(item)) = lexer.next_item() {
        out.push(item);
    }
    out
}

/// `text` cut to [`QUOTED`] characters.
fn quoted(text: &str) -> String {
    match text.char_indices().nth(QUOTED) {
        Some((at, _)) => format!("{}...", &text[..at]),
        None => text.to_string(),
    }
}

/// The diffuse block's label that `text` starts with (after spaces), and the rest.
fn label(text: &str) -> Option<(Label, &str)> {
    let trimmed = text.trim_start();
    let head = trimmed.as_bytes();
    LABELS
        .iter()
        .find(|(words, _)| {
            head.len() >= words.len() && head[..words.len()].eq_ignore_ascii_case(words.as_bytes())
        })
        .map(|&(words, label)| (label, &trimmed[words.len()..]))
}

/// Whether `text` holds numbers and nothing else but separators.
fn only_numbers(text: &str) -> bool {
    let spans = number_spans(text);
    if spans.is_empty() {
        return false;
    }
    let mut at = 0;
    let separators = |part: &str| {
        part.chars()
            .all(|c| c.is_whitespace() || matches!(c, ',' | '(' | ')' | '[' | ']' | '-' | ':'))
    };
    for (start, end) in spans {
        if !separators(&text[at..start]) {
            return false;
        }
        at = end;
    }
    separators(&text[at..])
}

/// A tag: its spelling, and whether it is matched in any case and whether it may be
/// glued to the word before it (`Thetotal dist is`, as one copy prints it).
struct Tag {
    spelling: &'static str,
    any_case: bool,
    glued_before: bool,
}

/// The tags, which may share a line; each runs to the next.
const TAGS: [Tag; 11] = [
    Tag::exact("PIX"),
    Tag::exact("WRL"),
    Tag::exact("FND"),
    Tag::exact("HIT"),
    Tag::exact("AMB"),
    Tag::exact("DIFFUSE"),
    Tag::exact("base X"),
    Tag::exact("dir X"),
    Tag::exact("hits:"),
    Tag {
        spelling: "total dist is",
        any_case: true,
        glued_before: true,
    },
    Tag {
        spelling: "world coordinates",
        any_case: true,
        glued_before: false,
    },
];

impl Tag {
    const fn exact(spelling: &'static str) -> Tag {
        Tag {
            spelling,
            any_case: false,
            glued_before: false,
        }
    }
}

/// The tags in `text` as words, each with the text up to the next tag. `Pix` is
/// matched in any case (one copy prints `Pix: ROW = ..`).
fn tagged(text: &str) -> Vec<(&'static str, &str)> {
    let bytes = text.as_bytes();
    let word = |c: Option<&u8>| c.is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_');
    let mut found: Vec<(usize, &'static str)> = Vec::new();
    let mut find = |spelling: &'static str, any_case: bool, glued_before: bool| {
        let length = spelling.len();
        if bytes.len() < length {
            return;
        }
        let mut start = 0;
        while start + length <= bytes.len() {
            let here = &bytes[start..start + length];
            let matched = match any_case {
                true => here.eq_ignore_ascii_case(spelling.as_bytes()),
                false => here == spelling.as_bytes(),
            };
            if matched
                && (glued_before || start == 0 || !word(bytes.get(start - 1)))
                && !word(bytes.get(start + length))
            {
                found.push((start, spelling));
                start += length;
            } else {
                start += 1;
            }
        }
    };
    for tag in &TAGS {
        find(tag.spelling, tag.any_case, tag.glued_before);
    }
    find("Pix", true, false);
    found.sort_unstable();
    found.dedup_by_key(|f| f.0);
    let mut out = Vec::with_capacity(found.len());
    for (k, &(start, tag)) in found.iter().enumerate() {
        let end = found.get(k + 1).map_or(text.len(), |&(next, _)| next);
        let from = (start + tag.len()).min(end);
        // `found` holds byte offsets of ASCII spellings, so both ends are on characters.
        out.push((tag, &text[from..end]));
    }
    out
}

/// What one tag says, from the text after it; `None` when its numbers are not there.
fn said(tag: &str, rest: &str) -> Option<Said> {
    let n = numbers(rest);
    let three = |from: usize| -> Option<[Num; 3]> {
        Some([*n.get(from)?, *n.get(from + 1)?, *n.get(from + 2)?])
    };
    let id = |k: usize| -> Option<i64> {
        let v = n.get(k)?.value;
        (v.is_finite() && v.fract() == 0.0 && v.abs() < 1e12).then_some(v as i64)
    };
    Some(match tag {
        "Pix" | "PIX" => Said::Pix {
            a: id(0)?,
            b: id(1)?,
            row_col: rest.to_ascii_uppercase().contains("ROW"),
        },
        "WRL" | "world coordinates" => Said::World(*n.first()?, *n.get(1)?),
        "FND" => Said::Found(id(0)?, *n.get(1)?),
        "HIT" => Said::Hit(id(0)?, *n.get(1)?, three(2)?),
        "AMB" => Said::Amb(three(0)?),
        "DIFFUSE" => Said::Diffuse(three(0)?),
        "base X" => Said::FoundBase(three(0)?),
        "dir X" => Said::FoundDir(three(0)?),
        "hits:" => Said::FoundHits(three(0)?),
        "total dist is" => Said::TotalDist(*n.first()?),
        _ => return None,
    })
}

/// Every number in `text`: C's `%d`, `%f`, `%e` and `%lf` output, `nan`, `-nan`, `inf`.
pub fn numbers(text: &str) -> Vec<Num> {
    number_spans(text)
        .into_iter()
        .filter_map(|(start, end)| number(&text[start..end]))
        .collect()
}

/// The value of one number's text and half a unit of its last digit.
fn number(text: &str) -> Option<Num> {
    let lower = text.to_ascii_lowercase();
    let unsigned = lower.trim_start_matches(['-', '+']);
    if unsigned.starts_with("nan") {
        return Some(Num {
            value: f64::NAN,
            half_unit: 0.0,
        });
    }
    let value: f64 = if unsigned.starts_with("inf") {
        if lower.starts_with('-') {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        }
    } else {
        lower.parse().ok()?
    };
    let (mantissa, exponent) = match lower.split_once('e') {
        Some((m, e)) => (m, e.parse::<i32>().unwrap_or(0)),
        None => (lower.as_str(), 0),
    };
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    Some(Num {
        value,
        half_unit: 0.5 * 10f64.powi(exponent.saturating_sub(decimals).clamp(-400, 400)),
    })
}

/// Where the numbers of `text` are: a sign, digits with at most one point, an exponent;
/// or `nan`/`inf` with a sign. A number glued to a word (`X1`, `f3d`) is not one. Each
/// byte is looked at a bounded number of times: linear in the line.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    // A number glued to a word, a point or any character outside ASCII (a letter of
    // another alphabet, a typographic minus) is part of something else.
    let glued = |i: usize| {
        i > 0
            && (bytes[i - 1].is_ascii_alphanumeric()
                || bytes[i - 1] == b'.'
                || !bytes[i - 1].is_ascii())
    };
    while i < bytes.len() {
        let start = i;
        let mut j = i;
        if matches!(bytes[j], b'-' | b'+') {
            j += 1;
        }
        // Bytes, not text: `i` may sit inside a character of another alphabet.
        let word = bytes.get(j..j + 3).map(<[u8]>::to_ascii_lowercase);
        if matches!(word.as_deref(), Some(b"nan" | b"inf")) && !glued(start) {
            let mut end = j + 3;
            if bytes
                .get(end..end + 5)
                .is_some_and(|rest| rest.eq_ignore_ascii_case(b"inity"))
            {
                end += 5;
            }
            // `nan(0x8000)` as some C libraries print it: letters, digits and `_` up to
            // the `)`, looked at once (where there is no `)`, the `(` ends the number).
            if bytes.get(end) == Some(&b'(') {
                let mut k = end + 1;
                while k < bytes.len() && (bytes[k].is_ascii_alphanumeric() || bytes[k] == b'_') {
                    k += 1;
                }
                if bytes.get(k) == Some(&b')') {
                    end = k + 1;
                }
            }
            spans.push((start, end));
            i = end;
            continue;
        }
        let digits_from = j;
        while j < bytes.len() && bytes[j].is_ascii_digit() {
            j += 1;
        }
        let mut any = j > digits_from;
        if j < bytes.len() && bytes[j] == b'.' {
            let after = j + 1;
            let mut k = after;
            while k < bytes.len() && bytes[k].is_ascii_digit() {
                k += 1;
            }
            if any || k > after {
                any = true;
                j = k;
            }
        }
        if !any || glued(start) {
            // A sign glued to a word is passed over alone (`x-3` reads 3); digits glued
            // to one are passed over whole, as none of them starts a number.
            i = match !any || matches!(bytes[start], b'-' | b'+') {
                true => start + 1,
                false => j,
            };
            continue;
        }
        if j < bytes.len() && matches!(bytes[j], b'e' | b'E') {
            let mut k = j + 1;
            if k < bytes.len() && matches!(bytes[k], b'-' | b'+') {
                k += 1;
            }
            let digits = k;
            while k < bytes.len() && bytes[k].is_ascii_digit() {
                k += 1;
            }
            if k > digits {
                j = k;
            }
        }
        if bytes.get(j).is_some_and(|b| b.is_ascii_alphabetic()) {
            // `3d`, `2nd`: part of a word.
            i = j;
            continue;
        }
        spans.push((start, j));
        i = j;
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(text: &str) -> Vec<f64> {
        numbers(text).iter().map(|n| n.value).collect()
    }

    #[test]
    fn numbers_as_c_prints_them() {
        assert_eq!(values("FND    3:  -1.0 - "), [3.0, -1.0]);
        assert_eq!(values("WRL ( -4.0,  -3.0) - "), [-4.0, -3.0]);
        assert_eq!(values("1.5e-3 2E+2 .5 7."), [1.5e-3, 200.0, 0.5, 7.0]);
        assert_eq!(values("base X: 1 Y: 2 Z: 3"), [1.0, 2.0, 3.0]);
        assert_eq!(values("x1 3d byte:7"), [7.0]);
        let nan = numbers("-nan nan inf -inf nan(0x8000)");
        assert!(nan[0].value.is_nan() && nan[1].value.is_nan() && nan[4].value.is_nan());
        assert_eq!(
            (nan[2].value, nan[3].value),
            (f64::INFINITY, f64::NEG_INFINITY)
        );
        assert_eq!(nan.len(), 5);
        // %5.1lf leaves half a tenth; %5.11f half of 1e-11; %e's exponent counts.
        assert_eq!(numbers("2.5")[0].half_unit, 0.05);
        assert!((numbers("0.12345678901")[0].half_unit - 0.5e-11).abs() < 1e-20);
        assert!((numbers("1.25e-3")[0].half_unit - 0.5e-5).abs() < 1e-18);
    }

    #[test]
    fn an_unclosed_nan_is_a_nan_and_the_rest_is_read() {
        // `nan(` without `)`: the number is `nan`; what follows is read on.
        let said = values("nan(nan(nan( 3");
        assert_eq!(said.len(), 4);
        assert!(said[..3].iter().all(|v| v.is_nan()));
        assert_eq!(said[3], 3.0);
    }

    #[test]
    fn tags_share_a_line_and_labels_take_the_next() {
        let text = "junk 1 2 3\nPIX    5    3 - WRL (  0.0,   0.0) - FND    0:   8.0 - FND 1: nan -\n\
                    HIT    0:   8.0 (  0.0,   0.0,  -5.0) - Thetotal dist is 8.000000\n\
                    normal at hitpoint\n   0.000    0.000   -1.000\ncos is :\t0.5\nAMB (0.6, 0.6, 0.0) -";
        let said: Vec<_> = read(text).into_iter().map(|l| (l.line, l.said)).collect();
        assert!(matches!(said[0], (2, Said::Pix { a: 5, b: 3, .. })));
        assert!(matches!(said[1], (2, Said::World(..))));
        assert!(matches!(said[2], (2, Said::Found(0, n)) if n.value == 8.0));
        assert!(matches!(said[3], (2, Said::Found(1, n)) if n.value.is_nan()));
        assert!(matches!(said[4], (3, Said::Hit(0, ..))));
        assert!(matches!(said[5], (3, Said::TotalDist(n)) if n.value == 8.0));
        assert!(matches!(&said[6], (4, Said::Labelled(Label::Normal, v)) if v[2].value == -1.0));
        assert!(matches!(&said[7], (6, Said::Labelled(Label::Cos, v)) if v[0].value == 0.5));
        assert!(matches!(said[8], (7, Said::Amb(_))));
        assert_eq!(said.len(), 9);
    }

    #[test]
    fn a_label_s_values_after_a_blank_line() {
        // As the course's own copy prints them: the label, a blank line, the values.
        let text = "normal at hitpoint       \n\n   0.003264   -0.304968   0.952357\n\
                    distance to light is     6.441930\nhit object occluded by 100\n\ndistance was 2.2";
        let said: Vec<_> = read(text).into_iter().map(|l| (l.line, l.said)).collect();
        assert!(
            matches!(&said[0], (1, Said::Labelled(Label::Normal, v)) if v[1].value == -0.304968)
        );
        assert!(matches!(&said[1], (4, Said::Labelled(Label::Distance, _))));
        assert!(
            matches!(&said[2], (5, Said::Labelled(Label::OccludedBy, v)) if v[0].value == 100.0)
        );
        assert!(matches!(
            &said[3],
            (7, Said::Labelled(Label::DistanceWas, _))
        ));
        // A label whose values never come is passed over; the next line is read.
        let said = read("normal at hitpoint\nFND 3: 1.0 -");
        assert_eq!(said.len(), 1);
        assert!(matches!(said[0].said, Said::Found(3, _)));
    }

    #[test]
    fn text_in_any_alphabet_is_passed_over() {
        assert_eq!(values("é1 ünan −2 ∞ 3"), [3.0]);
        assert!(read("FND é: ñ\nHIT ½ 2 (1, 2, 3)\ncos is ∞").is_empty());
    }

    #[test]
    fn the_pixel_labels_of_every_copy() {
        let said =
            read("PIX:  ROW = 12 COL = 7 - \nPix: ROW = 3 COL = 4\nPIX   64   48 - \npixel 3 4");
        let pix: Vec<_> = said.iter().map(|i| i.said.clone()).collect();
        assert_eq!(
            pix,
            [
                Said::Pix {
                    a: 12,
                    b: 7,
                    row_col: true
                },
                Said::Pix {
                    a: 3,
                    b: 4,
                    row_col: true
                },
                Said::Pix {
                    a: 64,
                    b: 48,
                    row_col: false
                },
            ]
        );
    }

    #[test]
    fn a_long_line_is_cut_and_the_next_read() {
        let mut text = "FND 1: 2.0 ".to_string();
        text.push_str(&"x".repeat(3 * MAX_LINE));
        text.push_str(" FND 9: 9.0\nFND 2: 3.0\n");
        let said = read(&text);
        assert_eq!(said.len(), 2);
        assert!(matches!(said[1].said, Said::Found(2, _)) && said[1].line == 2);
        assert!(said[0].text.len() < 200);
    }
}
