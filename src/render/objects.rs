//! The aggregate: the scene's objects behind the two questions the tracer asks (pbrt's
//! aggregate, the hierarchy just another way of answering): which object a ray hits
//! first ([`Objects::closest`], spec §4.6) and whether anything blocks a shadow ray
//! before the light ([`Objects::blocked`], spec §4.3).
//!
//! Inside, three ways of answering give the same answers: a camera ray tests its tile's
//! list, near to far ([`super::tiles`]); other rays walk the bounding volume hierarchy
//! ([`super::bvh`]) where the scene has enough bounded objects for it to pay; otherwise,
//! and for a trace, every object is tested in file order, as the course's program did.
//! All three count a hit only where the ray has entered the object's box
//! ([`Boxes::admits`]) and break ties with one rule ([`beats`]). The rules of which
//! objects a ray may hit live here too: the object a ray leaves is skipped (or, under
//! shadow-epsilon, every hit within ε of the base is), and the variants hidden and
//! no-shadow take one object out of one kind of test.
//!
//! The kernel is each query's type parameter, chosen by the caller once per render
//! (`with_kernel!`), so that no object test pays for the choice.

use super::bvh::{Aabb, Boxes, Bvh, beats};
use super::record::{Event, LightStep, Recorder, Skip};
use super::tiles::{Tile, Tiles};
use super::variant::{Kind, Rulebook};
use super::{Camera, Options};
use crate::scene::{Object, Scene};
use crate::shapes::kernel::Kernel;
use crate::shapes::{Ahead, Dirs, HitNote, LANES, Notes, Ray, discriminant_note};
use crate::threads::Threads;
use glam::DVec3;

/// How a query of the aggregate is answered: the caller's choice, an explicit value
/// ([`Plain`], [`EveryObject`], [`Near`], [`Noted`] or [`Forced`]), never the recorder's. The answer is the same
/// in every mode; what differs is which objects are tested and what the recorder hears.
pub(crate) trait Query: Copy {
    /// Whether every object is tested in file order with its reasons, as the course's
    /// program tested them (the readable trace), instead of through the tiles and the
    /// hierarchy.
    const EVERY_OBJECT: bool = false;

    /// Whether the shapes' decisions are told to the recorder for every object tested
    /// ([`Recorder::tested`]), also where the tiles and the hierarchy choose which.
    const NOTES: bool = Self::EVERY_OBJECT;

    /// Whether camera rays may test their tiles' lists: not every object, and no
    /// decision forced (a list leaves out what a nearer plane hides from its tile).
    const TILES: bool = !Self::EVERY_OBJECT;

    /// Whether a shadow query tests every object that may block it, rather than stopping
    /// at the first blocker: the margins', where a shadow is as sure as its surest
    /// blocker.
    const EVERY_BLOCKER: bool = false;

    /// How far past its answer (the best hit, or the light) the query goes on testing
    /// objects, as a share of the distance.
    #[inline(always)]
    fn reach(self) -> f64 {
        0.0
    }

    /// The query as it applies to rays of the kind `rays` (what a forced decision needs
    /// to know of the ray).
    #[inline(always)]
    fn on(self, _rays: Rays) -> Self {
        self
    }

    /// Whether object `index` is forced to a miss on the rays this query is on.
    #[inline(always)]
    fn misses(self, _index: usize) -> bool {
        false
    }

    /// What light `light`'s shadow test is forced to say (blocked or not), if forced.
    #[inline(always)]
    fn shadow(self, _light: usize) -> Option<bool> {
        None
    }

    /// Whether a hit on object `index`, a tiled plane, is forced to take the other
    /// tile's material.
    #[inline(always)]
    fn other_tile(self, _index: usize) -> bool {
        false
    }

    /// Whether a hit on object `index` is forced to trace no mirror ray.
    #[inline(always)]
    fn no_bounce(self, _index: usize) -> bool {
        false
    }

