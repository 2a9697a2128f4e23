//! The course notes' kernels: each family's hit written once, step by step as note 003
//! and note 004 write it, over the float type a tracer computes in ([`Real`]: f64 as the
//! course's C program, f32 as a tracer written with `float`), with the roots by the notes'
//! formula (-b ± sqrt(b² - 4ac)) / 2a or by the cancellation-free one ([`Formula`]). No
//! root is polished, and no bound is given slack: this is what a student's tracer
//! computes.

use super::{Kernel, Tangent, solve_quadratic};
use crate::shapes::axis_quadric::coefficients;
use crate::shapes::{AxisQuadric, HitNote, Notes, Plane, Quadric, Ray, RootRule, Sphere};
use glam::{DMat3, DMat4, DVec3, Mat3, Vec3, Vec4};
use num_traits::Float;

/// The notes' formula in f64: what most students' tracers compute.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Textbook;

/// The notes' coefficients with the cancellation-free root formula only.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Stable;

/// The notes' formula in f32: every input rounded to f32 and every operation done in f32,
/// as a tracer written with `float` does.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct TextbookF32;

/// How a, b, c become roots.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Formula {
    /// The notes' (-b ± sqrt(b² - 4ac)) / 2a.
    Notes,
    /// q = -(b + sign(b) sqrt(b² - 4ac)) / 2, roots q / a and c / q (in f64).
    Stable,
}

impl Formula {
    /// Both real roots, ascending, as f64, or `None`. a = 0 is solved as the linear
    /// equation b t + c = 0, as every kernel does (spec §5.6).
    #[inline(always)]
    fn roots<R: Real>(self, a: R, b: R, c: R, tangent: Tangent) -> Option<[f64; 2]> {
        match self {
            Formula::Notes => {
                if a == R::zero() {
                    return (b != R::zero()).then(|| [(-c / b).into(); 2]);
                }
                let two = R::one() + R::one();
                let discriminant = b * b - two * two * a * c;
                if !tangent.real(discriminant) {
                    return None;
                }
                let root = discriminant.sqrt();
                let (t0, t1) = ((-b - root) / (two * a), (-b + root) / (two * a));
                let (t0, t1): (f64, f64) = (t0.into(), t1.into());
                Some(if t0 <= t1 { [t0, t1] } else { [t1, t0] })
            }
            Formula::Stable => {
                let (a, b, c): (f64, f64, f64) = (a.into(), b.into(), c.into());
                if a != 0.0 && !tangent.real(b * b - 4.0 * a * c) {
                    return None;
                }
                solve_quadratic(a, b, c)
            }
        }
    }
}

/// The float type a tracer computes in, with the vectors it holds them in.
pub(crate) trait Real: Float + Into<f64> {
    /// A 3-vector of this type.
    type Vector: Copy + std::ops::Sub<Output = Self::Vector>;

    /// A world vector, rounded to this type.
    fn vector(v: DVec3) -> Self::Vector;

    /// A number, rounded to this type.
    fn number(x: f64) -> Self;

    /// rotmat v, the matrix rounded to this type.
    fn rotate(rotmat: &DMat3, v: Self::Vector) -> Self::Vector;

    /// The dot product u·v in this type.
    fn dot(u: Self::Vector, v: Self::Vector) -> Self;

    /// The components.
    fn array(v: Self::Vector) -> [Self; 3];

    /// Note 004's a = DᵀQD, b = 2 DᵀQP, c = PᵀQP for P = (B, 1), D = (D, 0).
    fn quadric_coefficients(q: &DMat4, base: Self::Vector, dir: Self::Vector) -> [Self; 3];
}

impl Real for f64 {
    type Vector = DVec3;

    #[inline(always)]
    fn vector(v: DVec3) -> DVec3 {
        v
    }

    #[inline(always)]
    fn number(x: f64) -> f64 {
        x
    }

    #[inline(always)]
    fn rotate(rotmat: &DMat3, v: DVec3) -> DVec3 {
        *rotmat * v
    }

