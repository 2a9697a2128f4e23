//! The comparison report as text, as `legacy-rt compare` prints it and the web page
//! shows it.

use super::causes::Cause;
use super::{Report, Verdict};
use crate::Options;
use crate::render::variant::Site;
use crate::render::variant::output_row;
use crate::render::{Choices, Variant};

/// `path` as a shell word: as it is when it needs no quoting, in single quotes when it
/// does, and in the `$'…'` quotes of bash and zsh, with escapes, when it holds a control
/// or invisible character (a newline or an escape code would otherwise act on the
/// terminal or start a line of its own in the report).
pub fn shell_word(path: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./-+,:=@%".contains(c);
    if !path.is_empty() && path.chars().all(plain) {
        return path.to_string();
    }
    let escaped = crate::error::escaped(path);
    if escaped == path {
        return format!("'{}'", path.replace('\'', r"'\''"));
    }
    let mut word = String::from("$'");
    for c in path.chars() {
        match c {
            '\\' => word.push_str("\\\\"),
            '\'' => word.push_str("\\'"),
            c if crate::error::escaped(&c.to_string()) != c.to_string() => {
                word.push_str(&format!("\\U{:08x}", u32::from(c)));
            }
            c => word.push(c),
        }
    }
    word.push('\'');
    word
}

/// The `trace` command that explains the pixel at (x, y) from the lower left of the
/// reference rendered from the scene file `scene` at `options`' size with `choices`, and
/// with the variants `under` besides (the whole-image causes a decision flip was found
/// under): the pixel whose ray is drawn there (under `--variant upside-down`, the
/// mirrored row's).
pub fn trace_command(
    choices: &Choices,
    options: &Options,
    scene: &str,
    x: usize,
    y: usize,
    under: &[Variant],
) -> String {
    let (w, h) = (options.width, options.height);
    let mut choices = choices.clone();
    choices.variants.extend(under);
    // The options the reference took `under` with: the scene's, where they conflict.
    let traced = options.with_variants(under).unwrap_or(*options);
    // The output row that holds (x, y), then the pixel row traced there.
    let y = traced.row_of(output_row(y.min(h - 1), h, false));
    let flags = choices.flags();
    format!(
        "legacy-rt trace {x} {y} {w} {h}{flags} < {}",
        shell_word(scene)
    )
}

/// 1234567 as "1,234,567".
fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// A share (0 to 1) as a percentage with enough decimals to tell small ones apart.
fn percent_of(share: f64) -> String {
    let p = share * 100.0;
    match p {
        _ if p == 0.0 || p >= 10.0 => format!("{p:.0} %"),
        _ if p >= 1.0 => format!("{p:.1} %"),
        _ => format!("{p:.2} %"),
    }
}

/// How many groups the text report lists; `--json` has them all.
const GROUPS_SHOWN: usize = 8;

/// "1 pixel differs", "1,204 pixels differ".
fn pixels_differ(n: usize) -> String {
    match n {
        1 => "1 pixel differs".to_string(),
        n => format!("{} pixels differ", thousands(n)),
    }
}

/// An agreement (0 to 1) in percent, rounded down to two decimals so that only a full
/// agreement shows as 100.00 %.
fn agreement(share: f64) -> String {
    format!("{:.2} %", (share * 10_000.0).floor() / 100.0)
}

/// The agreement from which the report says that one record's edit explains the image.
const LOCALISED: f64 = 0.99;

/// What a one-record edit does to its record, and where in the student's program to look
/// (its row's advice, the variant's value in it).
fn advice(variant: crate::render::Variant) -> (String, &'static str) {
    match variant.row().advice {
        Some((what, look)) => {
            let value = variant.value.unwrap_or(0.0);
            (what.replace("{}", &value.to_string()), look)
        }
        None => (
            format!("is rendered with --variant {}", variant.id()),
            "the rule it replaces",
        ),
    }
}

