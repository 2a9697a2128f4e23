//! `legacy-rt compare`: a student's image against the reference, where they differ, on
//! which objects, and which mistake explains it (spec §7.3's variants).
//!
//! [`report`] does it all: with a scene it renders the reference at the student image's
//! size, counts the pixels beyond the tolerance, groups them by the object the reference
//! ray hits first, lists the worst, and with `diagnose` tries every variant
//! ([`diagnose()`]). Everything here works on bytes in memory; reading files and
//! printing are the command line's.

pub mod causes;
mod diagnose;
pub mod flips;
mod margins;
mod reach;
pub mod read;
mod reference;
mod retrace;
pub mod text;

pub use reach::{Paths, Reach};
pub(crate) use reach::{Steps, packed};
pub use reference::{FirstHit, Fragility, Mark, render_with_margins, render_with_paths};
pub(crate) use retrace::by_distance;
pub use retrace::{
    Involved, PathChange, involved, path_agreement, path_agreement_at, render_forced,
    render_pixels, unblocked_at,
};

pub use diagnose::{
    Diagnosis, Focus, PROBE_LIMIT, diagnose, diagnose_and_focus, estimate_max_dist, roundest,
};
pub use read::{ReadError, read_image};

use crate::render::variant::{Site, output_row};
use crate::render::{Image, Options, Variant};
use crate::scene::Scene;
use serde::Serialize;

/// How close the student's image must be (the defaults pass a correct implementation,
/// see [`Tolerance::default`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// The largest per-channel difference, in byte levels, that still counts as equal.
    pub levels: u8,
    /// The share of pixels (0 to 1) that may differ by more on pixels the reference is
    /// sure of.
    pub allow: f64,
    /// The relative precision of the arithmetic a correct tracer is granted: where a
    /// decision of the reference came closer than this to going the other way, the
    /// pixel is fragile and a difference there is excused ([`Fragility`]).
    pub precision: f64,
}

/// The precision of `--precision f32`: what a correct tracer in single precision needs
/// (docs/compare.md has the measurements that chose it).
pub const F32: f64 = 16.0 * f32::EPSILON as f64;

/// The precision of `--precision f64`, for a tracer in double precision.
pub const F64: f64 = 16.0 * f64::EPSILON;

impl Default for Tolerance {
    /// 0 levels, no pixel the reference is sure of, and the precision of single
    /// precision arithmetic. The course's byte rule truncates (spec §4.7), so a tracer
    /// that computes what the spec says gets the same bytes wherever the reference's
    /// decisions are not fragile; where it does not, it is a mistake. A correct tracer
    /// differs only on fragile pixels: silhouettes where a grazing ray's root rounds the
    /// other way, tile edges, bytes at a step (docs/compare.md).
    fn default() -> Self {
        Tolerance {
            levels: 0,
            allow: 0.0,
            precision: F32,
        }
    }
}

/// The reference image and, when it was rendered from the scene, how sure it is of each
/// pixel and which object each camera ray hits first (output order).
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// The reference's pixels.
    pub image: Image,
    /// Per pixel, what a correct tracer may get otherwise and the object the camera ray
    /// hits first; empty for an image given as the reference (then no pixel is excused).
    pub marks: Vec<Mark>,
    /// Per pixel, what its path involves (rendered for `--diagnose`, else empty): the
    /// diagnosis re-traces only the pixels a candidate can change ([`Reach`]).
    pub paths: Vec<Paths>,
}

impl Reference {
    /// A reference given as an image: nothing is known of its pixels.
    pub fn image(image: Image) -> Reference {
        Reference {
            image,
            marks: Vec::new(),
            paths: Vec::new(),
        }
    }

    /// Pixel `i`'s fragility (none for an image).
    pub fn fragility(&self, i: usize) -> Fragility {
        self.marks.get(i).map(|m| m.fragility()).unwrap_or_default()
    }
}

/// Whether the images match within the tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// At most `allow` of the pixels differ by more than `levels`.
    Match,
    /// More pixels than `allow` differ by more than `levels`.
    Differ,
    /// The student's image is not of the size the grader fixed (`--size`): nothing was
    /// compared.
    WrongSize,
}

