//! Pixels: the course's ray tracer (spec §4).
//!
//! [`render`] casts one ray per pixel through the world window (§4.1) and the tracer
//! (`src/render/tracer.rs`) follows it as spec §4.2's ray_trace: the closest hit (§4.6),
//! ambient plus the diffuse light of every lamp that the hit point sees (§4.3), divided
//! by the distance travelled so far (§4.2), plus the mirror reflection weighted by the
//! specular triple (§4.5). The stage (spec §7.2) leaves parts of that out, `--show`
//! replaces it by a diagnostic colour, the variants (spec §7.3, §7.4) replace one rule
//! each, and [`trace()`] records every step of one pixel through the same functions.

mod bvh;
mod choices;
mod lists;
mod margins;
mod objects;
mod reach;
mod record;
mod shading;
mod stage;
mod tiles;
pub(crate) mod trace;
mod tracer;
pub mod variant;

pub use choices::{Choices, by_name, size_problem};
pub use reach::{Paths, Reach};
pub(crate) use reach::{Steps, packed};
pub use record::{Event, LightStep, Skip, Stats};
pub use shading::PatternNote;
pub use stage::{Show, Stage};
pub use trace::{CourseIds, Trace, Tracing, trace, tracing};
pub use variant::{Kind, VARIANTS, Variant, Variants};

/// The largest precision `compare` takes: how far past its answer a query goes on
/// testing objects while the margins are recorded, at most.
pub const MAX_PRECISION: f64 = record::MARGIN_REACH;

use crate::scene::Scene;
use crate::shapes::kernel::{Kernel, KernelChoice, with_kernel};
use crate::shapes::{Ray, unit};
use crate::threads::Threads;
use glam::{DVec2, DVec3};
use record::Recorder;
use std::borrow::Cow;
use std::sync::atomic::{AtomicU64, Ordering};
use tracer::Tracer;
use variant::{AsWritten, Rulebook, Rules};

/// The default MAX_DIST of spec §4.2.
pub const DEFAULT_MAX_DIST: f64 = 32.0;

/// A cap on mirror bounces, far beyond any real scene: a ray trapped between mirrors that
/// touch could otherwise bounce without the path length ever reaching MAX_DIST.
pub(crate) const MAX_BOUNCES: usize = 10_000;

pub use crate::threads::MAX_THREADS;

/// What to render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Image width in pixels, >= 2.
    pub width: usize,
    /// Image height in pixels, >= 2.
    pub height: usize,
    /// Paths longer than this are black (spec §4.2).
    pub max_dist: f64,
    /// How ray-shape distances are computed; [`KernelChoice::Accurate`] unless comparing.
    pub kernel: KernelChoice,
    /// Worker threads: 1 renders on the calling thread (the legacy behaviour), 0 uses
    /// every core, and more than [`MAX_THREADS`] counts as `MAX_THREADS`. The image is
    /// the same bytes for every value. Without the `threads` feature (the WebAssembly
    /// build) every render uses the calling thread.
    pub threads: usize,
    /// Test camera rays against their tiles' lists and walk a bounding volume hierarchy
    /// where the scene has enough bounded objects for it to pay off
    /// (`src/render/objects.rs`); `false` forces the legacy linear scan (for measurements
    /// and tests: the image is the same either way).
    pub accelerate: bool,
    /// How much of spec §4 applies: the course's assignments (spec §7.2).
    pub stage: Stage,
    /// A diagnostic image instead of the stage's, or `None`.
    pub show: Option<Show>,
    /// The rules of spec §4-§5 that this render replaces (spec §7.3, §7.4), in the order
    /// given ([`Options::with_variant`]); none by default. MAX_DIST and the kernel's
    /// variants set [`Options::max_dist`] and [`Options::kernel`] instead.
    pub variants: Variants,
}

impl Options {
    /// A `width` x `height` render with the default MAX_DIST and the shipped kernel.
    pub fn new(width: usize, height: usize) -> Options {
        Options {
            width,
            height,
            max_dist: DEFAULT_MAX_DIST,
            kernel: KernelChoice::Accurate,
            threads: 1,
            accelerate: true,
            stage: Stage::Full,
            show: None,
            variants: Variants::default(),
        }
    }
}

