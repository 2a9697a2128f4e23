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
mod objects;
pub(crate) mod record;
pub(crate) mod shading;
mod stage;
pub(crate) mod tiles;
pub(crate) mod trace;
pub(crate) mod tracer;
pub mod variant;

pub use choices::{Choices, by_name, size_problem};
pub(crate) use objects::{EveryObject, Forced, Near, Noted, Plain};
pub use objects::{Override, Rays};
pub use record::{Event, LightStep, Skip, Stats};
pub use shading::PatternNote;
pub use stage::{Show, Stage};
pub use trace::{CourseIds, Trace, Tracing, trace, tracing};
pub use variant::{ChoiceError, Kind, VARIANTS, Variant, Variants};

/// The largest precision `compare` takes: how far past its answer a query goes on
/// testing objects while the margins are recorded, at most.
pub const MAX_PRECISION: f64 = record::MARGIN_REACH;

use crate::scene::Scene;
use crate::shapes::kernel::{Kernel, KernelChoice, with_kernel};
use crate::shapes::{Dirs, LANES, Ray, unit, units};
use crate::threads::Threads;
use glam::{DVec2, DVec3};
use std::borrow::Cow;
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
    pub(crate) fn ray(&self, x: usize, y: usize) -> Option<Ray> {
        self.ray_through(self.world(x, y))
    }

    /// [`Camera::ray`] for a camera on the grid (not under jitter).
    #[inline(always)]
    fn grid_ray(&self, x: usize, y: usize) -> Option<Ray> {
        self.ray_through(DVec3::new(self.xs[x], self.ys[y], 0.0))
    }

    /// The directions of the grid's rays through the pixels (`xs(i)`, y) for i below
    /// `count` ([`Camera::grid_ray`]'s, the same bits), found together ([`units`]); bit
    /// i of the mask set where lane i has a ray.
    #[inline(always)]
    pub(crate) fn grid_dirs(
        &self,
        xs: impl Fn(usize) -> usize,
        y: usize,
        count: usize,
    ) -> (Dirs, u32) {
        let eye = self.viewpoint;
        let first = self.xs[xs(0)];
        // The target (x, y, 0) less the eye; past `count`, a copy of the first lane's.
        let x = std::array::from_fn(|i| match i < count {
            true => self.xs[xs(i)],
            false => first,
        } - eye.x);
        let (y, z) = ([self.ys[y] - eye.y; LANES], [0.0 - eye.z; LANES]);
        let (dirs, valid) = units(Dirs { x, y, z });
        (dirs, valid & ((1u64 << count) - 1) as u32)
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
pub(crate) struct Setup<'a> {
    pub(crate) scene: Cow<'a, Scene>,
    pub(crate) rules: Rules,
    pub(crate) camera: Camera,
    pub(crate) threads: Threads,
}

impl<'a> Setup<'a> {
    /// For rays traced on the calling thread (a pixel, a sample of pixels).
    pub(crate) fn new(scene: &'a Scene, options: &Options) -> Setup<'a> {
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
    pub(crate) fn for_image(scene: &'a Scene, options: &Options) -> Setup<'a> {
        Setup {
            threads: Threads::of(options),
            ..Setup::new(scene, options)
        }
    }

    /// The tracer, with tiles for the camera's rays, reading the render's rules.
    pub(crate) fn tracer(&self, options: &Options) -> Tracer<'_, &Rules> {
        self.tracer_with(&self.rules, options)
    }

    /// The tracer, reading the rules from `book`.
    pub(crate) fn tracer_with<B: Rulebook>(&self, book: B, options: &Options) -> Tracer<'_, B> {
        // Tiles' lists hold for rays through the pixels' grid: not under jitter.
        let tiles = self.camera.on_grid().then_some((&self.threads, None));
        Tracer::new(&self.scene, book, options, &self.camera, tiles)
    }

    /// The output row that holds pixel row `y` and the reverse: H - 1 - y, or y upside
    /// down (spec §4.1, §7.3).
    pub(crate) fn row_of(&self, y: usize, height: usize) -> usize {
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
    with_kernel!(options.kernel, K => match (tracer.together(), tracer.ambient_only()) {
        (true, _) => each_span(setup, options, spans::<K, B, true, false>(&tracer), progress),
        (false, true) => each_span(setup, options, spans::<K, B, false, true>(&tracer), progress),
        (false, false) => each_span(setup, options, spans::<K, B, false, false>(&tracer), progress),
    })
}

/// What fills a span of the plain render (the pixels from (first, y) on): their bytes,
/// the rays traced `TOGETHER` or not, `AMBIENT` or not ([`Tracer::span`]).
fn spans<'t, K: Kernel, B: Rulebook, const TOGETHER: bool, const AMBIENT: bool>(
    tracer: &'t Tracer<B>,
) -> impl Fn(usize, usize, &mut [[u8; 3]]) + Sync + 't {
    move |first: usize, y: usize, out: &mut [[u8; 3]]| {
        let count = out.len();
        let bytes = |i: usize, colour: DVec3| out[i] = tracer.bytes(colour);
        tracer.span::<K, TOGETHER, AMBIENT>(|i| first + i, y, count, bytes);
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
        with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, Plain, &mut stats));
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
pub(crate) fn each_pixel<T: Send + Clone + Default>(
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
pub(crate) fn each_span<T: Send + Sync + Clone + Default>(
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

/// The colour seen along one ray from the eye (spec §4.2 with total_dist = 0 and no
/// `last_hit`), before the conversion to bytes.
pub fn ray_trace(scene: &Scene, options: &Options, ray: Ray) -> DVec3 {
    let setup = Setup::new(scene, options);
    let tracer = Tracer::new(&setup.scene, &setup.rules, options, &setup.camera, None);
    with_kernel!(options.kernel, K => tracer.through::<K>(ray, Plain, &mut ()))
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
