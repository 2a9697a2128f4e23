//! `legacy-rt trace [X Y] --against FILE`: a student's own debug trace (spec §8) read
//! against the reference's, for one pixel or for every pixel the file holds.
//!
//! By concern:
//! - [`lex`]: a line of the file → tags, labels and numbers;
//! - [`stream`]: the file → pixel blocks, one at a time (linear time, bounded memory);
//! - [`layout`]: the file's dialect learnt from its first blocks (pixel labels, world
//!   points, ids, units), and where each block's pixel is;
//! - [`path`]: a block, and the reference's trace, grouped into the path's rays;
//! - [`compare`]: the two paths value by value, each difference with the outcome it
//!   changes;
//! - `words`: the reports.

pub mod compare;
pub mod layout;
pub mod lex;
pub mod path;
pub mod stream;
mod words;

pub use compare::Check;
use compare::Comparison;
use layout::{Layout, Located, SAMPLE};
use serde::Serialize;
use std::collections::HashMap;
use std::io::BufRead;

/// What the pixels of a group share: the step, the object, what differs, the outcome.
type GroupKey = (String, Option<String>, String, Option<String>);
use stream::{Block, Blocks};

use crate::render::{Trace, Tracing};
use crate::scene::Scene;

/// Why a student's trace cannot be read against this scene (or this pixel of it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unreadable(pub String);

impl Unreadable {
    /// The message for the student's file shown as `file`, as the command line and the
    /// page give it (without the command line's `error: `).
    pub fn about(&self, file: &str) -> String {
        format!("cannot read {file} against the reference: {}", self.0)
    }
}

/// One pixel's block read against the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The pixel, (0, 0) at the lower left.
    pub pixel: (usize, usize),
    /// The lines of FILE that hold the pixel's block (from 1, inclusive).
    pub lines: (usize, usize),
    /// Where the student's ids start.
    pub id_base: i64,
    /// How the file was read: its dialect, and how the block was found.
    pub notes: Vec<String>,
    /// Every comparison, in the reference's order.
    pub compared: Vec<Check>,
}

impl Report {
    /// The first difference that changes an outcome.
    pub fn first_difference(&self) -> Option<&Check> {
        self.compared.iter().find(|c| c.counts())
    }

    /// How many differences change an outcome.
    pub fn differences(&self) -> usize {
        self.compared.iter().filter(|c| c.counts()).count()
    }

    /// The differences that change nothing (printed values that differ where no
    /// decision and no byte depends on them).
    pub fn harmless(&self) -> impl Iterator<Item = &Check> {
        self.compared
            .iter()
            .filter(|c| !c.agrees && c.outcome.is_none())
    }
}

/// What `trace X Y --against --json` prints (and the page reads): the report with the
/// image's size and the student's file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary<'a> {
    /// The pixel, (0, 0) at the lower left.
    pub pixel: (usize, usize),
    /// The image's width and height.
    pub size: (usize, usize),
    /// The student's file, as named.
    pub file: &'a str,
    /// The lines of the file that hold the pixel's block (from 1, inclusive).
    pub lines: (usize, usize),
    /// Where the student's ids start.
    pub id_base: i64,
    /// Notes on how the trace was read.
    pub notes: &'a [String],
    /// Whether no difference changes an outcome.
    pub agrees: bool,
    /// How many differences change an outcome.
    pub differences: usize,
    /// The first of them.
    pub first_difference: Option<&'a Check>,
    /// Every comparison, in the reference's order.
    pub compared: &'a [Check],
}

impl Report {
    /// The report as `--json` gives it, for an image of `size` and the file `file`.
    pub fn summary<'a>(&'a self, size: (usize, usize), file: &'a str) -> Summary<'a> {
        Summary {
            pixel: self.pixel,
            size,
            file,
            lines: self.lines,
            id_base: self.id_base,
            notes: &self.notes,
            agrees: self.first_difference().is_none(),
            differences: self.differences(),
            first_difference: self.first_difference(),
            compared: &self.compared,
        }
    }

    /// The text report: agreement in a line, or the first difference with both values,
    /// the student's line, the reference's trace around it, and what differs after it.
    pub fn text(&self, scene: &Scene, trace: &Trace, file: &str) -> String {
        words::pixel(self, scene, trace, file)
    }
}

/// A file opened for reading against a scene: its first blocks, its dialect, and the
/// rest of its blocks to come.
struct Opened<R> {
    blocks: Blocks<R>,
    sample: std::vec::IntoIter<Block>,
    layout: Layout,
}