    /// Whether a path longer than MAX_DIST is forced to go on rather than end black.
    #[inline(always)]
    fn never_cut(self) -> bool {
        false
    }
}

/// The answer alone, the quickest way: the tiles' lists and the hierarchy.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Plain;

impl Query for Plain {}

/// Every object in file order, each test's decisions told: a trace.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EveryObject;

impl Query for EveryObject {
    const EVERY_OBJECT: bool = true;
}

/// The answer, and every object that comes within the reach (a share of the distance,
/// at most [`MARGIN_REACH`](super::record::MARGIN_REACH)) of changing it, each test's decisions told: the margins of
/// `compare`'s fragile pixels. A shadow query tests every object that may block it, not
/// only the first: the shadow is as sure as the surest of its blockers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Near(pub(crate) f64);

impl Query for Near {
    const NOTES: bool = true;
    const EVERY_BLOCKER: bool = true;

    #[inline(always)]
    fn reach(self) -> f64 {
        self.0
    }
}

/// The answer, with each test's decisions told, through the tiles and the hierarchy as
/// the plain render tests: the decisions on a pixel's path that a diagnosis may flip.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Noted;

impl Query for Noted {
    const NOTES: bool = true;
}

/// The answer with some of the tracer's decisions forced the other way, the same for
/// every pixel ([`Override`]): what a diagnosis tries when no variant explains a student's
/// image. Camera rays go through the hierarchy rather than their tiles' lists.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Forced<'o> {
    overrides: &'o [Override],
    /// The rays the query is on.
    rays: Rays,
}

impl Forced<'_> {
    /// The query that forces `overrides`.
    pub(crate) fn new(overrides: &[Override]) -> Forced<'_> {
        Forced {
            overrides,
            rays: Rays::Camera,
        }
    }
}

impl Query for Forced<'_> {
    const TILES: bool = false;

    #[inline]
    fn on(self, rays: Rays) -> Self {
        Forced { rays, ..self }
    }

    #[inline]
    fn misses(self, index: usize) -> bool {
        let rays = self.rays;
        (self.overrides.iter()).any(|o| {
            *o == Override::Miss {
                object: index,
                rays,
            }
        })
    }

    #[inline]
    fn shadow(self, light: usize) -> Option<bool> {
        self.overrides.iter().find_map(|o| match *o {
            Override::Shadow { light: l, blocked } if l == light => Some(blocked),
            _ => None,
        })
    }

    #[inline]
    fn other_tile(self, index: usize) -> bool {
        self.overrides.contains(&Override::Tile { object: index })
    }

    #[inline]
    fn no_bounce(self, index: usize) -> bool {
        self.overrides
            .contains(&Override::NoBounce { object: index })
    }

    #[inline]
    fn never_cut(self) -> bool {
        self.overrides.contains(&Override::NeverCut)
    }
}

/// The rays a forced miss applies to ([`Override::Miss`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rays {
    /// The camera rays.
    Camera,
    /// The mirror rays.
    Mirror,
    /// The shadow rays toward every light.
    Shadow,
}

/// One decision of the tracer forced the other way on every pixel, whatever the geometry
/// says: an object missed by one kind of ray, a light's shadow test decided, a tiled
/// plane's tile colour swapped, an object's mirror ray left out, or MAX_DIST's cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Override {
    /// Object `object` (its index among the scene's objects) is missed by `rays`.
    Miss {
        /// The object's index among the scene's objects.
        object: usize,
        /// The rays that miss it.
        rays: Rays,
    },
    /// Light `light`'s shadow test says `blocked`, where the stage casts shadow rays.
    Shadow {
        /// The light's index among the scene's lights.
        light: usize,
        /// Whether the light is blocked.
        blocked: bool,
    },
    /// A hit on tiled plane `object` takes the other tile's material (spec §5.4).
    Tile {
        /// The plane's index among the scene's objects.
        object: usize,
    },
    /// A hit on `object` traces no mirror ray (spec §4.5).
    NoBounce {
        /// The object's index among the scene's objects.
        object: usize,
    },
    /// A path longer than MAX_DIST goes on (spec §4.2 step 1 never ends it).
    NeverCut,
}

