//! The notes' coefficients solved by the cancellation-free root formula only
//! ([`crate::shapes::solve_quadratic`]).

use super::{Kernel, Textbook, axis_quadric_as_written, quadric_as_written};
use crate::shapes::{AxisQuadric, Plane, Quadric, Ray, solve_quadratic};

/// Stable roots of the textbook coefficients.
#[derive(Debug, Clone, Copy, Default)]
pub struct StableRoots;

/// [`solve_quadratic`], rejecting a zero discriminant when `strict`.
#[inline]
pub fn stable_roots(a: f64, b: f64, c: f64, strict: bool) -> Option<[f64; 2]> {
    if strict && a != 0.0 && b * b - 4.0 * a * c <= 0.0 {
        return None;
    }
    solve_quadratic(a, b, c)
}

impl Kernel for StableRoots {
    const NAME: &'static str = "stable";

    #[inline]
    fn axis_quadric(quadric: &AxisQuadric, ray: &Ray) -> Option<f64> {
        axis_quadric_as_written(quadric, ray, stable_roots)
    }

    #[inline]
    fn quadric(quadric: &Quadric, ray: &Ray) -> Option<f64> {
        quadric_as_written(quadric, ray, stable_roots)
    }

    /// The plane has no quadratic: the textbook division.
    #[inline]
    fn plane(plane: &Plane, ray: &Ray) -> Option<f64> {
        Textbook::plane(plane, ray)
    }
}
