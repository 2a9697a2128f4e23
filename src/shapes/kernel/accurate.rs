//! The kernel `legacy-rt` ships: the exact root of the f64 problem to within a few ulps.
//! A typical test costs about twice the textbook's; one that needs refining, two and a
//! half to four times (docs/speed-vs-error.md has the figures).
//!
//! Three steps:
//! 1. Move the ray's base along the ray to the point nearest the shape's centre, in world
//!    space: B'' = (B - C) + s0 D with s0 = -(B - C)·D. B - C is kept exactly as a
//!    rounded difference plus its rounding error (two-sum), and each component of
//!    s0 D + (B - C) is one fused multiply-add, rounded once on a result the size of the
//!    shape. B'' is then good to an ulp of the shape's size, not of its distance, and so
//!    are the coefficients of the quadratic in s = t - s0 ([`AxisQuadric::coefficients`]
//!    after `rotmat`). This is the geometric form of the discriminant, for every shape at
//!    once; the roots come from the stable formula ([`solve_quadratic`]).
//! 2. Estimate the error of each root from the sizes of the terms of f and of its
//!    gradient at the root, over the slope |f'(s)| ([`RootError`]). A ray that grazes the
//!    silhouette, runs nearly parallel to a cylinder's axis or a cone's generator, or
//!    starts next to a huge surface has a small slope or a small t, and there the
//!    estimate is large. A root out of bounds by more than twice its estimate is dropped
//!    as it is.
//! 3. Only then refine: evaluate f at the root from the world-space numbers
//!    (B - C + t D, then `rotmat`) with every rounding error kept ([`residual`],
//!    [`sum_as_f64`]), and solve the quadratic shifted to the root,
//!    a σ² + f'(t) σ + f(t) = 0, for the correction σ ([`correction`]: usually Newton's
//!    step with one curvature term). Its a and f'(t) need only a few correct digits, f(t)
//!    needs them all. A sphere seen from just outside is solved from the base instead
//!    ([`just_outside`]).
//!
//! The general `QUADRIC` takes the same steps about its centre
//! (`Centred`); a plane's dot products are recomputed with
//! their rounding errors when they cancel. Bound tests (local y, the plane's z = 0)
//! accept a hit within [`slack`] of the bound, so a point the scene puts exactly on a
//! bound does not flip from pixel to pixel on the rounding of t and of the ray.

use super::{Kernel, PlaneFrom, Tangent};
use super::{solve_quadratic, solve_quadratic_with_slope};
use crate::shapes::kernel::dd::{
    Dd, fused, scaled, scaled_product, square, sum_as_dd, sum_as_f64, two_prod, two_sum,
};
use crate::shapes::{
    AxisFrame, AxisQuadric, Dirs, HitNote, LANES, Notes, Plane, Quadric, Ray, RootRule, Sphere,
    each_lane,
};
use glam::DVec3;
use wide::f64x8;

/// The shipped kernel.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Accurate;

/// Refine when the estimated error exceeds this many EPS |t|. Set on the hard-case suite
/// (seed 0x2026_1121): at 8 the largest error is 3.64 ulps, at 16 it is 4.94 and at 32
/// 11.4, while the cost barely moves (refined rays are the hard ones whatever the value).
const REFINE_ABOVE_ULPS: f64 = 8.0;

/// At most this many refinement steps (each one squares the relative error).
const MAX_STEPS: usize = 3;

const EPS: f64 = f64::EPSILON;

/// The largest |a σ / slope| at which a refinement step takes Newton's correction
/// ([`correction`]): 2⁻³⁰, so that its error 2ρ² |σ| stays below 2⁻⁵⁹ |σ|.
const NEWTON_BEND: f64 = 1.0 / (1u64 << 30) as f64;

/// How far past a bound (the plane's z = 0, a quadric's y = 0 or h) a hit still counts:
/// 8 ulps of the size of the terms that computed the coordinate. A point that the scene
/// puts exactly on a bound then counts as inside, whatever the rounding of the ray.
#[inline]
fn slack(size: f64) -> f64 {
    8.0 * EPS * size
}

/// Step 2's estimate for one root: the root moves by at most about
/// EPS (`spread` / `slope` + |t| / 2), where `spread` sums the sizes of the terms whose
/// rounding perturbs f near the root and `slope` = |f'|. Kept as a fraction, so that the
/// common case costs two multiplications and no division.
#[derive(Clone, Copy)]
struct RootError {
    spread: f64,
    slope: f64,
}

impl RootError {
    /// Whether the estimate exceeds [`REFINE_ABOVE_ULPS`] EPS |t|. NaN (an overflowed
    /// estimate) refines too.
    #[inline]
    fn needs_refining(self, t: f64) -> bool {
        let allowed = (REFINE_ABOVE_ULPS - 0.5) * t.abs() * self.slope;
        self.spread > allowed || self.spread.is_nan() || allowed.is_nan()
    }

    /// Whether `distance` (how far the root lies past a bound, or behind the base) is
    /// more than twice the estimated error plus `slack`: refining cannot bring it back.
    #[inline]
    fn clearly_beyond(self, distance: f64, t: f64, slack: f64) -> bool {
        distance * self.slope > 2.0 * EPS * self.spread + (EPS * t.abs() + slack) * self.slope
    }
}

/// Step 1's result for a ray and a shape: the recentred ray, and the local ray it gives.
#[derive(Clone, Copy)]
struct Near {
    /// The recentring about the shape's centre (or a `QUADRIC`'s anchor).
    start: Recentred,
    /// B'' - C in the local frame.
    near: DVec3,
    /// D in the local frame.
    dir: DVec3,
}

impl Near {
    /// Step 1 for a quadric 21-24 or a sphere: B'' = B + s0 D next to the centre
    /// ([`recentre`]), then `rotmat`.
    #[inline(always)]
    fn of_axis_quadric(frame: &AxisFrame, ray: &Ray) -> Near {
        let start = recentre(ray, frame.centre);
        Near {
            start,
            near: frame.rotate(start.near),
            dir: frame.rotate(ray.dir),
        }
    }

