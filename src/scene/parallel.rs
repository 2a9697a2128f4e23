//! Reading a large scene on several threads, into the scene (or the error) that reading
//! it from the start gives.
//!
//! Spec §2 marks no record's start: a record is a type code line and then as many
//! numbers as its layout asks for, read as scanf reads them, across lines if need be. So
//! the text is cut into chunks at line starts, and each chunk is read from a guess: its
//! first line that starts a run of records without a syntax error in its first two.
//! Read from a wrong guess, a chunk's records are not the file's; that is found when
//! the chunks are joined in file order. Where the record after the last one taken so
//! far starts at one of a chunk's record starts, the reading from there on is the
//! reading from the start (a reader's state between records is only its offset), and
//! the chunk's records from there are taken as they are; otherwise the records are read
//! again, on the joining thread, until they meet one of the chunk's starts. A guess that
//! was right costs nothing; a wrong one costs only the time the records it missed take
//! to read.
//!
//! Everything the reading from the start decides is decided again when joining: which
//! error comes first (a syntax error anywhere, then the first error of meaning), the
//! note on the first group that ran across a line break, the records beyond
//! [`MAX_RECORDS`]. The chunks together read at most twice that many records, so a file
//! of too many records cannot exhaust memory here either.

use super::Files;
use super::Scene;
use super::build::Builder;
use crate::error::Pending;
use crate::scene_file::{MAX_RECORDS, Run, Sink, newlines, read_header, read_run, too_many};
use crate::threads::Threads;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The smallest text read on several threads: below it (about 20,000 records) reading
/// costs less than starting to share it.
const PARALLEL_FROM_BYTES: usize = 1 << 20;

/// Chunks per thread: more chunks even out the threads' shares.
pub(super) const CHUNKS_PER_THREAD: usize = 4;

/// How many groups that ran across a line break a chunk keeps: the first of those in
/// the records taken is the one the note names.
const SPLITS_KEPT: usize = 16;

/// How many lines of a chunk are tried as its first record's start.
const GUESSES: usize = 64;

/// Records read together before the shared count of records is updated.
const COUNT_BATCH: usize = 1024;

/// Whether reading `text` on `threads` pays: there are several, and the text is large.
pub(super) fn pays(text: &str, threads: &Threads) -> bool {
    threads.count() > 1 && text.len() >= PARALLEL_FROM_BYTES
}

/// The scene of `text` read in `chunks` chunks on `threads`.
pub(super) fn load_in_chunks(
    text: &str,
    files: &dyn Files,
    threads: &Threads,
    chunks: usize,
) -> Result<Scene, Pending> {
    let (window, viewpoint, first, split) = read_header(text)?;
    let mut main = Builder::new(files);
    main.header(window, viewpoint);
    let chunks = chunks.max(1);
    // Chunk k is text[bounds[k]..bounds[k + 1]], each bound a line's start.
    let mut bounds = vec![first];
    for k in 1..chunks {
        let cut = (first + (text.len() - first) * k / chunks).max(bounds[k - 1]);
        // A cut may fall inside a character; the newline after it is a character's end.
        let newline = text.as_bytes()[cut..].iter().position(|&b| b == b'\n');
        let line_start = newline.map_or(text.len(), |n| cut + n + 1);
        bounds.push(line_start.max(bounds[k - 1]));
    }
    bounds.push(text.len());
    let between = |from: usize, to: usize| newlines(&text.as_bytes()[from..to]);
    let mut lines = vec![1 + between(0, first)];
    for count in threads.map(chunks, |k| between(bounds[k], bounds[k + 1])) {
        lines.push(lines.last().unwrap() + count);
    }
    let read = AtomicUsize::new(0);
    let parts = threads.map(chunks, |k| {
        Part::read(
            text,
            files,
            (bounds[k], bounds[k + 1]),
            lines[k],
            k == 0,
            &read,
        )
    });
    for part in &parts {
        main.reserve_for(&part.builder);
    }
    let mut join = Join {
        text,
        threads,
        main,
        at: first,
        records: 0,
        split,
    };
    for (k, part) in parts.into_iter().enumerate() {
        join.chunk(part, (bounds[k], bounds[k + 1]), lines[k])?;
    }
    join.main.finish(join.split)
}

