//! Reading what a student's program printed with the course's `DBG_*` flags (spec §8):
//! text → one [`Said`] per tag or label, with the line it is on. Every copy of the course
//! program printed a little differently, so nothing here insists on spacing, colons,
//! precision or order: a line is searched for the tags (`PIX`, `WRL`, `FND`, `HIT`, `AMB`,
//! `DIFFUSE`) and the diffuse block's labels, and each takes the numbers that follow it;
//! what is neither (a model dump, matrices, `byte:` lines) is passed over.

/// A number as printed: its value, and half a unit of its last printed digit (what the
/// printing may have rounded away).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num {
    /// The value; NaN for `nan` and `-nan`.
    pub value: f64,
    /// Half a unit of the last digit printed.
    pub half_unit: f64,
}

/// A label of the diffuse block (spec §8), printed on a line of its own and followed by
/// its value(s), on that line or the next.
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

    /// What the label prints, in the words of the reports.
    pub fn words(self) -> &'static str {
        match self {
            Label::HitObject => "hit object id",
            Label::HitPoint => "hit point",
            Label::Normal => "normal at the hit point",
            Label::LightObject => "light id",
            Label::LightCenter => "light centre",
            Label::ToLight => "direction to the light",
            Label::Distance => "distance to the light",
            Label::Cos => "cos θ",
            Label::Emissivity => "emissivity of the light",
            Label::Reflectivity => "diffuse reflectivity",
            Label::Ivec => "intensity with this light (ivec)",
            Label::OccludedBy => "occluded by",
            Label::DistanceWas => "distance to the occluding object",
        }
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
    /// `PIX a b` (the order of x and y differs between copies), or `PIX: ROW = a COL = b`.
    Pix(i64, i64),
    /// `WRL (x, y)`: the pixel's world point.
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

/// One [`Said`] and the line of the file it starts on (from 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// The line number, from 1.
    pub line: usize,
    /// What it said.
    pub said: Said,
}

/// The tags, which may share a line; each runs to the next.
const TAGS: [&str; 10] = [
    "PIX",
    "WRL",
    "FND",
    "HIT",
    "AMB",
    "DIFFUSE",
    "base X",
    "dir X",
    "hits:",
    "total dist is",
];

/// Everything recognised in `text`, in order. Unknown lines, and tags whose numbers are
/// not all there, are passed over.
pub fn read(text: &str) -> Vec<Line> {
    let lines: Vec<&str> = text.lines().collect();
    read_lines(&lines, 0, |_| true)
}

/// What `lines` say, the first being line `first + 1` of the file; only the lines that
/// `wanted` accepts are read (the search for a pixel reads only those with `PIX` or `WRL`,
/// so that a whole image's trace is not held in memory at once).
pub fn read_lines(lines: &[&str], first: usize, wanted: impl Fn(&str) -> bool) -> Vec<Line> {
    let mut out = Vec::new();
    let mut index = 0;
    while index < lines.len() {
        let text = lines[index];
        let line = first + index + 1;
        index += 1;
        if !wanted(text) {
            continue;
        }
        if let Some((label, rest)) = label(text) {
            let mut values = numbers(rest);
            // The value may follow on the next lines (a label line, then its numbers).
            while values.len() < label.count() && index < lines.len() && only_numbers(lines[index])
            {
                values.extend(numbers(lines[index]));
                index += 1;
            }
            if values.len() >= label.count() {
                values.truncate(label.count());
                out.push(Line {
                    line,
                    said: Said::Labelled(label, values),
                });
            }
            continue;
        }
        for (tag, rest) in tagged(text) {
            if let Some(said) = said(tag, rest) {
                out.push(Line { line, said });
            }
        }
    }
    out
}

/// The diffuse block's label that `text` starts with (after spaces), and the rest.
fn label(text: &str) -> Option<(Label, &str)> {
    let trimmed = text.trim_start();
    let lower = trimmed.to_ascii_lowercase();
    LABELS
        .iter()
        .find(|(words, _)| lower.starts_with(words))
        .map(|&(words, label)| (label, &trimmed[words.len()..]))
}