    /// Step 1 about the anchor x0 of a `QUADRIC`'s centred form (`Centred`); no rotation.
    #[inline(always)]
    fn of_quadric(quadric: &Quadric, ray: &Ray) -> Near {
        let start = recentre(ray, quadric.centred.anchor);
        Near {
            start,
            near: start.near,
            dir: ray.dir,
        }
    }

    /// `slack` of the sizes that computed a local coordinate at `t`.
    #[inline(always)]
    fn bound_slack(&self, t: f64) -> f64 {
        let Recentred { offset, shift, .. } = self.start;
        slack(offset.abs().max_element() + shift.abs() + t.abs())
    }
}

impl Kernel for Accurate {
    #[inline(always)]
    fn sphere_surely_misses(sphere: &Sphere, (_, dw, ww): (f64, f64, f64)) -> bool {
        misses_by(sphere, dw, ww)
    }

    /// Most rays of a scene miss most spheres: `certainly_misses` says so in a few plain
    /// f64 operations, and only the other rays take the accurate path. (A trace, which
    /// wants the reasons, takes the accurate path for every ray: the same t.)
    #[inline]
    fn sphere<N: Notes>(sphere: &Sphere, ray: &Ray, notes: &mut N) -> Option<f64> {
        if N::KEPT {
            return axis_quadric_hit(&sphere.equation(), ray, notes);
        }
        if certainly_misses(sphere, ray) {
            return None;
        }
        sphere_hit(sphere, ray)
    }

    #[inline]
    fn axis_quadric<N: Notes>(quadric: &AxisQuadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        match N::KEPT {
            true => axis_quadric_hit(quadric, ray, notes),
            false => axis_hit(quadric, ray),
        }
    }

    #[inline]
    fn quadric<N: Notes>(quadric: &Quadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        match N::KEPT {
            true => quadric_hit_noted(quadric, ray, notes),
            false => quadric_hit(quadric, ray),
        }
    }

    /// The plane's t = N·(Q - B) / N·D, each dot product recomputed with its rounding
    /// errors where its terms cancel; a hit meant to lie on the screen (z = 0: a floor
    /// through the bottom edge of the window) comes out at z = ±1e-16 from the rounding of
    /// the ray's direction, and within a few ulps of the terms it counts as on the
    /// screen, which §5.1 draws.
    #[inline]
    fn plane<N: Notes>(plane: &Plane, ray: &Ray, notes: &mut N) -> Option<f64> {
        plane_split(plane, &Accurate::plane_from(plane, ray.base), ray, notes)
    }

    #[inline(always)]
    fn plane_from(plane: &Plane, base: DVec3) -> PlaneFrom {
        let over = plane.normal * (plane.point - base);
        let numerator = over.element_sum();
        PlaneFrom {
            numerator,
            cancels: cancels(numerator, over),
        }
    }

    #[inline(always)]
    fn plane_toward(plane: &Plane, from: &PlaneFrom, ray: &Ray) -> Option<f64> {
        plane_split(plane, from, ray, &mut ())
    }

    /// [`plane_split`] of a span's rays in the processor's vector registers where one
    /// division decides: each lane's N·D, its cancellation test, t and spec §5.1's rule
    /// on z, the same operations in the same order as [`plane_split`]'s. A lane whose
    /// terms cancel, or whose N·D is 0, takes [`plane_split`] itself, as do all where
    /// the numerator's terms cancel.
    #[inline(always)]
    fn planes_toward(
        plane: &Plane,
        from: &PlaneFrom,
        base: DVec3,
        dirs: &Dirs,
        lanes: u32,
    ) -> ([f64; LANES], u32) {
        let [x, y, z] = dirs.lanes();
        let n = plane.normal;
        let (ux, uy, uz) = (x * n.x, y * n.y, z * n.z);
        // As `element_sum` and `cancels`: (x + y) + z, 2|N·D| < (|x| + |y|) + |z|.
        let denominator = (ux + uy) + uz;
        let terms = (ux.abs() + uy.abs()) + uz.abs();
        let cancel = (denominator.abs() * 2.0).simd_lt(terms);
        let parallel = denominator.simd_eq(f64x8::ZERO);
        let quick = match from.cancels {
            true => 0,
            false => !(cancel | parallel).to_bitmask() & lanes,
        };
        let t = f64x8::splat(from.numerator) / denominator;
        // `Plane::verdict`: t ≥ 0 (not NaN, not below 0), then z within the limit or
        // within the slack of it, 8 EPS (|B.z| + |t|).
        let z = t * z + base.z;
        let slack = (t.abs() + base.z.abs()) * (8.0 * EPS);
        let limit = f64x8::splat(plane.z_limit);
        let counts = t.simd_ge(f64x8::ZERO) & (z.simd_le(limit) | (z - limit).simd_le(slack));
        let (slow, slow_hits) = each_lane(lanes & !quick, |i| {
            plane_split(plane, from, &Ray::new(base, dirs.get(i)), &mut ())
        });
        let t = t.to_array();
        let ts = std::array::from_fn(|i| match quick & 1 << i != 0 {
            true => t[i],
            false => slow[i],
        });
        (ts, quick & counts.to_bitmask() | slow_hits)
    }
}

/// Whether a dot product `dot` of these `terms` may have lost digits: it is good to a
/// few ulps unless its terms cancel.
#[inline(always)]
fn cancels(dot: f64, terms: DVec3) -> bool {
    2.0 * dot.abs() < terms.abs().element_sum()
}

/// [`Accurate::plane`] for a ray from the base `from` was prepared for: the denominator
/// N·D, then t, both dot products recomputed where either's terms cancel
/// ([`plane_dd`]), then spec §5.1's rule.
#[inline(always)]
fn plane_split(plane: &Plane, from: &PlaneFrom, ray: &Ray, notes: &mut impl Notes) -> Option<f64> {
    let under = plane.normal * ray.dir;
    let denominator = under.element_sum();
    let t = if from.cancels || cancels(denominator, under) {
        plane_dd(plane, ray)
    } else {
        (denominator != 0.0).then(|| from.numerator / denominator)
    };
    let Some(t) = t else {
        notes.note(HitNote::Parallel);
        return None;
    };
    plane.verdict(ray, t, || slack(ray.base.z.abs() + t.abs()), notes)
}