/// A chunk's records, read from a guess at its first record's start.
struct Part<'f> {
    builder: Builder<'f>,
    /// Where each record read starts, in order (the one with the syntax error included).
    starts: Vec<usize>,
    run: Run,
}

impl<'f> Part<'f> {
    /// The records of the chunk `from..until`, whose first line is `line`: read from
    /// `from` when it is known to be a record's start (`known`), else from the first of
    /// its lines where reading meets no syntax error in the first two records. `read`
    /// counts the records all chunks have read: past twice [`MAX_RECORDS`], a chunk
    /// stops (to be read on when joining, if its records are needed).
    fn read(
        text: &str,
        files: &'f dyn Files,
        (from, until): (usize, usize),
        line: usize,
        known: bool,
        read: &AtomicUsize,
    ) -> Part<'f> {
        let mut guess = from;
        for _ in 0..GUESSES {
            let mut builder = Builder::new(files);
            let mut starts = Vec::new();
            let mut batch = 0;
            let go_on = |at| {
                batch += 1;
                if batch == COUNT_BATCH {
                    batch = 0;
                    if read.fetch_add(COUNT_BATCH, Ordering::Relaxed) > 2 * MAX_RECORDS {
                        return Ok(false);
                    }
                }
                starts.push(at);
                Ok(true)
            };
            let run = read_run(
                text,
                (guess, until),
                (from, line),
                SPLITS_KEPT,
                &mut builder,
                go_on,
            );
            let wrong = !known && run.error.is_some() && starts.len() <= 2;
            let next_line = text[guess..until].find('\n').map(|n| guess + n + 1);
            match (wrong, next_line) {
                (true, Some(next)) if next < until => guess = next,
                (true, _) => break,
                (false, _) => {
                    return Part {
                        builder,
                        starts,
                        run,
                    };
                }
            }
        }
        // No guess held: the chunk is read when joining.
        Part {
            builder: Builder::new(files),
            starts: Vec::new(),
            run: Run {
                next: from,
                error: None,
                splits: Vec::new(),
            },
        }
    }
}

/// The chunks joined in file order.
struct Join<'t, 'f> {
    text: &'t str,
    threads: &'t Threads,
    /// The scene so far.
    main: Builder<'f>,
    /// Where the next record starts.
    at: usize,
    /// The records so far.
    records: usize,
    /// The note on the first group so far that ran across a line break.
    split: Option<String>,
}

impl Join<'_, '_> {
    /// Takes the records of chunk `from..until`, whose first line is `line`, from `part`
    /// where they are the file's, reading the others; or the scene's error.
    fn chunk(
        &mut self,
        part: Part<'_>,
        (from, until): (usize, usize),
        line: usize,
    ) -> Result<(), Pending> {
        let mut part = Some(part);
        let line_of = |at: usize| line + newlines(&self.text.as_bytes()[from..at]);
        while self.at < until {
            let at = self.at;
            let index = part.as_ref().and_then(|p| p.starts.binary_search(&at).ok());
            if let Some((index, taken)) = index.and_then(|index| Some((index, part.take()?))) {
                let record_line = line_of(at);
                if self.takes(&taken, record_line) {
                    self.take(taken, index, record_line, &line_of)?;
                    continue;
                }
                // Not taken here, nor further on (the reason holds there too).
            }
            // Read on to the chunk's end or to a start of `part`'s.
            let starts = part.as_ref().map_or(&[][..], |p| &p.starts[..]);
            let records = &mut self.records;
            let go_on = |next: usize| {
                if next != at && starts.binary_search(&next).is_ok() {
                    return Ok(false);
                }
                if *records == MAX_RECORDS {
                    return Err(too_many(next));
                }
                *records += 1;
                Ok(true)
            };
            let cap = usize::from(self.split.is_none());
            let run = read_run(
                self.text,
                (at, until),
                (from, line),
                cap,
                &mut self.main,
                go_on,
            );
            if self.split.is_none() {
                self.split = run.splits.into_iter().next().map(|(_, split)| split);
            }
            if let Some(error) = run.error {
                return Err(self.noted(error));
            }
            self.at = run.next;
        }
        Ok(())
    }

