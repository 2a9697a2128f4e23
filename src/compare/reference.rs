//! The reference `compare` sets a student's image against: the plain render's bytes
//! with, for each pixel, how sure the reference is of it ([`Fragility`]) and the object
//! its camera ray hits first ([`FirstHit`]), in one render with a recorder of margins
//! ([`super::margins`]) on the renderer's frame ([`Tracer::pixel`]); for `--diagnose`,
//! each pixel's paths too ([`super::reach`]).

use super::margins;
use super::reach::Paths;
use crate::render::tracer::Tracer;
use crate::render::variant::{AsWritten, Rulebook};
use crate::render::{Image, Options, Setup, each_span};
use crate::scene::Scene;
use crate::shapes::kernel::with_kernel;
use glam::DVec3;
use std::sync::atomic::{AtomicU64, Ordering};

/// The object a camera ray hits first, in 4 bytes (half of a reference pixel's
/// [`Mark`]): its index plus one, or nothing for the background.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FirstHit(Option<std::num::NonZeroU32>);

impl FirstHit {
    /// The object's index among the scene's objects, `None` for the background.
    pub fn index(self) -> Option<usize> {
        self.0.map(|n| n.get() as usize - 1)
    }

    fn of(index: Option<usize>) -> FirstHit {
        // A scene holds at most 1,000,000 records, so index + 1 fits.
        FirstHit(index.and_then(|i| std::num::NonZeroU32::new(i as u32 + 1)))
    }
}

/// How sure the reference is of one pixel at a precision (docs/compare.md): whether a
/// decision that chose what it shows (an object, a shadow, a tile) came within that
/// relative margin of going the other way, and which channels lie that close to a byte's
/// step ([`render_with_margins`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Fragility(u8);

impl Fragility {
    const STRUCTURAL: u8 = 1 << 3;

    /// Whether a tracer correct to the precision may show another colour here.
    pub fn structural(self) -> bool {
        self.0 & Fragility::STRUCTURAL != 0
    }

    /// Whether channel `c` (0 red, 1 green, 2 blue) may come out a level off.
    pub fn byte(self, c: usize) -> bool {
        self.0 & (1 << c) != 0
    }

    /// Whether the pixel is fragile in any way.
    pub fn any(self) -> bool {
        self.0 != 0
    }

    /// Whether a student's pixel `student` against the reference's `reference` is one a
    /// correct tracer may give here: anything where a decision was fragile, otherwise a
    /// level off on fragile bytes only (`levels`: the difference already tolerated).
    pub fn excuses(self, reference: [u8; 3], student: [u8; 3], levels: u8) -> bool {
        if self.structural() {
            return true;
        }
        (0..3).all(|c| {
            let d = reference[c].abs_diff(student[c]);
            d <= levels || (d <= 1 && self.byte(c))
        })
    }

    /// The pixel of a colour whose decisions' least margin is `least`, at precision
    /// `precision`, and whose channels `bytes` says are fragile.
    fn of(least: f64, bytes: [bool; 3], precision: f64) -> Fragility {
        let mut bits = u8::from(least < precision) * Fragility::STRUCTURAL;
        for (c, fragile) in bytes.into_iter().enumerate() {
            bits |= u8::from(fragile) << c;
        }
        Fragility(bits)
    }
}

/// How many roundings of the arithmetic a pixel's colour carries, at most, for a
/// scene of a few lights: the byte's margin is measured against that many.
const COLOUR_ROUNDINGS: f64 = 16.0;

/// What `compare` keeps of each pixel of the reference: its bytes, how sure it is, and
/// the object its camera ray hits first, in 8 bytes (a 4096x4096 reference keeps 128 MB
/// of them).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Mark(u64);

impl Mark {
    fn new(bytes: [u8; 3], fragility: Fragility, first: FirstHit) -> Mark {
        let [r, g, b] = bytes.map(u64::from);
        let first = first.0.map_or(0, |n| u64::from(n.get()));
        Mark(r | g << 8 | b << 16 | u64::from(fragility.0) << 24 | first << 32)
    }

    /// The pixel's bytes.
    pub fn bytes(self) -> [u8; 3] {
        [self.0 as u8, (self.0 >> 8) as u8, (self.0 >> 16) as u8]
    }

    /// What a correct tracer may get otherwise here.
    pub fn fragility(self) -> Fragility {
        Fragility((self.0 >> 24) as u8)
    }

    /// The object the camera ray hits first.
    pub fn first(self) -> FirstHit {
        FirstHit(std::num::NonZeroU32::new((self.0 >> 32) as u32))
    }
}

/// The reference image with each pixel's [`Mark`] at `precision`: what `compare` needs,
/// in one render with a recorder of margins (src/compare/margins.rs). The image is the
/// plain render's, byte for byte.
pub fn render_with_margins(scene: &Scene, options: &Options, precision: f64) -> (Image, Vec<Mark>) {
    let marks = marked::<false>(scene, options, precision, &[]);
    (image_of(options, &marks), marks)
}

