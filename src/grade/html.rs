//! index.html: one page, opened from disk, with no script and nothing from the network:
//! the class's table of verdicts and, per pair, the reference, the student's image and
//! the diff side by side with the diagnosis and the worst pixels' trace commands.

use super::{Grades, Row};
use std::collections::HashMap;
use std::fmt::Write;

/// How many of a pair's worst pixels the page lists with their trace commands.
const WORST_SHOWN: usize = 3;

/// `text` safe in HTML text and attribute values.
fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

const STYLE: &str = "
body { font: 14px/1.4 system-ui, sans-serif; margin: 16px; color: #222; }
table.grades { border-collapse: collapse; margin: 8px 0 16px; }
.grades th, .grades td { border: 1px solid #ccc; padding: 4px 8px; text-align: center; }
.grades th:first-child { text-align: left; }
.grades a { color: inherit; }
.match { background: #c8e6c9; } .differ { background: #ffcdd2; }
.wrong-size { background: #ffe0b2; } .missing { background: #e0e0e0; }
.unreadable { background: #f8bbd0; }
.warn, .warning { color: #b71c1c; font-weight: 600; }
.pair { border-top: 1px solid #ccc; padding: 8px 0; }
.pair h3 { margin: 4px 0; font-size: 15px; }
.pair h3 span { padding: 1px 6px; border-radius: 3px; }
.images { display: flex; flex-wrap: wrap; gap: 12px; }
figure { margin: 0; } figcaption { font-size: 12px; color: #555; }
img { display: block; max-width: 240px; image-rendering: pixelated; border: 1px solid #ddd; }
.explanation, pre, code { font: 12px/1.35 ui-monospace, monospace; white-space: pre-wrap;
  overflow-wrap: anywhere; }
pre { background: #f5f5f5; padding: 8px; }
";

/// The trace commands of the pair's worst pixels, as its compare report lists them (the
/// first few).
fn worst_traces(row: &Row) -> Vec<String> {
    #[derive(serde::Deserialize)]
    struct Worst {
        trace: Option<String>,
    }
    #[derive(serde::Deserialize)]
    struct Report {
        #[serde(default)]
        worst: Vec<Worst>,
    }
    let Some(raw) = &row.compare else {
        return Vec::new();
    };
    let report: Option<Report> = serde_json::from_str(raw.get()).ok();
    let worst = report.map_or(Vec::new(), |r| r.worst);
    worst
        .into_iter()
        .filter_map(|w| w.trace)
        .take(WORST_SHOWN)
        .collect()
}

/// The page.
pub fn page(grades: &Grades) -> String {
    let mut out = String::new();
    let title = format!(
        "Grades: {} students x {} scenes",
        grades.students.len(),
        grades.scenes.len()
    );
    let _ = write!(
        out,
        "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{}</h1>\n",
        esc(&title),
        esc(&title)
    );
    let _ = writeln!(
        out,
        "<p>Each pair graded as <code>legacy-rt compare {}</code> grades it{}.</p>",
        esc(&grades.options),
        grades
            .shard
            .as_ref()
            .map(|s| format!("; this is part {} of the pairs", esc(s)))
            .unwrap_or_default()
    );
    verdict_counts(&mut out, grades);
    table(&mut out, grades);
    if !grades.unexpected.is_empty() {
        let _ = writeln!(out, "<h2>Files that are no scene's image</h2>\n<ul>");
        for file in &grades.unexpected {
            let _ = writeln!(out, "<li><code>{}</code></li>", esc(file));
        }
        let _ = writeln!(out, "</ul>");
    }
    let _ = writeln!(out, "<h2>Every pair</h2>");
    for (i, row) in grades.rows.iter().enumerate() {
        pair(&mut out, i, row);
    }
    out + "</body>\n</html>\n"
}

/// The number of pairs of each verdict, and the points given.
fn verdict_counts(out: &mut String, grades: &Grades) {
    let counts = grades.verdicts();
    let given: f64 = grades.rows.iter().map(|r| r.points).sum();
    let possible: f64 = grades.rows.iter().map(|r| r.max_points).sum();
    let counts: Vec<String> = counts
        .iter()
        .map(|(v, n)| format!("<span class=\"{0}\">{n} {0}</span>", esc(v)))
        .collect();
    let _ = writeln!(
        out,
        "<p>{} pairs: {}; {} of {} points given.</p>",
        grades.rows.len(),
        counts.join(", "),
        given,
        possible
    );
}

/// Students down, scenes across, each cell the verdict (a link to the pair) and points.
fn table(out: &mut String, grades: &Grades) {
    let _ = write!(out, "<table class=\"grades\">\n<thead><tr><th>student</th>");
    for scene in &grades.scenes {
        let _ = write!(out, "<th>{}</th>", esc(scene));
    }
    let _ = writeln!(out, "<th>points</th></tr></thead>\n<tbody>");
    // Each student's rows, found once (a class of 50,000 rows stays linear).
    let mut by_student: HashMap<&str, Vec<(usize, &Row)>> = HashMap::new();
    for (i, row) in grades.rows.iter().enumerate() {
        by_student.entry(&row.student).or_default().push((i, row));
    }
    for student in &grades.students {
        let rows = by_student
            .get(student.as_str())
            .map_or(&[][..], Vec::as_slice);
        if rows.is_empty() {
            continue; // another part's student
        }
        let _ = write!(out, "<tr><th>{}</th>", esc(student));
        for scene in &grades.scenes {
            match rows.iter().find(|(_, r)| &r.scene == scene) {
                Some((i, row)) => {
                    // A warning on the row: a mark the grader sees in the table.
                    let mark = match &row.warning {
                        Some(warning) => format!(
                            " <span class=\"warn\" title=\"{}\">warning</span>",
                            esc(warning)
                        ),
                        None => String::new(),
                    };
                    let _ = write!(
                        out,
                        "<td class=\"{0}\"><a href=\"#pair-{i}\">{0}</a>{mark}<br><small>{1}/{2}</small></td>",
                        esc(&row.verdict),
                        row.points,
                        row.max_points
                    );
                }
                None => out.push_str("<td></td>"),
            }
        }
        let given: f64 = rows.iter().map(|(_, r)| r.points).sum();
        let possible: f64 = rows.iter().map(|(_, r)| r.max_points).sum();
        let _ = writeln!(out, "<td>{} / {}</td></tr>", given, possible);
    }
    let _ = write!(out, "</tbody>\n<tfoot><tr><th>matches</th>");
    for scene in &grades.scenes {
        let of: Vec<&Row> = grades.rows.iter().filter(|r| &r.scene == scene).collect();
        let matched = of.iter().filter(|r| r.verdict == "match").count();
        let _ = write!(out, "<td>{matched} / {}</td>", of.len());
    }
    let _ = writeln!(out, "<td></td></tr></tfoot>\n</table>");
}

/// One pair: its heading, images, diagnosis and worst pixels, and compare's report.
fn pair(out: &mut String, i: usize, row: &Row) {
    let differing = row
        .differing_pixels
        .map(|n| format!(", {n} pixels beyond the tolerance"))
        .unwrap_or_default();
    let size = match (row.width, row.height) {
        (Some(w), Some(h)) => format!(", {w}x{h}"),
        _ => String::new(),
    };
    let _ = writeln!(
        out,
        "<section class=\"pair\" id=\"pair-{i}\">\n<h3>{} &middot; {}: <span class=\"{}\">{}</span>{}{}, {}/{} points</h3>",
        esc(&row.student),
        esc(&row.scene),
        esc(&row.verdict),
        esc(&row.verdict),
        esc(&differing),
        esc(&size),
        row.points,
        row.max_points
    );
    if let Some(file) = &row.file {
        let _ = writeln!(out, "<p><code>{}</code></p>", esc(file));
    }
    if let Some(message) = &row.message {
        let _ = writeln!(out, "<p>{}</p>", esc(message));
    }
    if let Some(warning) = &row.warning {
        let _ = writeln!(out, "<p class=\"warning\">warning: {}</p>", esc(warning));
    }
    if let Some(images) = &row.images {
        out.push_str("<div class=\"images\">\n");
        let figures = [
            (images.reference.as_ref(), "reference"),
            (Some(&images.student), "student's image"),
            (
                images.diff.as_ref(),
                "diff: grey where equal; blue, yellow, red by how much; purple where excused",
            ),
        ];
        for (src, caption) in figures {
            if let Some(src) = src {
                let _ = writeln!(
                    out,
                    "<figure><img src=\"{0}\" alt=\"{1}\" loading=\"lazy\"><figcaption>{1}</figcaption></figure>",
                    esc(src),
                    esc(caption)
                );
            }
        }
        out.push_str("</div>\n");
    }
    if !row.explanation.is_empty() {
        let _ = writeln!(
            out,
            "<p class=\"explanation\">{}</p>",
            esc(&row.explanation.join("\n"))
        );
    }
    let worst = worst_traces(row);
    if !worst.is_empty() {
        out.push_str("<p>The worst pixels, traced in the reference:</p>\n<ul>\n");
        for command in worst {
            let _ = writeln!(out, "<li><code>{}</code></li>", esc(&command));
        }
        out.push_str("</ul>\n");
    }
    if let Some(text) = &row.text {
        let _ = writeln!(
            out,
            "<details><summary>compare's report</summary><pre>{}</pre></details>",
            esc(text)
        );
    }
    out.push_str("</section>\n");
}