/// Whether `text` holds numbers and nothing else but separators.
fn only_numbers(text: &str) -> bool {
    let rest: String = strip_numbers(text);
    !numbers(text).is_empty()
        && rest
            .chars()
            .all(|c| c.is_whitespace() || matches!(c, ',' | '(' | ')' | '[' | ']' | '-' | ':'))
}

/// `text` without its numbers.
fn strip_numbers(text: &str) -> String {
    let mut out = String::new();
    let mut at = 0;
    for (start, end) in number_spans(text) {
        out.push_str(&text[at..start]);
        at = end;
    }
    out.push_str(&text[at..]);
    out
}

/// The tags in `text` as whole words, each with the text up to the next tag.
fn tagged(text: &str) -> Vec<(&'static str, &str)> {
    let mut found: Vec<(usize, &'static str)> = Vec::new();
    for tag in TAGS {
        let mut from = 0;
        while let Some(at) = text[from..].find(tag) {
            let start = from + at;
            let end = start + tag.len();
            let before = text[..start].chars().next_back();
            let after = text[end..].chars().next();
            let word = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_');
            if !word(before) && !word(after) {
                found.push((start, tag));
            }
            from = end;
        }
    }
    found.sort_unstable();
    let mut out = Vec::new();
    for (k, &(start, tag)) in found.iter().enumerate() {
        let end = found.get(k + 1).map_or(text.len(), |&(next, _)| next);
        out.push((tag, &text[start + tag.len()..end]));
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
        "PIX" => Said::Pix(id(0)?, id(1)?),
        "WRL" => Said::World(*n.first()?, *n.get(1)?),
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
        half_unit: 0.5 * 10f64.powi(exponent - decimals),
    })
}

/// Where the numbers of `text` are: a sign, digits with at most one point, an exponent;
/// or `nan`/`inf` with a sign. A number glued to a word (`X1`, `f3d`) is not one.
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
            // `nan(0x8000)` as some C libraries print it.
            if bytes.get(end) == Some(&b'(')
                && let Some(close) = text[end..].find(')')
            {
                end += close + 1;
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
            i = start + 1;
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
        let nan = numbers("-nan nan inf -inf");
        assert!(nan[0].value.is_nan() && nan[1].value.is_nan());
        assert_eq!(
            (nan[2].value, nan[3].value),
            (f64::INFINITY, f64::NEG_INFINITY)
        );
        // %5.1lf leaves half a tenth; %5.11f half of 1e-11; %e's exponent counts.
        assert_eq!(numbers("2.5")[0].half_unit, 0.05);
        assert!((numbers("0.12345678901")[0].half_unit - 0.5e-11).abs() < 1e-20);
        assert!((numbers("1.25e-3")[0].half_unit - 0.5e-5).abs() < 1e-18);
    }

    #[test]
    fn tags_share_a_line_and_labels_take_the_next() {
        let text = "junk 1 2 3\nPIX    5    3 - WRL (  0.0,   0.0) - FND    0:   8.0 - FND 1: nan -\n\
                    HIT    0:   8.0 (  0.0,   0.0,  -5.0) - The total dist is 8.000000\n\
                    normal at hitpoint\n   0.000    0.000   -1.000\ncos is :\t0.5\nAMB (0.6, 0.6, 0.0) -";
        let said: Vec<_> = read(text).into_iter().map(|l| (l.line, l.said)).collect();
        assert!(matches!(said[0], (2, Said::Pix(5, 3))));
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
    fn text_in_any_alphabet_is_passed_over() {
        assert_eq!(values("é1 ünan −2 ∞ 3"), [3.0]);
        assert!(read("FND é: ñ\nHIT ½ 2 (1, 2, 3)\ncos is ∞").is_empty());
    }

    #[test]
    fn the_row_col_form() {
        let said = read("PIX:  ROW = 12 COL = 7 - ");
        assert_eq!(said[0].said, Said::Pix(12, 7));
    }
}
