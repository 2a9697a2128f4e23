//! The kernel `legacy-rt` ships: the exact root of the f64 problem to within a few ulps.
//! A miss costs about what the textbook's does; a hit that needs refining costs several
//! times more (docs/speed-vs-error.md has the figures).
//!
//! Three steps:
//! 1. Move the ray's base along the ray to the point nearest the shape's centre:
//!    B'' = B' + s0 D' with s0 = -(B'·D')/(D'·D'). The quadratic in s = t - s0 then has
//!    coefficients the size of the shape, not of its distance, so c = f(B'') no longer
//!    subtracts two huge numbers (a far object), and its stable roots
//!    ([`solve_quadratic`]) keep their digits. This is the geometric form of the
//!    discriminant, for every shape at once.
//! 2. Estimate the error of the root from the sizes of the terms and the slope f'(t) of
//!    the quadratic at the root. A ray that grazes the silhouette, runs nearly parallel
//!    to a cylinder's axis or a cone's generator, or starts next to the surface has a
//!    small slope, and there the estimate is large.
//! 3. Only then refine: evaluate f at the root in double-double ([`Dd`]), from the
//!    world-space numbers (B - C + t D, then `rotmat`, both without rounding), and solve
//!    the quadratic shifted to the root, a σ² + f'(t) σ + f(t) = 0, for the correction σ.
//!    Its a and f'(t) need only a few correct digits, f(t) needs them all.
//!
//! The general `QUADRIC` has no centre to move to and its coefficients can hold a
//! translation of 10^4 squared, so its root is always refined; a plane's dot products are
//! recomputed in double-double when they cancel. Bound tests (local y, the plane's z = 0)
//! accept a hit within [`slack`] of the bound, so a point the scene puts exactly on a
//! bound does not flip from pixel to pixel on the rounding of t and of the ray.

use super::stable::stable_roots;
use super::{Kernel, strict};
use crate::shapes::dd::{Dd, two_prod, two_sum};
use crate::shapes::{AxisFrame, AxisQuadric, Plane, Quadric, Ray, RootRule, solve_quadratic};
use glam::DVec3;

/// The shipped kernel.
#[derive(Debug, Clone, Copy, Default)]
pub struct Accurate;

/// Refine when the estimated error exceeds this many EPS |t|. The estimate is a loose
/// bound, so the value was set on the hard-case suite: at 8 its largest error is 3.7 ulps
/// (seed 0x2026_1121); at 16 it was 3.6 and at 64 over 5 (an earlier seed).
const REFINE_ABOVE_ULPS: f64 = 8.0;

/// At most this many refinement steps (each one squares the relative error).
const MAX_STEPS: usize = 3;

const EPS: f64 = f64::EPSILON;

/// How far past a bound (the plane's z = 0, a quadric's y = 0 or h) a hit still counts:
/// 8 ulps of the size of the terms that computed the coordinate. A point that the scene
/// puts exactly on a bound then counts as inside, whatever the rounding of the ray.
#[inline]
fn slack(size: f64) -> f64 {
    8.0 * EPS * size
}

/// Whether the estimated absolute error `error_bound * EPS` of t exceeds the threshold.
#[inline]
fn needs_refining(error_bound: f64, t: f64) -> bool {
    // NaN (an overflowed estimate) refines too.
    error_bound > REFINE_ABOVE_ULPS * t.abs() || error_bound.is_nan()
}

impl Kernel for Accurate {
    const NAME: &'static str = "accurate";

    #[inline]
    fn axis_quadric(quadric: &AxisQuadric, ray: &Ray) -> Option<f64> {
        let frame = &quadric.frame;
        let offset = ray.base - frame.centre;
        let base = frame.rotate(offset);
        let dir = frame.rotate(ray.dir);
        // Step 1: s0 and B''. D'·D' = 1 to within rounding, so no division is needed.
        let shift = -base.dot(dir);
        let near = base + shift * dir;
        let (a, b, c) = quadric.coefficients(near, dir);
        let roots = stable_roots(a, b, c, strict(quadric.rule))?;
        // Step 2's term sizes: f, its gradient, and how far B'' moved (the rounding of
        // B - C, of rotmat and of B'' is an error of about EPS times that in position).
        let largest_square = quadric.square.abs().max_element();
        let moved = offset.abs().max_element() + shift.abs();
        for (index, s) in roots.into_iter().enumerate() {
            let t = shift + s;
            let reach = near.abs().max_element() + s.abs();
            let gradient_size = 2.0 * largest_square * reach + quadric.linear_y.abs();
            let value_size = largest_square * reach * reach
                + quadric.linear_y.abs() * reach
                + quadric.constant.abs();
            let slope = (2.0 * a * s + b).abs();
            let error_bound = 2.0 * (value_size + gradient_size * moved) / slope + moved;
            let (t, y) = if needs_refining(error_bound, t) {
                refine_axis(quadric, ray, dir, a, t, index)
            } else {
                (t, near.y + s * dir.y)
            };
            match quadric.rule {
                RootRule::Nearer => return t.is_finite().then_some(t),
                RootRule::FirstPositiveWithin { low, high } => {
                    let slack = slack(moved + t.abs());
                    if t > 0.0 && low - slack <= y && y <= high + slack {
                        return Some(t);
                    }
                }
            }
        }
        None
    }