    /// Whether `part`'s records from the one at line `line` can be taken: what they
    /// built is all there (or not needed after an earlier error), and the first group
    /// among them that ran across a line break is known (or not needed).
    fn takes(&self, part: &Part<'_>, line: usize) -> bool {
        let built = self.main_has_error() || part.builder.holds_from(line);
        let splits = &part.run.splits;
        let split_known = self.split.is_some()
            || splits.len() < SPLITS_KEPT
            || splits.last().is_some_and(|&(l, _)| l >= line);
        built && split_known
    }

    fn main_has_error(&self) -> bool {
        self.main.has_error()
    }

    /// Takes `part`'s records from number `index` on, the one at line `line`: or the
    /// error they end in, or the error of a record beyond [`MAX_RECORDS`].
    fn take(
        &mut self,
        part: Part<'_>,
        index: usize,
        line: usize,
        line_of: &impl Fn(usize) -> usize,
    ) -> Result<(), Pending> {
        let Part {
            builder,
            starts,
            run,
        } = part;
        let first_split = |before: usize| {
            let mut splits = run.splits.iter();
            (splits.find(|&&(l, _)| l >= line && l < before)).map(|(_, split)| split.clone())
        };
        let count = starts.len() - index;
        if self.records + count > MAX_RECORDS {
            let at = starts[index + MAX_RECORDS - self.records];
            if self.split.is_none() {
                self.split = first_split(line_of(at));
            }
            return Err(self.noted(too_many(at)));
        }
        if self.split.is_none() {
            self.split = first_split(usize::MAX);
        }
        self.records += count;
        self.main.adopt(builder, line, self.threads);
        if let Some(error) = run.error {
            return Err(self.noted(error));
        }
        self.at = run.next;
        Ok(())
    }

