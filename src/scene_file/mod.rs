//! Syntax: scene text to records (spec §2-§3). The only module that knows `nom`.
//!
//! The reader follows the course program's `scanf`-then-`fgets` reading exactly: each group
//! skips whitespace (newlines included), reads its N numbers, and ignores the rest of the
//! physical line (spec §2.2). What a number *means* is left to [`crate::scene`]; this module
//! only records values and where they stood.

pub(crate) mod layout;
mod lexeme;

use crate::error::{Found, Pending, SyntaxError};
use layout::{Layout, Slot};
use lexeme::NumberToken;

/// The most lights and objects a scene may hold; beyond it the reader stops with an error
/// instead of exhausting memory.
pub const MAX_RECORDS: usize = 1_000_000;

/// A number and the byte offset where it stood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Number {
    /// The value (always finite).
    pub(crate) value: f64,
    /// Byte offset of its first character.
    pub(crate) at: usize,
}

/// The most numbers a group of the format holds (a position, a colour).
const GROUP_MAX: usize = 3;

/// The numbers of one group, kept in place: a scene of a million records reads six
/// million groups, and an allocation for each cost more than reading their numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GroupNumbers {
    numbers: [Number; GROUP_MAX],
    len: usize,
}

impl GroupNumbers {
    const EMPTY: GroupNumbers = GroupNumbers {
        numbers: [Number { value: 0.0, at: 0 }; GROUP_MAX],
        len: 0,
    };

    fn push(&mut self, number: Number) {
        self.numbers[self.len] = number;
        self.len += 1;
    }

    fn as_slice(&self) -> &[Number] {
        &self.numbers[..self.len]
    }
}

/// What one group holds.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum GroupData {
    /// The numbers of a numeric group, as many as its slot says.
    Numbers(GroupNumbers),
    /// The file-name token of the textured plane.
    FileName(String),
}

/// One group of a record, read according to its [`Slot`].
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Group {
    /// The slot's label (see [`layout::label`]).
    pub(crate) label: &'static str,
    /// Byte offset of its first token.
    pub(crate) at: usize,
    /// Its numbers with their positions, or the text of a texture name.
    pub(crate) data: GroupData,
}

impl Group {
    /// The numbers of a numeric group (empty for a file name).
    pub(crate) fn numbers(&self) -> &[Number] {
        match &self.data {
            GroupData::Numbers(numbers) => numbers.as_slice(),
            GroupData::FileName(_) => &[],
        }
    }
}

/// One record: a type code line (or a `QUADRIC` line) and the groups after it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Record {
    /// The layout the record was read with.
    pub(crate) layout: &'static Layout,
    /// Byte offset of the type code or keyword.
    pub(crate) at: usize,
    /// 1-based line of the type code.
    pub(crate) line: usize,
    /// The ten coefficients of a `QUADRIC` line; empty for numbered records.
    pub(crate) coefficients: Vec<Number>,
    /// The groups, one per slot of the layout.
    pub(crate) groups: Vec<Group>,
}

impl Record {
    /// The group with this label, if the record's layout has one.
    pub(crate) fn group(&self, label: &str) -> Option<&Group> {
        self.groups.iter().find(|g| g.label == label)
    }
}

impl Group {
    /// The group's first `N` numbers, or `None` if it holds fewer (a file name holds none).
    pub(crate) fn values<const N: usize>(&self) -> Option<[f64; N]> {
        let numbers = self.numbers();
        (numbers.len() >= N).then(|| std::array::from_fn(|i| numbers[i].value))
    }
}

/// A whole scene file as records: the header groups and the records in file order.
#[cfg(test)]
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SceneText {
    /// The world window width and height.
    pub(crate) window: Group,
    /// The viewpoint group: x y z.
    pub(crate) viewpoint: Group,
    /// The records, in file order.
    pub(crate) records: Vec<Record>,
    /// If a group's numbers ran across a line break: a note saying which, for any error
    /// found later (the usual cause is a missing number there).
    pub(crate) split: Option<String>,
}

/// The name the header has in messages. A `static`, so that it has one address:
/// `groups` tells the header by it (a `const` may be a different copy at each use).
static HEADER: &Layout = &Layout {
    code: 0,
    name: "header",
    slots: &layout::HEADER,
};