impl Verdict {
    /// The verdict as the report and the JSON write it.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Match => "match",
            Verdict::Differ => "differ",
            Verdict::WrongSize => "wrong-size",
        }
    }
}

/// Two images of different sizes.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "the images differ in size: the reference is {reference_width}x{reference_height}, \
     the student's {student_width}x{student_height}"
)]
pub struct SizeMismatch {
    /// The reference's width.
    pub reference_width: usize,
    /// The reference's height.
    pub reference_height: usize,
    /// The student's width.
    pub student_width: usize,
    /// The student's height.
    pub student_height: usize,
}

/// The differing pixels on one object (or the background) of the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Group {
    /// The object's kind ("cone", "tiled plane"), or "background".
    pub object: String,
    /// The line of its type code; `None` for the background.
    pub line: Option<usize>,
    /// Its index among the scene's objects (file order, from 0); `None` for the
    /// background.
    pub index: Option<usize>,
    /// How many of its pixels differ beyond the tolerance.
    pub pixels: usize,
    /// Their share of all the differing pixels (0 to 1).
    pub share: f64,
}

/// One of the most different pixels.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Worst {
    /// Column, 0 at the left.
    pub x: usize,
    /// Row, 0 at the **bottom** (the course's convention, spec §4.1).
    pub y: usize,
    /// The reference's bytes.
    pub reference: [u8; 3],
    /// The student's bytes.
    pub student: [u8; 3],
    /// The largest channel difference.
    pub difference: u8,
    /// Whether the difference is excused: the reference's pixel is fragile.
    pub fragile: bool,
    /// The command that explains the reference's pixel, when the command line knows the
    /// scene's file name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trace: Option<String>,
}

/// Everything `compare` says.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Match or differ.
    pub verdict: Verdict,
    /// The width of both images, in pixels.
    pub width: usize,
    /// The height of both images, in pixels.
    pub height: usize,
    /// Pixels compared (width × height).
    pub pixels: usize,
    /// The tolerance in byte levels.
    pub tolerance: u8,
    /// The share of pixels allowed beyond it (0 to 1).
    pub allow: f64,
    /// The precision granted to a correct tracer (relative).
    pub precision: f64,
    /// Pixels with a channel differing by more than the tolerance.
    pub differing_pixels: usize,
    /// Pixels where a correct tracer may get another colour: some decision of the
    /// reference came within the precision of going the other way (0 without a scene).
    pub fragile_pixels: usize,
    /// Differing pixels excused as fragile: not counted against the image.
    pub differing_fragile_pixels: usize,
    /// Their share (0 to 1).
    pub differing_fraction: f64,
    /// The largest channel difference anywhere.
    pub max_channel_difference: u8,
    /// The mean absolute channel difference, in byte levels.
    pub mean_absolute_error: f64,
    /// The differing pixels by the object the reference ray hits first, largest first
    /// (empty when comparing two images).
    pub groups: Vec<Group>,
    /// The worst pixels, largest difference first.
    pub worst: Vec<Worst>,
    /// With diagnose: the variants that explain the student's image better than the
    /// reference does, best first.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diagnosis: Option<Vec<Diagnosis>>,
    /// With diagnose: the object the differing pixels' paths involve most, and how.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub focus: Option<Focus>,
    /// With diagnose: the causes the pixels support, in order, each with the differing
    /// pixels it explains and the agreeing ones it breaks; empty when none explains at
    /// least half of what was left.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub causes: Option<Vec<causes::Cause>>,
    /// With diagnose: the groups of the differing pixels (those the whole-image causes
    /// leave) that one decision on the reference's path, or two, forced the other way
    /// explains, largest first, each with what its decisions share.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flips: Option<Vec<flips::Flip>>,
    /// The size the grader required (`--size W H`), when the student's image has
    /// another: `[W, H]` with verdict `wrong-size`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub expected_size: Option<[usize; 2]>,
    /// With diagnose, where the first cause in a ray or a colour was found under causes
    /// that move the pixels (a row off): the pixel whose ray its pixel shows, as the
    /// student's program labels that ray in its debug trace (not in the JSON).
    #[serde(skip)]
    pub ray_pixel: Option<[usize; 2]>,
    /// The command that traces `ray_pixel`, when the command line knows the scene's file
    /// name (not in the JSON).
    #[serde(skip)]
    pub ray_trace: Option<String>,
}