/// Note 003's algorithm for the sphere and the quadrics 21-24 in this kernel's steps:
/// the recentred local ray, a, b and c, the stable roots, then spec §5's rule on each,
/// refined only where its estimated error says so.
#[inline(always)]
fn axis_quadric_hit(quadric: &AxisQuadric, ray: &Ray, notes: &mut impl Notes) -> Option<f64> {
    // Step 1.
    let local = Near::of_axis_quadric(&quadric.frame, ray);
    let (a, b, c) = quadric.coefficients(local.near, local.dir);
    match quadric.rule {
        // The sphere: the smaller root of a discriminant > 0, even when negative.
        RootRule::Nearer => {
            let Some((s, slope)) = nearer_root(a, b, c) else {
                notes.note(HitNote::NoRealRoot);
                return None;
            };
            let t = sphere_distance(quadric, ray, &local, a, s, slope);
            notes.note(HitNote::Nearer { t });
            t
        }
        // The smallest positive root whose local y is within bounds; a zero
        // discriminant counts.
        rule => {
            let Some((roots, slope)) = solve_quadratic_with_slope(a, b, c)
                .filter(|&(_, slope)| Tangent::Counts.real(slope))
            else {
                notes.note(HitNote::NoRealRoot);
                return None;
            };
            let judge = |index, s| {
                let (t, y, settled) = distance_and_height(quadric, ray, &local, a, s, slope, index);
                (t, y, settled && rule.accepts(t, y, || local.bound_slack(t)))
            };
            rule.first_within(roots, judge, notes)
        }
    }
}

/// Steps 2 and 3 for the sphere's root s: t, refined where needed; `None` if it is not a
/// finite number.
#[inline(always)]
fn sphere_distance(
    quadric: &AxisQuadric,
    ray: &Ray,
    local: &Near,
    a: f64,
    s: f64,
    slope: f64,
) -> Option<f64> {
    let Near { start, near, dir } = *local;
    let t = start.shift + s;
    let error = RootError {
        spread: Spread::new(quadric, near, dir).at(s),
        slope,
    };
    let t = if error.needs_refining(t) {
        // From just outside, heading in, the base gives the root directly.
        just_outside(quadric, ray, start.offset, start.offset_error, a)
            .unwrap_or_else(|| refine_axis(quadric, ray, local, a, t, 0).0)
    } else {
        t
    };
    t.is_finite().then_some(t)
}

/// Steps 2 and 3 for root `index` (s) of a bounded quadric: t and the local y, and
/// whether they are settled. A root out of bounds (or behind the base) by more than twice
/// its estimated error stays out after refining: it is returned unrefined and unsettled.
#[inline(always)]
fn distance_and_height(
    quadric: &AxisQuadric,
    ray: &Ray,
    local: &Near,
    a: f64,
    s: f64,
    slope: f64,
    index: usize,
) -> (f64, f64, bool) {
    let Near { start, near, dir } = *local;
    let t = start.shift + s;
    let error = RootError {
        spread: Spread::new(quadric, near, dir).at(s),
        slope,
    };
    let y = near.y + s * dir.y;
    let (low, high) = quadric.rule.bounds();
    let outside = (-t).max(low - y).max(y - high);
    if outside > 0.0 && error.clearly_beyond(outside, t, local.bound_slack(t)) {
        return (t, y, false);
    }
    let (t, y) = if error.needs_refining(t) {
        refine_axis(quadric, ray, local, a, t, index)
    } else {
        (t, y)
    };
    (t, y, true)
}

/// Note 004's algorithm for a `QUADRIC` in this kernel's steps: f(x0 + u + s D) =
/// a s² + b s + c about the anchor, the stable roots, the first in front of the base,
/// refined only where its estimated error says so.
#[inline(always)]
fn quadric_hit_noted(quadric: &Quadric, ray: &Ray, notes: &mut impl Notes) -> Option<f64> {
    let local = Near::of_quadric(quadric, ray);
    let (centred, near, dir) = (&quadric.centred, local.near, local.dir);
    let m_dir = centred.second_order * dir;
    let m_near = centred.second_order * near;
    let a = dir.dot(m_dir);
    let b = 2.0 * (near.dot(m_dir) + centred.gradient.dot(dir));
    let c = near.dot(m_near) + 2.0 * centred.gradient.dot(near) + centred.value;
    let Some((roots, slope)) =
        solve_quadratic_with_slope(a, b, c).filter(|&(_, slope)| Tangent::Counts.real(slope))
    else {
        notes.note(HitNote::NoRealRoot);
        return None;
    };
    let judge = |index, s: f64| {
        let t = local.start.shift + s;
        let reach = s.abs() * local.dir.abs() + local.near.abs();
        let m_reach = centred.second_order_abs * reach;
        let gradient_abs = centred.gradient.abs();
        let value_size = reach.dot(m_reach) + 2.0 * gradient_abs.dot(reach) + centred.value.abs();
        let gradient_size = 2.0 * (m_reach + gradient_abs).element_sum();
        let error = RootError {
            spread: spread(value_size, gradient_size, reach),
            slope,
        };
        // Behind the base by more than twice its error: it stays behind after refining.
        if t < 0.0 && error.clearly_beyond(-t, t, 0.0) {
            return (t, false);
        }
        match error.needs_refining(t) {
            true => (refine_quadric(quadric, ray, a, t, index), true),
            false => (t, true),
        }
    };
    Quadric::first_in_front(roots, judge, notes)
}

/// The margin of [`certainly_misses`], 2^-46: 128 units in the last place of the sum it
/// multiplies.
const MISS_MARGIN: f64 = 1.0 / (1u64 << 46) as f64;