    #[inline]
    fn quadric(quadric: &Quadric, ray: &Ray) -> Option<f64> {
        let (a, b, c) = quadric.coefficients(ray);
        let roots = solve_quadratic(a, b, c)?;
        for (index, t) in roots.into_iter().enumerate() {
            // A root clearly behind the base needs no refining to be rejected.
            if t < 0.0 && roots[1] > 0.0 && t < -1e-6 * roots[1] {
                continue;
            }
            let t = refine_quadric(quadric, ray, a, t, index);
            if t > 0.0 {
                return Some(t);
            }
        }
        None
    }

    #[inline]
    fn plane(plane: &Plane, ray: &Ray) -> Option<f64> {
        let n = plane.normal;
        let offset = plane.point - ray.base;
        let numerator = n.dot(offset);
        let denominator = n.dot(ray.dir);
        // Each dot product is good to a few ulps unless its terms cancel.
        let cancels = |dot: f64, a: DVec3, b: DVec3| dot.abs() < 0.5 * (a * b).abs().element_sum();
        let t = if cancels(numerator, n, offset) || cancels(denominator, n, ray.dir) {
            plane_dd(plane, ray)?
        } else {
            if denominator == 0.0 {
                return None;
            }
            numerator / denominator
        };
        // The z rule. A hit meant to lie on the screen (z = 0: a floor through the bottom
        // edge of the window) comes out at z = ±1e-16 from the rounding of the ray's
        // direction, and would flip from pixel to pixel; within a few ulps of the terms
        // it counts as on the screen, which §5.1 draws.
        let z = ray.base.z + t * ray.dir.z;
        (t >= 0.0 && z <= slack(ray.base.z.abs() + t.abs())).then_some(t)
    }
}

/// Defines `$name`, which runs `$inner` from a copy compiled for the FMA instruction
/// when the CPU has it (checked once and cached by the standard library): the products
/// of [`two_prod`] are then one instruction instead of a call to the C library's `fma`.
/// Both copies compute the same bits.
macro_rules! fma_dispatch {
    ($(#[$meta:meta])* fn $name:ident => $inner:ident($($arg:ident: $ty:ty),*) -> $ret:ty) => {
        $(#[$meta])*
        #[inline(never)]
        fn $name($($arg: $ty),*) -> $ret {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "fma")]
                fn with_fma($($arg: $ty),*) -> $ret {
                    $inner($($arg),*)
                }
                if std::arch::is_x86_feature_detected!("fma") {
                    // SAFETY: the CPU has the instructions `with_fma` is compiled for.
                    return unsafe { with_fma($($arg),*) };
                }
            }
            $inner($($arg),*)
        }
    };
}

fma_dispatch!(
    /// [`plane_dd_any`].
    fn plane_dd => plane_dd_any(plane: &Plane, ray: &Ray) -> Option<f64>
);
fma_dispatch!(
    /// [`refine_axis_any`].
    fn refine_axis => refine_axis_any(
        quadric: &AxisQuadric, ray: &Ray, dir: DVec3, a: f64, t0: f64, index: usize
    ) -> (f64, f64)
);
fma_dispatch!(
    /// [`refine_quadric_any`].
    fn refine_quadric => refine_quadric_any(
        quadric: &Quadric, ray: &Ray, a: f64, t0: f64, index: usize
    ) -> f64
);