/// An 8-bit RGB image, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width * height` pixels, top row first.
    pub pixels: Vec<[u8; 3]>,
}

/// A channel in [0, 1] to a byte: clamp, times 255, truncate (spec §4.7). NaN gives 0.
/// Rust's cast from f64 to u8 truncates and saturates (below 0 and NaN to 0, above 255
/// to 255), which is the clamp: no branch.
#[inline]
pub(crate) fn to_byte(channel: f64) -> u8 {
    (channel * 255.0) as u8
}

/// The camera of spec §4.1: world x of each column, world y of each row.
pub(crate) struct Camera {
    pub(crate) viewpoint: DVec3,
    pub(crate) xs: Vec<f64>,
    pub(crate) ys: Vec<f64>,
    /// jitter (spec §7.5): the seed of each pixel's point, and a pixel's width and
    /// height in the world.
    jitter: Option<(u64, DVec2)>,
}

impl Camera {
    fn new(scene: &Scene, options: &Options, rules: &Rules) -> Camera {
        // The world coordinate of pixel index i, which row-offset and column-offset
        // (spec §7.5) move past the window's edge where i + N leaves it.
        let axis = |count: usize, size: f64, offset: i64| -> Vec<f64> {
            let last = (count - 1) as f64;
            let at = |i: usize| match rules.pixel_centre {
                // The variant pixel-centre: (i + 0.5) / count (spec §7.3).
                true => (i as f64 + offset as f64 + 0.5) / count as f64,
                false => (i as f64 + offset as f64) / last,
            };
            (0..count).map(|i| at(i) * size - size / 2.0).collect()
        };
        let spacing = |count: usize, size: f64| match rules.pixel_centre {
            true => size / count as f64,
            false => size / (count - 1) as f64,
        };
        Camera {
            viewpoint: scene.viewpoint,
            xs: axis(options.width, scene.window.x, rules.column_offset),
            ys: axis(options.height, scene.window.y, rules.row_offset),
            jitter: rules.jitter.map(|seed| {
                let pixel = DVec2::new(
                    spacing(options.width, scene.window.x),
                    spacing(options.height, scene.window.y),
                );
                (seed, pixel)
            }),
        }
    }

    /// The world point of pixel (x, y), (0, 0) at the lower left (spec §4.1); under
    /// jitter, a point drawn within half a pixel of it, the same for the same seed.
    // Jitter's draw is kept out of line, so that this inlines.
    #[inline(always)]
    fn world(&self, x: usize, y: usize) -> DVec3 {
        let point = DVec3::new(self.xs[x], self.ys[y], 0.0);
        match self.jitter {
            None => point,
            Some((seed, pixel)) => jittered(point, seed, pixel, x, y),
        }
    }

    /// Whether the camera's rays go through the points of a grid (not under jitter): the
    /// tiles' lists hold for them.
    fn on_grid(&self) -> bool {
        self.jitter.is_none()
    }

    /// The ray through pixel (x, y); `None` if the viewpoint is the pixel's own world
    /// point (no direction).
    #[inline(always)]
    fn ray(&self, x: usize, y: usize) -> Option<Ray> {
        self.ray_through(self.world(x, y))
    }

    /// [`Camera::ray`] for a camera on the grid (not under jitter).
    #[inline(always)]
    fn grid_ray(&self, x: usize, y: usize) -> Option<Ray> {
        self.ray_through(DVec3::new(self.xs[x], self.ys[y], 0.0))
    }

    /// The ray from the viewpoint through the point `target` of the screen; `None` if
    /// it is the viewpoint.
    #[inline]
    fn ray_through(&self, target: DVec3) -> Option<Ray> {
        let dir = unit(target - self.viewpoint)?;
        Some(Ray {
            base: self.viewpoint,
            dir,
        })
    }
}