/// Whether `ray`'s line passes so far from the sphere's centre that the sphere's
/// discriminant is certainly negative, which the accurate path would find too.
///
/// With w = C - B and p = w·D, the squared distance from C to the line is
/// d² = |w|² - p² / |D|², and the discriminant is 4|D|²(r² - d²): a miss when d² >= r².
/// In f64, w, |w|² and p² each carry a relative error of a few units u = 2^-53, and
/// |D|² = 1 within 4u (a unit vector), so q = |w|² - p² is d² within about 25u·|w|²
/// (p² <= |D|²|w|²). The test asks for q - r² above 128u·(|w|² + r²), five times that
/// bound: any ray it rejects lies far outside the sphere, never on a grazing tangent, and
/// the accurate path, whose discriminant is good to a few units of the same size, would
/// find no real root either. r² is the equation's own constant, so it is exact here.
/// Overflow gives NaN or infinity, and then the comparison is false: no rejection.
#[inline(always)]
fn certainly_misses(sphere: &Sphere, ray: &Ray) -> bool {
    let w = sphere.centre - ray.base;
    misses_by(sphere, w.dot(ray.dir), w.dot(w))
}

/// [`certainly_misses`] from p = w·D and |w|² (w = C - B). Its sign does not matter: p
/// enters squared, so D·(B - C), which is -p to the bit (a difference, each product and
/// the sum all change sign exactly), gives the same answer.
#[inline(always)]
fn misses_by(sphere: &Sphere, p: f64, ww: f64) -> bool {
    let r2 = sphere.radius_sq;
    (ww - p * p) - r2 > MISS_MARGIN * (ww + r2)
}

/// Defines `$name`, which evaluates `$body` in a copy compiled for the FMA instruction
/// when the CPU has it (checked once and cached by the standard library): the products
/// of [`two_prod`] are then one instruction instead of a call to the C library's `fma`.
/// Both copies compute the same bits.
macro_rules! fma_dispatch {
    ($(#[$meta:meta])* fn $name:ident($($arg:ident: $ty:ty),* $(,)?) -> $ret:ty { $body:expr }) => {
        $(#[$meta])*
        #[inline(never)]
        fn $name($($arg: $ty),*) -> $ret {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "fma")]
                fn with_fma($($arg: $ty),*) -> $ret {
                    $body
                }
                if std::arch::is_x86_feature_detected!("fma") {
                    // SAFETY: the CPU has the instructions `with_fma` is compiled for.
                    return unsafe { with_fma($($arg),*) };
                }
            }
            $body
        }
    };
}

fma_dispatch!(
    /// The plane's t with both dot products to within an ulp ([`plane_dd_any`]).
    fn plane_dd(plane: &Plane, ray: &Ray) -> Option<f64> {
        plane_dd_any(plane, ray)
    }
);
fma_dispatch!(
    /// [`axis_quadric_hit`] without notes, as the render calls it.
    fn axis_hit(quadric: &AxisQuadric, ray: &Ray) -> Option<f64> {
        axis_quadric_hit(quadric, ray, &mut ())
    }
);
fma_dispatch!(
    /// [`axis_hit`] of a sphere: its equation is built inside the copy that solves it,
    /// where the compiler folds its constants (αx = αy = αz = 1, β = 0, the nearer root).
    /// Built by the caller and passed by reference, it cost spec1 3-5 % (the loads of a
    /// struct just stored); the same steps, so the same t.
    fn sphere_hit(sphere: &Sphere, ray: &Ray) -> Option<f64> {
        axis_quadric_hit(&sphere.equation(), ray, &mut ())
    }
);
fma_dispatch!(
    /// [`quadric_hit_noted`] without notes, as the render calls it.
    fn quadric_hit(quadric: &Quadric, ray: &Ray) -> Option<f64> {
        quadric_hit_noted(quadric, ray, &mut ())
    }
);
fma_dispatch!(
    /// [`refine_axis_any`], kept out of line so that the common path stays small.
    fn refine_axis(
        quadric: &AxisQuadric,
        ray: &Ray,
        local: &Near,
        a: f64,
        t0: f64,
        index: usize,
    ) -> (f64, f64) {
        refine_axis_any(quadric, ray, local, a, t0, index)
    }
);
fma_dispatch!(
    /// [`refine_quadric_any`], kept out of line.
    fn refine_quadric(quadric: &Quadric, ray: &Ray, a: f64, t0: f64, index: usize) -> f64 {
        refine_quadric_any(quadric, ray, a, t0, index)
    }
);

/// Step 1's result for a ray and a centre C.
#[derive(Clone, Copy)]
struct Recentred {
    /// B - C, rounded.
    offset: DVec3,
    /// The rounding error of `offset`: B - C = offset + offset_error exactly.
    offset_error: DVec3,
    /// s0 = -(B - C)·D.
    shift: f64,
    /// B'' - C = (B - C) + s0 D, to an ulp of its own size.
    near: DVec3,
}

/// Step 1, in world space: B - C exactly as offset + offset_error, then
/// B'' - C = (B - C) + s0 D. Each fused multiply-add rounds once, on a result the size
/// of the shape, so B'' is good to an ulp of |B'' - C|, not of |B - C|.
#[inline(always)]
fn recentre(ray: &Ray, centre: DVec3) -> Recentred {
    let offset = ray.base - centre;
    let offset_error = sum_error(ray.base, -centre);
    let shift = -offset.dot(ray.dir);
    let near = DVec3::new(
        fused(shift, ray.dir.x, offset.x),
        fused(shift, ray.dir.y, offset.y),
        fused(shift, ray.dir.z, offset.z),
    ) + offset_error;
    Recentred {
        offset,
        offset_error,
        shift,
        near,
    }
}

