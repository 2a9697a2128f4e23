//! The course's tracer: spec §4.2's ray_trace, one function ([`Tracer::trace`]), with
//! the diffuse term of spec §4.3 ([`Tracer::diffuse`]) and the hit's surface and
//! material ([`Tracer::surface`]) beside it. The objects answer the closest hit and the
//! shadow test ([`Objects`]); the stage (spec §7.2) and the variants' [`Rules`] are
//! values read where each rule lives; a [`Recorder`] is told each step, one line each.
//! The one loop follows one camera ray ([`Tracer::pixel`]) or a tile's span of them
//! together ([`Tracer::span`], the plain render where shadow rays are cast), each step
//! across the span before the next.

use super::objects::{From, Hit, Objects, Plain, Query};
use super::record::{Event, LightStep, Recorder};
use super::shading::{Screen, material_and_pattern};
use super::stage::{Show, Stage};
use super::tiles::{TILE, Tile};
use super::variant::{Divisor, Kind, LightRules, ObjectRules, Rulebook};
use super::{Camera, Options, object_colour};
use crate::scene::{Light, Material, Object, Pattern, Scene};
use crate::shapes::kernel::Kernel;
use crate::shapes::{Dirs, Ray, Surface, unit};
use crate::threads::Threads;
use glam::{DVec2, DVec3};

/// A frame prepared for its pixels: the scene, its objects, the camera and what every
/// ray needs of the options. It answers one pixel ([`Tracer::pixel`]), a tile's span of
/// a row ([`Tracer::span`]) or a ray through any point of the screen
/// ([`Tracer::through`]); which objects each camera ray tests (its tile's list) stays
/// inside.
pub(crate) struct Tracer<'a, B> {
    scene: &'a Scene,
    /// The closest hit and the shadow test.
    objects: Objects<'a, B>,
    /// Each pixel's camera ray.
    camera: &'a Camera,
    rules: B,
    stage: Stage,
    show: Option<Show>,
    max_dist: f64,
    /// What texture tile mode needs of the projection.
    screen: Screen,
}