    #[inline(always)]
    fn dot(u: DVec3, v: DVec3) -> f64 {
        u.dot(v)
    }

    #[inline(always)]
    fn array(v: DVec3) -> [f64; 3] {
        v.to_array()
    }

    #[inline(always)]
    fn quadric_coefficients(q: &DMat4, base: DVec3, dir: DVec3) -> [f64; 3] {
        let (p, d) = (base.extend(1.0), dir.extend(0.0));
        let qp = *q * p;
        [d.dot(*q * d), 2.0 * d.dot(qp), p.dot(qp)]
    }
}

impl Real for f32 {
    type Vector = Vec3;

    #[inline(always)]
    fn vector(v: DVec3) -> Vec3 {
        v.as_vec3()
    }

    #[inline(always)]
    fn number(x: f64) -> f32 {
        x as f32
    }

    #[inline(always)]
    fn rotate(rotmat: &DMat3, v: Vec3) -> Vec3 {
        let rotmat: Mat3 = rotmat.as_mat3();
        rotmat * v
    }

    #[inline(always)]
    fn dot(u: Vec3, v: Vec3) -> f32 {
        u.dot(v)
    }

    #[inline(always)]
    fn array(v: Vec3) -> [f32; 3] {
        v.to_array()
    }

    #[inline(always)]
    fn quadric_coefficients(q: &DMat4, base: Vec3, dir: Vec3) -> [f32; 3] {
        let q = q.as_mat4();
        let (p, d): (Vec4, Vec4) = (base.extend(1.0), dir.extend(0.0));
        let qp = q * p;
        [d.dot(q * d), 2.0 * d.dot(qp), p.dot(qp)]
    }
}

/// Note 003's hit of the sphere and the quadrics 21-24, in `R`, with the roots by
/// `formula`.
#[inline(always)]
pub(crate) fn axis_quadric<R: Real>(
    quadric: &AxisQuadric,
    ray: &Ray,
    formula: Formula,
    notes: &mut impl Notes,
) -> Option<f64> {
    let frame = &quadric.frame;
    // "The arithmetic is much simpler if the center of the cylinder is at the origin. So
    // we start by moving it there": B' = B - C, D does not change.
    let mut base = R::vector(ray.base) - R::vector(frame.centre);
    let mut dir = R::vector(ray.dir);
    // "If the centerline already lies on the y-axis there is nothing more to do. If not",
    // rotate the center line onto +y: B' = rotmat B', D' = rotmat D.
    if let Some(rotation) = &frame.rotation {
        base = R::rotate(&rotation.rotmat, base);
        dir = R::rotate(&rotation.rotmat, dir);
    }
    // "a = dx² + dz², b = 2(bx dx + bz dz), c = bx² + bz² - r²" for the cylinder, and the
    // other rows of the table of `AxisQuadric`.
    let alpha = R::array(R::vector(quadric.alpha));
    let (linear_y, constant) = (R::number(quadric.linear_y), R::number(quadric.constant));
    let (a, b, c) = coefficients(alpha, linear_y, constant, R::array(base), R::array(dir));
    // "t = (-b ± sqrt(b² - 4ac)) / 2a".
    match quadric.rule {
        // The sphere: the smaller root of a discriminant > 0, even when negative.
        RootRule::Nearer => {
            let Some([t, _]) = formula.roots(a, b, c, Tangent::Misses) else {
                notes.note(HitNote::NoRealRoot);
                return None;
            };
            notes.note(HitNote::Nearer { t: Some(t) });
            Some(t)
        }
        // "Next it is necessary to check to see if the y component of H is less than 0 or
        // greater than h": the smallest positive root whose H = B' + t D' is in bounds.
        rule => {
            let Some(roots) = formula.roots(a, b, c, Tangent::Counts) else {
                notes.note(HitNote::NoRealRoot);
                return None;
            };
            let [by, dy] = [R::array(base)[1], R::array(dir)[1]].map(Into::<f64>::into);
            let judge = |_, t: f64| {
                let y = by + t * dy;
                (t, y, rule.accepts(t, y, || 0.0))
            };
            rule.first_within(roots, judge, notes)
        }
    }
}