/// The sphere seen from just outside it, heading in: when f(B) = c0 is small beside
/// |B - C|², the hit is near the base and B'' lies far from it, so t = s0 + s cancels.
/// There the root is taken from the base instead, c0 / q of the stable formula with
/// c0 = |B - C|² - r² to the last bit (B - C exact, squares by two-prod) and
/// b0 = 2 (B - C)·D to within a few ulps (to the last bit where its terms cancel).
/// `None` unless the discriminant b0² - 4 a c0 keeps more than three
/// quarters of b0², so that it loses no digits either (q, the sum of two positive terms,
/// cannot), and the ray starts outside and heads in; the caller then refines.
#[inline(always)]
fn just_outside(
    quadric: &AxisQuadric,
    ray: &Ray,
    offset: DVec3,
    offset_error: DVec3,
    a: f64,
) -> Option<f64> {
    let distance_sq = offset.length_squared();
    let rough = distance_sq + quadric.constant;
    if !(rough > 0.0 && rough < 0.125 * distance_sq) {
        return None;
    }
    let heading = offset.dot(ray.dir);
    // A NaN heading fails the discriminant's test below.
    if heading >= 0.0 {
        return None;
    }
    let exact = |hi: f64, lo: f64| Dd { hi, lo };
    let c0 = sum_as_f64([
        square(exact(offset.x, offset_error.x)),
        square(exact(offset.y, offset_error.y)),
        square(exact(offset.z, offset_error.z)),
        Dd::new(quadric.constant),
    ]);
    // (B - C)·D cancels for a ray that heads in nearly along the surface; there it is
    // recomputed to the last bit.
    let b0 = if 2.0 * heading.abs() < (offset * ray.dir).abs().element_sum() {
        2.0 * sum_as_f64([
            scaled(ray.dir.x, exact(offset.x, offset_error.x)),
            scaled(ray.dir.y, exact(offset.y, offset_error.y)),
            scaled(ray.dir.z, exact(offset.z, offset_error.z)),
        ])
    } else {
        2.0 * (heading + offset_error.dot(ray.dir))
    };
    let discriminant = b0 * b0 - 4.0 * a * c0;
    if !(c0 > 0.0 && discriminant > 0.75 * b0 * b0) {
        return None;
    }
    let q = 0.5 * (discriminant.sqrt() - b0);
    Some(c0 / q)
}

/// Step 2's bound on the terms of f and of its gradient along the recentred local ray
/// near + s dir: with reachᵢ = |nearᵢ| + |s| |dirᵢ| (no coordinate of the point between
/// the base and the root exceeds it), the terms of f sum to at most
/// Σ |αᵢ| reachᵢ² + |β| reach_y + |γ| and those of ∇f to at most 2 Σ |αᵢ| reachᵢ + |β|.
/// The rounding of c, b and a perturbs f by EPS times the first; that of B'', which may
/// lie along any axis after `rotmat`, by EPS times the second times the largest reachᵢ.
/// The absolute values are taken once per ray.
struct Spread {
    near: DVec3,
    dir: DVec3,
    square: DVec3,
    linear: f64,
    constant: f64,
}

impl Spread {
    #[inline(always)]
    fn new(quadric: &AxisQuadric, near: DVec3, dir: DVec3) -> Spread {
        Spread {
            near: near.abs(),
            dir: dir.abs(),
            square: quadric.alpha.abs(),
            linear: quadric.linear_y.abs(),
            constant: quadric.constant.abs(),
        }
    }

    /// The `spread` of [`RootError`] at the root s.
    #[inline(always)]
    fn at(&self, s: f64) -> f64 {
        let reach = s.abs() * self.dir + self.near;
        let weighted = self.square * reach;
        let value_size = weighted.dot(reach) + self.linear * reach.y + self.constant;
        let gradient_size = 2.0 * weighted.element_sum() + self.linear;
        spread(value_size, gradient_size, reach)
    }
}

/// Step 2's `spread` from the sizes of the terms of f and of its gradient at a point whose
/// coordinates are at most `reach` (see [`Spread`]).
#[inline(always)]
fn spread(value_size: f64, gradient_size: f64, reach: DVec3) -> f64 {
    2.0 * value_size + gradient_size * reach.max_element()
}

/// The smaller root of a s² + b s + c = 0 for a > 0 when the discriminant is positive
/// (a tangent ray misses the sphere, spec §5.2), and the slope sqrt(b² - 4ac) there:
/// q / a or c / q of the stable formula, whichever is smaller, chosen by the signs.
#[inline(always)]
fn nearer_root(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let discriminant = b * b - 4.0 * a * c;
    if !(Tangent::Misses.real(discriminant) && a > 0.0) {
        return None;
    }
    let root = discriminant.sqrt();
    let q = -0.5 * (b + root.copysign(b));
    // b's sign bit decides (b = -0.0 from a ray through the centre counts as negative):
    // set, q >= 0 and c / q is the more negative root; clear, q < 0 and q / a is.
    Some((if b.is_sign_negative() { c / q } else { q / a }, root))
}

/// The rounding error of the f64 sum a + b, component by component ([`two_sum`]'s low
/// part, exact).
#[inline(always)]
fn sum_error(a: DVec3, b: DVec3) -> DVec3 {
    DVec3::new(
        two_sum(a.x, b.x).lo,
        two_sum(a.y, b.y).lo,
        two_sum(a.z, b.z).lo,
    )
}

/// The plane's t with both dot products to within an ulp; `None` if N·D is zero.
#[inline(always)]
fn plane_dd_any(plane: &Plane, ray: &Ray) -> Option<f64> {
    let denominator = plane_denominator(plane.normal, ray.dir);
    if denominator == 0.0 {
        return None;
    }
    // Each dot product is now within an ulp of the exact one: t within 1.5 ulps.
    Some(plane_numerator(plane, ray) / denominator)
}

/// The plane's N·(Q - B) to within an ulp, where its terms cancel: Q - B kept exactly
/// (two-sum) and the products added with their rounding errors ([`sum_as_f64`]).
#[inline(always)]
fn plane_numerator(plane: &Plane, ray: &Ray) -> f64 {
    let n = plane.normal;
    let offset = plane.point - ray.base;
    let offset_error = sum_error(plane.point, -ray.base);
    let term = |n: f64, hi: f64, lo: f64| scaled(n, Dd { hi, lo });
    sum_as_f64([
        term(n.x, offset.x, offset_error.x),
        term(n.y, offset.y, offset_error.y),
        term(n.z, offset.z, offset_error.z),
    ])
}

