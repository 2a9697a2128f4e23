//! Pixels: the course's ray tracer (spec §4).
//!
//! [`render`] casts one ray per pixel through the world window (§4.1) and [`ray_trace`]
//! follows it: the closest hit (§4.6), ambient plus the diffuse light of every lamp that
//! the hit point sees (§4.3), divided by the distance travelled so far (§4.2), plus the
//! mirror reflection weighted by the specular triple (§4.5). The stage (spec §7.2) leaves
//! parts of that out, `--show` replaces it by a diagnostic colour, and [`trace()`] records
//! every step of one pixel through the same functions ([`trace::Recorder`]).

mod bvh;
mod choices;
mod lists;
mod shading;
mod tiles;
pub mod trace;
pub mod variant;

pub use bvh::{Boxes, Bvh};
pub use choices::{Choices, by_name, size_problem};
pub use shading::PatternNote;
pub(crate) use shading::{Screen, material_and_pattern};
pub use trace::{Event, LightStep, Recorder, Show, Stage, Trace, trace};
pub use variant::{Deviations, Variant};

use crate::scene::{Light, Scene};
use crate::shapes::kernel::{Accurate, Kernel, KernelChoice, StableRoots, Textbook, TextbookF32};
use crate::shapes::{Ray, Shape, Surface, unit};
use glam::{DVec2, DVec3};
use std::marker::PhantomData;
use tiles::{Tile, Tiles};
use variant::{AsSpecified, Deviating, Divisor, FirstRoot, Rules};

/// The default MAX_DIST of spec §4.2.
pub const DEFAULT_MAX_DIST: f64 = 32.0;

/// A cap on mirror bounces, far beyond any real scene: a ray trapped between mirrors that
/// touch could otherwise bounce without the path length ever reaching MAX_DIST.
pub(crate) const MAX_BOUNCES: usize = 10_000;

/// The most worker threads a render starts, whatever [`Options::threads`] asks for:
/// beyond the cores there is nothing to gain, and a typo must not start 100,000 threads.
pub const MAX_THREADS: usize = 256;

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
    /// Test camera rays against their tiles' lists (`src/render/tiles.rs`) and walk the
    /// bounding volume hierarchy of `src/render/bvh.rs` where the scene has enough
    /// bounded objects for it to pay off; `false` forces the legacy linear scan (for
    /// measurements and tests: the image is the same either way).
    pub accelerate: bool,
    /// How much of spec §4 applies: the course's assignments (spec §7.2).
    pub stage: Stage,
    /// A diagnostic image instead of the stage's, or `None`.
    pub show: Option<Show>,
    /// The rules of spec §4-§5 that this render replaces by a student's mistake (spec
    /// §7.3; [`Options::with_variant`]); none by default.
    pub deviations: Deviations,
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
            deviations: Deviations::default(),
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

/// How many rays of each kind a render cast.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// One per pixel.
    pub camera: u64,
    /// One per light test that got past the cosine and spotlight checks.
    pub shadow: u64,
    /// One per mirror bounce.
    pub reflected: u64,
}

impl std::ops::Add for Stats {
    type Output = Stats;
    fn add(self, other: Stats) -> Stats {
        Stats {
            camera: self.camera + other.camera,
            shadow: self.shadow + other.shadow,
            reflected: self.reflected + other.reflected,
        }
    }
}

impl std::ops::AddAssign for Stats {
    fn add_assign(&mut self, other: Stats) {
        *self = *self + other;
    }
}

impl Stats {
    /// All rays.
    pub fn total(&self) -> u64 {
        self.camera + self.shadow + self.reflected
    }
}

/// A channel in [0, 1] to a byte: clamp, times 255, truncate (spec §4.7). NaN gives 0.
#[inline]
pub(crate) fn to_byte(channel: f64) -> u8 {
    if channel.is_nan() {
        return 0;
    }
    (channel.clamp(0.0, 1.0) * 255.0) as u8
}

/// The camera of spec §4.1: world x of each column, world y of each row.
struct Camera {
    viewpoint: DVec3,
    xs: Vec<f64>,
    ys: Vec<f64>,
}

