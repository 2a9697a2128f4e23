//! The course's tracer: spec §4.2's ray_trace, one function ([`Tracer::trace`]), with
//! the diffuse term of spec §4.3 ([`Tracer::diffuse`]) and the hit's surface and
//! material ([`Tracer::surface`]) beside it. The objects answer the closest hit and the
//! shadow test ([`Objects`]); the stage (spec §7.2) and the variants' [`Rules`] are
//! values read where each rule lives; a [`Recorder`] is told each step, one line each.
//! A render that casts shadow rays takes the same steps a tile's span of pixels at a
//! time ([`Tracer::span`]), each step across the span before the next.

use super::objects::{From, Hit, Objects};
use super::record::{Event, LightStep, Recorder};
use super::shading::{Screen, material_and_pattern};
use super::stage::{Show, Stage};
use super::tiles::{TILE, Tile};
use super::variant::{Divisor, LightRules, ObjectRules, Rulebook};
use super::{Camera, Options, object_colour};
use crate::scene::{Light, Material, Scene};
use crate::shapes::kernel::Kernel;
use crate::shapes::{Ray, Surface, unit};
use crate::threads::Threads;
use glam::{DVec2, DVec3};

/// The scene, its objects and what every ray needs of the options.
pub(crate) struct Tracer<'a, B> {
    scene: &'a Scene,
    /// The closest hit and the shadow test.
    pub(crate) objects: Objects<'a, B>,
    rules: B,
    stage: Stage,
    show: Option<Show>,
    max_dist: f64,
    /// What texture tile mode needs of the projection.
    screen: Screen,
}