/// A light as the diagnosis names it: "light (line 19)".
pub(crate) fn light_name(scene: &Scene, light: usize) -> String {
    format!("light (line {})", scene.lights[light].line)
}

impl Report {
    /// Gives each pixel the report names (the worst, each diagnosis', each cause's, each
    /// decision flip's) the `trace` command that shows it: `command(x, y, under)`, where
    /// `under` are the whole-image causes a cause or a decision flip was found under (a
    /// row off), which its pixel is traced with.
    pub fn add_trace_commands(&mut self, command: impl Fn(usize, usize, &[Variant]) -> String) {
        for worst in &mut self.worst {
            worst.trace = Some(command(worst.x, worst.y, &[]));
        }
        // A pair's pixel is traced under its first where that moves the rays, as the
        // pair's second cause is.
        for found in self.diagnosis.iter_mut().flatten() {
            let under = match &found.variants[..] {
                [first, _] if first.kind.row().site == Site::Camera => &found.variants[..1],
                _ => &[],
            };
            found.trace = found.pixel.map(|[x, y]| command(x, y, under));
        }
        self.ray_trace = self.ray_pixel.map(|[x, y]| command(x, y, &[]));
        for cause in self.causes.iter_mut().flatten() {
            cause.trace = cause.pixel.map(|[x, y]| command(x, y, &cause.under));
        }
        for flip in self.flips.iter_mut().flatten() {
            let [x, y] = flip.pixel;
            flip.trace = Some(command(x, y, &flip.under));
        }
    }
}

/// The largest channel difference of two pixels.
#[inline]
pub fn pixel_difference(a: [u8; 3], b: [u8; 3]) -> u8 {
    (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0)
}

/// Whether two pixels' channels all differ by at most `levels`: `pixel_difference(a, b)
/// <= levels`, and at the default tolerance of 0 the bytes' equality, compared packed in
/// a word.
#[inline]
pub(crate) fn within(a: [u8; 3], b: [u8; 3], levels: u8) -> bool {
    match levels {
        0 => packed(a) == packed(b),
        _ => pixel_difference(a, b) <= levels,
    }
}

/// The sum of the three channels' differences.
fn channel_sum_of(a: [u8; 3], b: [u8; 3]) -> u16 {
    (0..3).map(|c| u16::from(a[c].abs_diff(b[c]))).sum()
}

/// Which pixels differ by more than `levels` (pixel i: bit i % 64 of word i / 64) and how
/// many, in one pass without a branch per pixel (under another byte rule half the pixels
/// differ, in no pattern a branch could learn).
pub(crate) fn differing(reference: &Image, student: &Image, levels: u8) -> (Vec<u64>, usize) {
    let mut mask = Vec::with_capacity(reference.pixels.len().div_ceil(64));
    let mut count = 0;
    for (a, b) in (reference.pixels.chunks(64)).zip(student.pixels.chunks(64)) {
        let mut word = 0u64;
        for (k, (&a, &b)) in a.iter().zip(b).enumerate() {
            word |= u64::from(!within(a, b, levels)) << k;
        }
        count += word.count_ones() as usize;
        mask.push(word);
    }
    (mask, count)
}

/// `each(i)` for the pixels i whose bits are set in `mask` (pixel i: bit i % 64 of word
/// i / 64), in order: a word at a time, the set bits found by counting zeros.
fn for_each_set(mask: &[u64], mut each: impl FnMut(usize)) {
    for (w, &word) in mask.iter().enumerate() {
        let mut bits = word;
        while bits != 0 {
            each(w * 64 + bits.trailing_zeros() as usize);
            bits &= bits - 1;
        }
    }
}

/// Whether pixel `i` is set in `mask` (bit i % 64 of word i / 64).
#[inline]
pub(crate) fn is_set(mask: &[u64], i: usize) -> bool {
    mask[i / 64] >> (i % 64) & 1 == 1
}