/// The report as `legacy-rt compare` prints it: `reference` and `student` name the two
/// files, and `choices` are those the reference was rendered with (`None` when it is an
/// image).
pub fn text(report: &Report, reference: &str, student: &str, choices: Option<&Choices>) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let mut line = |text: String| {
        let _ = writeln!(out, "{text}");
    };
    let (w, h) = (report.width, report.height);
    // Of an image of the wrong size no reference was rendered.
    match choices.filter(|_| report.verdict != Verdict::WrongSize) {
        Some(choices) => {
            let flags = choices.flags();
            let how = match flags.is_empty() {
                true => String::new(),
                false => format!(" with{flags}"),
            };
            line(format!("reference: {reference}, rendered at {w}x{h}{how}"));
        }
        None => line(format!("reference: {reference}")),
    }
    line(format!("student:   {student}"));
    if let (Verdict::WrongSize, Some([ew, eh])) = (report.verdict, report.expected_size) {
        line(format!(
            "size: {w}x{h}, but the image must be {ew}x{eh} (--size): nothing compared"
        ));
        line(format!("verdict: {}", report.verdict.name()));
        return out;
    }
    line(format!(
        "size: {w}x{h}, {} pixels compared",
        thousands(report.pixels)
    ));
    line(format!(
        "beyond the tolerance of {} levels: {} pixels ({})",
        report.tolerance,
        thousands(report.differing_pixels),
        percent_of(report.differing_fraction),
    ));
    if choices.is_some() {
        // With a scene: how many of them a correct tracer may give.
        let counted = report.differing_pixels - report.differing_fragile_pixels;
        line(format!(
            "  of them on fragile pixels (excused): {}; counted: {} ({} may be)",
            thousands(report.differing_fragile_pixels),
            thousands(counted),
            percent_of(report.allow)
        ));
        line(format!(
            "fragile pixels of the reference at precision {:.3e}: {} ({})",
            report.precision,
            thousands(report.fragile_pixels),
            percent_of(report.fragile_pixels as f64 / report.pixels.max(1) as f64)
        ));
    } else {
        line(format!(
            "  {} may be (two images: no pixel is known to be fragile)",
            percent_of(report.allow)
        ));
    }
    line(format!(
        "largest channel difference: {}",
        report.max_channel_difference
    ));
    line(format!(
        "mean absolute error: {:.3} levels per channel",
        report.mean_absolute_error
    ));
    line(format!("verdict: {}", report.verdict.name()));
    if !report.groups.is_empty() {
        line(String::new());
        line("differing pixels by what the reference ray hits first:".to_string());
        for group in report.groups.iter().take(GROUPS_SHOWN) {
            let name = match group.line {
                Some(at) => format!("{} (line {at})", group.object),
                None => group.object.clone(),
            };
            line(format!(
                "  {name}: {}, {} of the differences",
                pixels_differ(group.pixels),
                percent_of(group.share)
            ));
        }
        let rest = &report.groups[report.groups.len().min(GROUPS_SHOWN)..];
        if !rest.is_empty() {
            let pixels = rest.iter().map(|g| g.pixels).sum();
            let share = rest.iter().map(|g| g.share).sum();
            line(format!(
                "  {} more objects: {}, {} of the differences (--json lists them all)",
                rest.len(),
                pixels_differ(pixels),
                percent_of(share)
            ));
        }
    }
    if !report.worst.is_empty() {
        line(String::new());
        line("worst pixels, (0, 0) at the lower left: reference -> student".to_string());
        for worst in &report.worst {
            let [r, g, b] = worst.reference;
            let [sr, sg, sb] = worst.student;
            let at = format!("({}, {})", worst.x, worst.y);
            let mut text = format!(
                "  {at:<12} {r:3} {g:3} {b:3} -> {sr:3} {sg:3} {sb:3}  (by {:3}{})",
                worst.difference,
                if worst.fragile { ", fragile" } else { "" }
            );
            if let Some(trace) = &worst.trace {
                text += &format!("  {trace}");
            }
            line(text);
        }
    }
    let diagnosis = diagnosis(report);
    if !diagnosis.is_empty() {
        line(String::new());
        for text in diagnosis {
            line(text);
        }
    }
    out
}

/// Whether two lists hold the same variants, in any order (a candidate's and its causes').
fn same_variants(a: &[Variant], b: &[Variant]) -> bool {
    a.len() == b.len() && a.iter().all(|v| b.contains(v))
}