/// `point` moved within half a `pixel` by the numbers drawn for (x, y) from `seed`.
#[cold]
#[inline(never)]
fn jittered(point: DVec3, seed: u64, pixel: DVec2, x: usize, y: usize) -> DVec3 {
    let (u, v) = jitter(seed, x, y);
    point + DVec3::new((u - 0.5) * pixel.x, (v - 0.5) * pixel.y, 0.0)
}

/// Two numbers in [0, 1) drawn for pixel (x, y) from `seed`: SplitMix64 of the three,
/// fixed for a seed on every machine (spec §7.5's jitter is reproducible).
fn jitter(seed: u64, x: usize, y: usize) -> (f64, f64) {
    let mix = |mut z: u64| {
        z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    let key = mix(seed ^ mix((x as u64) << 32 ^ y as u64));
    let unit = |bits: u64| (bits >> 11) as f64 / (1u64 << 53) as f64;
    (unit(key), unit(mix(key)))
}

/// What every entry point needs before its first ray: the scene as its variants change
/// it, the rules they set, the camera, and the threads.
struct Setup<'a> {
    scene: Cow<'a, Scene>,
    rules: Rules,
    camera: Camera,
    threads: Threads,
}

impl<'a> Setup<'a> {
    /// For rays traced on the calling thread (a pixel, a sample of pixels).
    fn new(scene: &'a Scene, options: &Options) -> Setup<'a> {
        let scene = Rules::scene(options, scene);
        let rules = Rules::new(options, &scene);
        let camera = Camera::new(&scene, options, &rules);
        Setup {
            scene,
            rules,
            camera,
            threads: Threads::one(),
        }
    }

    /// For a whole image: on the threads `options` asks for, which build the tiles too.
    fn for_image(scene: &'a Scene, options: &Options) -> Setup<'a> {
        Setup {
            threads: Threads::of(options),
            ..Setup::new(scene, options)
        }
    }

    /// The tracer, with tiles for the camera's rays, reading the render's rules.
    fn tracer(&self, options: &Options) -> Tracer<'_, &Rules> {
        self.tracer_with(&self.rules, options)
    }

    /// The tracer, reading the rules from `book`.
    fn tracer_with<B: Rulebook>(&self, book: B, options: &Options) -> Tracer<'_, B> {
        // Tiles' lists hold for rays through the pixels' grid: not under jitter.
        let tiles = self.camera.on_grid().then_some((&self.threads, None));
        Tracer::new(&self.scene, book, options, &self.camera, tiles)
    }

    /// The output row that holds pixel row `y` and the reverse: H - 1 - y, or y upside
    /// down (spec §4.1, §7.3).
    fn row_of(&self, y: usize, height: usize) -> usize {
        variant::output_row(y, height, self.rules.upside_down)
    }
}

/// Renders the scene; `progress` is called with the number of rows done after each row.
pub fn render(scene: &Scene, options: &Options, mut progress: impl FnMut(usize)) -> Image {
    let setup = Setup::for_image(scene, options);
    // The rules as written are constants to the tracer (`variant::Rulebook`).
    let pixels = match setup.rules.as_written() {
        true => pixels_of(
            &setup,
            setup.tracer_with(AsWritten, options),
            options,
            &mut progress,
        ),
        false => pixels_of(&setup, setup.tracer(options), options, &mut progress),
    };
    Image {
        width: options.width,
        height: options.height,
        pixels,
    }
}

/// Every pixel's bytes, in output order, a tile's span of a row at a time
/// ([`Tracer::span`]).
fn pixels_of<B: Rulebook>(
    setup: &Setup,
    tracer: Tracer<B>,
    options: &Options,
    progress: &mut impl FnMut(usize),
) -> Vec<[u8; 3]> {
    with_kernel!(options.kernel, K => match tracer.together() {
        true => each_span(setup, options, spans::<K, B, true>(&tracer), progress),
        false => each_span(setup, options, spans::<K, B, false>(&tracer), progress),
    })
}

