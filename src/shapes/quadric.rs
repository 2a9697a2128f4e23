//! The general quadric x^T Q x = 0 (spec §3.3; note 004). Built by
//!
//! ```text
//! QUADRIC 1 0 0 0 1 0 0 1 0 -4   A B C D E F G H I J: the sphere x² + y² + z² = 4
//! 0.2 0.2 0.2   ambient
//! 2 2 2         diffuse
//! 0 0 0         specular
//! ```
//! The coefficients fill the symmetric matrix Q = [A B C D; B E F G; C F H I; D G I J].

use super::kernel::{Accurate, Kernel};
use super::{Invalid, Ray, unit};
use crate::error::MeaningError;
use crate::scene_file::layout::label;
use glam::{DMat4, DVec3, DVec4};

/// A general quadric surface, unbounded unless the quadric itself is closed.
#[derive(Debug, Clone, PartialEq)]
pub struct Quadric {
    /// A..J as written.
    pub coefficients: [f64; 10],
    /// The symmetric 4x4 matrix Q.
    pub q: DMat4,
}

impl Quadric {
    /// Builds Q; all ten coefficients zero is an error.
    pub fn new(coefficients: [f64; 10]) -> Result<Quadric, Invalid> {
        if coefficients.iter().all(|&c| c == 0.0) {
            let (label, index, error) = (label::COEFFICIENTS, 0, MeaningError::ZeroQuadric);
            return Err(Invalid {
                label,
                index,
                error,
            });
        }
        let [a, b, c, d, e, f, g, h, i, j] = coefficients;
        let q = DMat4::from_cols(
            DVec4::new(a, b, c, d),
            DVec4::new(b, e, f, g),
            DVec4::new(c, f, h, i),
            DVec4::new(d, g, i, j),
        );
        Ok(Quadric { coefficients, q })
    }

    /// a = dᵀQd, b = 2 dᵀQp, c = pᵀQp with p = (B, 1), d = (D, 0) (note 004).
    #[inline]
    pub fn coefficients(&self, ray: &Ray) -> (f64, f64, f64) {
        let p = ray.base.extend(1.0);
        let d = ray.dir.extend(0.0);
        let qp = self.q * p;
        (d.dot(self.q * d), 2.0 * d.dot(qp), p.dot(qp))
    }

    /// The smallest positive root of a t² + b t + c = 0 (a double root counts: a grazing
    /// ray touches the surface).
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        Accurate::quadric(self, ray)
    }

    /// The gradient (Ax+By+Cz+D, Bx+Ey+Fz+G, Cx+Fy+Hz+I), normalised, not flipped.
    #[inline]
    pub fn normal(&self, point: DVec3) -> DVec3 {
        let gradient = (self.q * point.extend(1.0)).truncate();
        unit(gradient).unwrap_or(DVec3::ZERO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrix_form_expands_to_the_scalar_equation_with_2i_z() {
        let coefficients = [2.0, 3.0, 5.0, 7.0, 11.0, 13.0, 17.0, 19.0, 23.0, 29.0];
        let quadric = Quadric::new(coefficients).unwrap();
        let [a, b, c, d, e, f, g, h, i, j] = coefficients;
        let (x, y, z) = (0.5, -1.25, 2.0);
        let scalar = a * x * x
            + 2.0 * b * x * y
            + 2.0 * c * x * z
            + 2.0 * d * x
            + e * y * y
            + 2.0 * f * y * z
            + 2.0 * g * y
            + h * z * z
            + 2.0 * i * z
            + j;
        let p = DVec4::new(x, y, z, 1.0);
        assert_eq!(p.dot(quadric.q * p), scalar);
    }

    #[test]
    fn unit_sphere_as_a_quadric() {
        let sphere = Quadric::new([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, -1.0]).unwrap();
        let ray = Ray {
            base: DVec3::new(0.0, 0.0, 5.0),
            dir: DVec3::NEG_Z,
        };
        assert_eq!(sphere.hit(&ray), Some(4.0));
        assert_eq!(sphere.normal(DVec3::Z), DVec3::Z);
        // From inside, the far side is hit (unlike code 13).
        let inside = Ray {
            base: DVec3::ZERO,
            dir: DVec3::X,
        };
        assert_eq!(sphere.hit(&inside), Some(1.0));
    }

    #[test]
    fn no_real_points_renders_nothing_and_all_zero_is_an_error() {
        let empty = Quadric::new([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
        let ray = Ray {
            base: DVec3::new(0.0, 0.0, 5.0),
            dir: DVec3::NEG_Z,
        };
        assert_eq!(empty.hit(&ray), None);
        assert!(Quadric::new([0.0; 10]).is_err());
    }
}