impl<R: BufRead> Opened<R> {
    fn new(scene: &Scene, frame: &Tracing<'_>, input: R) -> Result<Opened<R>, Unreadable> {
        let mut blocks = Blocks::new(input);
        let mut sample = Vec::new();
        while sample.len() < SAMPLE {
            match blocks.next_block()? {
                Some(block) => sample.push(block),
                None => break,
            }
        }
        if !sample.iter().any(Block::traced) {
            return Err(Unreadable(
                "it has no line the course's DBG_ flags print (FND, HIT, AMB or the diffuse \
                 block's labels, spec §8): is it the standard error of the course program \
                 built with them?"
                    .into(),
            ));
        }
        let layout = Layout::learn(scene, frame, &sample);
        same_scene(scene, frame, &layout, &sample)?;
        Ok(Opened {
            blocks,
            sample: sample.into_iter(),
            layout,
        })
    }

    fn next(&mut self) -> Result<Option<Block>, Unreadable> {
        match self.sample.next() {
            Some(block) => Ok(Some(block)),
            None => self.blocks.next_block(),
        }
    }
}

/// Fails when the file cannot be of this scene at this size: most of its ids name none
/// of the scene's records as any copy numbers them, or its world points are those of
/// another image size.
fn same_scene(
    scene: &Scene,
    frame: &Tracing<'_>,
    layout: &Layout,
    sample: &[Block],
) -> Result<(), Unreadable> {
    if let Some((count, id, line)) = layout.unexplained {
        let printed: usize = sample
            .iter()
            .flat_map(|b| &b.items)
            .filter(|i| matches!(i.said, lex::Said::Found(..) | lex::Said::Hit(..)))
            .count();
        // Light centres printed, none of which is one of the scene's lights.
        let centres: Vec<glam::DVec3> = sample
            .iter()
            .flat_map(|b| &b.items)
            .filter_map(|i| match &i.said {
                lex::Said::Labelled(lex::Label::LightCenter, v) => Some(path::vector(v)),
                _ => None,
            })
            .collect();
        let strangers = !centres.is_empty()
            && centres.iter().all(|c| {
                !scene
                    .lights
                    .iter()
                    .any(|l| (l.location - *c).length() <= 1e-3 * (1.0 + c.length()))
            });
        if count * 2 > printed.max(1) || strangers {
            return Err(Unreadable(format!(
                "{count} of its ids (the first {id}, line {line}) name none of this scene's {} \
                 objects and {} lights, however a copy numbers them (from 0, 1 or 100; in file \
                 order or the objects first, spec §7.1): the trace is of another scene",
                scene.objects.len(),
                scene.lights.len()
            )));
        }
    }
    let (w, h) = layout.size;
    if let Some(size) = words::other_size(frame, layout, sample) {
        return Err(Unreadable(format!(
            "its world points are those of a {}x{} image, not {w}x{h}: give W H as the \
             student's program rendered (another image size)",
            size.0, size.1
        )));
    }
    if let Some(layout::FarOff { line, label, world }) = layout.far_off(frame, sample) {
        return Err(Unreadable(format!(
            "its block labelled ({}, {}) (line {line}) has the world point ({}, {}), more than \
             three pixels from that pixel's at {w}x{h}, as most of its blocks do: the trace is \
             of another image size (give W H as the student's program rendered) or of another \
             scene",
            label.0,
            label.1,
            layout::show(world.0),
            layout::show(world.1)
        )));
    }
    Ok(())
}

/// One block read against the reference's trace of where it is.
fn read_block(
    scene: &Scene,
    frame: &Tracing<'_>,
    layout: &Layout,
    block: &Block,
    located: &Located,
) -> (Report, Trace) {
    let (x, y) = located.pixel;
    // The reference's trace of where the block's camera ray goes: a pixel's (its own, or
    // the one its label is off to), or the point it printed.
    let trace = match located.traced {
        Some((i, j)) => frame.trace(i, j).expect("a traced pixel is inside"),
        None => frame.through((x, y), located.through),
    };
    let mut comparison = Comparison {
        scene,
        frame,
        trace: &trace,
        ids: &layout.ids,
        units: layout.units,
        checks: Vec::new(),
    };
    comparison.located(located);
    let theirs = path::student(&block.items);
    let ours = path::reference(&trace);
    comparison.path(&theirs, &ours);
    let mut notes = layout.notes.clone();
    if located.by != "label" {
        notes.push(format!("block found by its {}", located.by));
    }
    let report = Report {
        pixel: (x, y),
        lines: block.lines,
        id_base: layout.ids.numbering.base,
        notes,
        compared: comparison.checks,
    };
    (report, trace)
}

