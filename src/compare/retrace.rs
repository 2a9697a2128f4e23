//! The renderer's pixels as `compare --diagnose` needs them, on the renderer's frame
//! ([`Tracer::pixel`], [`Tracer::span`]): the bytes of chosen pixels only
//! ([`render_pixels`]), what each pixel's path involves ([`involved`]), and where each
//! pixel's bytes change as MAX_DIST grows ([`path_agreement`]).

use crate::render::record::{Event, LightStep, Recorder};
use crate::render::tiles;
use crate::render::tracer::Tracer;
use crate::render::variant::{Rulebook, Rules};
use crate::render::{Forced, Near, Noted, Options, Override, Plain, Setup, each_pixel};
use crate::scene::Scene;
use crate::shapes::kernel::{Kernel, with_kernel};
use glam::DVec3;

/// The bytes of the pixels `indices` (output order: row 0 at the top) of the scene's
/// image under `options`, without the rest: the same bytes as
/// [`render`](crate::render::render) gives there. For `compare --diagnose`, which tries
/// a variant on a sample of pixels, and re-traces the pixels a variant can change,
/// rather than render whole images. The camera rays go
/// through the lists of the tiles the pixels fall in where they are dense enough to pay
/// for them (`PIXELS_PER_LIST`, 8 a tile); the hierarchy is kept. Where shadow rays are
/// cast, the pixels that follow each other in `indices` within one row of one tile are
/// traced together, a span as in `render`.
pub fn render_pixels(scene: &Scene, options: &Options, indices: &[usize]) -> Vec<[u8; 3]> {
    // The kernel chosen once, outside the loop over the pixels (as in `render`), and
    // whether the spans' rays go together or need only the ambient: each loop is
    // compiled for one.
    with_kernel!(options.kernel, K => with_tracer(scene, options, indices, |_, tracer, rows| {
        match (tracer.together(), tracer.ambient_only()) {
            (true, _) => spans_of::<K, true, false>(tracer, indices, rows),
            (false, true) => spans_of::<K, false, true>(tracer, indices, rows),
            (false, false) => spans_of::<K, false, false>(tracer, indices, rows),
        }
    }))
}

/// [`render_pixels`] with `tracer`, the rays of each span traced `TOGETHER` or not,
/// `AMBIENT` or not ([`Tracer::span`]).
fn spans_of<K: Kernel, const TOGETHER: bool, const AMBIENT: bool>(
    tracer: &Tracer<&Rules>,
    indices: &[usize],
    rows: &mut Rows,
) -> Vec<[u8; 3]> {
    // Every pixel is written: a span whose tile sees nothing gives black's bytes.
    let mut pixels = vec![[0; 3]; indices.len()];
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
        tracer.span::<K, TOGETHER, AMBIENT>(|i| xs[i], y, count, bytes);
    }
    pixels
}

/// The bytes of the pixels `indices` (output order) with the decisions `overrides` forced
/// on every pixel's path: the image the scene would give there were an object missed by
/// one kind of ray, or a light's shadow test decided ([`Override`]). What a diagnosis
/// tries where no variant explains a student's pixels.
pub fn render_forced(
    scene: &Scene,
    options: &Options,
    indices: &[usize],
    overrides: &[Override],
) -> Vec<[u8; 3]> {
    let mut each = render_forced_each(scene, options, &[(overrides, indices)]);
    each.pop().unwrap_or_default()
}

/// [`render_forced`] for each of `jobs` (the overrides, and the pixels to force them
/// on), on one frame: the decision flips of `compare --diagnose` try many sets of
/// overrides, each on a few pixels. The camera rays go through the hierarchy, not the
/// tiles' lists ([`Forced`]), so none is built.
pub(crate) fn render_forced_each(
    scene: &Scene,
    options: &Options,
    jobs: &[(&[Override], &[usize])],
) -> Vec<Vec<[u8; 3]>> {
    with_tracer(scene, options, &[], |_, tracer, rows| {
        let each = |&(overrides, indices): &(&[Override], &[usize])| {
            let query = Forced::new(overrides);
            let pixel = |&i: &usize| {
                let (x, y) = rows.at(i);
                let colour =
                    with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, query, &mut ()));
                tracer.bytes(colour)
            };
            indices.iter().map(pixel).collect()
        };
        jobs.iter().map(each).collect()
    })
}