impl<'a, B: Rulebook> Tracer<'a, B> {
    /// The tracer of `scene` (as its variants changed it) under `options` and `rules`,
    /// with tiles for the camera's rays when a camera is given (built on its threads):
    /// every tile's list, or those `cells` marks
    /// ([`Tiles::new`](super::tiles::Tiles::new)).
    pub(crate) fn new(
        scene: &'a Scene,
        rules: B,
        options: &Options,
        camera: Option<(&Camera, &Threads)>,
        cells: Option<&[bool]>,
    ) -> Tracer<'a, B> {
        Tracer {
            scene,
            objects: Objects::new(scene, rules, options, camera, cells),
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

    /// What texture tile mode needs of the projection.
    pub(crate) fn screen(&self) -> Screen {
        self.screen
    }

    /// Whether the camera rays' colours need shadow rays: the stage casts them and the
    /// scene has a light. [`Tracer::span`] pays where they are (a pixel waits on the
    /// chain from its hit to its shadow ray's walk), not where they are not.
    pub(crate) fn shadow_rays(&self) -> bool {
        self.show.is_none() && self.stage.shadows() && !self.scene.lights.is_empty()
    }

    /// The colour of a camera ray (with its tile's list, [`Objects::tile`]): the stage's
    /// image, or the diagnostic image of `--show`. `K` is the render's kernel, chosen by
    /// the caller once per render (`with_kernel!`) so that the tracer's queries run in
    /// loops compiled for it.
    #[inline(always)]
    pub(crate) fn pixel<K: Kernel>(
        &self,
        ray: Ray,
        tile: Option<Tile>,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        match self.show {
            None => self.trace::<K>(ray, From::Eye(tile), rec),
            Some(show) => self.show::<K>(ray, show, From::Eye(tile), rec),
        }
    }

    /// ray_trace of spec §4.2 from `from` along `ray`, the mirror recursion as a loop: the
    /// colour is Σ (S₁ ⊙ … ⊙ Sₖ) ⊙ Iₖ₊₁ / total_distₖ₊₁ over the bounces.
    #[inline(always)]
    pub(crate) fn trace<K: Kernel>(
        &self,
        mut ray: Ray,
        mut from: From,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        let mut colour = DVec3::ZERO;
        let mut weight = DVec3::ONE;
        let mut total_dist = 0.0;
        let bounces = self.rules.bounces();
        for depth in 0..bounces + 1 {
            // 1. A path longer than MAX_DIST is black from here.
            if total_dist > self.max_dist {
                rec.record(|| Event::CutOff { total_dist });
                break;
            }
            rec.record(|| Event::Segment {
                depth,
                ray,
                total_dist,
            });
            // 2. The closest hit, skipping the object the ray leaves; nothing: black.
            let hit = self.objects.closest::<K, _>(&ray, from, rec);
            rec.record(|| Event::Closest {
                hit: hit.map(|h| (h.object, h.t)),
            });
            let Some(Hit { object, t }) = hit else { break };
            let rules = self.rules.object(object);
            // 3. The path grows by the segment.
            total_dist += t;
            let (surface, material) = self.surface(object, rules, &ray, t, total_dist, rec);
            // 4. The ambient, and 5. every light's diffuse term.
            let mut intensity = material.ambient;
            if self.stage.lights() {
                for (light, lamp) in self.scene.lights.iter().enumerate() {
                    rec.record(|| Event::Lamp { light });
                    let lamp_rules = self.rules.light(light);
                    let contribution = match rules.unlit() {
                        false => {
                            self.diffuse::<K>(lamp, lamp_rules, object, &surface, &material, rec)
                        }
                        true => DVec3::ZERO,
                    };
                    intensity += contribution;
                    rec.record(|| Event::Lit {
                        light,
                        contribution,
                        intensity,
                    });
                }
            }
            // 6. I / total_dist.
            let seen = intensity / self.divisor(total_dist, t);
            colour += weight * seen;
            rec.record(|| Event::Divided {
                intensity,
                total_dist,
                seen,
                weight,
                colour,
            });
            // 7. The mirror: S ⊙ ray_trace(hit, R, total_dist, this object).
            if depth == bounces || !self.reflects(rules, &material) {
                break;
            }
            let Some(mirror) = mirror(&ray, &surface) else {
                break;
            };
            weight *= material.specular;
            ray = mirror;
            from = From::Surface(object);
        }
        colour
    }

    /// The colours `out` of the camera rays `ray_of(i)`, i below `out`'s length, of one
    /// span of a row (its pixels in one tile, at most [`TILE`]; a pixel whose ray is `None`
    /// is black), each the colour [`Tracer::pixel`] gives it with no recorder: the loop of
    /// [`Tracer::trace`], each step taken across the span before the next. At each depth,
    /// every live ray's closest hit; then, light by light, every hit's direction to the
    /// light, then the shadow rays, then the terms; then the divisions by the path and the
    /// mirror rays. Each pixel gets the same operations in the same order as on its own, so
    /// the same bytes. A pixel on its own waits on its chain of square roots and divisions,
    /// from the hit point to the shadow ray; across the span the chains of neighbouring
    /// pixels, which do not depend on each other, overlap.
    #[inline(always)]
    pub(crate) fn span<K: Kernel>(
        &self,
        ray_of: impl Fn(usize) -> Option<Ray>,
        tile: Option<Tile>,
        out: &mut [DVec3],
    ) {
        out.fill(DVec3::ZERO);
        // Not reached from the renders (`shadow_rays` is false under `--show`): kept so
        // that a span is right for any caller.
        if self.show.is_some() {
            for (i, out) in out.iter_mut().enumerate() {
                if let Some(ray) = ray_of(i) {
                    *out = self.pixel::<K>(ray, tile, &mut ());
                }
            }
            return;
        }
        let mut paths: [Option<Path>; TILE] = [None; TILE];
        let paths = &mut paths[..out.len()];
        for (i, path) in paths.iter_mut().enumerate() {
            *path = ray_of(i).map(|ray| Path {
                ray,
                leaves: None,
                weight: DVec3::ONE,
                total_dist: 0.0,
            });
        }
        let bounces = self.rules.bounces();
        for depth in 0..bounces + 1 {
            // 1.-3. Every live path's closest hit and the surface there.
            let mut hits: [Option<Lit>; TILE] = [None; TILE];
            let hits = &mut hits[..paths.len()];
            let mut live = false;
            for (path, hit) in paths.iter_mut().zip(hits.iter_mut()) {
                let Some(p) = path else { continue };
                if p.total_dist > self.max_dist {
                    *path = None;
                    continue;
                }
                let from = match p.leaves {
                    None => From::Eye(tile),
                    Some(object) => From::Surface(object),
                };
                let Some(Hit { object, t }) = self.objects.closest::<K, _>(&p.ray, from, &mut ())
                else {
                    *path = None;
                    continue;
                };
                let rules = self.rules.object(object);
                p.total_dist += t;
                let (surface, material) =
                    self.surface(object, rules, &p.ray, t, p.total_dist, &mut ());
                *hit = Some(Lit {
                    object,
                    rules,
                    t,
                    surface,
                    material,
                    intensity: material.ambient,
                });
                live = true;
            }
            if !live {
                break;
            }
            // 4. The ambient, and 5. every light's diffuse term.
            if self.stage.lights() {
                for (light, lamp) in self.scene.lights.iter().enumerate() {
                    self.light_span::<K>(light, lamp, hits);
                }
            }
            // 6. I / total_dist, and 7. the mirror.
            for ((path, hit), colour) in paths.iter_mut().zip(hits.iter()).zip(out.iter_mut()) {
                let (Some(p), Some(h)) = (path.as_mut(), hit) else {
                    continue;
                };
                let seen = h.intensity / self.divisor(p.total_dist, h.t);
                *colour += p.weight * seen;
                let mirror = match depth == bounces || !self.reflects(h.rules, &h.material) {
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
        }
    }

    /// Step 5 of [`Tracer::span`] for one light: every hit's direction to it, then the
    /// shadow rays, then the terms, each added to its hit's intensity.
    #[inline(always)]
    fn light_span<K: Kernel>(&self, light: usize, lamp: &Light, hits: &mut [Option<Lit>]) {
        let rules = self.rules.light(light);
        let mut towards: [Option<Towards>; TILE] = [None; TILE];
        let towards = &mut towards[..hits.len()];
        for (hit, towards) in hits.iter().zip(towards.iter_mut()) {
            if let Some(h) = hit.as_ref().filter(|h| !h.rules.unlit()) {
                *towards = self.towards(lamp, rules, &h.surface, &h.material, &mut ());
            }
        }
        for (hit, towards) in hits.iter().zip(towards.iter_mut()) {
            if let (Some(h), Some(to)) = (hit, &towards)
                && self.shadowed::<K>(rules, h.object, to, &mut ())
            {
                *towards = None;
            }
        }
        for (hit, towards) in hits.iter_mut().zip(towards.iter()) {
            if let Some(h) = hit {
                h.intensity += match towards {
                    Some(to) => term(lamp, rules, &h.material, to),
                    None => DVec3::ZERO,
                };
            }
        }
    }

    /// Where `ray` meets `object` at `t`: the point, the normal (as computed, spec §4.4;
    /// turned toward the ray under facing-normals, reversed under flipped-normal) and the
    /// material there (tiles, textures, shaders).
    #[inline(always)]
    fn surface(
        &self,
        object: usize,
        rules: ObjectRules,
        ray: &Ray,
        t: f64,
        total_dist: f64,
        rec: &mut impl Recorder,
    ) -> (Surface, Material) {
        let record = &self.scene.objects[object];
        let mut surface = record.shape.surface(ray, t);
        if rules.facing_normals() && surface.normal.dot(ray.dir) > 0.0 {
            surface.normal = -surface.normal;
        }
        if rules.flipped_normal() {
            surface.normal = -surface.normal;
        }
        let (material, pattern) = material_and_pattern(record, &surface, &self.screen);
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

    /// One light's diffuse term at a hit on `object` (spec §4.3): diffuse × emissivity ×
    /// cos θ / dist, where the light faces the surface, its beam reaches it and no object
    /// blocks the shadow ray.
    #[inline]
    fn diffuse<K: Kernel>(
        &self,
        light: &Light,
        rules: LightRules,
        object: usize,
        surface: &Surface,
        material: &Material,
        rec: &mut impl Recorder,
    ) -> DVec3 {
        let Some(towards) = self.towards(light, rules, surface, material, rec) else {
            return DVec3::ZERO;
        };
        if self.shadowed::<K>(rules, object, &towards, rec) {
            return DVec3::ZERO;
        }
        term(light, rules, material, &towards)
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
        if rules.off() {
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

    /// Whether an object blocks the shadow ray toward the light, where the stage casts
    /// shadow rays and no variant stops this one.
    #[inline(always)]
    fn shadowed<K: Kernel>(
        &self,
        rules: LightRules,
        object: usize,
        towards: &Towards,
        rec: &mut impl Recorder,
    ) -> bool {
        if !self.stage.shadows() || rules.unshadowed() {
            return false;
        }
        let shadow = &towards.shadow;
        rec.record(|| Event::Light(LightStep::ShadowRay { ray: *shadow }));
        self.objects
            .blocked::<K, _>(shadow, object, towards.dist, rec)
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
        material.specular != DVec3::ZERO && self.stage.reflects() && !rules.no_mirror()
    }

    /// The diagnostic image of `show` at the first hit along `ray`.
    fn show<K: Kernel>(&self, ray: Ray, show: Show, from: From, rec: &mut impl Recorder) -> DVec3 {
        rec.record(|| Event::Segment {
            depth: 0,
            ray,
            total_dist: 0.0,
        });
        let hit = self.objects.closest::<K, _>(&ray, from, rec);
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

/// A ray of [`Tracer::span`] between its bounces: the ray about to be traced, the object
/// it leaves (none for the camera ray), the product of the mirrors' speculars so far and
/// the path's length.
#[derive(Clone, Copy)]
struct Path {
    ray: Ray,
    leaves: Option<usize>,
    weight: DVec3,
    total_dist: f64,
}

/// A hit of [`Tracer::span`], with what its shading needs.
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
/// [`Tracer::span`] keeps the ray here from the direction's step to the shadow rays':
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
    let falloff = if rules.square_falloff() {
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