/// What fills a span of the plain render (the pixels from (first, y) on): their bytes,
/// the rays traced `TOGETHER` or not ([`Tracer::span`]).
fn spans<'t, K: Kernel, B: Rulebook, const TOGETHER: bool>(
    tracer: &'t Tracer<B>,
) -> impl Fn(usize, usize, &mut [[u8; 3]]) + Sync + 't {
    move |first: usize, y: usize, out: &mut [[u8; 3]]| {
        let count = out.len();
        let bytes = |i: usize, colour: DVec3| out[i] = tracer.bytes(colour);
        tracer.span::<K, TOGETHER>(|i| first + i, y, count, bytes);
    }
}

/// The rays a render of the scene casts (camera, shadow, reflected), counted by
/// rendering it once more with a recorder that counts: for the benchmarks' rays per
/// second.
pub fn count_rays(scene: &Scene, options: &Options) -> Stats {
    let setup = Setup::for_image(scene, options);
    let tracer = setup.tracer(options);
    let count = |x: usize, y: usize| -> Stats {
        let mut stats = Stats::default();
        with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, &mut stats));
        stats
    };
    let per_pixel = each_pixel(&setup, options, count, &mut |_| {});
    let counted = per_pixel.into_iter().fold(Stats::default(), |a, b| a + b);
    Stats {
        camera: (options.width * options.height) as u64,
        ..counted
    }
}

/// Which accelerations a render of `scene` under `options` uses: whether a bounding volume
/// hierarchy is built, and whether camera rays test their tiles' lists (for the tests
/// and the benchmarks; the image is the same either way).
pub fn acceleration(scene: &Scene, options: &Options) -> (bool, bool) {
    let setup = Setup::new(scene, options);
    setup.tracer(options).accelerated()
}

/// `per_pixel(x, y)` of every pixel, in output order (rows top to bottom, spec §4.1), on
/// the setup's threads; `progress` is told the rows done.
fn each_pixel<T: Send + Clone + Default>(
    setup: &Setup,
    options: &Options,
    per_pixel: impl Fn(usize, usize) -> T + Sync,
    progress: &mut impl FnMut(usize),
) -> Vec<T> {
    let render_row = |y: usize, out: &mut [T]| {
        for (x, pixel) in out.iter_mut().enumerate() {
            *pixel = per_pixel(x, y);
        }
    };
    each_row(setup, options, render_row, progress)
}

/// [`each_pixel`] a tile's span of a row at a time: `per_span(first, y, out)` fills the
/// pixels from (first, y) on.
fn each_span<T: Send + Sync + Clone + Default>(
    setup: &Setup,
    options: &Options,
    per_span: impl Fn(usize, usize, &mut [T]) + Sync,
    progress: &mut impl FnMut(usize),
) -> Vec<T> {
    let render_row = |y: usize, out: &mut [T]| {
        for (span, out) in out.chunks_mut(tiles::TILE).enumerate() {
            per_span(span * tiles::TILE, y, out);
        }
    };
    each_row(setup, options, render_row, progress)
}

/// The image's pixels in output order, `render_row(y, out)` filling the output row that
/// holds pixel row y (spec §4.1), on the setup's threads; `progress` is told the rows done.
fn each_row<T: Send + Clone + Default>(
    setup: &Setup,
    options: &Options,
    render_row: impl Fn(usize, &mut [T]) + Sync,
    progress: &mut impl FnMut(usize),
) -> Vec<T> {
    let mut pixels = vec![T::default(); options.width * options.height];
    let output_row = |row: usize, out: &mut [T]| render_row(setup.row_of(row, options.height), out);
    in_bands(
        &setup.threads,
        options.width,
        &mut pixels,
        output_row,
        progress,
    );
    pixels
}