impl<'a, B: Rulebook> Tracer<'a, B> {
    /// The frame of `scene` (as its variants changed it) under `options` and `rules`,
    /// seen through `camera`, with tiles for the camera's rays when `tiles` gives the
    /// threads to build them on: every tile's list, or those the cells mark
    /// ([`Tiles::new`](super::tiles::Tiles::new)).
    pub(crate) fn new(
        scene: &'a Scene,
        rules: B,
        options: &Options,
        camera: &'a Camera,
        tiles: Option<(&Threads, Option<&[bool]>)>,
    ) -> Tracer<'a, B> {
        let cells = tiles.and_then(|(_, cells)| cells);
        let tiles = tiles.map(|(threads, _)| (camera, threads));
        Tracer {
            scene,
            objects: Objects::new(scene, rules, options, tiles, cells),
            camera,
            rules,
            stage: options.stage,
            show: options.show,
            max_dist: options.max_dist,
            screen: Screen {
                last_pixel: DVec2::new((options.width - 1) as f64, (options.height - 1) as f64),
                window: scene.window,
            },
        }
    }

    /// A colour's bytes under the render's byte rule (spec §4.7, or round-bytes or
    /// scale-256): a constant of the rules as written.
    #[inline(always)]
    pub(crate) fn bytes(&self, colour: DVec3) -> [u8; 3] {
        self.rules.bytes().of(colour)
    }

    /// What texture tile mode needs of the projection.
    pub(crate) fn screen(&self) -> Screen {
        self.screen
    }

    /// Whether a hierarchy and tiles were built (for the benchmarks and the tests).
    pub(crate) fn accelerated(&self) -> (bool, bool) {
        self.objects.accelerated()
    }

    /// Whether a span's camera rays pay for being traced together ([`Tracer::span`]):
    /// where their colours need shadow rays (the stage casts them and the scene has a
    /// light), for a pixel on its own waits on the chain from its hit to its shadow
    /// ray's walk; not where they do not.
    pub(crate) fn together(&self) -> bool {
        self.show.is_none() && self.stage.shadows() && !self.scene.lights.is_empty()
    }

    /// Whether every colour is the ambient of its first hit over its distance: no light
    /// that the stage lights (step 5 of spec §4.2 adds nothing) and no object that the
    /// stage reflects (step 7 ends every path), under no `--show`. A span's rays then
    /// take the loop's first step alone ([`Tracer::span`]'s `AMBIENT`,
    /// [`Tracer::ambient_span`]), which gives the same colours in fewer instructions
    /// (docs/architecture.md).
    pub(crate) fn ambient_only(&self) -> bool {
        let lit = self.stage.lights() && !self.scene.lights.is_empty();
        let mirrors = || self.stage.reflects() && self.scene.objects.iter().any(Object::reflects);
        self.show.is_none() && !lit && !mirrors()
    }

    /// The colour of pixel (x, y), (0, 0) at the lower left: its camera ray's (spec §4.1,
    /// §4.2), or the diagnostic image of `--show`, each step told to `rec`. `K` is the
    /// render's kernel, chosen by the caller once per render (`with_kernel!`) so that
    /// the tracer's queries run in loops compiled for it.
    #[inline(always)]
    pub(crate) fn pixel<K: Kernel>(
        &self,
        x: usize,
        y: usize,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        match self.camera.ray(x, y) {
            Some(ray) => self.along::<K>(ray, self.objects.tile(x, y), query, rec),
            None => DVec3::ZERO,
        }
    }

    /// The colour along `ray` from the eye, through any point of the screen (a trace's,
    /// a sample inside a pixel), every object tested.
    #[inline(always)]
    pub(crate) fn through<K: Kernel>(
        &self,
        ray: Ray,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        self.along::<K>(ray, None, query, rec)
    }

    /// [`Tracer::pixel`] where [`Tracer::ambient_only`] holds: the loop's first step
    /// alone, as [`Tracer::ambient_span`] takes it, each step told to `rec`. The same
    /// colour and the same events as the loop's, but the surface of a hit on a plain
    /// object, which such a colour does not read (no light, no mirror and no pattern
    /// reads it after).
    #[inline(always)]
    pub(crate) fn ambient_pixel<K: Kernel>(
        &self,
        x: usize,
        y: usize,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        let Some(ray) = self.camera.ray(x, y) else {
            return DVec3::ZERO;
        };
        // The camera ray's path is 0 long.
        let from = || From::Eye(self.objects.tile(x, y));
        let Some(hit) = self.segment::<K>(&ray, (0, 0.0), from, query, rec) else {
            return DVec3::ZERO;
        };
        self.ambient(&ray, hit, query, rec)
    }

    /// Whether pixel (x, y)'s tile sees no object: every pixel of it is the background,
    /// without a ray.
    #[inline(always)]
    pub(crate) fn sees_nothing(&self, x: usize, y: usize) -> bool {
        (self.objects.tile(x, y)).is_some_and(|tile| tile.objects.is_empty())
    }

    /// The colours of the pixels (`xs(i)`, y) for i below `count` (at most [`TILE`],
    /// all in one tile), each [`Tracer::pixel`]'s without a recorder, given to
    /// `out(i, colour)`: the tile's list looked up once (black without a ray where the
    /// tile sees no object), and the rays traced `TOGETHER`
    /// ([`Tracer::trace`]'s lanes) or one by one, the same colours either way; or, where
    /// [`Tracer::ambient_only`] says so, `AMBIENT` ([`Tracer::ambient_span`]). The caller
    /// chooses these once, from [`Tracer::together`] and [`Tracer::ambient_only`], so
    /// that each loop over the spans is compiled for one.
    #[inline(always)]
    pub(crate) fn span<K: Kernel, const TOGETHER: bool, const AMBIENT: bool>(
        &self,
        xs: impl Fn(usize) -> usize,
        y: usize,
        count: usize,
        mut out: impl FnMut(usize, DVec3),
    ) {
        let tile = self.objects.tile(xs(0), y);
        if tile.is_some_and(|tile| tile.objects.is_empty()) {
            // The tile sees no object: the background, without a ray.
            (0..count).for_each(|i| out(i, DVec3::ZERO));
            return;
        }
        // The grid's rays without jitter's test in the loop over the span: with it there,
        // the plain render took 20-55 % more CPU time at 2048x1536 (bench/ab.py, spec1, a04,
        // d04, the gallery) for 2-3 % more instructions.
        let camera = self.camera;
        // 1. of the ambient spans: a camera ray's path is 0 long, cut only under a
        // MAX_DIST below 0.
        if AMBIENT && self.show.is_none() && 0.0 > self.max_dist {
            return (0..count).for_each(|i| out(i, DVec3::ZERO));
        }
        // The grid's rays in lanes where the span has a tile's list (compare's sampled
        // pixels have lists under jitter too: those take `ambient_span`).
        if AMBIENT
            && self.show.is_none()
            && camera.on_grid()
            && let Some(tile) = tile
        {
            let (dirs, walking) = camera.grid_dirs(xs, y, count);
            return self.ambient_tiled::<K>(&dirs, walking, tile, count, out);
        }
        match camera.on_grid() {
            true => {
                let rays = |i| camera.grid_ray(xs(i), y);
                self.rays::<K, TOGETHER, AMBIENT>(rays, tile, count, out)
            }
            false => self.rays::<K, TOGETHER, AMBIENT>(|i| camera.ray(xs(i), y), tile, count, out),
        }
    }

    /// [`Tracer::span`] for the camera rays `rays(i)`.
    #[inline(always)]
    fn rays<K: Kernel, const TOGETHER: bool, const AMBIENT: bool>(
        &self,
        rays: impl Fn(usize) -> Option<Ray>,
        tile: Option<Tile>,
        count: usize,
        mut out: impl FnMut(usize, DVec3),
    ) {
        if AMBIENT && self.show.is_none() {
            return self.ambient_span::<K>(rays, tile, count, out);
        }
        // Under --show (never together) each ray's diagnostic colour; a ray alone (a
        // sampled pixel of compare's) without the other lanes' steps.
        if !TOGETHER || self.show.is_some() || count == 1 {
            for i in 0..count {
                let colour = match rays(i) {
                    Some(ray) => self.along::<K>(ray, tile, Plain, &mut ()),
                    None => DVec3::ZERO,
                };
                out(i, colour);
            }
            return;
        }
        let mut colours = [DVec3::ZERO; TILE];
        let rays = |i: usize| (i < count).then(|| rays(i)).flatten();
        self.trace::<K, _, (), TILE>(rays, tile, Plain, &mut [(); TILE], &mut colours);
        for (i, colour) in colours.into_iter().enumerate().take(count) {
            out(i, colour);
        }
    }

    /// [`Tracer::rays`] where [`Tracer::ambient_only`] says so and the rays are not the
    /// grid's (under jitter): each colour is step 6's ambient over the length of the
    /// camera ray to its first hit ([`Tracer::ambient`]).
    #[inline(always)]
    fn ambient_span<K: Kernel>(
        &self,
        rays: impl Fn(usize) -> Option<Ray>,
        tile: Option<Tile>,
        count: usize,
        mut out: impl FnMut(usize, DVec3),
    ) {
        // 1. Taken by `span`. 2. The closest hit.
        for i in 0..count {
            let colour = rays(i).map_or(DVec3::ZERO, |ray| {
                let hit = (self.objects).closest::<K, _, _>(&ray, From::Eye(tile), Plain, &mut ());
                self.ambient(&ray, hit, Plain, &mut ())
            });
            out(i, colour);
        }
    }

    /// [`Tracer::ambient_span`] of the grid's camera rays along `dirs` (bit i of
    /// `walking` set where lane i has one) in `tile`: their closest hits found together
    /// ([`Objects::closest_from_eye`]).
    #[inline(always)]
    fn ambient_tiled<K: Kernel>(
        &self,
        dirs: &Dirs,
        walking: u32,
        tile: Tile,
        count: usize,
        mut out: impl FnMut(usize, DVec3),
    ) {
        // 1. Taken by `span`. 2. The closest hits.
        let eye = self.camera.viewpoint;
        let hits = (self.objects).closest_from_eye::<K>(eye, dirs, walking, tile);
        for (i, hit) in hits.into_iter().enumerate().take(count) {
            out(
                i,
                self.ambient(&Ray::new(eye, dirs.get(i)), hit, Plain, &mut ()),
            );
        }
    }

    /// Steps 3, 4 and 6 of [`Tracer::trace`] for a camera ray whose path its first `hit`
    /// ends ([`Tracer::ambient_only`]): the path's length, the ambient there (read from
    /// the surface only where the object's material varies over it) and the colour,
    /// [`Tracer::divided`] as in the loop; black without a hit. The same values as the
    /// loop's, so the same colour.
    #[inline(always)]
    fn ambient(
        &self,
        ray: &Ray,
        hit: Option<Hit>,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        let Some(Hit { object, t }) = hit else {
            return DVec3::ZERO;
        };
        // 3. The path grows by the segment.
        let path = Path {
            ray: *ray,
            leaves: None,
            weight: DVec3::ONE,
            total_dist: 0.0 + t,
        };
        // 4. The ambient.
        let look = &self.scene.objects[object].look;
        let ambient = match look.pattern {
            Pattern::Plain => look.material.ambient,
            _ => {
                let at = (object, self.rules.object(object), query.other_tile(object));
                (self.surface(at, ray, t, path.total_dist, rec).1).ambient
            }
        };
        // 6. I / total_dist.
        let mut colour = DVec3::ZERO;
        self.divided(&path, ambient, t, &mut colour, rec);
        colour
    }

    /// The colour along a camera ray, with its tile's list where it has one.
    #[inline(always)]
    fn along<K: Kernel>(
        &self,
        ray: Ray,
        tile: Option<Tile>,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        match self.show {
            None => {
                let mut colour = [DVec3::ZERO];
                let recs = std::array::from_mut(rec);
                self.trace::<K, _, _, 1>(|_| Some(ray), tile, query, recs, &mut colour);
                colour[0]
            }
            Some(show) => self.show::<K>(ray, show, From::Eye(tile), query, rec),
        }
    }

    /// ray_trace of spec §4.2 along the camera rays `rays(lane)` of N lanes (one pixel's,
    /// or a tile's span of a row; `None`: a black pixel), each lane's colour into `out`
    /// and its steps told to its recorder in `recs`. The colour is Σ (S₁ ⊙ … ⊙ Sₖ) ⊙
    /// Iₖ₊₁ / total_distₖ₊₁ over the bounces, the mirror recursion a loop. Each step is
    /// taken across the lanes before the next: the chains of square roots, divisions
    /// and shadow walks of neighbouring pixels, which do not depend on each other,
    /// overlap. Each lane gets the same operations in the same order as on its own, so
    /// the same bytes and the same events. Where the paths are kept in arrays of N,
    /// one lane compiles to about the instructions of a loop over one ray
    /// (docs/architecture.md gives the figures).
    #[inline(always)]
    pub(crate) fn trace<K: Kernel, Q: Query, R: Recorder, const N: usize>(
        &self,
        rays: impl Fn(usize) -> Option<Ray>,
        tile: Option<Tile>,
        query: Q,
        recs: &mut [R; N],
        out: &mut [DVec3; N],
    ) {
        let mut paths: [Option<Path>; N] = [None; N];
        for (lane, path) in paths.iter_mut().enumerate() {
            *path = rays(lane).map(|ray| Path {
                ray,
                leaves: None,
                weight: DVec3::ONE,
                total_dist: 0.0,
            });
        }
        let bounces = self.rules.bounces();
        for depth in 0..bounces + 1 {
            let mut hits: [Option<Lit>; N] = [None; N];
            for lane in 0..N {
                let (path, rec) = (&mut paths[lane], &mut recs[lane]);
                let Some(p) = path else { continue };
                // 1-2. Black where MAX_DIST ends the path, else the closest hit,
                // skipping the object the ray leaves; nothing: black.
                let leaves = p.leaves;
                let from = || match leaves {
                    None => From::Eye(tile),
                    Some(object) => From::Surface(object),
                };
                let segment = (depth, p.total_dist);
                let Some(Some(Hit { object, t })) =
                    self.segment::<K>(&p.ray, segment, from, query, rec)
                else {
                    *path = None;
                    continue;
                };
                let rules = self.rules.object(object);
                // 3. The path grows by the segment.
                p.total_dist += t;
                let other_tile = query.other_tile(object);
                let at = (object, rules, other_tile);
                let (surface, material) = self.surface(at, &p.ray, t, p.total_dist, rec);
                // 4. The ambient.
                hits[lane] = Some(Lit {
                    object,
                    rules,
                    t,
                    surface,
                    material,
                    intensity: material.ambient,
                });
            }
            if hits.iter().all(Option::is_none) {
                break;
            }
            // 5. Every light's diffuse term.
            if self.stage.lights() {
                for (light, lamp) in self.scene.lights.iter().enumerate() {
                    self.diffuse::<K, Q, R, N>(light, lamp, &mut hits, query, recs);
                }
            }
            for lane in 0..N {
                let (path, colour, rec) = (&mut paths[lane], &mut out[lane], &mut recs[lane]);
                let (Some(p), Some(h)) = (path.as_mut(), &hits[lane]) else {
                    continue;
                };
                // 6. I / total_dist.
                self.divided(p, h.intensity, h.t, colour, rec);
                // 7. The mirror: S ⊙ ray_trace(hit, R, total_dist, this object).
                let stops = depth == bounces || query.no_bounce(h.object);
                let mirror = match stops || !self.reflects(h.rules, &h.material) {
                    true => None,
                    false => mirror(&p.ray, &h.surface),
                };
                let Some(mirror) = mirror else {
                    *path = None;
                    continue;
                };
                p.weight *= h.material.specular;
                p.ray = mirror;
                p.leaves = Some(h.object);
            }
            // Every path ended: no empty step after the last.
            if paths.iter().all(Option::is_none) {
                break;
            }
        }
    }

    /// Step 6 of [`Tracer::trace`]: the `intensity` at the hit at `t` that ends the path
    /// `p` so far, over the path's length (or what a variant divides by), weighted by
    /// the mirrors before it and added to the lane's `colour`.
    #[inline(always)]
    fn divided(
        &self,
        p: &Path,
        intensity: DVec3,
        t: f64,
        colour: &mut DVec3,
        rec: &mut impl Recorder,
    ) {
        let seen = intensity / self.divisor(p.total_dist, t);
        *colour += p.weight * seen;
        rec.record(|| Event::Divided {
            intensity,
            total_dist: p.total_dist,
            seen,
            weight: p.weight,
            colour: *colour,
        });
    }

    /// One light's diffuse term (spec §4.3) at each hit of [`Tracer::trace`]'s step,
    /// added to its intensity: diffuse × emissivity × cos θ / dist, where the hit's
    /// object is lit, the light faces the surface, its beam reaches it and no object
    /// blocks the shadow ray. Every hit's direction to the light, then the shadow rays,
    /// then the terms.
    #[inline(always)]
    fn diffuse<K: Kernel, Q: Query, R: Recorder, const N: usize>(
        &self,
        light: usize,
        lamp: &Light,
        hits: &mut [Option<Lit>; N],
        query: Q,
        recs: &mut [R; N],
    ) {
        let rules = self.rules.light(light);
        let mut towards: [Option<Towards>; N] = [None; N];
        for lane in 0..N {
            let Some(h) = &hits[lane] else { continue };
            let rec = &mut recs[lane];
            rec.record(|| Event::Lamp { light });
            if !h.rules.has(Kind::Unlit) {
                towards[lane] = self.towards(lamp, rules, &h.surface, &h.material, rec);
            }
        }
        for lane in 0..N {
            if let (Some(h), Some(to)) = (&hits[lane], &towards[lane])
                && self.shadowed::<K>(light, rules, h.object, to, query, &mut recs[lane])
            {
                towards[lane] = None;
            }
        }
        for lane in 0..N {
            let Some(h) = &mut hits[lane] else { continue };
            let contribution = match &towards[lane] {
                Some(to) => term(lamp, rules, &h.material, to),
                None => DVec3::ZERO,
            };
            h.intensity += contribution;
            let intensity = h.intensity;
            recs[lane].record(|| Event::Lit {
                light,
                contribution,
                intensity,
            });
        }
    }

    /// Where `ray` meets `object` at `t`: the point, the normal (as computed, spec §4.4;
    /// turned toward the ray under facing-normals, reversed under flipped-normal) and the
    /// material there (tiles, textures, shaders).
    #[inline(always)]
    fn surface(
        &self,
        (object, rules, other_tile): (usize, ObjectRules, bool),
        ray: &Ray,
        t: f64,
        total_dist: f64,
        rec: &mut impl Recorder,
    ) -> (Surface, Material) {
        let record = &self.scene.objects[object];
        let mut surface = record.shape.surface(ray, t);
        if rules.has(Kind::FacingNormals) && surface.normal.dot(ray.dir) > 0.0 {
            surface.normal = -surface.normal;
        }
        if rules.has(Kind::FlippedNormal) {
            surface.normal = -surface.normal;
        }
        let (material, pattern) = material_and_pattern(record, &surface, &self.screen, other_tile);
        rec.record(|| Event::Surface {
            object,
            t,
            total_dist,
            surface,
            material,
            pattern,
        });
        (surface, material)
    }

    /// The light as the hit sees it: the shadow ray toward it, its distance and cos θ,
    /// where the material scatters light, the light is on, faces the surface and its
    /// beam reaches it; `None` where the term is zero for one of those reasons.
    #[inline(always)]
    fn towards(
        &self,
        light: &Light,
        rules: LightRules,
        surface: &Surface,
        material: &Material,
        rec: &mut impl Recorder,
    ) -> Option<Towards> {
        if material.diffuse == DVec3::ZERO {
            rec.record(|| Event::Light(LightStep::NoDiffuse));
            return None;
        }
        if rules.has(Kind::NoLight) {
            rec.record(|| Event::Light(LightStep::Off));
            return None;
        }
        let to_light = light.location - surface.point;
        let dist = to_light.length();
        // A light at the hit point, or so far away that the distance overflowed, has no
        // direction: no contribution rather than a NaN.
        if dist.is_nan() || dist <= 0.0 || dist.is_infinite() {
            rec.record(|| Event::Light(LightStep::NoDirection { dist }));
            return None;
        }
        let u = to_light / dist;
        let cos = surface.normal.dot(u);
        rec.record(|| Event::Light(LightStep::Towards { u, dist, cos }));
        if cos.is_nan() || cos <= 0.0 {
            return None;
        }
        if let Some(beam) = &light.beam {
            let along = (-u).dot(beam.direction);
            let lit = along > beam.cos_limit;
            rec.record(|| Event::Light(LightStep::Spot { along, lit }));
            if !lit {
                return None;
            }
        }
        Some(Towards {
            shadow: Ray {
                base: surface.point,
                dir: u,
            },
            dist,
            cos,
        })
    }

    /// Whether an object blocks the shadow ray toward light `light`, where the stage casts
    /// shadow rays and no variant stops this one; or what the query forces it to say.
    #[inline(always)]
    fn shadowed<K: Kernel>(
        &self,
        light: usize,
        rules: LightRules,
        object: usize,
        towards: &Towards,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> bool {
        if !self.stage.shadows() || rules.has(Kind::Unshadowed) {
            return false;
        }
        if let Some(blocked) = query.shadow(light) {
            return blocked;
        }
        let shadow = &towards.shadow;
        rec.record(|| Event::Light(LightStep::ShadowRay { ray: *shadow }));
        self.objects
            .blocked::<K, _, _>(shadow, object, towards.dist, query, rec)
    }

    /// What step 6 of spec §4.2 divides by: the path's length, or under a variant this
    /// segment's, or nothing.
    #[inline(always)]
    fn divisor(&self, total_dist: f64, t: f64) -> f64 {
        match self.rules.divisor() {
            Divisor::Path => total_dist,
            Divisor::Segment => t,
            Divisor::Nothing => 1.0,
        }
    }

    /// Whether a mirror ray leaves an object with these `rules` and this `material` (spec
    /// §4.5): its specular is not zero, the stage reflects, and no variant stops it.
    #[inline(always)]
    fn reflects(&self, rules: ObjectRules, material: &Material) -> bool {
        material.specular != DVec3::ZERO && self.stage.reflects() && !rules.has(Kind::NoMirror)
    }

    /// Spec §4.2 steps 1 and 2 for the segment of a path along `ray`, the `depth`th, whose
    /// path is `total_dist` long before it: `None` where MAX_DIST ends the path (black
    /// from here), else the closest hit, skipping what `from` gives; each told to `rec`.
    /// The loop and [`Tracer::ambient_pixel`] both take this step.
    #[inline(always)]
    fn segment<'t, K: Kernel>(
        &self,
        ray: &Ray,
        (depth, total_dist): (usize, f64),
        from: impl FnOnce() -> From<'t>,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> Option<Option<Hit>> {
        if total_dist > self.max_dist && !query.never_cut() {
            rec.record(|| Event::CutOff { total_dist });
            return None;
        }
        rec.record(|| Event::Segment {
            depth,
            ray: *ray,
            total_dist,
        });
        let hit = self.objects.closest::<K, _, _>(ray, from(), query, rec);
        rec.record(|| Event::Closest {
            hit: hit.map(|h| (h.object, h.t)),
        });
        Some(hit)
    }

    /// The diagnostic image of `show` at the first hit along `ray`.
    fn show<K: Kernel>(
        &self,
        ray: Ray,
        show: Show,
        from: From,
        query: impl Query,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        rec.record(|| Event::Segment {
            depth: 0,
            ray,
            total_dist: 0.0,
        });
        let hit = self.objects.closest::<K, _, _>(&ray, from, query, rec);
        rec.record(|| Event::Closest {
            hit: hit.map(|h| (h.object, h.t)),
        });
        let Some(Hit { object, t }) = hit else {
            return DVec3::ZERO;
        };
        let colour = match show {
            Show::Normals => {
                let normal = self.scene.objects[object].shape.surface(&ray, t).normal;
                (normal + DVec3::ONE) / 2.0
            }
            Show::Objects => object_colour(object),
            Show::Depth => DVec3::splat(1.0 - t / self.max_dist),
        };
        rec.record(|| Event::Shown { show, colour });
        colour
    }
}

