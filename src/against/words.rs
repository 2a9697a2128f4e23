//! The reports of `trace --against`: one pixel's (the first difference, the student's
//! line, the reference's trace around it), and a whole file's (how many pixels agree,
//! the differing ones grouped by their first difference).

use super::layout::Layout;
use super::lex::Said;
use super::stream::Block;
use super::{Check, Report, Whole};
use crate::render::{Trace, Tracing};
use crate::scene::Scene;
use std::fmt::Write;

/// One pixel's report.
pub fn pixel(report: &Report, scene: &Scene, trace: &Trace, file: &str) -> String {
    let mut out = String::new();
    let (x, y) = report.pixel;
    let compared = report.compared.len();
    for note in &report.notes {
        let _ = writeln!(out, "note: {note}");
    }
    let harmless: Vec<&Check> = report.harmless().collect();
    let Some(first) = report.first_difference() else {
        let _ = writeln!(
            out,
            "your trace of pixel ({x}, {y}) ({file}, lines {}-{}) agrees with the \
             reference: {compared} values compared within their printed precision",
            report.lines.0, report.lines.1
        );
        harmless_lines(&mut out, &harmless);
        return out;
    };
    let _ = writeln!(
        out,
        "first difference: {}: {}",
        first.place(),
        first.sentence
    );
    let _ = writeln!(
        out,
        "  yours ({file} line {}): {}",
        first.student_line, first.text
    );
    let _ = writeln!(out, "  the reference: {}", first.reference);
    let (readable, starts) = trace.readable_with_starts(scene);
    let lines: Vec<&str> = readable.lines().collect();
    let at = starts.get(first.event_index).copied().unwrap_or(0);
    let from = at.saturating_sub(3);
    let to = (at + 4).min(lines.len());
    let (w, h) = (trace.options.width, trace.options.height);
    let (tx, ty) = trace.pixel;
    let _ = writeln!(
        out,
        "the reference's trace around it (legacy-rt trace {tx} {ty} {w} {h}):"
    );
    for (k, text) in lines.iter().enumerate().take(to).skip(from) {
        let mark = if k == at { ">" } else { " " };
        let _ = writeln!(out, "{mark} {text}");
    }
    let rest: Vec<&Check> = report
        .compared
        .iter()
        .filter(|c| c.counts())
        .skip(1)
        .collect();
    if rest.is_empty() {
        let _ = writeln!(
            out,
            "nothing else changes an outcome ({compared} values compared)"
        );
    } else {
        let _ = writeln!(
            out,
            "after it, {} more differ (a first difference often explains the rest):",
            rest.len()
        );
        check_lines(&mut out, &rest, 5);
        if rest.len() > 5 {
            let _ = writeln!(
                out,
                "  ... and {} more (--json lists them all)",
                rest.len() - 5
            );
        }
    }
    harmless_lines(&mut out, &harmless);
    out
}

/// The differences that change nothing, a line each (three at most).
fn harmless_lines(out: &mut String, harmless: &[&Check]) {
    if harmless.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "{} printed value(s) differ without changing a hit, a shadow or a byte:",
        harmless.len()
    );
    check_lines(out, harmless, 3);
}

/// The first `most` of `checks`, a line each: the student's line, the step, the sentence.
fn check_lines(out: &mut String, checks: &[&Check], most: usize) {
    for check in checks.iter().take(most) {
        let _ = writeln!(
            out,
            "  line {}: {}: {}",
            check.student_line,
            check.place(),
            check.sentence
        );
    }
}

/// A whole file's report.
pub fn whole(report: &Whole, file: &str, command: impl Fn(usize, usize) -> String) -> String {
    let mut out = String::new();
    for note in &report.notes {
        let _ = writeln!(out, "note: {note}");
    }
    let (w, h) = report.size;
    let _ = writeln!(
        out,
        "{file}: {} pixel blocks of the {w}x{h} image read; {} agree with the reference, {} differ",
        report.pixels, report.agree, report.differ
    );
    if report.unread > 0 {
        let _ = writeln!(
            out,
            "  ({} blocks are no pixel of the image or hold nothing a ray prints)",
            report.unread
        );
    }
    if report.groups.is_empty() {
        return out;
    }
    let _ = writeln!(out, "the differing pixels by their first difference:");
    for group in &report.groups {
        let object = group
            .object
            .as_ref()
            .map_or(String::new(), |o| format!(", {o}"));
        let (x, y) = group.pixel;
        let _ = writeln!(
            out,
            "  {} pixels: {}{object}: {}",
            group.count, group.event, group.quantity
        );
        let _ = writeln!(
            out,
            "    e.g. ({x}, {y}), line {}: {}",
            group.student_line, group.sentence
        );
        let _ = writeln!(out, "    {}", command(x, y));
    }
    out
}

/// The image size whose grid a file's world points are on, where it is another than the
/// one given and the labels say which pixel each point is: solved for from each labelled
/// block's point (spec §4.1 read backwards), and the same for every block.
pub fn other_size(
    frame: &Tracing<'_>,
    layout: &Layout,
    sample: &[Block],
) -> Option<(usize, usize)> {
    if !layout.world.is_some_and(|w| w.jittered)
        || !matches!(layout.labels, super::layout::Labels::XY)
    {
        return None;
    }
    let first = frame.world(0, 0);
    let (w, h) = layout.size;
    let last = frame.world(w - 1, h - 1);
    let (span_x, span_y) = (last.x - first.x, last.y - first.y);
    let mut size: Option<(i64, i64)> = None;
    for block in sample {
        let (Some((a, b, _)), Some(world)) = (block.label(), block.world()) else {
            continue;
        };
        let Said::World(wx, wy) = world.said else {
            continue;
        };
        if a <= 0 || b <= 0 {
            continue;
        }
        // a / (W' - 1) · span = wx - first.x.
        let fx = a as f64 * span_x / (wx.value - first.x);
        let fy = b as f64 * span_y / (wy.value - first.y);
        if !(fx.is_finite() && fy.is_finite() && fx > 0.5 && fy > 0.5 && fx < 1e6 && fy < 1e6) {
            return None;
        }
        let this = (fx.round() as i64 + 1, fy.round() as i64 + 1);
        if size.is_some_and(|s| s != this) {
            return None;
        }
        size = Some(this);
    }
    size.map(|(w, h)| (w as usize, h as usize))
}