/// The share of pixels (0 to 1) whose channels all differ by at most `levels`.
pub fn agreement(reference: &Image, student: &Image, levels: u8) -> f64 {
    let within = (reference.pixels.iter().zip(&student.pixels))
        .filter(|&(&a, &b)| within(a, b, levels))
        .count();
    within as f64 / reference.pixels.len().max(1) as f64
}

/// Fails unless the two images have one size.
pub fn same_size(reference: &Image, student: &Image) -> Result<(), SizeMismatch> {
    if (reference.width, reference.height) == (student.width, student.height) {
        return Ok(());
    }
    Err(SizeMismatch {
        reference_width: reference.width,
        reference_height: reference.height,
        student_width: student.width,
        student_height: student.height,
    })
}

/// What to compare and how.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// How close the student's pixels must be to the reference's.
    pub tolerance: Tolerance,
    /// How many worst pixels to list.
    pub worst: usize,
    /// Whether to try the variants.
    pub diagnose: bool,
}

/// The report on a student's image of another size than the `expected` one: verdict
/// [`Verdict::WrongSize`], nothing compared.
pub fn wrong_size(student: &Image, expected: (usize, usize), settings: &Settings) -> Report {
    Report {
        verdict: Verdict::WrongSize,
        width: student.width,
        height: student.height,
        pixels: 0,
        tolerance: settings.tolerance.levels,
        allow: settings.tolerance.allow,
        precision: settings.tolerance.precision,
        differing_pixels: 0,
        fragile_pixels: 0,
        differing_fragile_pixels: 0,
        differing_fraction: 0.0,
        max_channel_difference: 0,
        mean_absolute_error: 0.0,
        groups: Vec::new(),
        worst: Vec::new(),
        diagnosis: None,
        focus: None,
        causes: None,
        flips: None,
        expected_size: Some([expected.0, expected.1]),
        ray_pixel: None,
        ray_trace: None,
    }
}

/// The reference of `scene` under `options`, at the student image's size, with how sure
/// it is of each pixel at relative `precision` ([`Tolerance::precision`]), and with what
/// each pixel's path involves when it is to `diagnose`.
pub fn reference(
    scene: &Scene,
    options: &Options,
    student: &Image,
    precision: f64,
    diagnose: bool,
) -> Reference {
    let options = Options {
        width: student.width,
        height: student.height,
        ..*options
    };
    reference_at(scene, &options, precision, diagnose)
}

/// The reference of `scene` under `options`, at their size, with how sure it is of each
/// pixel at relative `precision`, and with what each pixel's path involves when it is to
/// `diagnose`: what `grade` renders once for every student of a size.
pub fn reference_at(scene: &Scene, options: &Options, precision: f64, diagnose: bool) -> Reference {
    match diagnose {
        true => {
            let (image, marks, paths) = render_with_paths(scene, options, precision);
            Reference {
                image,
                marks,
                paths,
            }
        }
        false => {
            let (image, marks) = render_with_margins(scene, options, precision);
            Reference {
                image,
                marks,
                paths: Vec::new(),
            }
        }
    }
}

/// Pixel `i` of an image `width` by `height` (row by row from the top, as files hold
/// them) as (x, y) from the lower left, the position every report names. `trace` takes
/// the pixel a ray is traced for, which the position holds through the options' row map
/// ([`text::trace_command`] applies it: `--variant upside-down` moves it).
pub fn pixel_at(i: usize, width: usize, height: usize) -> [usize; 2] {
    let width = width.max(1);
    [i % width, output_row(i / width, height, false)]
}