/// The diagnosis's lines of the report (empty without `--diagnose`): the variants that
/// explain the student's image, the decisions on the reference's paths whose change
/// gives the student's bytes, the sentence that names one object's or light's
/// mistake, or where the differences concentrate, and the advice to read the student's
/// own trace with `--against`. `compare`'s text ends with them; `grade`'s report shows
/// them for each pair.
pub fn diagnosis(report: &Report) -> Vec<String> {
    let mut out = Vec::new();
    let mut line = |text: String| out.push(text);
    let Some(diagnosis) = &report.diagnosis else {
        return out;
    };
    let causes = report.causes.as_deref().unwrap_or(&[]);
    if report.differing_pixels == 0 {
        line("diagnosis: nothing to explain, every pixel is within the tolerance".into());
    } else if causes.is_empty() {
        line(
            "diagnosis: no cause explains the differences: no mistake of the catalogue \
             (docs/variants.md), alone or two together, makes at least half of the differing \
             pixels agree without making others differ"
                .to_string(),
        );
    } else {
        // The catalogue's candidate, where the causes are its variants (in any order): its
        // agreement.
        let variants: Vec<Variant> = causes.iter().flat_map(|c| c.variants.clone()).collect();
        let whole_image_first = causes.first().is_some_and(|c| c.variants.is_empty());
        let found = (diagnosis.iter())
            .find(|d| same_variants(&d.variants, &variants))
            .filter(|_| !whole_image_first);
        if let Some(found) = found {
            line(format!(
                "diagnosis: the reference agrees with {} of the student's pixels; rendered as \
                 if with",
                agreement(found.agreement_before)
            ));
            let ids: Vec<String> = found.variants.iter().map(|v| v.id()).collect();
            let about: Vec<String> = found.variants.iter().map(|v| v.describe()).collect();
            line(format!(
                "  --variant {}: {} ({})",
                ids.join(","),
                agreement(found.agreement_after),
                about.join("; ")
            ));
        } else {
            let before = 1.0 - report.differing_pixels as f64 / report.pixels.max(1) as f64;
            line(format!(
                "diagnosis: the reference agrees with {} of the student's pixels",
                agreement(before)
            ));
        }
        line(
            "causes, in order, each with the differing pixels it explains (of those left) and \
             the agreeing ones it would make differ:"
                .to_string(),
        );
        for (k, cause) in causes.iter().enumerate() {
            let missing = super::causes::missing_object(&cause.variants).is_some();
            let what = match (cause.variants.is_empty(), &cause.subject) {
                (true, _) => format!("{} ({})", cause.id, cause.about),
                (false, Some(subject)) if missing => format!(
                    "--variant {} ({subject} is missing: no camera, mirror or shadow ray meets \
                     it)",
                    cause.id
                ),
                (false, Some(subject)) => format!("--variant {} ({subject})", cause.id),
                (false, None) => format!("--variant {}", cause.id),
            };
            let mut text = format!(
                "  {}. {what}: explains {} of {}, breaks {}",
                k + 1,
                thousands(cause.explains),
                thousands(cause.of),
                thousands(cause.breaks)
            );
            if let Some(trace) = &cause.trace {
                text += &format!("; `{trace}` traces one");
            }
            line(text);
        }
        // A pair stated together because each hides the other's pixels: its first is no
        // cause alone, and the report says why it is one, with the pair's counts: the
        // catalogue's pair's where it is one, else the two causes' summed.
        if let [first, second, ..] = causes
            && !super::causes::supported(first.explains, first.of, first.breaks)
        {
            // Jitter read against the image the first moves, with a rule of the bytes
            // read so too where there is one: found together, from the images, and
            // counted together.
            // (Jitter has no variant; a rule of the bytes has one, of the bytes' site.)
            let read = |c: &&Cause| {
                let from_images = c.variants.iter().all(|v| v.kind.row().site == Site::Bytes);
                !c.under.is_empty() && c.under == first.variants && from_images
            };
            let moved: Vec<&Cause> = causes[1..].iter().take_while(read).take(2).collect();
            let moved_jitter = moved.iter().any(|c| c.variants.is_empty());
            let together = match moved_jitter {
                true => &causes[..=moved.len()],
                false => &causes[..2],
            };
            let both: Vec<Variant> = (first.variants.iter().chain(&second.variants))
                .copied()
                .collect();
            let pair =
                (diagnosis.iter()).find(|d| !moved_jitter && same_variants(&d.variants, &both));
            let (explains, breaks) = match pair.and_then(|p| Some((p.explains?, p.breaks?))) {
                Some(counts) => counts,
                None => (
                    together.iter().map(|c| c.explains).sum(),
                    together.iter().map(|c| c.breaks).sum(),
                ),
            };
            let which = match together.len() {
                2 => "1 and 2",
                _ => "1, 2 and 3",
            };
            let why = match (moved_jitter, together.len()) {
                (true, 2) => {
                    "the move leaves every jittered pixel, and jitter read in place meets \
                         another pixel's ray"
                }
                (true, _) => {
                    "the move leaves every jittered pixel and every byte the rule stepped, and \
                         jitter read in place meets another pixel's ray"
                }
                (false, _) => "neither alone makes half of them agree without breaking others",
            };
            line(format!(
                "  ({which} hide each other's pixels: {why}; together they explain {} of {} and \
                 break {})",
                thousands(explains),
                thousands(first.of),
                thousands(breaks)
            ));
        }
        // The best, when it is one record's edit that explains nearly everything, in
        // words a student acts on.
        if let Some(best) = diagnosis.first()
            && let (Some(subject), [variant]) = (&best.subject, best.variants.as_slice())
            && best.agreement_after >= LOCALISED
            && causes.iter().any(|c| c.variants == [*variant])
        {
            let (what, look) = advice(*variant);
            let mut sentence = format!(
                "your image agrees with the reference at {} if {subject} {what}: look at {look}",
                agreement(best.agreement_after)
            );
            if let Some(trace) = &best.trace {
                sentence += &format!("; `{trace}` shows one");
            }
            line(sentence);
        }
    }
    line_flips(report, &mut line);
    if let Some(focus) = &report.focus
        && causes.is_empty()
    {
        let part =
            |share: f64, what: &str| (share > 0.0).then(|| format!("{} {what}", percent_of(share)));
        let parts: Vec<String> = [
            part(focus.camera, "where the camera ray hits it"),
            part(focus.shadow, "where it blocks a shadow ray"),
            part(focus.mirror, "where a mirror shows it"),
        ]
        .into_iter()
        .flatten()
        .collect();
        line(format!(
            "the differences concentrate on {}: {} of the differing pixels involve it ({})",
            focus.object,
            percent_of(focus.share),
            parts.join(", ")
        ));
        if let Some(light) = &focus.light {
            line(format!(
                "they follow the term of {}: it lights {} of the differing pixels and {} of \
                 the agreeing ones; look at where your program puts it and how it computes \
                 its distance and direction (spec §4.3)",
                light.light,
                percent_of(light.differing),
                percent_of(light.agreeing)
            ));
        }
        if let Some(differ) = focus.material {
            line(format!(
                "no decision on their paths differs: the colour of {} is computed otherwise \
                 ({} of the pixels where a ray hits it differ, each channel one way); \
                 look at its ambient, diffuse and specular as your program reads them and at \
                 how it computes its terms (spec §4.2)",
                focus.object,
                percent_of(differ)
            ));
        }
    }
    // Where the causes lie only in how the image is written and explain every
    // difference, a debug trace, ray by ray, agrees with the reference: said so, rather
    // than a pixel to trace against it.
    let explained: usize = causes.iter().map(|c| c.explains).sum();
    if !causes.is_empty()
        && causes.iter().all(|c| c.written_only())
        && explained >= report.differing_pixels
    {
        line(
            "the causes above change no ray and no colour, only where each pixel is written \
             or how its colour becomes bytes: a debug trace of your program, ray by ray, \
             agrees with the reference; look at the loop that writes the image and at the \
             conversion to bytes (spec §4.1, §4.7)"
                .to_string(),
        );
        return out;
    }
    // The student's own program can say where it leaves the reference, number by
    // number: its DBG_ trace of a differing pixel, read with --against.
    // Under a row off, the ray that the first cause in a ray or a colour shows at its
    // pixel (the program labels its trace by ray); else the pixel named just above if
    // there is one, else the worst.
    let named = diagnosis
        .first()
        .filter(|best| best.subject.is_some() && best.agreement_after >= LOCALISED)
        .filter(|_| !causes.is_empty())
        .and_then(|best| best.trace.as_ref());
    let worst = report.worst.iter().find_map(|w| w.trace.as_ref());
    if let Some(command) = report.ray_trace.as_ref().or(named).or(worst)
        && let Some((command, scene)) = command.split_once(" < ")
    {
        line(format!(
            "to find the first number where your program goes wrong, build it with its \
             DBG_ flags, run it with 2> dbg.txt and run: `{command} --against dbg.txt < \
             {scene}` (docs/trace.md)"
        ));
    }
    out
}

