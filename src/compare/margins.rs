//! How sure the reference is of each pixel: the recorder of `compare`'s fragile pixels
//! (docs/compare.md). While the reference renders, [`Margins`] hears every decision that
//! shaped a pixel's bytes and keeps the smallest *relative margin*: how far the
//! decision's quantity lay from the value where it would go the other way, over the size
//! of the numbers it was computed from. A tracer whose arithmetic is good to a relative
//! error p decides like the reference wherever every margin exceeds p; where one does
//! not, a correct tracer may get another colour, and the pixel is *fragile*.
//!
//! The decisions and their margins, with S the size of a point's coordinates (the ray's
//! base |B|∞, plus t, plus the object's anchor: its centre, point or corner):
//!
//! | decision (spec) | margin |
//! |---|---|
//! | a quadratic has real roots (§5.2, §5.6) | \|b² - 4ac\| / (b² + 4\|ac\|) |
//! | a root or a plane's t is in front of the base (§4.6) | \|t\| / S |
//! | a root's local y within the bounds (§5.6) | min(\|y - lo\|, \|y - hi\|) / S |
//! | the z > 0 rule (§5.1) | \|z\| / S |
//! | inside the rectangle (§5.3) | min(\|qx\|, \|qx - w\|, \|qy\|, \|qy - h\|) / S |
//! | which object is closest (§4.6) | (t₂ - t₁) / S for the two nearest |
//! | a shadow hit before the light (§4.3) | \|t - dist\| / S |
//! | the spotlight's cone (§4.3) | \|along - cos limit\| · dist / (dist + \|P\|∞ + \|L\|∞) |
//! | MAX_DIST (§4.2) | \|total_dist - MAX_DIST\| / MAX_DIST |
//! | the tile, the texel (§5.4, §5.8) | the distance to the cell's edge / (S + the offset's size) |
//! | a stripe (§5.5) | \|f - round f\| / (the terms of f, and its gradient times S) |
//! | the byte (§4.7) | \|255 c - k\| / 255 c, k the nearest step, over 16 κ |
//!
//! κ is the largest condition (spread / t) of the roots the path took: a decision taken
//! at or after a point found from a badly conditioned root is divided by it.
//!
//! A decision matters to a query only if it could change its answer: an object's own
//! decisions count when it wins, or when what it decides lies no further than the winner
//! (a miss that nearly hit in front of it); a shadow is as sure as its surest blocker,
//! and an unblocked light as its nearest miss. The queries go on testing objects a little
//! past their answer for this recorder ([`Sizes::query`]): 64 times the precision, so
//! that what lies that close behind the answer, measured on a point of size up to 64
//! times its distance, is heard (at most [`MARGIN_REACH`]).

use super::reach::Paths;
use crate::render::Near;
use crate::render::record::{Event, LightStep, MARGIN_REACH, Recorder};
use crate::render::shading::{PatternNote, Screen};
use crate::scene::{Pattern, Scene, Shader, TextureMode};
use crate::shapes::{HitNote, Ray, Shape};
use glam::DVec3;

/// What the recorder needs of the scene for every pixel, computed once.
pub(crate) struct Sizes<'a> {
    scene: &'a Scene,
    /// What each object's decisions are measured against.
    facts: Vec<Facts>,
    max_dist: f64,
    screen: Screen,
    /// How far past their answer the queries test objects ([`Sizes::query`]); margins
    /// beyond it are not kept.
    reach: f64,
    /// The closest hits' decisions whose margins clear the reach.
    cutoff: Cutoff,
}

/// Which margins a query can leave out: those at or above a bound, told from the
/// decision's quantity and size without dividing one by the other.
#[derive(Clone, Copy)]
struct Cutoff(f64);

impl Cutoff {
    /// Every margin counts.
    const NONE: Cutoff = Cutoff(f64::INFINITY);

    /// Margins of `reach` or more. The bound is raised by 4 ulps, so that quantity >=
    /// bound × size (rounded twice) implies quantity / size >= reach, rounded.
    fn at(reach: f64) -> Cutoff {
        Cutoff(reach * (1.0 + 4.0 * f64::EPSILON))
    }