/// Runs `render_row(row, out)` for every output row of `pixels` (`width` wide) on
/// `threads`, telling `progress` the rows done.
fn in_bands<T: Send>(
    threads: &Threads,
    width: usize,
    pixels: &mut [T],
    render_row: impl Fn(usize, &mut [T]) + Sync,
    progress: &mut impl FnMut(usize),
) {
    #[cfg(feature = "threads")]
    if let Some(pool) = threads.pool() {
        use rayon::prelude::*;
        let height = pixels.len() / width.max(1);
        // Bands of rows, each spread over the pool, so that progress is reported from
        // this thread; at least a 32nd of the image each, for each band waits for its
        // slowest row (a04 at 1600x1200 on two threads: 89 ms with bands of 8 rows, 77
        // ms with 37). Every pixel is computed exactly as on one thread; only the order
        // differs, so the bytes are the same.
        let band = (4 * pool.current_num_threads()).max(height / 32);
        for (index, chunk) in pixels.chunks_mut(band * width).enumerate() {
            let first = index * band;
            pool.install(|| {
                (chunk.par_chunks_mut(width).enumerate())
                    .for_each(|(row, out)| render_row(first + row, out));
            });
            progress((first + band).min(height));
        }
        return;
    }
    let _ = threads;
    for (row, out) in pixels.chunks_mut(width).enumerate() {
        render_row(row, out);
        progress(row + 1);
    }
}

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
/// in one render with a recorder of margins (src/render/margins.rs). The image is the
/// plain render's, byte for byte.
pub fn render_with_margins(scene: &Scene, options: &Options, precision: f64) -> (Image, Vec<Mark>) {
    let marks = marked::<false>(scene, options, precision, &[]);
    (image_of(options, &marks), marks)
}

/// [`render_with_margins`], and each pixel's [`Paths`]: what `compare --diagnose` needs
/// to re-trace only the pixels a variant can change ([`Reach`]).
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
            let colour = tracer.pixel::<K>(x, y, &mut rec);
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
            let bytes = [
                fragile(colour.x, error.x),
                fragile(colour.y, error.y),
                fragile(colour.z, error.z),
            ];
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

/// The bytes of the pixels `indices` (output order: row 0 at the top) of the scene's
/// image under `options`, without the rest: the same bytes as [`render`] gives there. For
/// `compare --diagnose`, which tries a variant on a sample of pixels, and re-traces the
/// pixels a variant can change, rather than render whole images. The camera rays go
/// through the lists of the tiles the pixels fall in where they are dense enough to pay
/// for them (`PIXELS_PER_LIST`, 8 a tile); the hierarchy is kept. Where shadow rays are
/// cast, the pixels that follow each other in `indices` within one row of one tile are
/// traced together, a span as in `render`.
pub fn render_pixels(scene: &Scene, options: &Options, indices: &[usize]) -> Vec<[u8; 3]> {
    // The kernel chosen once, outside the loop over the pixels (as in `render`), and
    // whether the spans' rays go together: each loop is compiled for one.
    with_kernel!(options.kernel, K => with_tracer(scene, options, indices, |_, tracer, background, rows| {
        match tracer.together() {
            true => spans_of::<K, true>(tracer, indices, background, rows),
            false => spans_of::<K, false>(tracer, indices, background, rows),
        }
    }))
}

/// [`render_pixels`] with `tracer`, the rays of each span traced `TOGETHER` or not.
fn spans_of<K: Kernel, const TOGETHER: bool>(
    tracer: &Tracer<&Rules>,
    indices: &[usize],
    background: [u8; 3],
    rows: &mut Rows,
) -> Vec<[u8; 3]> {
    let mut pixels = vec![background; indices.len()];
    let mut at = 0;
    while at < indices.len() {
        // The pixel at `at` and those after it in its row and tile, as in `render`'s
        // spans: at most a tile's width.
        let (x, y) = rows.at(indices[at]);
        let mut xs = [x; tiles::TILE];
        let mut count = 1;
        while count < tiles::TILE
            && let Some(&i) = indices.get(at + count)
            && let (next, row) = rows.at(i)
            && row == y
            && next / tiles::TILE == x / tiles::TILE
        {
            xs[count] = next;
            count += 1;
        }
        let out = &mut pixels[at..at + count];
        at += count;
        let bytes = |i: usize, colour: DVec3| out[i] = tracer.bytes(colour);
        tracer.span::<K, TOGETHER>(|i| xs[i], y, count, bytes);
    }
    pixels
}

