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
    let setup = Setup::for_image(scene, options);
    // As in `render`: the rules as written are constants to the tracer.
    match setup.rules.as_written() {
        true => margins_of::<PATHS, _>(
            &setup,
            setup.tracer_with(AsWritten, options),
            options,
            precision,
            slots,
        ),
        false => margins_of::<PATHS, _>(&setup, setup.tracer(options), options, precision, slots),
    }
}

/// Every pixel's mark at `precision`, in output order; with `PATHS` its paths in
/// `slots`.
fn margins_of<const PATHS: bool, B: Rulebook>(
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
            let colour = tracer.pixel::<K>(x, y, sizes.query(), &mut rec);
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