/// What the paths of the pixels `indices` (output order) tell a recorder `R` each, with
/// the shapes' decisions on every object tested ([`Noted`]: the tiles and the hierarchy
/// still choose which are tested): the decisions the diagnosis may flip.
pub(crate) fn recorded<R: Recorder + Default>(
    scene: &Scene,
    options: &Options,
    indices: &[usize],
) -> Vec<R> {
    at_pixels(scene, options, indices, |_, tracer, x, y| {
        let mut path = R::default();
        with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, Noted, &mut path));
        path
    })
}

/// How many of the pixels to trace a tile must hold, on average, for its list to be
/// built. On a04 at 640x480 a tile's list costs about 6,000 instructions to build
/// (callgrind: `Tiles::new` 30M for 4,800 tiles), some 0.5 µs at the 12 instructions a
/// nanosecond the plain render runs at there, and a camera ray that tests a list rather
/// than the hierarchy saves about 70 ns (33,466 pixels re-traced in 4.5 ms without lists,
/// 2.2 ms with them): the lists pay from about 7 pixels a tile.
const PIXELS_PER_LIST: usize = 8;

/// `per_pixel(setup, tracer, x, y)` for each of the pixels `indices` (output
/// order), with [`with_tracer`]'s tracer.
fn at_pixels<T>(
    scene: &Scene,
    options: &Options,
    indices: &[usize],
    mut per_pixel: impl FnMut(&Setup, &Tracer<&Rules>, usize, usize) -> T,
) -> Vec<T> {
    with_tracer(scene, options, indices, |setup, tracer, rows| {
        // A plain loop: as `map(..).collect()` the same tracing took some 15 % longer
        // (a02, every pixel, 14.9 ms against 13.7 ms; `render` 12.8 ms).
        let mut pixels = Vec::with_capacity(indices.len());
        for &i in indices {
            let (x, y) = rows.at(i);
            pixels.push(per_pixel(setup, tracer, x, y));
        }
        pixels
    })
}

/// `trace(setup, tracer, rows)` with a tracer with the lists of the tiles the
/// pixels `indices` fall in where they hold [`PIXELS_PER_LIST`] of them a tile, and the
/// pixels' (x, y) by their index.
fn with_tracer<T>(
    scene: &Scene,
    options: &Options,
    indices: &[usize],
    trace: impl FnOnce(&Setup, &Tracer<&Rules>, &mut Rows) -> T,
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
    trace(&setup, &tracer, &mut rows)
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
    at_pixels(scene, options, indices, |_, tracer, x, y| {
        let mut path = Involved::default();
        with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, Plain, &mut path));
        path
    })
}

/// For each of the pixels `indices` (output order), under `options`, the least
/// shadow epsilon ε (spec §7.5: a ray leaving a surface counts only the hits past ε) at
/// which one of its blocked shadow rays is blocked no more: the farthest blocker of the
/// ray whose farthest is nearest. `None` where no shadow ray of the pixel is blocked.
/// The path is the one of `options`: what ε would change on mirror rays, and on the
/// object a ray leaves, is not counted; the diagnosis renders what this suggests.
pub fn unblocked_at(scene: &Scene, options: &Options, indices: &[usize]) -> Vec<Option<f64>> {
    /// The pixel's answer so far, and the open shadow ray's distance to its light and
    /// farthest blocker.
    #[derive(Default)]
    struct Blockers {
        least: Option<f64>,
        dist: f64,
        open: Option<f64>,
    }
    impl Recorder for Blockers {
        fn record(&mut self, event: impl FnOnce() -> Event) {
            match event() {
                Event::Light(LightStep::Towards { dist, .. }) => self.dist = dist,
                Event::Light(LightStep::ShadowRay { .. }) => self.open = Some(0.0),
                Event::Tested { t: Some(t), .. } if t > 0.0 && t < self.dist => {
                    if let Some(farthest) = self.open.as_mut() {
                        *farthest = farthest.max(t);
                    }
                }
                Event::Light(LightStep::Blocked { blocker }) => {
                    let farthest = self.open.take();
                    if let Some(farthest) = farthest.filter(|_| blocker.is_some()) {
                        self.least = Some(self.least.map_or(farthest, |l| l.min(farthest)));
                    }
                }
                _ => {}
            }
        }
    }
    // Every blocker tested, not only the first ([`Near`]'s shadow queries).
    at_pixels(scene, options, indices, |_, tracer, x, y| {
        let mut path = Blockers::default();
        with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, Near(0.0), &mut path));
        path.least
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
    let first = at_pixels(scene, options, indices, |setup, tracer, x, y| {
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
pub(crate) fn by_distance(changes: &mut [PathChange]) {
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
    with_kernel!(options.kernel, K => tracer.pixel::<K>(x, y, Plain, &mut path));
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