/// [`render_with_margins`], and each pixel's [`Paths`]: what `compare --diagnose` needs
/// to re-trace only the pixels a variant can change ([`Reach`](super::Reach)).
pub fn render_with_paths(
    scene: &Scene,
    options: &Options,
    precision: f64,
) -> (Image, Vec<Mark>, Vec<Paths>) {
    // Each pixel's paths, stored by the thread that renders it.
    let slots: Vec<AtomicU64> = (0..options.width * options.height)
        .map(|_| AtomicU64::new(0))
        .collect();
    let marks = marked::<true>(scene, options, precision, &slots);
    // In place: a slot and its paths are one u64.
    let paths = (slots.into_iter())
        .map(|slot| Paths::from_bits(slot.into_inner()))
        .collect();
    (image_of(options, &marks), marks, paths)
}

/// The image whose pixels `marks` hold.
fn image_of(options: &Options, marks: &[Mark]) -> Image {
    Image {
        width: options.width,
        height: options.height,
        pixels: marks.iter().map(|m| m.bytes()).collect(),
    }
}

/// Every pixel's mark, in output order, from one render with a recorder of margins at
/// `precision`; with `PATHS` each pixel's paths stored in `slots` (output order).
fn marked<const PATHS: bool>(
    scene: &Scene,
    options: &Options,
    precision: f64,
    slots: &[AtomicU64],
) -> Vec<Mark> {
    marked_by::<PATHS>(scene, options, precision, slots, Shortcut::Ambient)
}

/// Which pixels take a shorter way than the loop of spec §4.2 ([`Tracer::pixel`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shortcut {
    /// Every pixel where [`Tracer::ambient_only`] holds: [`Tracer::ambient_pixel`], the
    /// loop's first step alone: the same marks and paths (the unit test below), and
    /// `compare` of a02 a row off 18 % fewer instructions (docs/architecture.md).
    Ambient,
    /// None: the tests' check of the shortcut.
    #[cfg(test)]
    None,
}

/// [`marked`], with `shortcut`.
fn marked_by<const PATHS: bool>(
    scene: &Scene,
    options: &Options,
    precision: f64,
    slots: &[AtomicU64],
    shortcut: Shortcut,
) -> Vec<Mark> {
    let setup = Setup::for_image(scene, options);
    // As in `render`: the rules as written are constants to the tracer, and so is the
    // way each pixel is traced.
    match setup.rules.as_written() {
        true => by::<PATHS, _>(
            &setup,
            setup.tracer_with(AsWritten, options),
            options,
            precision,
            slots,
            shortcut,
        ),
        false => by::<PATHS, _>(
            &setup,
            setup.tracer(options),
            options,
            precision,
            slots,
            shortcut,
        ),
    }
}

/// [`margins_of`] with the way each pixel is traced chosen from `shortcut` and the
/// tracer.
fn by<const PATHS: bool, B: Rulebook>(
    setup: &Setup,
    tracer: Tracer<B>,
    options: &Options,
    precision: f64,
    slots: &[AtomicU64],
    shortcut: Shortcut,
) -> Vec<Mark> {
    match shortcut == Shortcut::Ambient && tracer.ambient_only() {
        true => margins_of::<PATHS, true, B>(setup, tracer, options, precision, slots),
        false => margins_of::<PATHS, false, B>(setup, tracer, options, precision, slots),
    }
}

