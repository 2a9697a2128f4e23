//! The course notes' kernel: the coefficients as note 003 writes them and the roots by
//! (-b ± sqrt(b² - 4ac)) / 2a, in f64.

use super::{Kernel, axis_quadric_as_written, plane_rule, quadric_as_written};
use crate::shapes::{AxisQuadric, Plane, Quadric, Ray};

/// The notes' formula in f64.
#[derive(Debug, Clone, Copy, Default)]
pub struct Textbook;

/// Both roots by the textbook formula, ascending; a = 0 is solved as linear, as every
/// kernel does (spec §5.6).
#[inline]
pub fn textbook_roots(a: f64, b: f64, c: f64, strict: bool) -> Option<[f64; 2]> {
    if a == 0.0 {
        return (b != 0.0).then(|| [-c / b; 2]);
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 || (strict && discriminant == 0.0) || discriminant.is_nan() {
        return None;
    }
    let root = discriminant.sqrt();
    let (t0, t1) = ((-b - root) / (2.0 * a), (-b + root) / (2.0 * a));
    Some(if t0 <= t1 { [t0, t1] } else { [t1, t0] })
}

impl Kernel for Textbook {
    const NAME: &'static str = "textbook";

    #[inline]
    fn axis_quadric(quadric: &AxisQuadric, ray: &Ray) -> Option<f64> {
        axis_quadric_as_written(quadric, ray, textbook_roots)
    }

    #[inline]
    fn quadric(quadric: &Quadric, ray: &Ray) -> Option<f64> {
        quadric_as_written(quadric, ray, textbook_roots)
    }

    #[inline]
    fn plane(plane: &Plane, ray: &Ray) -> Option<f64> {
        let denominator = plane.normal.dot(ray.dir);
        if denominator == 0.0 {
            return None;
        }
        plane_rule(ray, plane.normal.dot(plane.point - ray.base) / denominator)
    }
}