/// A lane of [`Tracer::trace`] between its bounces: the ray about to be traced, the object
/// it leaves (none for the camera ray), the product of the mirrors' speculars so far and
/// the path's length.
#[derive(Clone, Copy)]
struct Path {
    ray: Ray,
    leaves: Option<usize>,
    weight: DVec3,
    total_dist: f64,
}

/// A lane's hit in [`Tracer::trace`], with what its shading needs.
#[derive(Clone, Copy)]
struct Lit {
    object: usize,
    rules: ObjectRules,
    t: f64,
    surface: Surface,
    material: Material,
    /// The ambient, then plus each light's term in turn.
    intensity: DVec3,
}

/// A light as a hit sees it (spec §4.3): the shadow ray from the hit toward it (its
/// direction the unit vector u), the light's distance, and cos θ against the normal.
/// [`Tracer::trace`] keeps the ray here from the direction's step to the shadow rays':
/// a ray put together just before its walk was read back before its stores had
/// landed, a stall that cost more than the staging saved.
#[derive(Clone, Copy)]
struct Towards {
    shadow: Ray,
    dist: f64,
    cos: f64,
}

/// The light's term once it reaches the hit: diffuse × emissivity × cos θ / dist (or
/// dist² under square-falloff).
#[inline(always)]
fn term(light: &Light, rules: LightRules, material: &Material, towards: &Towards) -> DVec3 {
    let Towards { dist, cos, .. } = *towards;
    let falloff = if rules.has(Kind::SquareFalloff) {
        dist * dist
    } else {
        dist
    };
    material.diffuse * light.emissivity * (cos / falloff)
}

/// The mirror ray from the hit (spec §4.5): R = D - 2 (D·N) N, made unit; `None` when it
/// has no direction.
#[inline(always)]
fn mirror(ray: &Ray, surface: &Surface) -> Option<Ray> {
    let d = ray.dir;
    let dir = unit(d - 2.0 * d.dot(surface.normal) * surface.normal)?;
    Some(Ray {
        base: surface.point,
        dir,
    })
}