/// Every pixel's mark at `precision`, in output order; with `PATHS` its paths in
/// `slots`; with `AMBIENT` each pixel by [`Tracer::ambient_pixel`] (where
/// [`Tracer::ambient_only`] holds), else by [`Tracer::pixel`].
fn margins_of<const PATHS: bool, const AMBIENT: bool, B: Rulebook>(
    setup: &Setup,
    tracer: Tracer<B>,
    options: &Options,
    precision: f64,
    slots: &[AtomicU64],
) -> Vec<Mark> {
    let sizes = margins::Sizes::new(&setup.scene, options.max_dist, tracer.screen(), precision);
    let background = setup.rules.bytes(DVec3::ZERO);
    // A pixel whose tile sees no object: its paths involve nothing (the slot's 0).
    let empty = Mark::new(background, Fragility::default(), FirstHit::default());
    with_kernel!(options.kernel, K => {
        let per_pixel = |x: usize, y: usize| -> Mark {
            let mut rec = margins::Margins::<PATHS>::new(&sizes);
            let colour = match AMBIENT {
                true => tracer.ambient_pixel::<K>(x, y, sizes.query(), &mut rec),
                false => tracer.pixel::<K>(x, y, sizes.query(), &mut rec),
            };
            // The colour is some sixteen roundings from the hit point: ambient plus each
            // light's diffuse × emissivity × cos θ / dist, over the path, times the
            // mirrors.
            // A byte is fragile where its margin, over that many, is below the precision.
            let limit = precision * (COLOUR_ROUNDINGS * rec.kappa);
            // Past a mirror the colour also carries the error its path's points and
            // normals grew by: relative to the channel, and over as many roundings.
            let fragile = |c: f64, error: f64| {
                let limit = match error > 0.0 {
                    false => limit,
                    true => limit + precision * COLOUR_ROUNDINGS * error / c,
                };
                setup.rules.bytes.fragile(c, limit)
            };
            let error = rec.colour_error;
            // Without a mirror there is no such error: one test, and no division.
            let bytes = match error == DVec3::ZERO {
                true => colour.to_array().map(|c| setup.rules.bytes.fragile(c, limit)),
                false => [
                    fragile(colour.x, error.x),
                    fragile(colour.y, error.y),
                    fragile(colour.z, error.z),
                ],
            };
            let fragility = Fragility::of(rec.least, bytes, precision);
            let first = FirstHit::of(rec.first.flatten());
            let bytes = setup.rules.bytes(colour);
            if PATHS {
                rec.paths.colour(colour, bytes);
                let index = setup.row_of(y, options.height) * options.width + x;
                slots[index].store(rec.paths.bits(), Ordering::Relaxed);
            }
            Mark::new(bytes, fragility, first)
        };
        let per_span = |first: usize, y: usize, out: &mut [Mark]| {
            if tracer.sees_nothing(first, y) {
                out.fill(empty);
                return;
            }
            for (x, out) in (first..).zip(out) {
                *out = per_pixel(x, y);
            }
        };
        each_span(setup, options, per_span, &mut |_| {})
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{Stage, Variant};
    use crate::shapes::kernel::KernelChoice::{Accurate, TextbookF32};
    use std::path::Path;

    /// Every pixel's marks and paths, by `shortcut`.
    fn marks(scene: &Scene, options: &Options, precision: f64, shortcut: Shortcut) -> Vec<u64> {
        let pixels = options.width * options.height;
        let slots: Vec<AtomicU64> = (0..pixels).map(|_| AtomicU64::new(0)).collect();
        let marks = marked_by::<true>(scene, options, precision, &slots, shortcut);
        let paths = slots.into_iter().map(AtomicU64::into_inner);
        marks.into_iter().map(|m| m.0).chain(paths).collect()
    }

    #[test]
    fn the_ambient_shortcut_gives_the_loop_s_marks_and_paths() {
        // Every example and course scene at the ambient stage (tiles, textures and
        // shaders among them: the shortcut reads a patterned surface), and the course's
        // ambient assignments as they are, at both precisions and under the kernels that
        // compute roots otherwise; each pixel's mark and paths as the loop gives them.
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut paths = Vec::new();
        for dir in [root.join("examples"), root.join("../shared/course-scenes")] {
            if let Ok(entries) = std::fs::read_dir(dir) {
                paths.extend(entries.flatten().map(|e| e.path()));
            }
        }
        paths.retain(|p| p.extension().is_some_and(|e| e == "txt"));
        paths.sort();
        assert!(paths.len() >= 20, "the examples are found");
        // The rules the shortcut reads otherwise than the loop does: the camera's, the
        // division, the bytes, the tiles' colours and the far clip of the closest hit.
        let variants = [
            "",
            "round-bytes",
            "jitter,no-distance",
            "pixel-centre,tile-parity,scale-256",
            "far-clip=6,segment-distance",
        ];
        let mut checked = 0;
        for path in &paths {
            let scene = crate::load(&std::fs::read_to_string(path).unwrap()).unwrap();
            for stage in [Stage::Ambient, Stage::Full] {
                for (kernel, precision) in [(Accurate, 1.2e-7), (TextbookF32, 2.3e-16)] {
                    let mut options = Options::new(64, 48);
                    options.stage = stage;
                    options.kernel = kernel;
                    let setup = Setup::for_image(&scene, &options);
                    if !setup.tracer(&options).ambient_only() {
                        continue;
                    }
                    for variants in variants {
                        let parsed = variants.split(',').filter(|v| !v.is_empty());
                        let parsed = parsed.map(|v| Variant::parse(v).unwrap());
                        let parsed: Vec<Variant> = parsed.collect();
                        let options = options.with_variants(&parsed).unwrap();
                        let fast = marks(&scene, &options, precision, Shortcut::Ambient);
                        let slow = marks(&scene, &options, precision, Shortcut::None);
                        let case = format!("{} {stage:?} {kernel:?} {variants}", path.display());
                        assert!(fast == slow, "{case}");
                        checked += 1;
                    }
                }
            }
        }
        // Each scene at the ambient stage, the course's three ambient scenes as they are.
        assert!(checked >= 2 * 5 * paths.len(), "{checked} renders checked");
    }
}