/// The closest hit of a ray: the object's index among the scene's objects, and t.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    /// The object's index among the scene's objects.
    pub(crate) object: usize,
    /// The distance along the ray.
    pub(crate) t: f64,
}

/// Where a ray starts: the eye, through a pixel (a camera ray), or an object's surface
/// (a shadow or mirror ray, which skips that object).
#[derive(Clone, Copy)]
pub(crate) enum From<'t> {
    /// A camera ray, with the list of its pixel's tile when there is one
    /// ([`Objects::tile`]).
    Eye(Option<Tile<'t>>),
    /// A ray leaving object k's surface.
    Surface(usize),
}

/// The scene's objects, with what answers the two questions quickly.
pub(crate) struct Objects<'a, B> {
    scene: &'a Scene,
    /// Every object's box: a hit counts only inside its object's box.
    boxes: Boxes,
    /// The hierarchy over the bounded objects, when there are enough of them.
    bvh: Option<Bvh>,
    /// The camera rays' lists, per tile of pixels.
    tiles: Option<Tiles>,
    /// Which objects a ray skips, where variants change it.
    rules: B,
}

impl<'a, B: Rulebook> Objects<'a, B> {
    /// The aggregate of `scene` for a render with `options` and `rules`, with tiles for
    /// the camera's rays when a camera is given (those `cells` marks, or all).
    pub(crate) fn new(
        scene: &'a Scene,
        rules: B,
        options: &Options,
        camera: Option<(&Camera, &Threads)>,
        cells: Option<&[bool]>,
    ) -> Objects<'a, B> {
        let one = Threads::one();
        let threads = camera.map_or(&one, |(_, threads)| threads);
        let boxes = Boxes::on(scene, options.kernel, threads);
        let accelerate = options.accelerate;
        let rays = options.width * options.height;
        let bvh = accelerate
            .then(|| Bvh::for_rays(&boxes, rays, threads))
            .flatten();
        let hidden =
            |index: usize| rules.some(Kind::Hidden) && rules.object(index).has(Kind::Hidden);
        let tiles = (camera.filter(|_| accelerate)).and_then(|(camera, threads)| {
            let pixels = (&camera.xs[..], &camera.ys[..]);
            Tiles::new(
                scene,
                &boxes,
                camera.viewpoint,
                pixels,
                hidden,
                cells,
                threads,
            )
        });
        Objects {
            scene,
            boxes,
            bvh,
            tiles,
            rules,
        }
    }

    /// The list of the tile of pixel (x, y), (0, 0) at the lower left: every object the
    /// camera ray through it may hit, near to far; `None` where the tile keeps no list.
    #[inline]
    pub(crate) fn tile(&self, x: usize, y: usize) -> Option<Tile<'_>> {
        self.tiles.as_ref().and_then(|tiles| tiles.at(x, y))
    }

    /// Whether a hierarchy and tiles were built (for the benchmarks and the tests).
    pub(crate) fn accelerated(&self) -> (bool, bool) {
        (self.bvh.is_some(), self.tiles.is_some())
    }

    /// What a ray from `from` skips, and above which t a hit counts: the object it leaves
    /// and t > 0 (spec §4.2, §4.3), or nothing and t > ε under shadow-epsilon.
    #[inline(always)]
    fn leaving(&self, from: From) -> (Option<usize>, f64) {
        match from {
            From::Eye(..) => (None, 0.0),
            From::Surface(object) => match self.rules.epsilon(object) {
                Some(epsilon) => (None, epsilon),
                None => (Some(object), 0.0),
            },
        }
    }

    /// Whether object `index` is out of camera and mirror rays' tests (hidden).
    #[inline(always)]
    fn hidden(&self, index: usize) -> bool {
        self.rules.some(Kind::Hidden) && self.rules.object(index).has(Kind::Hidden)
    }

    /// Whether object `index` is out of shadow rays' tests (no-shadow).
    #[inline(always)]
    fn casts_no_shadow(&self, index: usize) -> bool {
        self.rules.some(Kind::NoShadow) && self.rules.object(index).has(Kind::NoShadow)
    }

    /// The closest object hit along `ray` with t > 0, skipping the one it leaves; ties go
    /// to the earlier object (spec §4.6). `K` is the render's kernel.
    #[inline(always)]
    pub(crate) fn closest<K: Kernel, Q: Query, R: Recorder>(
        &self,
        ray: &Ray,
        from: From,
        query: Q,
        rec: &mut R,
    ) -> Option<Hit> {
        let (skip, least) = self.leaving(from);
        let objects = &self.scene.objects;
        let out = |index: usize| self.out_of_closest(index, skip);
        // The tile's loop below calls the test and the check as methods, which are
        // inlined always: a closure called from three loops may not be, and for the
        // camera rays its call cost the plain render some 3 % (the ambient plane).
        let counts = |index: usize, t: f64| self.counts(index, ray, t, least);
        let query = query.on(match from {
            From::Eye(_) => Rays::Camera,
            From::Surface(_) => Rays::Mirror,
        });
        let test =
            |index: usize, rec: &mut R| self.closest_test::<K, Q, R>(index, skip, ray, query, rec);
        // A query of margins tests the objects that come near the best hit too.
        let slack = 1.0 + query.reach();
        let mut best: Option<(usize, f64)> = None;
        let tile = match from {
            From::Eye(tile) => tile,
            From::Surface(_) => None,
        };
        if let Some(tile) = tile.filter(|_| Q::TILES) {
            // Near to far: past the best hit so far, nothing can win or tie.
            for &index in tile.objects {
                let index = index as usize;
                if best.is_some_and(|(_, t)| tile.passed(index, t * slack)) {
                    break;
                }
                if let Some(t) = self.closest_test::<K, Q, R>(index, skip, ray, query, rec)
                    && beats(best, index, t)
                    && self.counts(index, ray, t, least)
                {
                    best = Some((index, t));
                }
            }
        } else if let Some(bvh) = self.bvh.as_ref().filter(|_| !Q::EVERY_OBJECT) {
            best = bvh.closest(ray, |index| test(index, rec), counts, slack);
        } else {
            in_file_order(objects.len(), skip, out, rec, |index, rec| {
                if let Some(t) = test(index, rec)
                    && beats(best, index, t)
                    && counts(index, t)
                {
                    best = Some((index, t));
                }
                false
            });
        }
        best.map(|(object, t)| Hit { object, t })
    }

    /// [`Objects::closest`] of the camera rays from `eye` along `dirs` (a tile's span of a
    /// row; bit `lane` of `walking` clear: that lane has no ray), all in `tile`, for the
    /// plain render: the tile's list walked once for the span, each object's test made
    /// ready for the eye once ([`Shape::for_base`](crate::shapes::Shape::for_base)) and
    /// taken by the rays together
    /// ([`ForBase::hits`](crate::shapes::ForBase::hits)), and each ray leaving the walk
    /// where its own would end. Each ray gets the tests, the checks and the tie rule of
    /// its own walk, in the same order, so the same hit.
    #[inline(always)]
    pub(crate) fn closest_from_eye<K: Kernel>(
        &self,
        eye: DVec3,
        dirs: &Dirs,
        mut walking: u32,
        tile: Tile,
    ) -> [Option<Hit>; LANES] {
        // Each ray's best hit so far, none as (∞, u32::MAX): `beats` takes any hit with
        // t ≤ ∞ over it, as over none, and a NaN or negative t never counts.
        let mut best_t = [f64::INFINITY; LANES];
        let mut best = [u32::MAX; LANES];
        for &index in tile.objects {
            // Near to far: past a ray's best hit so far, nothing can win or tie.
            walking &= !tile.passed_lanes(index as usize, &best_t);
            if walking == 0 {
                break;
            }
            if self.out_of_closest(index as usize, None) {
                continue;
            }
            let test = self.scene.objects[index as usize].shape.for_base::<K>(eye);
            let boxed = self.boxes.of(index as usize);
            let (ts, hits) = test.hits::<K>(eye, dirs, walking);
            for lane in 0..LANES {
                let t = ts[lane];
                if hits & (1 << lane) != 0
                    && beats(Some((best[lane] as usize, best_t[lane])), index as usize, t)
                    && self.counts_boxed(boxed, &Ray::new(eye, dirs.get(lane)), t, 0.0)
                {
                    (best[lane], best_t[lane]) = (index, t);
                }
            }
        }
        std::array::from_fn(|lane| {
            let object = best[lane] as usize;
            let t = best_t[lane];
            (best[lane] != u32::MAX).then_some(Hit { object, t })
        })
    }

    /// Whether a hit on object `index` at `t` counts for [`Objects::closest`]: t above
    /// `least`, below far-clip's distance (spec §7.5; ∞ as written) and within the
    /// object's box.
    #[inline(always)]
    fn counts(&self, index: usize, ray: &Ray, t: f64, least: f64) -> bool {
        self.counts_boxed(self.boxes.of(index), ray, t, least)
    }

    /// [`Objects::counts`] of an object whose box `boxed` is already looked up (one
    /// lookup for a span's rays).
    #[inline(always)]
    fn counts_boxed(&self, boxed: Option<&Aabb>, ray: &Ray, t: f64, least: f64) -> bool {
        t > least && self.rules.far().is_none_or(|far| t < far) && Boxes::admitted(boxed, ray, t)
    }

    /// Whether object `index` is out of [`Objects::closest`]'s tests: the object the ray
    /// leaves (`skip`), or a hidden one.
    #[inline(always)]
    fn out_of_closest(&self, index: usize, skip: Option<usize>) -> bool {
        Some(index) == skip || self.hidden(index)
    }

    /// `object`'s t along `ray` for [`Objects::closest`]: none for an object out of its
    /// tests ([`Objects::out_of_closest`]).
    #[inline(always)]
    fn closest_test<K: Kernel, Q: Query, R: Recorder>(
        &self,
        index: usize,
        skip: Option<usize>,
        ray: &Ray,
        query: Q,
        rec: &mut R,
    ) -> Option<f64> {
        if self.out_of_closest(index, skip) || query.misses(index) {
            return None;
        }
        test_and_record::<K, Q, R>(index, &self.scene.objects[index], ray, query, rec)
    }

    /// Whether an object lies on `ray` (leaving object `from`) closer than `dist`, blocking
    /// the light (spec §4.3); the recorder is told which, the first in file order for a
    /// trace. `K` is the render's kernel.
    #[inline(always)]
    pub(crate) fn blocked<K: Kernel, Q: Query, R: Recorder>(
        &self,
        ray: &Ray,
        from: usize,
        dist: f64,
        query: Q,
        rec: &mut R,
    ) -> bool {
        let (skip, least) = self.leaving(From::Surface(from));
        let objects = &self.scene.objects;
        let query = query.on(Rays::Shadow);
        let out = |index: usize| {
            Some(index) == skip || self.casts_no_shadow(index) || query.misses(index)
        };
        // Under far-clip (spec §7.5) a blocker as far as its distance is no hit.
        let dist = self.rules.far().map_or(dist, |far| dist.min(far));
        let blocks =
            |index: usize, t: f64| t > least && t < dist && self.boxes.admits(index, ray, t);
        // A query of margins tests every blocker: the shadow is as sure as the surest.
        let every_blocker = Q::EVERY_BLOCKER;
        let mut blocker = None;
        let mut test = |index: usize, rec: &mut R| {
            if let Some(t) = test_and_record::<K, Q, R>(index, &objects[index], ray, query, rec)
                && blocks(index, t)
                && blocker.is_none()
            {
                blocker = Some((index, t));
            }
            !every_blocker && blocker.is_some()
        };
        if let Some(bvh) = self.bvh.as_ref().filter(|_| !Q::EVERY_OBJECT) {
            let limit = dist * (1.0 + query.reach());
            bvh.any(ray, limit, |index| !out(index) && test(index, rec));
        } else {
            in_file_order(objects.len(), skip, out, rec, test);
        }
        rec.record(|| Event::Light(LightStep::Blocked { blocker }));
        blocker.is_some()
    }
}