impl Camera {
    fn new(scene: &Scene, options: &Options) -> Camera {
        let centres = options.deviations.pixel_centre;
        let axis = |count: usize, size: f64| -> Vec<f64> {
            let last = (count - 1) as f64;
            let at = |i: usize| match centres {
                // The variant pixel-centre: (i + 0.5) / count (spec §7.3).
                true => (i as f64 + 0.5) / count as f64,
                false => i as f64 / last,
            };
            (0..count).map(|i| at(i) * size - size / 2.0).collect()
        };
        Camera {
            viewpoint: scene.viewpoint,
            xs: axis(options.width, scene.window.x),
            ys: axis(options.height, scene.window.y),
        }
    }

    /// The world point of pixel (x, y), (0, 0) at the lower left (spec §4.1).
    #[inline]
    fn world(&self, x: usize, y: usize) -> DVec3 {
        DVec3::new(self.xs[x], self.ys[y], 0.0)
    }

    /// The ray through pixel (x, y); `None` if the viewpoint is the pixel's own world
    /// point (no direction).
    #[inline]
    fn ray(&self, x: usize, y: usize) -> Option<Ray> {
        let target = self.world(x, y);
        let dir = unit(target - self.viewpoint)?;
        Some(Ray {
            base: self.viewpoint,
            dir,
        })
    }
}

/// Something to run with the tracer's types chosen from the options: the kernel `K` and
/// whether the rules deviate (`V`).
trait WithTracer {
    type Output;
    fn run<K: Kernel, V: Rules>(self) -> Self::Output;
}

/// Runs `job` with the kernel of `options` and [`AsSpecified`] rules unless a variant
/// changes the tracer's.
fn dispatch<W: WithTracer>(options: &Options, job: W) -> W::Output {
    let deviates = options.deviations.in_tracer();
    match (options.kernel, deviates) {
        (KernelChoice::Accurate, false) => job.run::<Accurate, AsSpecified>(),
        (KernelChoice::Stable, false) => job.run::<StableRoots, AsSpecified>(),
        (KernelChoice::Textbook, false) => job.run::<Textbook, AsSpecified>(),
        (KernelChoice::TextbookF32, false) => job.run::<TextbookF32, AsSpecified>(),
        (KernelChoice::Accurate, true) => job.run::<Accurate, Deviating>(),
        (KernelChoice::Stable, true) => job.run::<StableRoots, Deviating>(),
        (KernelChoice::Textbook, true) => job.run::<Textbook, Deviating>(),
        (KernelChoice::TextbookF32, true) => job.run::<TextbookF32, Deviating>(),
    }
}

/// Renders the scene; `progress` is called with the number of rows done after each row.
pub fn render(scene: &Scene, options: &Options, progress: impl FnMut(usize)) -> (Image, Stats) {
    struct Job<'a, P>(&'a Scene, &'a Options, P);
    impl<P: FnMut(usize)> WithTracer for Job<'_, P> {
        type Output = (Image, Stats);
        fn run<K: Kernel, V: Rules>(self) -> (Image, Stats) {
            let scene = self.1.deviations.scene(self.0);
            render_with::<K, V>(&scene, self.1, self.2)
        }
    }
    dispatch(options, Job(scene, options, progress))
}

fn render_with<K: Kernel, V: Rules>(
    scene: &Scene,
    options: &Options,
    mut progress: impl FnMut(usize),
) -> (Image, Stats) {
    let camera = Camera::new(scene, options);
    let tracer = Tracer::<K, V>::new(scene, options);
    let tiles = (options.accelerate)
        .then(|| {
            Tiles::new(
                scene,
                &tracer.boxes,
                camera.viewpoint,
                &camera.xs,
                &camera.ys,
            )
        })
        .flatten();
    let (width, height) = (options.width, options.height);
    // What a camera ray that hits nothing gives, in every stage and diagnostic image.
    let background = tracer.bytes(DVec3::ZERO);
    let mut pixels = vec![[0u8; 3]; width * height];
    // One output row: pixel y = height - 1 - row (spec §4.1, top row first).
    let render_row = |row: usize, out: &mut [[u8; 3]]| {
        let mut stats = Stats::default();
        // Output row r holds pixel row y = H - 1 - r (spec §4.1), or y = r upside down;
        // the rules as specified need no look at the options.
        let y = match V::DEVIATES {
            true => options.row_of(row),
            false => height - 1 - row,
        };
        for (x, pixel) in out.iter_mut().enumerate() {
            stats.camera += 1;
            let first = tiles.as_ref().and_then(|tiles| tiles.at(x, y));
            // A tile that sees no object: its camera rays hit nothing, and the pixel is
            // the background's, without a ray.
            if first.is_some_and(|tile| tile.objects.is_empty()) {
                *pixel = background;
                continue;
            }
            let colour = match camera.ray(x, y) {
                Some(ray) => tracer.pixel(ray, first, options.show, &mut stats, &mut ()),
                None => DVec3::ZERO,
            };
            *pixel = tracer.bytes(colour);
        }
        stats
    };
    let stats = in_bands(options, &mut pixels, render_row, &mut progress);
    let image = Image {
        width,
        height,
        pixels,
    };
    (image, stats)
}