    /// Whether the margin `quantity / size` is surely at or above the bound; never where
    /// the margin would be NaN, which counts as unsure: a NaN fails the comparison, and
    /// 0 / 0 and ∞ / ∞ have quantity = size.
    #[inline(always)]
    fn clears(self, quantity: f64, size: f64) -> bool {
        quantity >= self.0 * size && quantity != size
    }
}

impl<'a> Sizes<'a> {
    /// The query the margins need of the renderer: the answer and every object within
    /// the reach of changing it, with each test's decisions.
    pub(crate) fn query(&self) -> Near {
        Near(self.reach)
    }

    pub(crate) fn new(
        scene: &'a Scene,
        max_dist: f64,
        screen: Screen,
        precision: f64,
    ) -> Sizes<'a> {
        let facts = scene.objects.iter().map(|o| Facts::of(&o.shape)).collect();
        let reach = (64.0 * precision).min(MARGIN_REACH);
        Sizes {
            scene,
            facts,
            max_dist,
            screen,
            reach,
            cutoff: Cutoff::at(reach),
        }
    }
}

/// What one object's decisions are measured against, read from its shape at load.
struct Facts {
    /// |point|∞ of the point its equation is written about: its centre, its plane's
    /// point, its corner.
    anchor: f64,
    /// The bounds of a quadric 21-24's local y (spec §5.6).
    bounds: Option<(f64, f64)>,
    /// The z limit of its plane's rule, where it has one (spec §5.1: 0).
    z_limit: Option<f64>,
    /// A finite plane's width and height (spec §5.3).
    rectangle: Option<glam::DVec2>,
}

impl Facts {
    fn of(shape: &Shape) -> Facts {
        let (anchor, bounds) = match shape {
            Shape::Sphere(sphere) => (sphere.centre, None),
            Shape::Plane(plane) => (plane.point, None),
            Shape::FinitePlane(rectangle) => (rectangle.frame.plane.point, None),
            Shape::TiledPlane(frame) => (frame.plane.point, None),
            Shape::Quadric(q) => (q.centred.anchor, None),
            Shape::Paraboloid(p) => (p.equation.frame.centre, Some(p.equation.rule.bounds())),
            Shape::Cylinder(c) => (c.equation.frame.centre, Some(c.equation.rule.bounds())),
            Shape::Cone(c) => (c.equation.frame.centre, Some(c.equation.rule.bounds())),
            Shape::Hyperboloid(h) => (h.equation.frame.centre, Some(h.equation.rule.bounds())),
        };
        Facts {
            anchor: anchor.abs().max_element(),
            bounds,
            z_limit: shape
                .plane()
                .map(|plane| plane.z_limit)
                .filter(|l| l.is_finite()),
            rectangle: match shape {
                Shape::FinitePlane(rectangle) => Some(rectangle.size),
                _ => None,
            },
        }
    }
}

/// One pixel's margins, as the tracer tells its steps; and with `PATHS` what its path
/// involves, for `compare --diagnose`.
pub(crate) struct Margins<'s, 'a, const PATHS: bool> {
    sizes: &'s Sizes<'a>,
    /// The smallest margin of a decision that chose what the pixel shows.
    pub(crate) least: f64,
    /// The object the camera ray hits first, once the first query is answered.
    pub(crate) first: Option<Option<usize>>,
    /// How many times the arithmetic's precision the path's points may be off, relative
    /// to their distance: the largest spread / t of the roots it took (1 for planes). A
    /// decision downstream of a point, and the bytes, are that much less sure.
    pub(crate) kappa: f64,
    /// The current ray's |B|∞.
    base: f64,
    /// The distance to the current light.
    light_dist: f64,
    /// While a shadow ray's query is under way, the distance to its light.
    shadow: Option<f64>,
    /// The current light and the current hit point (for the spotlight's margin).
    light: usize,
    point: DVec3,
    /// The current query's decisions that came near: (potential t, margin).
    near: Vec<(usize, f64, f64)>,
    /// The two nearest hits in front of the base: (object, t, the spread of its root),
    /// nearest first.
    nearest: [Option<(usize, f64, f64)>; 2],
    /// The surest blocker's margin so far (shadow rays).
    surest_blocker: f64,
    /// The nearest unblocking decision's margin (shadow rays).
    nearest_miss: f64,
    /// What the path involves, for `compare --diagnose` (src/compare/reach.rs).
    pub(crate) paths: Paths,
    /// The error the current ray carries, in units of the precision: how far its base may
    /// be off (a length) and its direction (an angle). A camera ray's are its base's size
    /// and 1, which the margins' sizes hold; a mirror's grow with each bounce ([`Spread`]).
    spread: Spread,
    /// The excess of the current query's error over a fresh ray's, added to the size of
    /// a decision at distance t as excess.0 + t · excess.1: zero but past a mirror.
    excess: (f64, f64),
    /// The current hit point's error (a length) and its normal's (an angle), in units of
    /// the precision.
    hit_error: f64,
    normal_error: f64,
    /// Whether the current ray is a mirror's.
    mirrored: bool,
    /// cos θ of the current light.
    light_cos: f64,
    /// The error of the current mirror segment's intensity, and of the colour from the
    /// mirrors' segments, in units of the precision (absolute, per channel).
    intensity_error: DVec3,
    pub(crate) colour_error: DVec3,
}