/// Reads the student's file `input` against pixel (x, y) of `scene` traced under
/// `frame`: the pixel's block found (by its label, its world point or its place), and
/// read against the reference's trace of where its camera ray goes. Returns the report
/// and that trace.
pub fn against(
    scene: &Scene,
    frame: &Tracing<'_>,
    (x, y): (usize, usize),
    input: impl BufRead,
) -> Result<(Report, Trace), Unreadable> {
    let mut opened = Opened::new(scene, frame, input)?;
    let mut seen: Vec<(usize, usize)> = Vec::new();
    let mut count = 0;
    while let Some(block) = opened.next()? {
        let Some(located) = opened.layout.locate(frame, &block) else {
            continue;
        };
        count += 1;
        if seen.len() < 2 {
            seen.push(located.pixel);
        } else {
            seen[1] = located.pixel;
        }
        if located.pixel != (x, y) {
            continue;
        }
        if !block.traced() {
            return Err(Unreadable(format!(
                "its block of pixel ({x}, {y}) (lines {}-{}) has no line the course's DBG_ \
                 flags print (FND, HIT, AMB or the diffuse block's labels, spec §8)",
                block.lines.0, block.lines.1
            )));
        }
        return Ok(read_block(scene, frame, &opened.layout, &block, &located));
    }
    let span = match seen.as_slice() {
        [] => "none of its blocks is a pixel of this image".to_string(),
        [only] => format!("its one pixel is ({}, {})", only.0, only.1),
        [first, last] => format!(
            "its {count} pixels run from ({}, {}) to ({}, {})",
            first.0, first.1, last.0, last.1
        ),
        _ => unreachable!("at most two are kept"),
    };
    Err(Unreadable(format!(
        "it has no trace of pixel ({x}, {y}): {span}; trace a pixel it has, or read the whole \
         file (leave out X Y)"
    )))
}

/// The pixels whose first difference is the same: the step, the object, what differs
/// and the outcome it changes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Group {
    /// The step.
    pub event: String,
    /// The object or light, if one.
    pub object: Option<String>,
    /// What differs.
    pub quantity: String,
    /// The outcome it changes.
    pub outcome: Option<String>,
    /// How many pixels.
    pub count: usize,
    /// The first of them, (0, 0) at the lower left.
    pub pixel: (usize, usize),
    /// Its first difference in a sentence.
    pub sentence: String,
    /// Its line in the file.
    pub student_line: usize,
}

/// Every block of a file read against the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Whole {
    /// The image's width and height.
    pub size: (usize, usize),
    /// How many pixel blocks were read.
    pub pixels: usize,
    /// How many agree (no difference changes an outcome).
    pub agree: usize,
    /// How many differ.
    pub differ: usize,
    /// Blocks that are no pixel of the image, or hold nothing a ray prints.
    pub unread: usize,
    /// How the file was read.
    pub notes: Vec<String>,
    /// The differing pixels grouped by their first difference, the largest group first.
    pub groups: Vec<Group>,
}

impl Whole {
    /// Whether every pixel read agrees.
    pub fn agrees(&self) -> bool {
        self.differ == 0
    }

    /// The text report; `command(x, y)` is the command that reads one pixel.
    pub fn text(&self, file: &str, command: impl Fn(usize, usize) -> String) -> String {
        words::whole(self, file, command)
    }
}

/// Reads every pixel block of the student's file `input` against the reference's trace
/// of where it is, one block at a time.
pub fn whole(scene: &Scene, frame: &Tracing<'_>, input: impl BufRead) -> Result<Whole, Unreadable> {
    let mut opened = Opened::new(scene, frame, input)?;
    let mut out = Whole {
        size: opened.layout.size,
        pixels: 0,
        agree: 0,
        differ: 0,
        unread: 0,
        notes: opened.layout.notes.clone(),
        groups: Vec::new(),
    };
    // Each group's place in `groups`, by what its pixels share.
    let mut index: HashMap<GroupKey, usize> = HashMap::new();
    while let Some(block) = opened.next()? {
        let located = opened.layout.locate(frame, &block);
        let Some(located) = located.filter(|_| block.traced()) else {
            out.unread += 1;
            continue;
        };
        out.pixels += 1;
        let (report, _) = read_block(scene, frame, &opened.layout, &block, &located);
        let Some(first) = report.first_difference() else {
            out.agree += 1;
            continue;
        };
        out.differ += 1;
        let key = (
            first.event.clone(),
            first.object.clone(),
            first.quantity.clone(),
            first.outcome.clone(),
        );
        match index.get(&key) {
            Some(&k) => out.groups[k].count += 1,
            None => {
                index.insert(key, out.groups.len());
                out.groups.push(Group {
                    event: first.event.clone(),
                    object: first.object.clone(),
                    quantity: first.quantity.clone(),
                    outcome: first.outcome.clone(),
                    count: 1,
                    pixel: report.pixel,
                    sentence: first.sentence.clone(),
                    student_line: first.student_line,
                });
            }
        }
    }
    // The largest group first; among equals, the one met first.
    out.groups.sort_by_key(|g| std::cmp::Reverse(g.count));
    Ok(out)
}