/// Compares `student` with `reference`; with the scene (and the options the reference
/// was rendered with) the differences are grouped by object, and diagnosed if asked.
pub fn report(
    rendered: &Reference,
    student: &Image,
    scene: Option<(&Scene, &Options)>,
    settings: &Settings,
) -> Result<Report, SizeMismatch> {
    let reference = &rendered.image;
    same_size(reference, student)?;
    let levels = settings.tolerance.levels;
    let (width, height) = (reference.width, reference.height);
    let pixels = width * height;
    let excused = |i: usize| {
        let (a, b) = (reference.pixels[i], student.pixels[i]);
        rendered.fragility(i).excuses(a, b, levels)
    };
    // The differing pixels counted by the object the reference's camera ray hits there
    // (the last slot: the background), when the scene is known.
    let grouped = match scene {
        Some((scene, _)) if rendered.marks.len() == pixels => Some(scene.objects.len()),
        _ => None,
    };
    let mut by_object = vec![0usize; grouped.map_or(0, |objects| objects + 1)];
    // The differences that count first, then the largest difference, then the largest
    // sum over the channels, then the first in the image: the same order on every run.
    // Kept in a heap of the `worst` first so far, whose top is the last of them: memory
    // for the list, not for every differing pixel.
    let mut kept = std::collections::BinaryHeap::with_capacity(settings.worst.min(pixels) + 1);
    // The pixels beyond the tolerance, in one pass.
    let (beyond, differing_pixels) = differing(reference, student, levels);
    // The channels' differences, summed and the largest: at the tolerance 0 every pixel
    // that differs at all is beyond it, and they are summed in the pass below; above it,
    // over every pixel.
    let (mut channel_sum, mut max_channel_difference) = (0u64, 0u8);
    if levels > 0 {
        for (&a, &b) in reference.pixels.iter().zip(&student.pixels) {
            channel_sum += u64::from(channel_sum_of(a, b));
            max_channel_difference = max_channel_difference.max(pixel_difference(a, b));
        }
    }
    // Then the pixels beyond it: those excused, their objects, the worst.
    let mut differing_fragile_pixels = 0;
    for_each_set(&beyond, |i| {
        let (a, b) = (reference.pixels[i], student.pixels[i]);
        let excused = excused(i);
        differing_fragile_pixels += usize::from(excused);
        if let Some(background) = grouped {
            let object = rendered.marks[i].first().index().unwrap_or(background);
            by_object[object] += 1;
        }
        let (difference, sum) = (pixel_difference(a, b), channel_sum_of(a, b));
        if levels == 0 {
            channel_sum += u64::from(sum);
            max_channel_difference = max_channel_difference.max(difference);
        }
        // The order above in one number: excused last, then the larger difference, the
        // larger sum, the earlier pixel first.
        let difference = 255 - u128::from(difference);
        let sum = 1023 - u128::from(sum);
        let key = u128::from(excused) << 127 | difference << 119 | sum << 109 | i as u128;
        if kept.len() == settings.worst && kept.peek().is_none_or(|&last| key >= last) {
            return;
        }
        kept.push(key);
        if kept.len() > settings.worst {
            kept.pop();
        }
    });
    let fragile_pixels = rendered
        .marks
        .iter()
        .filter(|m| m.fragility().any())
        .count();
    let differing_fraction = differing_pixels as f64 / pixels.max(1) as f64;
    // Only the pixels the reference is sure of count against the image.
    let counted = differing_pixels - differing_fragile_pixels;
    let verdict = match counted as f64 <= settings.tolerance.allow * pixels as f64 {
        true => Verdict::Match,
        false => Verdict::Differ,
    };
    let groups = match scene {
        Some((scene, _)) if differing_pixels > 0 && grouped.is_some() => group(scene, &by_object),
        _ => Vec::new(),
    };
    let order = kept.into_sorted_vec();
    let worst = (order.iter())
        .map(|&key| {
            let i = (key & ((1 << 109) - 1)) as usize;
            let (a, b) = (reference.pixels[i], student.pixels[i]);
            let [x, y] = pixel_at(i, width, height);
            Worst {
                x,
                y,
                reference: a,
                student: b,
                difference: pixel_difference(a, b),
                fragile: key >> 127 == 1,
                trace: None,
            }
        })
        .collect();
    let (diagnosis, focus, causes, flips, ray_pixel) = match scene {
        Some((scene, options)) if settings.diagnose => {
            let options = Options {
                width,
                height,
                ..*options
            };
            let mask = (&beyond[..], differing_pixels);
            let (found, focus, causes, flips) =
                causes::explain(scene, &options, rendered, student, levels, mask);
            let ray_pixel = ray_pixel(&options, &causes);
            (Some(found), focus, Some(causes), Some(flips), ray_pixel)
        }
        _ => (None, None, None, None, None),
    };
    Ok(Report {
        verdict,
        width,
        height,
        pixels,
        tolerance: levels,
        allow: settings.tolerance.allow,
        precision: settings.tolerance.precision,
        differing_pixels,
        fragile_pixels,
        differing_fragile_pixels,
        differing_fraction,
        max_channel_difference,
        mean_absolute_error: channel_sum as f64 / (3 * pixels).max(1) as f64,
        groups,
        worst,
        diagnosis,
        focus,
        causes,
        flips,
        expected_size: None,
        ray_pixel,
        ray_trace: None,
    })
}