/// Where the reader hands what it reads, as it reads it: a scene of a million records is
/// built record by record instead of being held as text records first.
pub(crate) trait Sink {
    /// The header's two groups: world window and viewpoint.
    fn header(&mut self, window: Group, viewpoint: Group);
    /// The next record, lent: the reader reuses its groups' storage for the one after.
    fn record(&mut self, record: &Record);
}

/// Collects everything: [`read`].
#[cfg(test)]
struct Collect(Option<(Group, Group)>, Vec<Record>);

#[cfg(test)]
impl Sink for Collect {
    fn header(&mut self, window: Group, viewpoint: Group) {
        self.0 = Some((window, viewpoint));
    }

    fn record(&mut self, record: &Record) {
        self.1.push(record.clone());
    }
}

/// Reads the scene text into records, all at once (the tests' view of the reader).
#[cfg(test)]
pub(crate) fn read(text: &str) -> Result<SceneText, Pending> {
    let mut collect = Collect(None, Vec::new());
    let split = read_into(text, &mut collect)?;
    let (window, viewpoint) = collect.0.expect("a header precedes every record");
    Ok(SceneText {
        window,
        viewpoint,
        records: collect.1,
        split,
    })
}

/// Reads the scene text into `sink`, to the end or to the first syntax error. On success,
/// the note on the first group whose numbers ran across a line break, if any (the likely
/// cause of any error found in the numbers later).
pub(crate) fn read_into(text: &str, sink: &mut impl Sink) -> Result<Option<String>, Pending> {
    if text.starts_with('\u{feff}') {
        return Err(Pending::new(0, SyntaxError::ByteOrderMark));
    }
    let mut reader = Reader::new(text, (0, 1), 1);
    // A group that ran on across a line break is legal (scanf reads that way), but it is
    // also what a missing number looks like, and the error then shows up records later.
    read_all(&mut reader, sink).map_err(|error| match reader.splits.first() {
        Some((_, split)) => error.with_note(split.clone()),
        None => error,
    })
}

fn read_all(reader: &mut Reader<'_>, sink: &mut impl Sink) -> Result<Option<String>, Pending> {
    let (window, viewpoint) = reader.header()?;
    sink.header(window, viewpoint);
    let mut records = 0;
    reader
        .records(usize::MAX, sink, |at| match records == MAX_RECORDS {
            true => Err(too_many(at)),
            false => {
                records += 1;
                Ok(true)
            }
        })
        .map_err(|(_, error)| error)?;
    Ok(reader.splits.pop().map(|(_, split)| split))
}

/// The error of a scene whose record starting at `at` is one more than [`MAX_RECORDS`].
pub(crate) fn too_many(at: usize) -> Pending {
    let limit = MAX_RECORDS;
    Pending::new(at, SyntaxError::TooManyRecords { limit })
}

/// The world window and the viewpoint, where the first record starts (the text's length
/// if none does), and the note on the header's group that ran across a line break, if
/// one did; or the header's error, with that note.
pub(crate) fn read_header(text: &str) -> Result<(Group, Group, usize, Option<String>), Pending> {
    if text.starts_with('\u{feff}') {
        return Err(Pending::new(0, SyntaxError::ByteOrderMark));
    }
    let mut reader = Reader::new(text, (0, 1), 1);
    let header = reader.header();
    let split = reader.splits.pop().map(|(_, split)| split);
    let (window, viewpoint) = header.map_err(|error| match &split {
        Some(split) => error.with_note(split.clone()),
        None => error,
    })?;
    reader.skip(lexeme::blank);
    Ok((window, viewpoint, reader.offset(), split))
}

/// What [`read_run`] read.
pub(crate) struct Run {
    /// Where the next record starts, the first at or after `until` (the text's length if
    /// none does), or the one `go_on` stopped at; where the syntax error's record starts.
    pub(crate) next: usize,
    /// The syntax error in the record begun last, which ended the run.
    pub(crate) error: Option<Pending>,
    /// The first `cap` groups that ran on across a line break, each with the line of its
    /// record's start, in file order, and the note [`read_into`] would give for it.
    pub(crate) splits: Vec<(usize, String)>,
}