/// The plane's N·D to within an ulp, where its terms cancel (a grazing ray).
#[inline(always)]
fn plane_denominator(normal: DVec3, dir: DVec3) -> f64 {
    sum_as_f64([
        two_prod(normal.x, dir.x),
        two_prod(normal.y, dir.y),
        two_prod(normal.z, dir.z),
    ])
}

/// The local point rotmat (B - C + t D) as hi + lo pairs, exact to about 2^-106 of its
/// size: B - C is `offset` (hi) + `offset_error` (lo), exact. Unless `exact_y`, the local
/// y is only rounded to f64: f of a cylinder does not depend on it, and its bound test
/// needs no more.
#[inline(always)]
fn local_point(
    frame: &AxisFrame,
    offset: DVec3,
    offset_error: DVec3,
    dir: DVec3,
    t: f64,
    exact_y: bool,
) -> [Dd; 3] {
    let world = |offset: f64, offset_error: f64, dir: f64| {
        let step = two_prod(t, dir);
        let sum = two_sum(offset, step.hi);
        Dd {
            hi: sum.hi,
            lo: sum.lo + (step.lo + offset_error),
        }
    };
    let world = [
        world(offset.x, offset_error.x, dir.x),
        world(offset.y, offset_error.y, dir.y),
        world(offset.z, offset_error.z, dir.z),
    ];
    let Some(rotation) = &frame.rotation else {
        return world;
    };
    // Row i of rotmat is column i of irot.
    let row = |axis: DVec3| {
        sum_as_dd([
            scaled(axis.x, world[0]),
            scaled(axis.y, world[1]),
            scaled(axis.z, world[2]),
        ])
    };
    let irot = &rotation.irot;
    let y = if exact_y {
        row(irot.y_axis)
    } else {
        Dd::new(
            irot.y_axis
                .dot(DVec3::new(world[0].hi, world[1].hi, world[2].hi)),
        )
    };
    [row(irot.x_axis), y, row(irot.z_axis)]
}

/// f = Σ αᵢ Lᵢ² + β Ly + γ at the local point L given as hi + lo pairs, with every
/// rounding error kept: each hi² exactly by two-prod, the cross term 2 hi lo as a
/// correction (lo² is below the precision), the terms added by [`sum_as_f64`]. Every shape
/// of the table has αx = αz = 1, whose products need no rounding.
#[inline(always)]
fn residual(quadric: &AxisQuadric, x: Dd, y: Dd, z: Dd) -> f64 {
    let alpha = quadric.alpha;
    let (mut xx, mut zz) = (square(x), square(z));
    if alpha.x != 1.0 || alpha.z != 1.0 {
        xx = scaled(alpha.x, xx);
        zz = scaled(alpha.z, zz);
    }
    sum_as_f64([
        xx,
        zz,
        scaled(alpha.y, square(y)),
        scaled(quadric.linear_y, y),
        Dd::new(quadric.constant),
    ])
}

/// One step's correction: the root `index` (0 the smaller, 1 the larger) of
/// a σ² + slope σ + value = 0, or the vertex -slope / 2a if rounding left no real root.
///
/// Usually the correction is tiny beside the distance to the other root, -slope / a, and
/// Newton's σₙ = -value / slope, bent by the curvature, σₙ (1 - ρ) with ρ = a σₙ / slope,
/// is that root to within 2ρ² |σ|: one division instead of a square root and two. Only
/// when |ρ| > 2⁻³⁰ (two roots close together, a grazing ray) is the quadratic solved.
#[inline(always)]
fn correction(a: f64, slope: f64, value: f64, index: usize) -> f64 {
    let inverse = 1.0 / slope;
    let newton = -value * inverse;
    let bend = a * newton * inverse;
    if bend.abs() <= NEWTON_BEND {
        return newton - newton * bend;
    }
    match solve_quadratic(a, slope, value) {
        Some(roots) => roots[index],
        None if a != 0.0 => -slope / (2.0 * a),
        None => 0.0,
    }
}

/// Refines root `index` of an axis quadric; returns t and the local y of the hit.
#[inline(always)]
fn refine_axis_any(
    quadric: &AxisQuadric,
    ray: &Ray,
    local: &Near,
    a: f64,
    t0: f64,
    index: usize,
) -> (f64, f64) {
    let Near { start, dir, .. } = *local;
    let (mut t, mut y) = (t0, f64::NAN);
    let Recentred {
        offset,
        offset_error,
        ..
    } = start;
    let exact_y = quadric.alpha.y != 0.0 || quadric.linear_y != 0.0;
    for _ in 0..MAX_STEPS {
        let [x, ly, z] = local_point(&quadric.frame, offset, offset_error, ray.dir, t, exact_y);
        let value = residual(quadric, x, ly, z);
        let point = DVec3::new(x.hi, ly.hi, z.hi);
        let gradient = quadric.gradient(point);
        let slope = gradient.dot(dir);
        let sigma = correction(a, slope, value, index);
        let next = t + sigma;
        if !next.is_finite() {
            break;
        }
        y = ly.value() + sigma * dir.y;
        // One step leaves an error of about σ times the relative error of the slope,
        // EPS |∇f| / |f'|; another step only if that is more than half an ulp.
        let settled = sigma.abs() * gradient.abs().element_sum() <= 0.5 * slope.abs() * next.abs();
        t = next;
        if settled {
            break;
        }
    }
    if y.is_nan() {
        // Not one finite step: keep the f64 root and its y.
        let local = quadric.frame.point_to_local(ray.base + t * ray.dir);
        y = local.y;
    }
    (t, y)
}