/// The error a ray carries into its query, in units of the precision (the ray
/// differentials of docs/compare.md): its base's (a length) and its direction's (an
/// angle).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Spread {
    base: f64,
    dir: f64,
}

impl Spread {
    /// A ray from `base` along a direction known to the precision: the camera's.
    fn fresh(base: f64) -> Spread {
        Spread { base, dir: 1.0 }
    }

    /// The error of the point at distance `t` along the ray, found from a root whose
    /// error is `root` (its spread, or t for a plane's).
    fn at(self, t: f64, root: f64) -> f64 {
        self.base + t.abs() * self.dir + root
    }

    /// The ray reflected at a point off by `point_error` where the normal is off by
    /// `normal_error`: R = D - 2 (D·N) N turns with D one for one, and with N at most four
    /// times as much.
    fn reflected(self, point_error: f64, normal_error: f64) -> Spread {
        Spread {
            base: point_error,
            dir: self.dir + 4.0 * normal_error,
        }
    }
}

impl<'s, 'a, const PATHS: bool> Margins<'s, 'a, PATHS> {
    pub(crate) fn new(sizes: &'s Sizes<'a>) -> Margins<'s, 'a, PATHS> {
        Margins {
            sizes,
            least: f64::INFINITY,
            first: None,
            kappa: 1.0,
            base: 0.0,
            light_dist: f64::INFINITY,
            shadow: None,
            light: 0,
            point: DVec3::ZERO,
            near: Vec::new(),
            nearest: [None; 2],
            surest_blocker: 0.0,
            nearest_miss: f64::INFINITY,
            paths: Paths::default(),
            spread: Spread::fresh(0.0),
            excess: (0.0, 0.0),
            hit_error: 0.0,
            normal_error: 0.0,
            mirrored: false,
            light_cos: 1.0,
            intensity_error: DVec3::ZERO,
            colour_error: DVec3::ZERO,
        }
    }

    /// Takes a margin of a decision that chose what the pixel shows.
    fn take(&mut self, margin: f64) {
        // A NaN margin (a NaN decision) is as unsure as can be. Over a κ of 1 (every
        // path without a root) the margin is itself: no division.
        self.least = match margin.is_nan() {
            true => 0.0,
            false if self.kappa == 1.0 => self.least.min(margin),
            false => self.least.min(margin / self.kappa),
        };
    }

    /// A new query along `ray`: a shadow ray's to a light at `shadow`, or a closest hit.
    fn start(&mut self, ray: &Ray, shadow: Option<f64>) {
        self.base = ray.base.abs().max_element();
        // Past a mirror, what the ray's error has beyond a fresh ray's: a shadow ray's
        // base is the hit point, its direction off by the point's error over the light's
        // distance.
        self.excess = match (self.mirrored, shadow) {
            (false, _) => (0.0, 0.0),
            (true, None) => (
                (self.spread.base - self.base).max(0.0),
                (self.spread.dir - 1.0).max(0.0),
            ),
            (true, Some(dist)) => ((self.hit_error - self.base).max(0.0), self.hit_error / dist),
        };
        self.shadow = shadow;
        self.near.clear();
        self.nearest = [None; 2];
        self.surest_blocker = 0.0;
        self.nearest_miss = f64::INFINITY;
    }