/// How many of the pixels to trace a tile must hold, on average, for its list to be
/// built. On a04 at 640x480 a tile's list costs about 6,000 instructions to build
/// (callgrind: `Tiles::new` 30M for 4,800 tiles), some 0.5 µs at the 12 instructions a
/// nanosecond the plain render runs at there, and a camera ray that tests a list rather
/// than the hierarchy saves about 70 ns (33,466 pixels re-traced in 4.5 ms without lists,
/// 2.2 ms with them): the lists pay from about 7 pixels a tile.
const PIXELS_PER_LIST: usize = 8;

/// `per_pixel(setup, tracer, background, x, y)` for each of the pixels `indices` (output
/// order), with [`with_tracer`]'s tracer.
fn at_pixels<T>(
    scene: &Scene,
    options: &Options,
    indices: &[usize],
    mut per_pixel: impl FnMut(&Setup, &Tracer<&Rules>, [u8; 3], usize, usize) -> T,
) -> Vec<T> {
    with_tracer(
        scene,
        options,
        indices,
        |setup, tracer, background, rows| {
            // A plain loop: as `map(..).collect()` the same tracing took some 15 % longer
            // (a02, every pixel, 14.9 ms against 13.7 ms; `render` 12.8 ms).
            let mut pixels = Vec::with_capacity(indices.len());
            for &i in indices {
                let (x, y) = rows.at(i);
                pixels.push(per_pixel(setup, tracer, background, x, y));
            }
            pixels
        },
    )
}

/// `trace(setup, tracer, background, rows)` with a tracer with the lists of the tiles the
/// pixels `indices` fall in where they hold [`PIXELS_PER_LIST`] of them a tile, the
/// bytes of black under the rules and the pixels' (x, y) by their index.
fn with_tracer<T>(
    scene: &Scene,
    options: &Options,
    indices: &[usize],
    trace: impl FnOnce(&Setup, &Tracer<&Rules>, [u8; 3], &mut Rows) -> T,
) -> T {
    let setup = Setup::new(scene, options);
    let mut rows = Rows::new(&setup, options);
    // The tiles the pixels fall in, and whether they are dense enough for lists.
    let (across, down) = tiles::tiles_across(options.width, options.height);
    let mut cells = vec![false; across * down];
    let mut count = 0;
    for &i in indices {
        let (x, y) = rows.at(i);
        let cell = &mut cells[tiles::cell(x, y, across)];
        count += usize::from(!*cell);
        *cell = true;
    }
    let cells = (indices.len() >= PIXELS_PER_LIST * count).then_some(cells);
    let tiles = (cells.as_deref()).map(|cells| (&setup.threads, Some(cells)));
    let tracer = Tracer::new(&setup.scene, &setup.rules, options, &setup.camera, tiles);
    let background = setup.rules.bytes(DVec3::ZERO);
    trace(&setup, &tracer, background, &mut rows)
}

/// A pixel's (x, y) from its index in output order, the row's division done once per
/// row as the indices run along it.
struct Rows<'s, 'a> {
    setup: &'s Setup<'a>,
    width: usize,
    height: usize,
    /// The output row last seen and its first index.
    row: (usize, usize),
}

impl<'s, 'a> Rows<'s, 'a> {
    fn new(setup: &'s Setup<'a>, options: &Options) -> Rows<'s, 'a> {
        Rows {
            setup,
            width: options.width.max(1),
            height: options.height,
            row: (0, 0),
        }
    }

    /// The (x, y) of pixel `i`, (0, 0) at the lower left.
    fn at(&mut self, i: usize) -> (usize, usize) {
        let (mut row, mut start) = self.row;
        if !(start..start + self.width).contains(&i) {
            row = i / self.width;
            start = row * self.width;
            self.row = (row, start);
        }
        (i - start, self.setup.row_of(row, self.height))
    }
}