/// Runs `render_row(row, out)` for every output row of `pixels` on `options.threads`
/// threads, telling `progress` the rows done, and sums the rows' statistics.
fn in_bands<T: Send>(
    options: &Options,
    pixels: &mut [T],
    render_row: impl Fn(usize, &mut [T]) -> Stats + Sync,
    progress: &mut impl FnMut(usize),
) -> Stats {
    let width = options.width;
    #[cfg(feature = "threads")]
    if options.threads != 1
        && let Some(stats) = on_a_pool(options, pixels, &render_row, progress)
    {
        return stats;
    }
    let mut stats = Stats::default();
    for (row, out) in pixels.chunks_mut(width).enumerate() {
        stats += render_row(row, out);
        progress(row + 1);
    }
    stats
}

/// [`in_bands`] on a pool of `options.threads` threads; `None` when no pool can be
/// started (then the caller renders on its own thread).
#[cfg(feature = "threads")]
fn on_a_pool<T: Send>(
    options: &Options,
    pixels: &mut [T],
    render_row: &(impl Fn(usize, &mut [T]) -> Stats + Sync),
    progress: &mut impl FnMut(usize),
) -> Option<Stats> {
    use rayon::prelude::*;
    let (width, height) = (options.width, options.height);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads.min(MAX_THREADS))
        .build()
        .ok()?;
    // Bands of rows, each spread over the pool, so that progress is reported from this
    // thread. Every pixel is computed exactly as on one thread; only the order differs,
    // so the bytes are the same.
    let mut stats = Stats::default();
    let band = 4 * pool.current_num_threads();
    for (index, chunk) in pixels.chunks_mut(band * width).enumerate() {
        let first = index * band;
        stats += pool.install(|| {
            chunk
                .par_chunks_mut(width)
                .enumerate()
                .map(|(row, out)| render_row(first + row, out))
                .reduce(Stats::default, |a, b| a + b)
        });
        progress((first + band).min(height));
    }
    Some(stats)
}

/// `per_pixel` of every camera ray (`None` where the eye is the pixel's world point),
/// in output order (rows top to bottom, spec §4.1), on `options.threads` threads;
/// `per_pixel` is also told the pixel's output index.
fn map_pixels<T: Send + Clone + Default>(
    scene: &Scene,
    options: &Options,
    per_pixel: impl Fn(usize, Option<Ray>, &mut Stats) -> T + Sync,
) -> Vec<T> {
    let camera = Camera::new(scene, options);
    let mut pixels = vec![T::default(); options.width * options.height];
    let render_row = |row: usize, out: &mut [T]| {
        let mut stats = Stats::default();
        // Output row r holds pixel row y = H - 1 - r, the same map both ways.
        let y = options.row_of(row);
        for (x, pixel) in out.iter_mut().enumerate() {
            *pixel = per_pixel(row * options.width + x, camera.ray(x, y), &mut stats);
        }
        stats
    };
    in_bands(options, &mut pixels, render_row, &mut |_| {});
    pixels
}

/// The object a camera ray hits first, in 4 bytes (a pixel of a 4096x4096 reference
/// keeps one): its index plus one, or nothing for the background.
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