    /// The size of a point at distance `t` on `object`'s equation.
    fn size(&self, object: usize, t: f64) -> f64 {
        let size = self.base + t.abs() + self.sizes.facts[object].anchor;
        match self.mirrored {
            false => size,
            true => size + self.excess.0 + t.abs() * self.excess.1,
        }
    }

    /// The smallest margin of `object`'s decisions in `notes`, and the t where it lies;
    /// margins of `cutoff` or more may be left out (infinite), their divisions not done:
    /// a camera ray keeps only those below the reach.
    #[inline]
    fn notes_margin(&self, object: usize, notes: &[HitNote], cutoff: Cutoff) -> (f64, f64) {
        let facts = &self.sizes.facts[object];
        let size = |t: f64| self.size(object, t);
        let mut least = (f64::INFINITY, f64::INFINITY);
        let mut plane_t = f64::INFINITY;
        // The margin `quantity / size` of a decision at `t`.
        let mut take = |quantity: f64, size: f64, t: f64| {
            if cutoff.clears(quantity, size) {
                return;
            }
            let margin = quantity / size;
            if margin.is_nan() || margin < least.0 {
                least = (margin, t);
            }
        };
        for note in notes {
            match *note {
                // Past a mirror, the ray's excess error moves the discriminant as it moves
                // a point at the vertex: the margin shrinks by the sizes' ratio.
                HitNote::Discriminant {
                    relative, vertex, ..
                } => match self.mirrored {
                    false => take(relative, 1.0, vertex),
                    true => {
                        let fresh = self.base + vertex.abs() + facts.anchor;
                        take(relative * fresh, size(vertex), vertex)
                    }
                },
                HitNote::Nearer { t: Some(t) } | HitNote::QuadricRoot { t, .. } => {
                    take(t.abs(), size(t), t)
                }
                HitNote::Root { t, y, .. } => {
                    let size = size(t);
                    take(t.abs(), size, t);
                    if let Some((low, high)) = facts.bounds {
                        take((y - low).abs().min((y - high).abs()), size, t);
                    }
                }
                HitNote::Plane { t, z, .. } => {
                    plane_t = t;
                    let size = size(t);
                    take(t.abs(), size, t);
                    if let Some(limit) = facts.z_limit {
                        take((z - limit).abs(), size, t);
                    }
                }
                HitNote::Rectangle { q, .. } => {
                    if let Some(rectangle) = facts.rectangle {
                        let (w, h) = (rectangle.x, rectangle.y);
                        let edge =
                            (q.x.abs().min((q.x - w).abs())).min(q.y.abs().min((q.y - h).abs()));
                        take(edge, size(plane_t), plane_t);
                    }
                }
                HitNote::Nearer { t: None } | HitNote::NoRealRoot | HitNote::Parallel => {}
            }
        }
        least
    }

    /// One object's test along the current ray.
    #[inline(always)]
    fn test(&mut self, object: usize, t: Option<f64>, notes: &[HitNote]) {
        // A shadow ray's decisions count whatever their margins; a closest hit's only
        // below the reach.
        let cutoff = match self.shadow {
            Some(_) => Cutoff::NONE,
            None => self.sizes.cutoff,
        };
        let (margin, at) = self.notes_margin(object, notes, cutoff);
        let hit = t.filter(|&t| t > 0.0);
        if let Some(dist) = self.shadow {
            match hit {
                Some(t) if t < dist => {
                    let edge = (t - dist).abs() / self.size(object, t);
                    self.surest_blocker = self.surest_blocker.max(margin.min(edge));
                }
                _ => {
                    let mut miss = if at < dist * (1.0 + self.sizes.reach) {
                        margin
                    } else {
                        f64::INFINITY
                    };
                    if let Some(t) = hit {
                        miss = miss.min((t - dist).abs() / self.size(object, t));
                    }
                    self.nearest_miss = self.nearest_miss.min(miss);
                }
            }
            return;
        }
        if margin < self.sizes.reach {
            self.near.push((object, at, margin));
        }
        if let Some(t) = hit {
            let spread = (notes.iter())
                .find_map(|note| match *note {
                    HitNote::Discriminant { spread, .. } => Some(spread),
                    _ => None,
                })
                .unwrap_or(0.0);
            let entry = Some((object, t, spread));
            match self.nearest {
                [Some((_, first, _)), _] if t < first => self.nearest = [entry, self.nearest[0]],
                [Some(_), Some((_, second, _))] if t >= second => {}
                [Some(_), _] => self.nearest[1] = entry,
                [None, _] => self.nearest[0] = entry,
            }
        }
    }