/// The plane's t with both dot products in double-double; `None` if N·D is zero.
#[inline(always)]
fn plane_dd_any(plane: &Plane, ray: &Ray) -> Option<f64> {
    let numerator = dot_dd(plane.normal, difference_dd(plane.point, ray.base));
    let dir = [Dd::new(ray.dir.x), Dd::new(ray.dir.y), Dd::new(ray.dir.z)];
    let denominator = dot_dd(plane.normal, dir);
    if denominator.hi == 0.0 {
        return None;
    }
    Some(divide(numerator, denominator))
}

/// B - C exactly, component by component.
#[inline(always)]
fn difference_dd(b: DVec3, c: DVec3) -> [Dd; 3] {
    [two_sum(b.x, -c.x), two_sum(b.y, -c.y), two_sum(b.z, -c.z)]
}

/// v · w with v in f64 and w in double-double.
#[inline(always)]
fn dot_dd(v: DVec3, w: [Dd; 3]) -> Dd {
    v.x * w[0] + v.y * w[1] + v.z * w[2]
}

/// n / d rounded to f64 with one correction step (a few tenths of an ulp).
#[inline(always)]
fn divide(n: Dd, d: Dd) -> f64 {
    let t = n.hi / d.hi;
    let remainder = n - t * d;
    t + remainder.value() / d.hi
}

/// The local point rotmat (B - C + t D) in double-double.
#[inline(always)]
fn local_point(frame: &AxisFrame, ray: &Ray, t: f64) -> [Dd; 3] {
    let [x, y, z] = difference_dd(ray.base, frame.centre);
    let world = [
        x + two_prod(t, ray.dir.x),
        y + two_prod(t, ray.dir.y),
        z + two_prod(t, ray.dir.z),
    ];
    if frame.identity {
        return world;
    }
    // Row i of rotmat is column i of irot.
    let irot = &frame.irot;
    [
        dot_dd(irot.x_axis, world),
        dot_dd(irot.y_axis, world),
        dot_dd(irot.z_axis, world),
    ]
}

/// One step's correction: the root `index` (0 the smaller, 1 the larger) of
/// a σ² + slope σ + value = 0, or the vertex -slope / 2a if rounding left no real root.
#[inline(always)]
fn correction(a: f64, slope: f64, value: f64, index: usize) -> f64 {
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
    dir: DVec3,
    a: f64,
    t0: f64,
    index: usize,
) -> (f64, f64) {
    let (mut t, mut y) = (t0, f64::NAN);
    for _ in 0..MAX_STEPS {
        let [x, ly, z] = local_point(&quadric.frame, ray, t);
        let sq = quadric.square;
        let value = sq.x * (x * x)
            + sq.y * (ly * ly)
            + sq.z * (z * z)
            + quadric.linear_y * ly
            + Dd::new(quadric.constant);
        let point = DVec3::new(x.hi, ly.hi, z.hi);
        let slope = quadric.gradient(point).dot(dir);
        let sigma = correction(a, slope, value.value(), index);
        let next = t + sigma;
        if !next.is_finite() {
            break;
        }
        y = ly.value() + sigma * dir.y;
        // One step leaves an error of about σ times the relative error of the slope,
        // EPS |∇f| / |f'|; another step only if that is more than half an ulp.
        let gradient = quadric.gradient(point).length();
        let settled = sigma.abs() * gradient <= 0.5 * slope.abs() * next.abs();
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
        let x = Dd::new(ray.base.x) + two_prod(t, ray.dir.x);
        let y = Dd::new(ray.base.y) + two_prod(t, ray.dir.y);
        let z = Dd::new(ray.base.z) + two_prod(t, ray.dir.z);
        // A x² + E y² + H z² + 2(B xy + C xz + F yz) + 2(D x + G y + I z) + J.
        let value = qa * (x * x)
            + qe * (y * y)
            + qh * (z * z)
            + (2.0 * qb) * (x * y)
            + (2.0 * qc) * (x * z)
            + (2.0 * qf) * (y * z)
            + (2.0 * qd) * x
            + (2.0 * qg) * y
            + (2.0 * qi) * z
            + Dd::new(qj);
        let point = DVec3::new(x.hi, y.hi, z.hi).extend(1.0);
        let slope = 2.0 * dir.dot(quadric.q * point);
        let sigma = correction(a, slope, value.value(), index);
        let next = t + sigma;
        if !next.is_finite() {
            break;
        }
        let gradient = (quadric.q * point).truncate().length();
        let settled = sigma.abs() * gradient <= 0.25 * slope.abs() * next.abs();
        t = next;
        if settled {
            break;
        }
    }
    t
}
