//! The course notes' kernels: the ray and the coefficients exactly as note 003 and note
//! 004 write them, and the roots by the notes' formula (-b ± sqrt(b² - 4ac)) / 2a
//! ([`Textbook`], and [`TextbookF32`](super::TextbookF32) in single precision) or by the
//! cancellation-free formula of [`solve_quadratic`](super::solve_quadratic)
//! ([`StableRoots`]). No root is polished. What differs between them is a [`Formula`] and
//! a [`Precision`]; the kernel is written once, as [`AsWritten`].

use super::{Kernel, Steps, Tangent, solve_quadratic};
use crate::shapes::{AxisFrame, AxisQuadric, Plane, Quadric, Ray};
use glam::DVec3;
use num_traits::Float;
use std::marker::PhantomData;

/// The notes' steps in precision `P`, with roots by formula `F`.
#[derive(Debug, Clone, Copy, Default)]
pub struct AsWritten<F, P>(PhantomData<(F, P)>);

/// The notes' formula in f64: what most students' tracers compute.
pub type Textbook = AsWritten<TextbookFormula, Double>;

/// The notes' coefficients with the cancellation-free root formula only.
pub type StableRoots = AsWritten<StableFormula, Double>;

/// How an as-written kernel turns a, b, c (in `R`) into roots.
pub trait Formula<R>: Copy + Default + Send + Sync + 'static {
    /// Both real roots, ascending, as f64, or `None`.
    fn roots(a: R, b: R, c: R, tangent: Tangent) -> Option<[f64; 2]>;
}

/// The notes' formula (-b ± sqrt(b² - 4ac)) / 2a.
#[derive(Debug, Clone, Copy, Default)]
pub struct TextbookFormula;

/// The cancellation-free formula: q = -(b + sign(b) sqrt(b² - 4ac)) / 2, roots q / a and
/// c / q.
#[derive(Debug, Clone, Copy, Default)]
pub struct StableFormula;

impl<R: Float + Into<f64>> Formula<R> for TextbookFormula {
    /// a = 0 is solved as the linear equation b t + c = 0, as every kernel does (spec
    /// §5.6).
    #[inline(always)]
    fn roots(a: R, b: R, c: R, tangent: Tangent) -> Option<[f64; 2]> {
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
}

impl Formula<f64> for StableFormula {
    #[inline(always)]
    fn roots(a: f64, b: f64, c: f64, tangent: Tangent) -> Option<[f64; 2]> {
        if a != 0.0 && !tangent.real(b * b - 4.0 * a * c) {
            return None;
        }
        solve_quadratic(a, b, c)
    }
}

/// A ray as the notes hold it: base and direction, in the shape's frame, as `DVec3`
/// or, in single precision, `Vec3`.
#[derive(Debug, Clone, Copy)]
pub struct Plain<V> {
    /// B'.
    pub base: V,
    /// D'.
    pub dir: V,
}

/// The precision the notes' steps are computed in.
pub trait Precision: Copy + Default + Send + Sync + 'static {
    /// A vector.
    type Vector: Copy;
    /// A number.
    type Real: Float + Into<f64>;

    /// B' = rotmat (B - C), D' = rotmat D.
    fn local_ray(frame: &AxisFrame, ray: &Ray) -> Plain<Self::Vector>;

    /// Note 003's a, b, c.
    fn coefficients(
        quadric: &AxisQuadric,
        local: &Plain<Self::Vector>,
    ) -> (Self::Real, Self::Real, Self::Real);

    /// The local y at distance `t`, in f64: B'y + t D'y.
    fn height(local: &Plain<Self::Vector>, t: f64) -> f64;

    /// The plane's N·(Q - B) / N·D, `None` if N·D = 0.
    fn plane_distance(plane: &Plane, ray: &Ray) -> Option<f64>;

    /// The world ray.
    fn world_ray(ray: &Ray) -> Plain<Self::Vector>;