    /// The closest-hit query's answer: which of its decisions chose it.
    #[inline(always)]
    fn closest(&mut self, hit: Option<(usize, f64)>) {
        self.first.get_or_insert(hit.map(|(object, _)| object));
        let best = hit.map_or(f64::INFINITY, |(_, t)| t);
        let winner = hit.map(|(object, _)| object);
        let mut least = f64::INFINITY;
        for &(object, at, margin) in &self.near {
            if Some(object) == winner || at <= best * (1.0 + self.sizes.reach) {
                least = least.min(margin);
            }
        }
        if let [Some((first, t1, _)), Some((_, t2, _))] = self.nearest {
            least = least.min((t2 - t1) / self.size(first, t2));
        }
        self.take(least);
        // What follows starts from the hit point, as sure as its root. The winner is one
        // of the two nearest hits but where a variant's ε or a box refused a nearer one;
        // then its condition is not known and not taken.
        let won = |entry: &Option<(usize, f64, f64)>| entry.filter(|e| Some(e.0) == winner);
        let root = self.nearest.iter().find_map(won);
        // A root found without a spread (a plane's) leaves κ as it was.
        if let Some((_, t, spread)) = root
            && spread != 0.0
        {
            self.kappa = self.kappa.max(spread / t.abs());
        }
        // The hit point's error: the ray's at t, and the root's own.
        if let Some((_, t)) = hit {
            let spread = root.map_or(0.0, |(_, _, spread)| spread);
            self.hit_error = self.spread.at(t, spread.max(t.abs()));
        }
    }

    /// The pattern's decision at the hit on `object` at distance `t` (spec §5.4, §5.5,
    /// §5.8): how far the truncated quantity lay from the next integer.
    fn pattern(&mut self, object: usize, t: f64, surface: &crate::shapes::Surface) {
        let record = &self.sizes.scene.objects[object];
        let size = self.size(object, t);
        let q = surface.plane_xy;
        // The distance from `a` to the nearest integer, in units of `cell`.
        let edge = |a: f64, cell: f64| (a - a.round()).abs() * cell.abs();
        let margin = match &record.look.pattern {
            Pattern::Plain => f64::INFINITY,
            Pattern::Tiles { tile, .. } => {
                // trunc(10000 + q/w): the 10000 rounds with q.
                let x = edge(q.x / tile.x, tile.x) / (size + 1e4 * tile.x.abs());
                let y = edge(q.y / tile.y, tile.y) / (size + 1e4 * tile.y.abs());
                x.min(y)
            }
            Pattern::Texture {
                texture,
                mode,
                size: fit,
            } => {
                let (tw, th) = (texture.width as f64, texture.height as f64);
                let (sx, sy) = match mode {
                    TextureMode::Fit => (tw / fit.x, th / fit.y),
                    TextureMode::Tile => {
                        let screen = &self.sizes.screen;
                        let last = screen.last_pixel;
                        (last.x / screen.window.x, last.y / screen.window.y)
                    }
                };
                let x = edge(q.x * sx, 1.0 / sx);
                let y = edge(q.y * sy, 1.0 / sy);
                x.min(y) / size
            }
            Pattern::Shader {
                shader: Shader::Stripes,
                origin,
            } => {
                let v = surface.point - *origin;
                let terms = [v.x * v.y * v.y / 100.0, v.x * v.y / 100.0];
                let f = 1000.0 + terms[0] + terms[1];
                let gradient =
                    ((v.y * v.y + v.y) / 100.0).abs() + ((2.0 * v.x * v.y + v.x) / 100.0).abs();
                let scale = 1000.0 + terms[0].abs() + terms[1].abs() + gradient * size;
                (f - f.round()).abs() / scale
            }
            Pattern::Shader {
                shader: Shader::ColourWheel,
                ..
            } => f64::INFINITY,
        };
        self.take(margin);
    }
}