/// What one pixel's path involves: the objects it hits (the camera ray's and each
/// mirror ray's), the objects that block its shadow rays, and the lights that light it
/// or whose shadow rays are blocked; indices among the scene's objects and lights.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Involved {
    /// The objects hit, camera ray first, then each mirror ray's.
    pub hits: Vec<usize>,
    /// The objects that block a shadow ray, with the light's index.
    pub blockers: Vec<(usize, usize)>,
    /// The lights that add to the colour.
    pub lit_by: Vec<usize>,
    /// Whether a mirror ray leaves the path's first hit: only then can MAX_DIST change
    /// the pixel (spec §4.2 step 1).
    pub reflected: bool,
}

impl Recorder for Involved {
    const ON: bool = true;
    const EVERY_OBJECT: bool = false;

    fn record(&mut self, event: impl FnOnce() -> Event) {
        match event() {
            Event::Closest {
                hit: Some((object, _)),
            } => self.hits.push(object),
            Event::Segment { depth, .. } if depth > 0 => self.reflected = true,
            Event::CutOff { .. } => self.reflected = true,
            Event::Lamp { light } => self.lit_by.push(light),
            // A light that added nothing does not light the pixel.
            Event::Lit {
                light,
                contribution,
                ..
            } if contribution == DVec3::ZERO && self.lit_by.last() == Some(&light) => {
                self.lit_by.pop();
            }
            Event::Light(LightStep::Blocked {
                blocker: Some((object, _)),
            }) => {
                if let Some(&light) = self.lit_by.last() {
                    self.blockers.push((object, light));
                }
            }
            _ => {}
        }
    }
}

/// What the paths of the pixels `indices` (output order) involve, under `options`.
pub fn involved(scene: &Scene, options: &Options, indices: &[usize]) -> Vec<Involved> {
    at_pixels(scene, options, indices, |_, tracer, _, x, y| {
        let mut path = Involved::default();
        with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, &mut path));
        path
    })
}

/// Where a pixel's bytes change as MAX_DIST grows: once D reaches `start` (where a
/// segment of the pixel's path starts), the pixel's bytes are those with that segment
/// added, and they agree with the student's or not.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathChange {
    /// The path's length where the segment starts.
    pub start: f64,
    /// The pixel's output index.
    pub pixel: u32,
    /// Whether the bytes from there on agree.
    pub agrees: bool,
}

/// The image under every MAX_DIST up to `options.max_dist` at the cost of one render, as
/// far as `agrees(pixel, bytes)` tells: per pixel (output order) whether its bytes agree
/// under the smallest MAX_DIST (the camera ray's segment alone), and every change of its
/// bytes as D grows, sorted by D (spec §4.2 step 1: under MAX_DIST D a pixel has the
/// bytes after the last segment starting at D or less). Only changes are kept, so the
/// memory grows with the mirror bounces that change a byte, not with the image.
pub fn path_agreement(
    scene: &Scene,
    options: &Options,
    agrees: impl Fn(usize, [u8; 3]) -> bool + Sync,
) -> (Vec<bool>, Vec<PathChange>) {
    let setup = Setup::for_image(scene, options);
    let tracer = setup.tracer(options);
    let changes = std::sync::Mutex::new(Vec::new());
    let path = |x: usize, y: usize| -> bool {
        let pixel = setup.row_of(y, options.height) * options.width + x;
        let (first, mine) = path_changes(&setup, options, &tracer, (x, y), pixel, &agrees);
        if !mine.is_empty()
            && let Ok(mut changes) = changes.lock()
        {
            changes.extend(mine);
        }
        first
    };
    let first = each_pixel(&setup, options, path, &mut |_| {});
    let mut changes = changes.into_inner().unwrap_or_default();
    by_distance(&mut changes);
    (first, changes)
}