/// Reads the records from `from` (a record's start, or a guess at one: spec §2 marks no
/// record's start, and a reader started inside a record reads on as scanf would) into
/// `sink`, as [`read_into`] reads them, while they start before `until` and `go_on`,
/// asked each one's start before it is read, says so. `known` is an offset at or before
/// `from` and the line it lies on; `cap` is how many split groups to keep.
pub(crate) fn read_run(
    text: &str,
    (from, until): (usize, usize),
    known: (usize, usize),
    cap: usize,
    sink: &mut impl Sink,
    go_on: impl FnMut(usize) -> Result<bool, Pending>,
) -> Run {
    let mut reader = Reader::new(text, known, cap);
    reader.rest = &text[from..];
    let result = reader.records(until, sink, go_on);
    let (next, error) = match result {
        Ok(next) => (next, None),
        Err((at, error)) => (at, Some(error)),
    };
    Run {
        next,
        error,
        splits: reader.splits,
    }
}

/// The newlines in `bytes`: counted in byte-sized sums of at most 255, which the
/// compiler turns into vector code (a scene of a million records has six million lines).
#[inline(always)]
pub(crate) fn newlines(bytes: &[u8]) -> usize {
    (bytes.chunks(255))
        .map(|chunk| chunk.iter().fold(0u8, |n, &b| n + u8::from(b == b'\n')))
        .map(usize::from)
        .sum()
}

struct Reader<'a> {
    text: &'a str,
    rest: &'a str,
    /// An offset and the 1-based line it lies on: lines are counted from the last one
    /// asked for, since the reader mostly asks for the next.
    counted: std::cell::Cell<(usize, usize)>,
    /// The first `split_cap` groups whose numbers ran across a line break: their
    /// record's line and a description.
    splits: Vec<(usize, String)>,
    split_cap: usize,
    /// The last record's groups, emptied and refilled for the next: one allocation for
    /// a scene rather than one a record.
    spare: Vec<Group>,
}

