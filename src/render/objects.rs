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
//! The kernel is chosen at run time, once per ray: each query is one `match` to a loop
//! compiled for that kernel, so that no object test pays for the choice.

use super::bvh::{Boxes, Bvh, beats};
use super::record::{Event, LightStep, Recorder, Skip};
use super::tiles::{Tile, Tiles};
use super::variant::Rulebook;
use super::{Camera, Options};
use crate::scene::{Object, Scene};
use crate::shapes::kernel::{Kernel, KernelChoice, with_kernel};
use crate::shapes::{HitNote, Ray};

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
    kernel: KernelChoice,
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
    /// the camera's rays when a camera is given.
    pub(crate) fn new(
        scene: &'a Scene,
        rules: B,
        options: &Options,
        camera: Option<&Camera>,
    ) -> Objects<'a, B> {
        let boxes = Boxes::for_kernel(scene, options.kernel);
        let accelerate = options.accelerate;
        let rays = options.width * options.height;
        let bvh = accelerate.then(|| Bvh::for_rays(&boxes, rays)).flatten();
        let tiles = (camera.filter(|_| accelerate))
            .and_then(|camera| Tiles::new(scene, &boxes, camera.viewpoint, &camera.xs, &camera.ys));
        Objects {
            scene,
            kernel: options.kernel,
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

    /// The closest object hit along `ray` with t > 0, skipping the one it leaves, by the
    /// objects' own kernel.
    pub(crate) fn closest_any(&self, ray: &Ray, from: From) -> Option<Hit> {
        with_kernel!(self.kernel, K => self.closest::<K>(ray, from, &mut ()))
    }

    /// Whether object `index` is out of camera and mirror rays' tests (hidden).
    #[inline(always)]
    fn hidden(&self, index: usize) -> bool {
        self.rules.some_hidden() && self.rules.object(index).hidden()
    }

    /// Whether object `index` is out of shadow rays' tests (no-shadow).
    #[inline(always)]
    fn casts_no_shadow(&self, index: usize) -> bool {
        self.rules.some_cast_no_shadow() && self.rules.object(index).casts_no_shadow()
    }

    /// The closest object hit along `ray` with t > 0, skipping the one it leaves; ties go
    /// to the earlier object (spec §4.6). `K` is the render's kernel.
    #[inline(always)]
    pub(crate) fn closest<K: Kernel>(
        &self,
        ray: &Ray,
        from: From,
        rec: &mut impl Recorder,
    ) -> Option<Hit> {
        let (skip, least) = self.leaving(from);
        let objects = &self.scene.objects;
        let out = |index: usize| Some(index) == skip || self.hidden(index);
        let counts = |index: usize, t: f64| t > least && self.boxes.admits(index, ray, t);
        let test = |index: usize| match out(index) {
            true => None,
            false => objects[index].shape.hit_by::<K>(ray, &mut ()),
        };
        let mut best: Option<(usize, f64)> = None;
        let tile = match from {
            From::Eye(tile) => tile,
            From::Surface(_) => None,
        };
        if let Some(tile) = tile.filter(|_| !every_object(rec)) {
            // Near to far: past the best hit so far, nothing can win or tie.
            for &index in tile.objects {
                let index = index as usize;
                if best.is_some_and(|(_, t)| tile.nearest[index] > t) {
                    break;
                }
                if let Some(t) = test(index)
                    && beats(best, index, t)
                    && counts(index, t)
                {
                    best = Some((index, t));
                }
            }
        } else if let Some(bvh) = self.bvh.as_ref().filter(|_| !every_object(rec)) {
            best = bvh.closest(ray, test, counts);
        } else {
            // The course's loop: every object in file order.
            for (index, object) in objects.iter().enumerate() {
                if out(index) {
                    let reason = skipped(Some(index) == skip);
                    rec.record(|| Event::Skipped {
                        object: index,
                        reason,
                    });
                    continue;
                }
                if let Some(t) = test_and_record::<K>(index, object, ray, rec)
                    && beats(best, index, t)
                    && counts(index, t)
                {
                    best = Some((index, t));
                }
            }
        }
        best.map(|(object, t)| Hit { object, t })
    }

    /// Whether an object lies on `ray` (leaving object `from`) closer than `dist`, blocking
    /// the light (spec §4.3). A trace is told the first such object in file order. `K` is
    /// the objects' kernel.
    #[inline(always)]
    pub(crate) fn blocked<K: Kernel>(
        &self,
        ray: &Ray,
        from: usize,
        dist: f64,
        rec: &mut impl Recorder,
    ) -> bool {
        let (skip, least) = self.leaving(From::Surface(from));
        let objects = &self.scene.objects;
        let out = |index: usize| Some(index) == skip || self.casts_no_shadow(index);
        let blocks =
            |index: usize, t: f64| t > least && t < dist && self.boxes.admits(index, ray, t);
        if let Some(bvh) = self.bvh.as_ref().filter(|_| !every_object(rec)) {
            return bvh.any(ray, dist, |index| {
                !out(index)
                    && (objects[index].shape.hit_by::<K>(ray, &mut ()))
                        .is_some_and(|t| blocks(index, t))
            });
        }
        for (index, object) in objects.iter().enumerate() {
            if out(index) {
                let reason = skipped(Some(index) == skip);
                rec.record(|| Event::Skipped {
                    object: index,
                    reason,
                });
                continue;
            }
            if let Some(t) = test_and_record::<K>(index, object, ray, rec)
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
}

/// Why an object was not tested: the ray leaves it, or a variant took it out.
fn skipped(leaves: bool) -> Skip {
    match leaves {
        true => Skip::Leaves,
        false => Skip::Variant,
    }
}

/// `object`'s t along `ray`, told to `rec` with the shape's reasons when it records every
/// object's test.
#[inline(always)]
fn test_and_record<K: Kernel>(
    index: usize,
    object: &Object,
    ray: &Ray,
    rec: &mut impl Recorder,
) -> Option<f64> {
    if !every_object(rec) {
        return object.shape.hit_by::<K>(ray, &mut ());
    }
    let mut notes: Vec<HitNote> = Vec::new();
    let t = object.shape.hit_by::<K>(ray, &mut notes);
    rec.record(|| Event::Tested {
        object: index,
        t,
        notes,
    });
    t
}

/// `R::EVERY_OBJECT` of a recorder given by reference.
#[inline(always)]
fn every_object<R: Recorder>(_: &R) -> bool {
    R::EVERY_OBJECT
}