/// [`path_agreement`] on the pixels `indices` (output order) only: `agrees` and the
/// changes take a pixel's position in `indices`, not its index in the image.
pub fn path_agreement_at(
    scene: &Scene,
    options: &Options,
    indices: &[usize],
    agrees: impl Fn(usize, [u8; 3]) -> bool,
) -> (Vec<bool>, Vec<PathChange>) {
    let mut changes = Vec::new();
    let mut at = 0;
    let first = at_pixels(scene, options, indices, |setup, tracer, _, x, y| {
        let (first, mine) = path_changes(setup, options, tracer, (x, y), at, &agrees);
        changes.extend(mine);
        at += 1;
        first
    });
    by_distance(&mut changes);
    (first, changes)
}

/// Sorts path changes by D, then by pixel; a pixel's own changes were pushed in path
/// order and the sort is stable, so they stay in that order.
fn by_distance(changes: &mut [PathChange]) {
    changes.sort_by(|a, b| a.start.total_cmp(&b.start).then(a.pixel.cmp(&b.pixel)));
}

/// One pixel's path for [`path_agreement`], numbered `pixel`: whether its bytes agree
/// under the smallest MAX_DIST, and where along the path they change.
fn path_changes<B: Rulebook>(
    setup: &Setup,
    options: &Options,
    tracer: &Tracer<B>,
    (x, y): (usize, usize),
    pixel: usize,
    agrees: &impl Fn(usize, [u8; 3]) -> bool,
) -> (bool, Vec<PathChange>) {
    /// Each segment's start and the colour after it.
    struct Path(Vec<(f64, DVec3)>);
    impl Recorder for Path {
        const ON: bool = true;
        const EVERY_OBJECT: bool = false;
        fn record(&mut self, event: impl FnOnce() -> Event) {
            match event() {
                Event::Segment { total_dist, .. } => {
                    let colour = self.0.last().map_or(DVec3::ZERO, |&(_, c)| c);
                    self.0.push((total_dist, colour));
                }
                Event::Divided { colour, .. } => {
                    if let Some(last) = self.0.last_mut() {
                        last.1 = colour;
                    }
                }
                _ => {}
            }
        }
    }
    let mut path = Path(Vec::new());
    with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, &mut path));
    let bytes = |colour: DVec3| setup.rules.bytes(colour);
    let mut entries = path.0.iter();
    let first = entries.next().map_or(DVec3::ZERO, |&(_, c)| c);
    let mut last = bytes(first);
    let mut mine = Vec::new();
    // Segments that change no byte (deep bounces between two mirrors) are left out: D
    // passing them gives the same image.
    for &(start, colour) in entries {
        let now = bytes(colour);
        if now != last {
            mine.push(PathChange {
                start,
                pixel: pixel as u32,
                agrees: agrees(pixel, now),
            });
            last = now;
        }
    }
    (agrees(pixel, bytes(first)), mine)
}

/// The colour seen along one ray from the eye (spec §4.2 with total_dist = 0 and no
/// `last_hit`), before the conversion to bytes.
pub fn ray_trace(scene: &Scene, options: &Options, ray: Ray) -> DVec3 {
    let setup = Setup::new(scene, options);
    let tracer = Tracer::new(&setup.scene, &setup.rules, options, &setup.camera, None);
    with_kernel!(options.kernel, K => tracer.through::<K>(ray, &mut ()))
}

/// A distinct, stable colour for object `index` in `--show objects`: the golden-ratio
/// walk around the hue circle, so that neighbours in the file differ most.
pub fn object_colour(index: usize) -> DVec3 {
    let hue = (index as f64 * 0.618_033_988_749_895).fract();
    let channel = |offset: f64| {
        let angle = std::f64::consts::TAU * (hue + offset);
        0.55 + 0.45 * angle.cos()
    };
    DVec3::new(channel(0.0), channel(1.0 / 3.0), channel(2.0 / 3.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_are_clamped_truncated_and_nan_free() {
        assert_eq!(to_byte(0.625), 159); // 159.375, the debug scene's centre (spec §6)
        assert_eq!(to_byte(0.999), 254); // 254.745 truncates, it does not round
        assert_eq!(to_byte(1.5), 255);
        assert_eq!(to_byte(-0.5), 0);
        assert_eq!(to_byte(f64::INFINITY), 255);
        assert_eq!(to_byte(f64::NAN), 0);
    }
}