impl<const PATHS: bool> Recorder for Margins<'_, '_, PATHS> {
    #[inline(always)]
    fn record(&mut self, event: impl FnOnce() -> Event) {
        match event() {
            Event::Segment {
                depth,
                ray,
                total_dist,
            } => {
                if total_dist > 0.0 {
                    let max = self.sizes.max_dist;
                    self.take((total_dist - max).abs() / max);
                }
                if PATHS {
                    self.paths.segment(depth);
                }
                self.mirrored = depth > 0;
                self.spread = match self.mirrored {
                    false => Spread::fresh(ray.base.abs().max_element()),
                    true => self.spread.reflected(self.hit_error, self.normal_error),
                };
                self.intensity_error = DVec3::ZERO;
                self.start(&ray, None);
            }
            Event::CutOff { total_dist } => {
                if PATHS {
                    self.paths.cut();
                }
                let max = self.sizes.max_dist;
                self.take((total_dist - max).abs() / max);
            }
            Event::Closest { hit } => {
                if PATHS && let Some((object, t)) = hit {
                    self.paths.hit(object);
                    self.paths.far(t);
                }
                self.closest(hit);
            }
            Event::Surface {
                object,
                t,
                surface,
                pattern,
                ..
            } => {
                self.point = surface.point;
                let curvature = self.sizes.scene.objects[object]
                    .shape
                    .curvature(surface.point);
                self.normal_error = curvature * self.hit_error + 1.0;
                if !matches!(pattern, PatternNote::Plain) {
                    self.pattern(object, t, &surface);
                }
            }
            Event::Lamp { light } => self.light = light,
            Event::Lit {
                light,
                contribution,
                ..
            } => {
                if PATHS && contribution != DVec3::ZERO {
                    self.paths.lit(light);
                }
                if self.mirrored && contribution != DVec3::ZERO {
                    // diffuse × emissivity × cos θ / dist at a point off by the hit's
                    // error, with the normal off by its own: cos θ moves by the normal's
                    // error and the direction's (the point's over the distance), the
                    // distance by the point's.
                    let along = self.hit_error / self.light_dist;
                    let relative = (self.normal_error + along) / self.light_cos + along;
                    self.intensity_error += contribution.abs() * relative;
                }
            }
            Event::Divided {
                total_dist,
                seen,
                weight,
                ..
            } if self.mirrored => {
                // I / total_dist, the path's length off by the hit's error.
                let error = (self.intensity_error + seen.abs() * self.hit_error) / total_dist;
                self.colour_error += weight.abs() * error;
            }
            Event::Light(LightStep::Towards { dist, cos, .. }) => {
                self.light_dist = dist;
                self.light_cos = cos;
            }
            Event::Light(LightStep::Spot { along, .. }) => {
                let light = &self.sizes.scene.lights[self.light];
                if let Some(beam) = &light.beam {
                    let dist = self.light_dist;
                    let size =
                        dist + self.point.abs().max_element() + light.location.abs().max_element();
                    self.take((along - beam.cos_limit).abs() * dist / size);
                }
            }
            Event::Light(LightStep::ShadowRay { ray }) => {
                self.start(&ray, Some(self.light_dist));
            }
            Event::Light(LightStep::Blocked { blocker }) => {
                if PATHS && let Some((object, t)) = blocker {
                    self.paths.blocked(object, self.light);
                    self.paths.far(t);
                }
                let margin = match blocker {
                    Some(_) => self.surest_blocker,
                    None => self.nearest_miss,
                };
                self.take(margin);
                self.shadow = None;
            }
            _ => {}
        }
    }