/// Note 004's hit of a `QUADRIC` in `R`: a = DᵀQD, b = 2 DᵀQP, c = PᵀQP, the roots by
/// `formula`, and the smallest in front of the base.
#[inline(always)]
pub(crate) fn quadric<R: Real>(
    quadric: &Quadric,
    ray: &Ray,
    formula: Formula,
    notes: &mut impl Notes,
) -> Option<f64> {
    let [a, b, c] = R::quadric_coefficients(&quadric.q, R::vector(ray.base), R::vector(ray.dir));
    let Some(roots) = formula.roots(a, b, c, Tangent::Counts) else {
        notes.note(HitNote::NoRealRoot);
        return None;
    };
    Quadric::first_in_front(roots, |_, t| (t, true), notes)
}

/// Spec §5.1's plane in `R`: t = N·(Q - B) / N·D, a miss where N·D = 0.
#[inline(always)]
pub(crate) fn plane<R: Real>(plane: &Plane, ray: &Ray, notes: &mut impl Notes) -> Option<f64> {
    let normal = R::vector(plane.normal);
    let denominator = R::dot(normal, R::vector(ray.dir));
    if denominator == R::zero() {
        notes.note(HitNote::Parallel);
        return None;
    }
    let numerator = R::dot(normal, R::vector(plane.point) - R::vector(ray.base));
    plane.verdict(ray, (numerator / denominator).into(), || 0.0, notes)
}

impl Kernel for Textbook {
    #[inline(always)]
    fn sphere<N: Notes>(sphere: &Sphere, ray: &Ray, notes: &mut N) -> Option<f64> {
        axis_quadric::<f64>(&sphere.equation(), ray, Formula::Notes, notes)
    }

    #[inline(always)]
    fn axis_quadric<N: Notes>(quadric: &AxisQuadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        axis_quadric::<f64>(quadric, ray, Formula::Notes, notes)
    }

    #[inline(always)]
    fn quadric<N: Notes>(q: &Quadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        quadric::<f64>(q, ray, Formula::Notes, notes)
    }

    #[inline(always)]
    fn plane<N: Notes>(p: &Plane, ray: &Ray, notes: &mut N) -> Option<f64> {
        plane::<f64>(p, ray, notes)
    }
}

impl Kernel for Stable {
    #[inline(always)]
    fn sphere<N: Notes>(sphere: &Sphere, ray: &Ray, notes: &mut N) -> Option<f64> {
        axis_quadric::<f64>(&sphere.equation(), ray, Formula::Stable, notes)
    }

    #[inline(always)]
    fn axis_quadric<N: Notes>(quadric: &AxisQuadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        axis_quadric::<f64>(quadric, ray, Formula::Stable, notes)
    }

    #[inline(always)]
    fn quadric<N: Notes>(q: &Quadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        quadric::<f64>(q, ray, Formula::Stable, notes)
    }

    #[inline(always)]
    fn plane<N: Notes>(p: &Plane, ray: &Ray, notes: &mut N) -> Option<f64> {
        plane::<f64>(p, ray, notes)
    }
}

impl Kernel for TextbookF32 {
    #[inline(always)]
    fn sphere<N: Notes>(sphere: &Sphere, ray: &Ray, notes: &mut N) -> Option<f64> {
        axis_quadric::<f32>(&sphere.equation(), ray, Formula::Notes, notes)
    }

    #[inline(always)]
    fn axis_quadric<N: Notes>(quadric: &AxisQuadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        axis_quadric::<f32>(quadric, ray, Formula::Notes, notes)
    }

    #[inline(always)]
    fn quadric<N: Notes>(q: &Quadric, ray: &Ray, notes: &mut N) -> Option<f64> {
        quadric::<f32>(q, ray, Formula::Notes, notes)
    }

    #[inline(always)]
    fn plane<N: Notes>(p: &Plane, ray: &Ray, notes: &mut N) -> Option<f64> {
        plane::<f32>(p, ray, notes)
    }
}