/// The decision flips of `report`, a line each: what the student's program decides
/// otherwise, on which rays and where, with the counts and a pixel to trace.
fn line_flips(report: &Report, line: &mut impl FnMut(String)) {
    let flips = report.flips.as_deref().unwrap_or(&[]);
    let Some(first) = flips.first() else {
        return;
    };
    let pixels = match first.sampled_from {
        Some(all) => format!(
            "{} of the {} differing pixels no whole-image cause explains (an even sample)",
            thousands(first.of),
            thousands(all)
        ),
        None => format!(
            "the {} differing pixels no whole-image cause explains",
            thousands(first.of)
        ),
    };
    line(format!(
        "decisions on the reference's paths whose change gives the student's bytes, on \
         {pixels}:"
    ));
    for flip in flips {
        let mut text = format!("  - {}", flip.decision);
        if let Some(condition) = &flip.condition {
            text += &format!(" {condition}");
            if let Some(holds) = flip.condition_holds.filter(|&n| n < flip.explains) {
                text += &format!(" ({} of them)", thousands(holds));
            }
        }
        text += &format!(": {} of {}", thousands(flip.explains), thousands(flip.of));
        if let Some(lights) = &flip.lights {
            text += &format!(", toward {lights}");
        }
        text += &match (flip.breaks, flip.breaks_sampled) {
            (0, _) => "; no agreeing pixel whose path takes it would change".to_string(),
            (n, sampled) => format!(
                "; {}{} agreeing pixels whose path takes it would change",
                if sampled { "about " } else { "" },
                thousands(n)
            ),
        };
        text += &format!("; {}", flip.advice);
        if let Some(trace) = &flip.trace {
            text += &format!("; `{trace}` shows one");
        }
        line(text);
    }
}