/// The object each camera ray hits first (spec §4.6), in output order.
pub fn first_hits(scene: &Scene, options: &Options) -> Vec<FirstHit> {
    struct Job<'a>(&'a Scene, &'a Options);
    impl WithTracer for Job<'_> {
        type Output = Vec<FirstHit>;
        fn run<K: Kernel, V: Rules>(self) -> Self::Output {
            let Job(scene, options) = self;
            let scene = options.deviations.scene(scene);
            let tracer = Tracer::<K, V>::new(&scene, options);
            let first = |_, ray: Option<Ray>, _: &mut Stats| {
                let hit = ray.and_then(|ray| tracer.closest_hit(&ray, None, None, &mut ()));
                FirstHit::of(hit.map(|(index, _)| index))
            };
            map_pixels(&scene, options, first)
        }
    }
    dispatch(options, Job(scene, options))
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
/// under the smallest MAX_DIST (the camera ray's segment alone), and every change of
/// every change of its bytes as D grows, sorted by D (spec §4.2 step 1: under MAX_DIST
/// D a pixel has the bytes after the last segment starting at D or less). Only changes
/// are kept, so the memory grows with the mirror bounces that change a byte, not with
/// the image.
pub fn path_agreement(
    scene: &Scene,
    options: &Options,
    agrees: impl Fn(usize, [u8; 3]) -> bool + Sync,
) -> (Vec<bool>, Vec<PathChange>) {
    /// Each segment's start and the colour after it.
    struct Path(Vec<(f64, DVec3)>);
    impl Recorder for Path {
        const ENABLED: bool = true;
        const EVERY_TEST: bool = false;
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
    struct Job<'a, A>(&'a Scene, &'a Options, A);
    impl<A: Fn(usize, [u8; 3]) -> bool + Sync> WithTracer for Job<'_, A> {
        type Output = (Vec<bool>, Vec<PathChange>);
        fn run<K: Kernel, V: Rules>(self) -> Self::Output {
            let Job(scene, options, agrees) = self;
            let scene = options.deviations.scene(scene);
            let tracer = Tracer::<K, V>::new(&scene, options);
            let changes = std::sync::Mutex::new(Vec::new());
            let path = |pixel: usize, ray: Option<Ray>, stats: &mut Stats| {
                let mut path = Path(Vec::new());
                if let Some(ray) = ray {
                    tracer.trace(ray, None, stats, &mut path);
                }
                let bytes =
                    |colour: DVec3| colour.to_array().map(|c| options.deviations.bytes.byte(c));
                let mut entries = path.0.iter();
                let first = entries.next().map_or(DVec3::ZERO, |&(_, c)| c);
                let mut last = bytes(first);
                let mut mine = Vec::new();
                // Segments that change no byte (deep bounces between two mirrors) are
                // left out: D passing them gives the same image.
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
                if !mine.is_empty()
                    && let Ok(mut changes) = changes.lock()
                {
                    changes.extend(mine);
                }
                agrees(pixel, bytes(first))
            };
            let first = map_pixels(&scene, options, path);
            let mut changes = changes.into_inner().unwrap_or_default();
            // By D, then by pixel; a pixel's own changes were pushed in path order and
            // the sort is stable, so they stay in that order.
            changes.sort_by(|a, b| a.start.total_cmp(&b.start).then(a.pixel.cmp(&b.pixel)));
            (first, changes)
        }
    }
    dispatch(options, Job(scene, options, agrees))
}

/// The colour seen along one ray from the eye (spec §4.2 with total_dist = 0 and no
/// `last_hit`), before the conversion to bytes.
pub fn ray_trace(scene: &Scene, options: &Options, ray: Ray) -> DVec3 {
    struct Job<'a>(&'a Scene, &'a Options, Ray);
    impl WithTracer for Job<'_> {
        type Output = DVec3;
        fn run<K: Kernel, V: Rules>(self) -> DVec3 {
            let Job(scene, options, ray) = self;
            let scene = options.deviations.scene(scene);
            let tracer = Tracer::<K, V>::new(&scene, options);
            tracer.pixel(ray, None, options.show, &mut Stats::default(), &mut ())
        }
    }
    dispatch(options, Job(scene, options, ray))
}

/// The scene and what every ray needs of the options; `K` computes the hits, and `V`
/// says whether the rules deviate ([`variant`]).
struct Tracer<'a, K, V> {
    scene: &'a Scene,
    /// The objects' boxes: a hit counts only inside its object's box (`Boxes::admits`).
    boxes: Boxes,
    /// The hierarchy over the bounded objects, when there are enough of them.
    bvh: Option<Bvh>,
    max_dist: f64,
    screen: Screen,
    /// Which parts of spec §4 apply (spec §7.2).
    stage: Stage,
    /// The variants' rules; read only where `V::DEVIATES`.
    deviations: Deviations,
    kernel: PhantomData<(K, V)>,
}