/// Refines root `index` of a general quadric: f(t) = pᵀQp with p = (B + tD, 1).
#[inline(always)]
fn refine_quadric_any(quadric: &Quadric, ray: &Ray, a: f64, t0: f64, index: usize) -> f64 {
    let [qa, qb, qc, qd, qe, qf, qg, qh, qi, qj] = quadric.coefficients;
    let dir = ray.dir.extend(0.0);
    let mut t = t0;
    for _ in 0..MAX_STEPS {
        // p = B + t D as hi + lo pairs (the sum's and the product's rounding in lo).
        let coordinate = |base: f64, dir: f64| {
            let step = two_prod(t, dir);
            let sum = two_sum(base, step.hi);
            Dd {
                hi: sum.hi,
                lo: sum.lo + step.lo,
            }
        };
        let (x, y, z) = (
            coordinate(ray.base.x, ray.dir.x),
            coordinate(ray.base.y, ray.dir.y),
            coordinate(ray.base.z, ray.dir.z),
        );
        // A x² + E y² + H z² + 2(B xy + C xz + F yz) + 2(D x + G y + I z) + J.
        let value = sum_as_f64([
            scaled_product(qa, x, x),
            scaled_product(qe, y, y),
            scaled_product(qh, z, z),
            scaled_product(2.0 * qb, x, y),
            scaled_product(2.0 * qc, x, z),
            scaled_product(2.0 * qf, y, z),
            scaled(2.0 * qd, x),
            scaled(2.0 * qg, y),
            scaled(2.0 * qi, z),
            Dd::new(qj),
        ]);
        let point = DVec3::new(x.hi, y.hi, z.hi).extend(1.0);
        let slope = 2.0 * dir.dot(quadric.q * point);
        let sigma = correction(a, slope, value, index);
        let next = t + sigma;
        if !next.is_finite() {
            break;
        }
        let gradient = (quadric.q * point).truncate().abs().element_sum();
        let settled = sigma.abs() * gradient <= 0.25 * slope.abs() * next.abs();
        t = next;
        if settled {
            break;
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_certain_miss_is_a_miss_of_the_accurate_path_and_clear_misses_are_certain() {
        // Rays at distance d = r (1 + e) from the centre, e from -1e-3 to 1e-1 on both
        // sides of tangency, spheres from 1e-6 to 1e6 across, bases near and far.
        let mut numbers = crate::shapes::testing::Numbers(0x2545_f491_4f6c_dd1d);
        let mut next = || numbers.next();
        let (mut rejected, mut clear) = (0, 0);
        for case in 0..20_000 {
            let scale = 10f64.powf(12.0 * next() - 6.0);
            let centre = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 10.0 * scale;
            let radius = scale * (0.5 + next());
            let sphere = Sphere::new(centre, radius, "sphere").unwrap();
            let dir = crate::shapes::unit(DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5));
            let dir = dir.unwrap_or(DVec3::X);
            let side = crate::shapes::unit(dir.cross(DVec3::new(0.3, 0.7, -0.2))).unwrap();
            let e = [-1e-3, -1e-9, 0.0, 1e-12, 1e-9, 1e-6, 1e-3, 1e-1][case % 8];
            let closest = centre + side * radius * (1.0 + e);
            let base = closest - dir * scale * 20.0 * (next() + 0.01);
            let ray = Ray::new(base, dir);
            if certainly_misses(&sphere, &ray) {
                rejected += 1;
                assert_eq!(
                    axis_hit(&sphere.equation(), &ray),
                    None,
                    "case {case}: {ray:?}"
                );
            }
            if e >= 1e-6 {
                clear += 1;
                assert!(certainly_misses(&sphere, &ray), "case {case}: e = {e}");
            }
        }
        assert!(rejected >= clear && clear > 5_000, "{rejected} {clear}");
    }

    #[test]
    fn the_quick_test_on_the_margins_terms_decides_as_the_kernel_s_own() {
        // compare's margins compute D·(B - C) and |B - C|² for the discriminant and hand
        // them to the quick test, which computes (C - B)·D and |C - B|² itself. Rays
        // passing at r (1 + e) from the centre with e across the test's threshold (its
        // margin, 2^-46 of |w|² + r², is e of about 1e-12 here), where any difference in
        // the last bits would show: the same answer on every one, and both answers met.
        let mut numbers = crate::shapes::testing::Numbers(0x9e37_79b9_7f4a_7c15);
        let mut next = || numbers.next();
        let mut answers = [0usize; 2];
        for case in 0..20_000 {
            let scale = 10f64.powf(8.0 * next() - 4.0);
            let centre = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 10.0 * scale;
            let sphere = Sphere::new(centre, scale * (0.5 + next()), "sphere").unwrap();
            let dir = crate::shapes::unit(DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5));
            let dir = dir.unwrap_or(DVec3::X);
            let side = crate::shapes::unit(dir.cross(DVec3::new(0.3, 0.7, -0.2))).unwrap();
            let e = 10f64.powf(-14.0 + 4.0 * next());
            let closest = centre + side * sphere.radius * (1.0 + e);
            let ray = Ray::new(closest - dir * scale * 20.0 * (next() + 0.01), dir);
            let own = certainly_misses(&sphere, &ray);
            let given = Accurate::sphere_surely_misses(&sphere, sphere.terms(&ray));
            assert_eq!(given, own, "case {case}: {ray:?}");
            answers[usize::from(own)] += 1;
        }
        assert!(answers.iter().all(|&n| n > 1_000), "{answers:?}");
    }

    #[test]
    fn a_span_s_plane_tests_are_each_ray_s_own() {
        // Spans of 8 rays from one base toward planes through the origin region: random
        // directions, rays nearly parallel to the plane (N·D cancels), exactly parallel,
        // behind, hits just beyond z = 0 (the slack) and planes whose numerator cancels.
        // Each lane's t and verdict are the bits of the plane's test of that ray alone.
        let mut numbers = crate::shapes::testing::Numbers(0x5851_f42d_4c95_7f2d);
        let mut next = || numbers.next();
        let (mut hits, mut misses, mut slow, mut slack) = (0, 0, 0, 0);
        for case in 0..3_000 {
            let normal = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
            let mut plane = Plane::new(normal, DVec3::new(next(), next(), next() - 2.0), "p")
                .unwrap_or_else(|_| Plane::new(DVec3::Z, DVec3::ZERO, "p").unwrap());
            if case % 7 == 0 {
                plane.z_limit = [f64::INFINITY, 1e-3][case / 7 % 2];
            }
            let base = match case % 5 {
                // The base on the plane's own point: t = 0 (±0).
                0 if case % 2 == 0 => plane.point,
                // The numerator N·(Q - B) cancels: the base on the plane, or nearly.
                0 => plane.point + plane.normal.any_orthogonal_vector() * (next() * 4.0),
                _ => DVec3::new(next() - 0.5, next() - 0.5, next() * 4.0),
            };
            let along = plane.normal.any_orthogonal_vector();
            // Up the plane in z, for hits at the z limit: within rounding of it, where the
            // slack decides.
            let up = DVec3::Z - plane.normal * plane.normal.z;
            let limit = plane.z_limit.min(1.0);
            let rays: [DVec3; LANES] = std::array::from_fn(|i| {
                let d = match (case + i) % 4 {
                    // Within about 1e-12 of parallel: N·D's terms cancel.
                    0 => along + plane.normal * ((next() - 0.5) * 1e-12),
                    1 if i == 3 => along,
                    2 if up.z > 1e-3 => {
                        let edge = plane.point + up * ((limit - plane.point.z) / up.z);
                        let level = plane.normal.cross(DVec3::Z);
                        let off = level * (next() - 0.5) + up * ((next() - 0.5) * 1e-14);
                        edge + off - base
                    }
                    _ => DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5),
                };
                crate::shapes::unit(d).unwrap_or(DVec3::X)
            });
            let dirs = Dirs {
                x: rays.map(|d| d.x),
                y: rays.map(|d| d.y),
                z: rays.map(|d| d.z),
            };
            let from = Accurate::plane_from(&plane, base);
            let lanes = [0xff, 0b1011_0110][case % 2];
            let (ts, mask) = Accurate::planes_toward(&plane, &from, base, &dirs, lanes);
            for (i, dir) in rays.iter().enumerate() {
                let own = Accurate::plane(&plane, &Ray::new(base, *dir), &mut ());
                let own = own.filter(|_| lanes & 1 << i != 0);
                let lane = (mask & 1 << i != 0).then_some(ts[i]);
                assert_eq!(
                    lane.map(f64::to_bits),
                    own.map(f64::to_bits),
                    "case {case}, lane {i}"
                );
                match own {
                    Some(_) => hits += 1,
                    None => misses += 1,
                }
                let under = plane.normal * *dir;
                slow += usize::from(from.cancels || cancels(under.element_sum(), under));
                let z = own.map(|t| base.z + t * dir.z);
                slack += usize::from(z.is_some_and(|z| z > plane.z_limit));
            }
        }
        assert!(
            hits > 5_000 && misses > 5_000 && slow > 2_000,
            "{hits} {misses} {slow}"
        );
        // The slack decided some of them.
        assert!(slack > 20, "{slack}");
    }

    #[test]
    fn nearer_root_follows_the_sign_bit_of_b() {
        let root = |a, b, c| nearer_root(a, b, c).map(|(s, _)| s);
        // (s - 2)(s + 2) = s² - 4: the nearer root is -2 whichever zero b is.
        assert_eq!(root(1.0, 0.0, -4.0), Some(-2.0));
        assert_eq!(root(1.0, -0.0, -4.0), Some(-2.0));
        // (s - 1)(s - 3) = s² - 4s + 3 and (s + 1)(s + 3) = s² + 4s + 3.
        assert_eq!(root(1.0, -4.0, 3.0), Some(1.0));
        assert_eq!(root(1.0, 4.0, 3.0), Some(-3.0));
        // A tangent ray (double root) misses the sphere.
        assert_eq!(root(1.0, -4.0, 4.0), None);
        // The slope |2as + b| at either root of s² - 4 is 4.
        assert_eq!(nearer_root(1.0, 0.0, -4.0), Some((-2.0, 4.0)));
    }

    #[test]
    fn a_ray_from_the_centre_finds_the_negative_root_in_every_direction() {
        let sphere = crate::shapes::Sphere::new(DVec3::new(0.0, 0.0, 3.0), 0.5, "s").unwrap();
        for dir in [
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ] {
            let ray = Ray {
                base: DVec3::new(0.0, 0.0, 3.0),
                dir,
            };
            assert_eq!(
                Accurate::axis_quadric(&sphere.equation(), &ray, &mut ()),
                Some(-0.5),
                "{dir}"
            );
        }
    }

    #[test]
    fn from_just_outside_the_base_formula_agrees_with_the_refinement() {
        // The eye 1e-3 to 10 above spheres of radius 1e4 to 1e6, looking down at 10 to
        // 80 degrees from the horizon: the base formula must take these rays, and agree
        // to 4 ulps with the general refinement started from the recentred root.
        for (radius, height, degrees) in [
            (1e4, 1e-3, 10.0),
            (1e5, 0.5, 45.0),
            (1e6, 10.0, 80.0),
            (3e5, 2.0, 30.0),
        ] {
            let centre = DVec3::new(1.5, -2.0, 0.25);
            let sphere = crate::shapes::Sphere::new(centre, radius, "s").unwrap();
            let up = DVec3::new(1.0, 2.0, -2.0) / 3.0;
            let side = DVec3::new(2.0, 1.0, 2.0) / 3.0;
            let angle = f64::to_radians(degrees);
            let ray = Ray::new(
                centre + (radius + height) * up,
                (-angle.sin() * up + angle.cos() * side).normalize(),
            );
            let quadric = &sphere.equation();
            let local = Near::of_axis_quadric(&quadric.frame, &ray);
            let (a, _, _) = quadric.coefficients(local.near, local.dir);
            let start = local.start;
            let direct = just_outside(quadric, &ray, start.offset, start.offset_error, a)
                .expect("the base formula takes a ray from just outside");
            let t0 = start.shift - (start.near.length_squared() - radius * radius).abs().sqrt();
            let (refined, _) = refine_axis_any(quadric, &ray, &local, a, t0, 0);
            let ulp = f64::EPSILON * refined.abs();
            assert!(
                (direct - refined).abs() <= 4.0 * ulp,
                "r {radius} h {height}: {direct} against {refined}"
            );
            // And the shipped kernel returns it.
            assert_eq!(Accurate::axis_quadric(quadric, &ray, &mut ()), Some(direct));
        }
    }
}