    #[inline(always)]
    fn tested(&mut self, object: usize, t: Option<f64>, notes: &[HitNote]) {
        self.test(object, t, notes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{Options, Setup};
    use crate::shapes::kernel::Accurate;

    /// Two spheres of radius 1 on the z axis, at z = -5 and at `far`, seen from (0, 0, 3).
    fn two_spheres(far: f64) -> Scene {
        let sphere = |z: f64| format!("13\n1 1 1\n0 0 0\n0 0 0\n0 0 {z}\n1\n\n");
        let text = format!("8 6\n0 0 3\n\n{}{}", sphere(-5.0), sphere(far));
        crate::load(&text).expect("a scene")
    }

    /// The least margin of the centre pixel of a 3x3 render, whose ray is the z axis.
    fn centre_margin(scene: &Scene) -> f64 {
        let options = Options::new(3, 3);
        let setup = Setup::new(scene, &options);
        let tracer = setup.tracer(&options);
        let sizes = Sizes::new(
            &setup.scene,
            options.max_dist,
            tracer.screen(),
            MARGIN_REACH,
        );
        let ray = setup.camera.ray(1, 1).expect("a ray");
        assert_eq!((ray.base, ray.dir), (DVec3::new(0.0, 0.0, 3.0), -DVec3::Z));
        let mut rec = Margins::<false>::new(&sizes);
        tracer.pixel::<Accurate>(1, 1, sizes.query(), &mut rec);
        rec.least
    }

    #[test]
    fn a_margin_cleared_without_dividing_is_at_or_above_the_bound() {
        // Quantities a few ulps either side of reach × size, and sizes across the
        // exponent range: where `clears` says so, the divided margin is at or above the
        // reach; and a margin that would be NaN is never cleared.
        for reach in [64.0 * 1.9073486328125e-6, 64.0 * f64::EPSILON, 1e-2] {
            let cutoff = Cutoff::at(reach);
            for size in [1e-300, 3e-7, 0.7, 1.0, 3.0, 12345.678, 1e200] {
                let mut quantity = reach * size;
                for _ in 0..12 {
                    quantity = f64::from_bits(quantity.to_bits() - 1);
                }
                for _ in 0..24 {
                    if cutoff.clears(quantity, size) {
                        assert!(quantity / size >= reach, "{quantity:e} / {size:e}");
                    }
                    quantity = f64::from_bits(quantity.to_bits() + 1);
                }
                assert!(cutoff.clears(reach * size * 2.0, size));
            }
            for (quantity, size) in [(0.0, 0.0), (f64::INFINITY, f64::INFINITY), (f64::NAN, 1.0)] {
                assert!(!cutoff.clears(quantity, size));
                assert!(!Cutoff::NONE.clears(quantity, size));
            }
        }
    }

    #[test]
    fn a_tie_between_two_objects_has_no_margin() {
        // Both spheres hit at t = 7 exactly: which is drawn is the tie rule's choice.
        assert_eq!(centre_margin(&two_spheres(-5.0)), 0.0);
    }

    #[test]
    fn the_nearest_decision_is_the_discriminant_of_the_sphere_hit() {
        // From B = (0, 0, 3) along -z to the sphere at z = -5: a = 1, b = 2 D·(B - C) = -16,
        // c = |B - C|² - 1 = 63; b² - 4ac = 4 over b² + 4|ac| = 508. The roots 7 and 9 are
        // far from 0 (7 / (3 + 7 + 5)), and the sphere at z = -9 is hit at t = 11, far
        // behind: (11 - 7) / (3 + 11 + 5).
        assert_eq!(centre_margin(&two_spheres(-9.0)), 4.0 / 508.0);
    }

    #[test]
    fn the_gap_to_the_next_object_counts_when_it_is_the_nearest() {
        // The sphere at z = -5.05 is hit at t = 7.05: the gap 0.05 over the size of the
        // farther point (3 + 7.05 + 5) is below the discriminant's 4 / 508.
        let expected = (7.05 - 7.0) / (3.0 + 7.05 + 5.0);
        let margin = centre_margin(&two_spheres(-5.05));
        assert!((margin - expected).abs() < 1e-12, "{margin} {expected}");
    }
}