impl<'a, K: Kernel, V: Rules> Tracer<'a, K, V> {
    fn new(scene: &'a Scene, options: &Options) -> Tracer<'a, K, V> {
        let screen = Screen {
            last_pixel: DVec2::new((options.width - 1) as f64, (options.height - 1) as f64),
            window: scene.window,
        };
        let boxes = Boxes::for_kernel(scene, options.kernel);
        Tracer {
            scene,
            bvh: (options.accelerate)
                .then(|| Bvh::for_rays(&boxes, options.width * options.height))
                .flatten(),
            boxes,
            max_dist: options.max_dist,
            screen,
            stage: options.stage,
            deviations: options.deviations,
            kernel: PhantomData,
        }
    }

    /// Whether the variant that `rule` picks out applies (never, at compile time, for
    /// the rules as specified).
    #[inline(always)]
    fn deviates(&self, rule: impl FnOnce(&Deviations) -> bool) -> bool {
        V::DEVIATES && rule(&self.deviations)
    }

    /// The pixel's bytes (spec §4.7, or round-bytes or scale-256).
    #[inline(always)]
    fn bytes(&self, colour: DVec3) -> [u8; 3] {
        match V::DEVIATES {
            true => colour.to_array().map(|c| self.deviations.bytes.byte(c)),
            false => colour.to_array().map(to_byte),
        }
    }

    /// What a ray leaving object `left` skips, and above which t a hit counts: the
    /// object itself and t > 0 (spec §4.2, §4.3), or nothing and t > ε under
    /// shadow-epsilon.
    #[inline(always)]
    fn leaving(&self, left: Option<usize>) -> (Option<usize>, f64) {
        match (V::DEVIATES, self.deviations.epsilon, left) {
            (true, Some(epsilon), Some(_)) => (None, epsilon),
            _ => (left, 0.0),
        }
    }

    /// Whether `shape` tries its smaller root only: a quadric 21-24 under nearer-root.
    #[inline(always)]
    fn nearer_root_only(&self, shape: &Shape) -> bool {
        self.deviates(|d| d.nearer_root) && shape.axis_frame().is_some()
    }

    /// The shape's t along `ray` (the caller keeps t > 0).
    #[inline(always)]
    fn hit(&self, shape: &Shape, ray: &Ray) -> Option<f64> {
        if self.nearer_root_only(shape) {
            let mut first = FirstRoot::default();
            shape.hit_noted::<K>(ray, &mut first);
            return first.t();
        }
        shape.hit_with::<K>(ray)
    }

    /// Object `index`'s t along `ray`, told to `rec` with the shape's reasons when it
    /// records (the normal render takes the kernel's fastest entry instead: same t).
    #[inline(always)]
    fn test<R: Recorder>(
        &self,
        index: usize,
        shape: &Shape,
        ray: &Ray,
        rec: &mut R,
    ) -> Option<f64> {
        if !R::EVERY_TEST {
            return self.hit(shape, ray);
        }
        let mut notes = Vec::new();
        let mut t = shape.hit_noted::<K>(ray, &mut notes);
        if self.nearer_root_only(shape) {
            t = FirstRoot::of(&mut notes);
        }
        rec.record(|| Event::Tested {
            object: index,
            t,
            notes,
        });
        t
    }

    /// The closest object with t > 0 along `ray`, skipping `last_hit`; ties go to the
    /// earlier object (spec §4.6). `candidates`, when given, holds near to far every
    /// object whose hit could count (a camera ray's tile).
    #[inline(always)]
    fn closest_hit<R: Recorder>(
        &self,
        ray: &Ray,
        last_hit: Option<usize>,
        candidates: Option<Tile>,
        rec: &mut R,
    ) -> Option<(usize, f64)> {
        let (last_hit, least) = self.leaving(last_hit);
        let counts = |index: usize, t: f64| t > least && self.boxes.admits(index, ray, t);
        if let Some(tile) = candidates
            && !R::EVERY_TEST
        {
            // Near to far: past the best hit so far, nothing can win or tie.
            let mut best: Option<(usize, f64)> = None;
            for &index in tile.objects {
                let index = index as usize;
                if best.is_some_and(|(_, t)| tile.nearest[index] > t) {
                    break;
                }
                if Some(index) != last_hit
                    && let Some(t) = self.hit(&self.scene.objects[index].shape, ray)
                    && bvh::beats(best, index, t)
                    && counts(index, t)
                {
                    best = Some((index, t));
                }
            }
            return best;
        }
        if let Some(bvh) = &self.bvh
            && !R::EVERY_TEST
        {
            let test = |index: usize| {
                let shape = &self.scene.objects[index].shape;
                (Some(index) != last_hit).then(|| self.hit(shape, ray))?
            };
            return bvh.closest(ray, test, counts);
        }
        let mut best: Option<(usize, f64)> = None;
        for (index, object) in self.scene.objects.iter().enumerate() {
            if Some(index) == last_hit {
                rec.record(|| Event::Skipped { object: index });
                continue;
            }
            if let Some(t) = self.test(index, &object.shape, ray, rec)
                && best.is_none_or(|(_, best_t)| t < best_t)
                && counts(index, t)
            {
                best = Some((index, t));
            }
        }
        best
    }

    /// Whether an object but `skip` lies on `ray` closer than `dist`, blocking the light
    /// (spec §4.3). The first such object in file order, with its t, is recorded.
    #[inline]
    fn blocked<R: Recorder>(&self, ray: &Ray, skip: usize, dist: f64, rec: &mut R) -> bool {
        // No object has index usize::MAX: nothing is skipped under shadow-epsilon.
        let (skip, least) = match self.leaving(Some(skip)) {
            (Some(skip), least) => (skip, least),
            (None, least) => (usize::MAX, least),
        };
        let blocks =
            |index: usize, t: f64| t > least && t < dist && self.boxes.admits(index, ray, t);
        if let Some(bvh) = &self.bvh
            && !R::EVERY_TEST
        {
            return bvh.any(ray, dist, |index| {
                index != skip
                    && self
                        .hit(&self.scene.objects[index].shape, ray)
                        .is_some_and(|t| blocks(index, t))
            });
        }
        for (index, object) in self.scene.objects.iter().enumerate() {
            if index == skip {
                rec.record(|| Event::Skipped { object: index });
                continue;
            }
            if let Some(t) = self.test(index, &object.shape, ray, rec)
                && blocks(index, t)
            {
                let blocker = Some((index, t));
                rec.record(|| Event::Light(LightStep::Blocked { blocker }));
                return true;
            }
        }
        rec.record(|| Event::Light(LightStep::Blocked { blocker: None }));
        false
    }

    /// ray_trace of spec §4.2, with the mirror recursion unrolled into a loop: the colour
    /// is Σ (S₁ ⊙ … ⊙ Sₖ) ⊙ Iₖ₊₁ / total_distₖ₊₁ over the bounces. The stage (spec §7.2)
    /// leaves out the lights, the shadow rays or the reflection.
    /// `first`, when given, is the camera ray's tile: every object the ray may hit.
    fn trace<R: Recorder>(
        &self,
        mut ray: Ray,
        first: Option<Tile>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> DVec3 {
        let mut colour = DVec3::ZERO;
        let mut weight = DVec3::ONE;
        let mut total_dist = 0.0;
        let mut last_hit = None;
        let bounces = match self.deviates(|d| d.one_bounce) {
            true => 1,
            false => MAX_BOUNCES,
        };
        for depth in 0..=bounces {
            if total_dist > self.max_dist {
                rec.record(|| Event::CutOff { total_dist });
                break;
            }
            rec.record(|| Event::Segment {
                depth,
                ray,
                total_dist,
            });
            let candidates = if depth == 0 { first } else { None };
            let hit = self.closest_hit(&ray, last_hit, candidates, rec);
            rec.record(|| Event::Closest { hit });
            let Some((index, t)) = hit else {
                break;
            };
            total_dist += t;
            let object = &self.scene.objects[index];
            let mut surface = object.shape.surface(&ray, t);
            if self.deviates(|d| d.facing_normals) && surface.normal.dot(ray.dir) > 0.0 {
                surface.normal = -surface.normal;
            }
            let (material, pattern) = material_and_pattern(object, &surface, &self.screen);
            rec.record(|| Event::Surface {
                object: index,
                t,
                total_dist,
                surface,
                material,
                pattern,
            });
            let mut intensity = material.ambient;
            if self.stage.lights() {
                for (light, lamp) in self.scene.lights.iter().enumerate() {
                    rec.record(|| Event::Lamp { light });
                    let diffuse = self.diffuse(lamp, index, &surface, material.diffuse, stats, rec);
                    intensity += diffuse;
                    rec.record(|| Event::Lit {
                        light,
                        contribution: diffuse,
                        intensity,
                    });
                }
            }
            let seen = match self.deviates(|d| d.divisor != Divisor::Path) {
                false => intensity / total_dist,
                true if self.deviations.divisor == Divisor::Segment => intensity / t,
                true => intensity,
            };
            colour += weight * seen;
            rec.record(|| Event::Divided {
                intensity,
                total_dist,
                seen,
                weight,
                colour,
            });
            if material.specular == DVec3::ZERO || !self.stage.reflects() || depth == bounces {
                break;
            }
            weight *= material.specular;
            stats.reflected += 1;
            let d = ray.dir;
            let n = surface.normal;
            let Some(dir) = unit(d - 2.0 * d.dot(n) * n) else {
                break;
            };
            ray = Ray {
                base: surface.point,
                dir,
            };
            last_hit = Some(index);
        }
        colour
    }

    /// One light's diffuse contribution at a hit on object `index` (spec §4.3).
    #[inline]
    fn diffuse<R: Recorder>(
        &self,
        light: &Light,
        index: usize,
        surface: &Surface,
        diffuse: DVec3,
        stats: &mut Stats,
        rec: &mut R,
    ) -> DVec3 {
        if diffuse == DVec3::ZERO {
            rec.record(|| Event::Light(LightStep::NoDiffuse));
            return DVec3::ZERO;
        }
        let to_light = light.location - surface.point;
        let dist = to_light.length();
        // A light at the hit point, or so far away that the distance overflowed, has no
        // direction: no contribution rather than a NaN.
        if dist.is_nan() || dist <= 0.0 || dist.is_infinite() {
            rec.record(|| Event::Light(LightStep::NoDirection { dist }));
            return DVec3::ZERO;
        }
        let u = to_light / dist;
        let cos = surface.normal.dot(u);
        rec.record(|| Event::Light(LightStep::Towards { u, dist, cos }));
        if cos.is_nan() || cos <= 0.0 {
            return DVec3::ZERO;
        }
        if let Some(beam) = &light.beam {
            let along = (-u).dot(beam.direction);
            let lit = along > beam.cos_limit;
            rec.record(|| Event::Light(LightStep::Spot { along, lit }));
            if !lit {
                return DVec3::ZERO;
            }
        }
        if self.stage.shadows() && !self.deviates(|d| d.no_shadows) {
            stats.shadow += 1;
            let shadow = Ray {
                base: surface.point,
                dir: u,
            };
            rec.record(|| Event::Light(LightStep::ShadowRay { ray: shadow }));
            if self.blocked(&shadow, index, dist, rec) {
                return DVec3::ZERO;
            }
        }
        let falloff = match self.deviates(|d| d.square_falloff) {
            true => dist * dist,
            false => dist,
        };
        diffuse * light.emissivity * (cos / falloff)
    }

    /// The diagnostic image of `show` at the first hit along `ray` (spec §7.2's companions:
    /// normals, object ids, distance).
    fn show<R: Recorder>(&self, ray: Ray, show: Show, first: Option<Tile>, rec: &mut R) -> DVec3 {
        rec.record(|| Event::Segment {
            depth: 0,
            ray,
            total_dist: 0.0,
        });
        let hit = self.closest_hit(&ray, None, first, rec);
        rec.record(|| Event::Closest { hit });
        let Some((index, t)) = hit else {
            return DVec3::ZERO;
        };
        let colour = match show {
            Show::Normals => {
                let normal = self.scene.objects[index].shape.surface(&ray, t).normal;
                (normal + DVec3::ONE) / 2.0
            }
            Show::Objects => object_colour(index),
            Show::Depth => DVec3::splat(1.0 - t / self.max_dist),
        };
        rec.record(|| Event::Shown { show, colour });
        colour
    }

    /// The colour of one camera ray under the options: the stage's image, or a
    /// diagnostic one.
    #[inline]
    fn pixel<R: Recorder>(
        &self,
        ray: Ray,
        first: Option<Tile>,
        show: Option<Show>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> DVec3 {
        match show {
            None => self.trace(ray, first, stats, rec),
            Some(show) => self.show(ray, show, first, rec),
        }
    }
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