impl<'a> Reader<'a> {
    /// A reader at the start of `text`, where offset `known.0` lies on line `known.1`,
    /// that keeps `split_cap` split groups.
    fn new(text: &'a str, known: (usize, usize), split_cap: usize) -> Reader<'a> {
        Reader {
            text,
            rest: text,
            counted: std::cell::Cell::new(known),
            splits: Vec::new(),
            split_cap,
            spare: Vec::new(),
        }
    }

    /// The header's two groups: the world window and the viewpoint.
    fn header(&mut self) -> Result<(Group, Group), Pending> {
        let mut header = Vec::new();
        self.groups(HEADER, 0, &mut header)?;
        let [window, viewpoint]: [Group; 2] = header.try_into().map_err(|_| {
            // The header's layout has two groups, each read or an error.
            let (record, label) = ("header", layout::label::WINDOW);
            Pending::new(0, crate::error::MeaningError::Internal { record, label })
        })?;
        Ok((window, viewpoint))
    }

    /// Reads records into `sink` while they start before `until` and `go_on`, asked
    /// each one's start, says so, and returns where the next one starts (the text's
    /// length at its end); or the first syntax error, with where its record starts.
    fn records(
        &mut self,
        until: usize,
        sink: &mut impl Sink,
        mut go_on: impl FnMut(usize) -> Result<bool, Pending>,
    ) -> Result<usize, (usize, Pending)> {
        loop {
            self.skip(lexeme::blank);
            let at = self.offset();
            if self.rest.is_empty() || at >= until || !go_on(at).map_err(|e| (at, e))? {
                return Ok(at);
            }
            let record = self.record().map_err(|e| (at, e))?;
            sink.record(&record);
            self.spare = record.groups;
        }
    }
    fn offset(&self) -> usize {
        self.text.len() - self.rest.len()
    }

    #[inline(always)]
    fn line_of(&self, offset: usize) -> usize {
        let (known, line) = self.counted.get();
        let newlines = |from: usize, to: usize| newlines(&self.text.as_bytes()[from..to]);
        let line = match offset >= known {
            true => line + newlines(known, offset),
            false => line - newlines(offset, known),
        };
        self.counted.set((offset, line));
        line
    }

    /// Runs a parser that cannot fail (whitespace, comments) and moves past what it took.
    fn skip(&mut self, parser: fn(&'a str) -> nom::IResult<&'a str, &'a str>) {
        if let Ok((rest, _)) = parser(self.rest) {
            self.rest = rest;
        }
    }

    /// What stands at the reader's position, for an error message, and where.
    fn found(&self) -> (usize, Found) {
        if self.rest.is_empty() {
            // Point just after the last character the file has, not at a blank last line.
            return (self.text.trim_end().len(), Found::EndOfInput);
        }
        if self.rest.starts_with(['\n', '\r']) {
            return (self.offset(), Found::EndOfLine);
        }
        let token = lexeme::token(self.rest).map_or("", |(_, t)| t);
        // Enough for the message, which cuts a long token short (`error::quoted`).
        let kept = token.char_indices().nth(64).map_or(token.len(), |(i, _)| i);
        (self.offset(), Found::Token(token[..kept].to_string()))
    }

    fn expected(&self, expected: String) -> Pending {
        let (at, found) = self.found();
        Pending::new(at, SyntaxError::Expected { expected, found })
    }

    /// One number: `Ok(None)` when no number stands here.
    fn number(&mut self, expected: impl Fn() -> String) -> Result<Option<Number>, Pending> {
        let at = self.offset();
        // Nearly every number of a scene is a short decimal that one rounding gives
        // (`lexeme::number`'s own first step): taken here without its wrapping.
        if let Some((length, Some(value))) = lexeme::scan_decimal(self.rest) {
            self.rest = &self.rest[length..];
            return Ok(Some(Number { value, at }));
        }
        match lexeme::number(self.rest) {
            Ok((rest, NumberToken::Finite(value))) => {
                self.rest = rest;
                Ok(Some(Number { value, at }))
            }
            Ok((_, NumberToken::NonFinite(text))) => Err(Pending::new(
                at,
                SyntaxError::NonFinite {
                    expected: expected(),
                    text: text.to_string(),
                },
            )),
            Err(_) => Ok(None),
        }
    }

    #[inline(always)]
    fn record(&mut self) -> Result<Record, Pending> {
        let at = self.offset();
        let line = self.line_of(at);
        let mut coefficients = Vec::new();
        let layout = if let Ok((rest, _)) = lexeme::quadric_keyword(self.rest) {
            self.rest = rest;
            for letter in "ABCDEFGHIJ".chars() {
                self.skip(lexeme::line_blank);
                let expected = || format!("coefficient {letter} of the QUADRIC line");
                match self.number(expected)? {
                    Some(number) => coefficients.push(number),
                    None => {
                        let (at, found) = self.found();
                        if matches!(found, Found::Token(_)) {
                            return Err(self.expected(expected()));
                        }
                        let count = coefficients.len();
                        return Err(Pending::new(
                            at,
                            SyntaxError::QuadricLineShort { count, found },
                        ));
                    }
                }
            }
            &layout::QUADRIC
        } else if let Ok((rest, (code, text))) = lexeme::type_code(self.rest) {
            let known = u32::try_from(code).ok();
            if let Some(layout) = known.and_then(layout::of_code) {
                self.rest = rest;
                layout
            } else if let Some((name, hint)) = known.and_then(layout::unsupported) {
                let code = code as u32;
                return Err(Pending::new(
                    at,
                    SyntaxError::Unsupported { code, name, hint },
                ));
            } else {
                let code = text.to_string();
                return Err(Pending::new(at, SyntaxError::UnknownTypeCode { code }));
            }
        } else {
            let error =
                self.expected("a type code (10-24) or QUADRIC to start the next record".into());
            let word = lexeme::token(self.rest).map_or("", |(_, t)| t);
            if word.eq_ignore_ascii_case("QUADRIC") {
                return Err(error.with_note("the keyword is QUADRIC, in upper case".into()));
            }
            return Err(error);
        };
        self.skip(lexeme::comment);
        let mut groups = std::mem::take(&mut self.spare);
        self.groups(layout, at, &mut groups)?;
        Ok(Record {
            layout,
            at,
            line,
            coefficients,
            groups,
        })
    }

    /// Reads the groups of a layout into `groups` (emptied first); `start` is where the
    /// record began, for notes.
    fn groups(
        &mut self,
        layout: &Layout,
        start: usize,
        groups: &mut Vec<Group>,
    ) -> Result<(), Pending> {
        let record = layout.name;
        let start_line = self.line_of(start);
        let note = |pending: Pending| {
            if std::ptr::eq(layout, HEADER) {
                return pending.with_note(
                    "a scene file starts with the world window (2 numbers) and the viewpoint (3)"
                        .to_string(),
                );
            }
            pending
                .with_note(format!("the {record} record starts on line {start_line}"))
                .with_note(layout.describe())
        };
        groups.clear();
        for slot in layout.slots {
            self.skip(lexeme::blank);
            let at = self.offset();
            let data = match *slot {
                Slot::Numbers { label, count } => {
                    let mut numbers = GroupNumbers::EMPTY;
                    for i in 1..=count {
                        let before = self.offset();
                        self.skip(lexeme::blank);
                        let expected = || match count {
                            1 => format!("the {record}'s {label} (1 number)"),
                            _ => {
                                format!("number {i} of the {count} on the {record}'s {label} line")
                            }
                        };
                        // The first such group is the likely cause; later ones follow from it.
                        // Numbers hold no newline, so the group has run on at the first
                        // blank between its numbers that holds one: the one just skipped.
                        let blank = &self.text.as_bytes()[before..self.offset()];
                        let moved_on = || blank.contains(&b'\n');
                        if i > 1 && self.splits.len() < self.split_cap && moved_on() {
                            let group_line = self.line_of(at);
                            let n = i - 1;
                            self.splits.push((start_line, format!(
                                "the {record}'s {label} line (line {group_line}) holds only {n} \
                                 of its {count} numbers, so the rest were read from the \
                                 following lines: is a number missing on line {group_line}?"
                            )));
                        }
                        match self.number(expected) {
                            Ok(Some(number)) => numbers.push(number),
                            Ok(None) => return Err(note(self.expected(expected()))),
                            Err(error) => return Err(note(error)),
                        }
                    }
                    GroupData::Numbers(numbers)
                }
                Slot::FileName { label } => match lexeme::token(self.rest) {
                    Ok((rest, name)) => {
                        self.rest = rest;
                        GroupData::FileName(name.to_string())
                    }
                    Err(_) => {
                        return Err(note(self.expected(format!("the {record}'s {label} name"))));
                    }
                },
            };
            self.skip(lexeme::comment);
            let label = slot.label();
            groups.push(Group { label, at, data });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(group: &Group) -> Vec<f64> {
        group.numbers().iter().map(|n| n.value).collect()
    }

    #[test]
    fn comments_may_hold_numbers_and_blank_lines_separate_groups() {
        let text = "8 6 world 1 2\n0 0 3\n\n13 sphere 99\n\n5 5 15   r g b ambient 5 5 15\n\
                    1 1 1\n0 0 0\n\n0 0 -3 centre\n2\n";
        let scene = read(text).unwrap();
        assert_eq!(values(&scene.window), [8.0, 6.0]);
        let sphere = &scene.records[0];
        assert_eq!(sphere.layout.code, 13);
        assert_eq!(sphere.line, 4);
        assert_eq!(
            values(sphere.group(layout::label::AMBIENT).unwrap()),
            [5.0, 5.0, 15.0]
        );
        assert_eq!(values(sphere.group(layout::label::RADIUS).unwrap()), [2.0]);
    }

    #[test]
    fn a_group_may_continue_on_the_next_line_as_scanf_reads_it() {
        let scene = read("8\n6\n0 0\n3\n").unwrap();
        assert_eq!(values(&scene.viewpoint), [0.0, 0.0, 3.0]);
    }

    #[test]
    fn quadric_coefficients_must_share_the_keyword_line() {
        let good = "8 6\n0 0 3\nQUADRIC 1 0 0 0 1 0 0 1 0 -1 sphere\n1 1 1\n2 2 2\n0 0 0\n";
        let scene = read(good).unwrap();
        assert_eq!(scene.records[0].coefficients.len(), 10);
        let short = "8 6\n0 0 3\nQUADRIC 1 0 0 0 1 0 0 1 0\n-1\n1 1 1\n2 2 2\n0 0 0\n";
        let error = read(short).unwrap_err();
        assert_eq!(
            error.kind,
            SyntaxError::QuadricLineShort {
                count: 9,
                found: Found::EndOfLine
            }
            .into()
        );
    }

    #[test]
    fn end_of_input_points_after_the_last_character() {
        let text = "8 6\n0 0 3\n13\n1 1 1\n\n\n";
        let error = read(text).unwrap_err();
        assert_eq!(error.at, text.trim_end().len());
    }
}