/// The course's loop: every object in file order, those `out` of the test told to `rec`
/// as skipped (`skip` is the one the ray leaves), until `each(index, rec)` says to stop.
#[inline(always)]
fn in_file_order<R: Recorder>(
    count: usize,
    skip: Option<usize>,
    out: impl Fn(usize) -> bool,
    rec: &mut R,
    mut each: impl FnMut(usize, &mut R) -> bool,
) {
    for index in 0..count {
        if out(index) {
            let reason = skipped(Some(index) == skip);
            rec.record(|| Event::Skipped {
                object: index,
                reason,
            });
            continue;
        }
        if each(index, rec) {
            break;
        }
    }
}

/// Whether `Q` is a query of margins: the shapes' decisions wanted where the tiles and
/// the hierarchy choose the objects (`Query::NOTES` without `EVERY_OBJECT`).
#[inline(always)]
fn margins<Q: Query>() -> bool {
    Q::NOTES && !Q::EVERY_OBJECT
}

/// Why an object was not tested: the ray leaves it, or a variant took it out.
fn skipped(leaves: bool) -> Skip {
    match leaves {
        true => Skip::Leaves,
        false => Skip::Variant,
    }
}

/// `object`'s t along `ray`, told to `rec` with the shape's reasons where the query wants
/// them.
#[inline(always)]
fn test_and_record<K: Kernel, Q: Query, R: Recorder>(
    index: usize,
    object: &Object,
    ray: &Ray,
    query: Q,
    rec: &mut R,
) -> Option<f64> {
    if !Q::NOTES {
        return object.shape.hit_by::<K>(ray, &mut ());
    }
    // A query of margins tells how close the ray came to touching a quadric. Where it
    // clearly misses and the kernel's quick test agrees, the recorder (whose margins
    // reach no further) is not told, and the kernel's notes are not taken.
    let mut first = None;
    if margins::<Q>() {
        match object.shape.ahead::<K>(ray, query.reach()) {
            Ahead::Clear => return None,
            Ahead::Quadratic((a, b, c)) => first = Some(discriminant_note(a, b, c)),
            Ahead::Flat => {}
        }
    }
    let mut notes = Few::default();
    if let Some(note) = first {
        notes.note(note);
    }
    let t = object.shape.hit_by::<K>(ray, &mut notes);
    rec.tested(index, t, notes.as_slice());
    t
}

/// The few decisions of one test (at most three: the discriminant and two roots, or a
/// plane's t and its rectangle), kept without allocating.
struct Few {
    notes: [HitNote; 3],
    len: usize,
}

impl Default for Few {
    fn default() -> Few {
        Few {
            notes: [HitNote::NoRealRoot; 3],
            len: 0,
        }
    }
}

impl Few {
    fn as_slice(&self) -> &[HitNote] {
        &self.notes[..self.len]
    }
}

impl Notes for Few {
    fn note(&mut self, note: HitNote) {
        debug_assert!(
            self.len < self.notes.len(),
            "a test with more than 3 decisions"
        );
        if self.len < self.notes.len() {
            self.notes[self.len] = note;
            self.len += 1;
        }
    }
}