    /// Note 004's a, b, c.
    fn quadric_coefficients(
        quadric: &Quadric,
        local: &Plain<Self::Vector>,
    ) -> (Self::Real, Self::Real, Self::Real);
}

/// Double precision, as the course's C program computed.
#[derive(Debug, Clone, Copy, Default)]
pub struct Double;

impl Precision for Double {
    type Vector = DVec3;
    type Real = f64;

    #[inline(always)]
    fn local_ray(frame: &AxisFrame, ray: &Ray) -> Plain<DVec3> {
        let (base, dir) = frame.to_local(ray);
        Plain { base, dir }
    }

    #[inline(always)]
    fn coefficients(quadric: &AxisQuadric, local: &Plain<DVec3>) -> (f64, f64, f64) {
        quadric.coefficients(local.base, local.dir)
    }

    #[inline(always)]
    fn height(local: &Plain<DVec3>, t: f64) -> f64 {
        local.base.y + t * local.dir.y
    }

    #[inline(always)]
    fn plane_distance(plane: &Plane, ray: &Ray) -> Option<f64> {
        let denominator = plane.normal.dot(ray.dir);
        if denominator == 0.0 {
            return None;
        }
        Some(plane.normal.dot(plane.point - ray.base) / denominator)
    }

    #[inline(always)]
    fn world_ray(ray: &Ray) -> Plain<DVec3> {
        Plain {
            base: ray.base,
            dir: ray.dir,
        }
    }

    #[inline(always)]
    fn quadric_coefficients(quadric: &Quadric, local: &Plain<DVec3>) -> (f64, f64, f64) {
        quadric.coefficients(local.base, local.dir)
    }
}

/// A kernel's name for `--kernel`, one per combination that is offered.
pub trait Named {
    /// The name ([`Kernel::NAME`] of the combination).
    const LABEL: &'static str;
}

impl Named for Textbook {
    const LABEL: &'static str = "textbook";
}

impl Named for StableRoots {
    const LABEL: &'static str = "stable";
}

impl<F, P> Kernel for AsWritten<F, P>
where
    P: Precision,
    F: Formula<P::Real>,
    Self: Named + Copy + Default + Send + Sync,
{
    const NAME: &'static str = <Self as Named>::LABEL;
    type Local = Plain<P::Vector>;
    type Coefficients = (P::Real, P::Real, P::Real);
    type Root = f64;

    #[inline(always)]
    fn local_ray(frame: &AxisFrame, ray: &Ray) -> Self::Local {
        P::local_ray(frame, ray)
    }

    #[inline(always)]
    fn coefficients(quadric: &AxisQuadric, local: &Self::Local) -> Self::Coefficients {
        P::coefficients(quadric, local)
    }

    #[inline(always)]
    fn roots((a, b, c): Self::Coefficients, tangent: Tangent) -> Option<[f64; 2]> {
        F::roots(a, b, c, tangent)
    }

    #[inline(always)]
    fn nearer_distance(_: &Steps<AxisQuadric, Self>, root: f64) -> Option<f64> {
        Some(root)
    }

    #[inline(always)]
    fn distance_and_height(
        steps: &Steps<AxisQuadric, Self>,
        root: f64,
        _: usize,
        _: (f64, f64),
    ) -> Result<(f64, f64), (f64, f64)> {
        Ok((root, P::height(steps.local, root)))
    }

    #[inline(always)]
    fn plane_distance(plane: &Plane, ray: &Ray) -> Option<f64> {
        P::plane_distance(plane, ray)
    }

    #[inline(always)]
    fn quadric_ray(_: &Quadric, ray: &Ray) -> Self::Local {
        P::world_ray(ray)
    }

    #[inline(always)]
    fn quadric_coefficients(quadric: &Quadric, local: &Self::Local) -> Self::Coefficients {
        P::quadric_coefficients(quadric, local)
    }

    #[inline(always)]
    fn quadric_distance(_: &Steps<Quadric, Self>, root: f64, _: usize) -> Result<f64, f64> {
        Ok(root)
    }
}