    /// A syntax error with the note on the first group before it that ran across a line
    /// break, as [`crate::scene_file::read_into`] gives it.
    fn noted(&self, error: Pending) -> Pending {
        match &self.split {
            Some(split) => error.with_note(split.clone()),
            None => error,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::InMemory;
    use crate::shapes::testing::Numbers;
    use std::sync::Arc;

    /// What loading gives, comparable: the scene with which objects share their
    /// predecessor's look, or the error as the user reads it.
    fn outcome(text: &str, result: Result<Scene, Pending>) -> Result<(Scene, Vec<bool>), String> {
        let scene = result.map_err(|pending| pending.locate(text).to_string())?;
        let objects = &scene.objects;
        let shared = (1..objects.len())
            .map(|i| Arc::ptr_eq(&objects[i].look, &objects[i - 1].look))
            .collect();
        Ok((scene, shared))
    }

    /// `text` read in each of several chunkings on three threads gives what reading it
    /// from the start gives.
    fn same_in_chunks(text: &str, name: &str) {
        let files = InMemory::new();
        let mut one = Builder::new(&files);
        let whole = crate::scene_file::read_into(text, &mut one).and_then(|s| one.finish(s));
        let whole = outcome(text, whole);
        let threads = Threads::new(3);
        for chunks in [2, 3, 5, 8, 13, 40, 200] {
            let parts = outcome(text, load_in_chunks(text, &files, &threads, chunks));
            assert_eq!(parts, whole, "{name} in {chunks} chunks");
        }
    }

    /// The scene files of the course, of the examples and of the error messages'
    /// tests.
    #[test]
    fn real_scenes_and_errors_read_in_chunks_as_from_the_start() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let folders = ["../shared/course-scenes", "examples", "tests/invalid"];
        let mut read = 0;
        for folder in folders.map(|f| root.join(f)) {
            let Ok(entries) = std::fs::read_dir(&folder) else {
                assert!(
                    !folder.ends_with("examples"),
                    "examples/ is in the repository"
                );
                continue;
            };
            for path in entries.map(|e| e.unwrap().path()) {
                if path.extension().is_some_and(|e| e == "txt") {
                    let bytes = std::fs::read(&path).unwrap();
                    let text = String::from_utf8_lossy(&bytes);
                    same_in_chunks(&text, &path.display().to_string());
                    read += 1;
                }
            }
        }
        assert!(read >= 20, "{read} files read");
    }

    /// A random record of each kind, in the course's layout, its numbers sometimes
    /// spread over lines or followed by comments that hold numbers, sometimes broken.
    fn record(numbers: &mut Numbers, broken: bool) -> String {
        let mut n = || (numbers.within(-9.0, 9.0) * 8.0).round() / 8.0;
        let material = [
            "1 0.5 0.5 ambient 2 of 3\n2 2 2\n0 0 0\n",
            "0.2 0.2 0.2\n1 1 1\n0 0 0\n",
        ][usize::from(n() > 0.0)];
        let mut record = match (n() + 9.0) as usize % 7 {
            0 => format!("10 light 13\n20 20 20\n{} {} {}\n", n(), n(), n()),
            1 => format!("11\n9 9 9\n{} 4 2\n0 0 -5\n30 degrees\n", n()),
            2 => format!("14 plane\n{material}0 1 0\n0 {} 0\n", n()),
            3 => format!("22\n{material}{} 0 -9\n0 1 0\n1 2\n", n()),
            4 => format!("QUADRIC 1 1 1 0 0 0 0 0 0 -{}\n{material}", n().abs() + 1.0),
            5 => format!("15\n{material}0 0 1\n{} 0 -8\n1 0 0\n2 3\n", n()),
            _ => format!(
                "13\n{material}{} {}\n{}\n0.{}\n",
                n(),
                n(),
                n(),
                1 + (n().abs() as u32)
            ),
        };
        if broken {
            // A number gone (a group runs on, or the file ends short), a radius that
            // no sphere has, a word where a number stands, an unknown code.
            let edits = ["", "-", "x", "12\n"];
            let at = (n().abs() * 7.0) as usize % record.len();
            let edit = edits[(n() + 9.0) as usize % 4];
            let cut = record
                .char_indices()
                .map(|(i, _)| i)
                .find(|&i| i >= at)
                .unwrap();
            record.insert_str(cut, edit);
            if edit.is_empty() {
                record.remove(cut);
            }
        }
        record
    }

    /// Generated scenes of many records, some with an error (of syntax or of meaning)
    /// somewhere: every chunking reads what reading from the start reads.
    #[test]
    fn generated_scenes_read_in_chunks_as_from_the_start() {
        let mut numbers = Numbers(0x2026_1127);
        for scene in 0..60 {
            let mut text = String::from("8 6 world\n0 0 3\n");
            let broken = scene % 3 == 0;
            for k in 0..80 {
                let breaks = broken && numbers.within(0.0, 1.0) < 0.03 && k > 0;
                text.push_str(&record(&mut numbers, breaks));
                if numbers.within(0.0, 1.0) < 0.2 {
                    text.push('\n');
                }
            }
            same_in_chunks(&text, &format!("scene {scene}:\n{text}"));
        }
    }

    /// Records whose every line could start one (each number a type code): guesses
    /// inside a record read on without an error, out of step with the file, and the
    /// join must find where the two meet or read the chunk itself.
    #[test]
    fn records_of_type_codes_alone_read_in_chunks_as_from_the_start() {
        let spheres = "13\n13 13 13\n13 13 13\n0 0 0\n13 13 -13\n13\n".repeat(60);
        let lights = "10\n13 13 13\n13 13 13\n".repeat(30);
        let spread = "13\n13\n13\n13\n13 13\n13\n13 13 13\n0 0 0\n13 13 -13\n13\n".repeat(40);
        for (name, records) in [
            ("spheres", &spheres),
            ("lights", &lights),
            ("spread", &spread),
        ] {
            let text = format!("8 6\n0 0 3\n{records}{records}");
            same_in_chunks(&text, name);
        }
        // The first group that runs across a line break far into the file, and an error
        // at its end whose message notes that group.
        let text = format!("8 6\n0 0 3\n{spheres}{lights}{spread}13\n1 1 1\n1");
        same_in_chunks(&text, "split groups, then an error");
        // The header's viewpoint run on to the next line, and an error far on: its
        // message notes the header (the fuzzer's second find).
        let text = format!("8 6\n0 0\n3\n{spheres}19\n1 1 1\n1 1 1\n0 0 0\n0 0 -9\n1\n2\n");
        same_in_chunks(&text, "a split header, then an error");
        // Comments of characters of several bytes: chunks are cut inside them.
        let accents =
            "13 sphère ☀☀\n1 1 1 ambiante ☀\n2 2 2 diffuse ☀\n0 0 0\n0 0 -9 ☀☀☀\n1 rayon\n";
        same_in_chunks(&format!("8 6\n0 0 3\n{}", accents.repeat(40)), "accents");
    }
}