/// Where the first cause in a ray or a colour was found under causes that move the
/// pixels (rows or columns off, the image upside down): the pixel whose ray its pixel
/// shows. A program with such a mistake traces each ray and writes it elsewhere, so its
/// debug trace holds that ray under this pixel's label.
fn ray_pixel(options: &Options, causes: &[causes::Cause]) -> Option<[usize; 2]> {
    let cause = causes.iter().find(|c| !c.written_only())?;
    let (under, [x, y]) = (&cause.under, cause.pixel?);
    if under.is_empty() {
        return None;
    }
    let moved = options.with_variants(under).ok()?;
    let from = diagnose::shifted_from(options, &moved, under)?;
    let (w, h) = (options.width, options.height);
    let shown = from(output_row(y, h, false) * w + x)?;
    Some(pixel_at(shown, w, h))
}

/// The groups of the differing pixels, from their count per object (`counts`, the
/// background last).
fn group(scene: &Scene, counts: &[usize]) -> Vec<Group> {
    let total: usize = counts.iter().sum();
    let mut groups: Vec<Group> = (counts.iter().enumerate())
        .filter(|&(_, &n)| n > 0)
        .map(|(index, &pixels)| {
            let object = scene.objects.get(index);
            Group {
                object: object.map_or("background", |o| o.kind()).to_string(),
                line: object.map(|o| o.line),
                index: object.map(|_| index),
                pixels,
                share: pixels as f64 / total as f64,
            }
        })
        .collect();
    // Largest first; on a tie, file order and the background last (a stable sort).
    groups.sort_by_key(|g| std::cmp::Reverse(g.pixels));
    groups
}

/// The colours of the diff image: the key of docs/compare.md.
pub mod key {
    /// A difference of 1 to 3 levels: rounding-sized.
    pub const SMALL: [u8; 3] = [40, 120, 255];
    /// 4 to 31 levels: a shade off.
    pub const MEDIUM: [u8; 3] = [255, 210, 0];
    /// 32 levels or more: another colour, or another object.
    pub const LARGE: [u8; 3] = [255, 30, 30];
    /// Any difference on a fragile pixel, excused: a correct tracer may get it.
    pub const FRAGILE: [u8; 3] = [200, 0, 255];
}

/// The diff image: the reference dimmed to grey where the pixels are within `levels`,
/// differing pixels the reference is sure of coloured by the size of their difference,
/// and the excused ones on fragile pixels in their own colour ([`key`]).
pub fn diff_image(
    rendered: &Reference,
    student: &Image,
    levels: u8,
) -> Result<Image, SizeMismatch> {
    let reference = &rendered.image;
    same_size(reference, student)?;
    let pixels = (reference.pixels.iter().zip(&student.pixels).enumerate())
        .map(|(i, (&a, &b))| match pixel_difference(a, b) {
            d if d > levels && rendered.fragility(i).excuses(a, b, levels) => key::FRAGILE,
            d if d <= levels => {
                // Rec. 601 luma, dimmed into 24..=100 so that every colour of the key
                // stands out against it.
                let luma =
                    0.299 * f64::from(a[0]) + 0.587 * f64::from(a[1]) + 0.114 * f64::from(a[2]);
                let grey = (24.0 + luma * (76.0 / 255.0)) as u8;
                [grey; 3]
            }
            1..=3 => key::SMALL,
            4..=31 => key::MEDIUM,
            _ => key::LARGE,
        })
        .collect();
    Ok(Image {
        width: reference.width,
        height: reference.height,
        pixels,
    })
}
