//! The general quadric x^T Q x = 0 (spec §3.3; note 004). Built by
//!
//! ```text
//! QUADRIC 1 0 0 0 1 0 0 1 0 -4   A B C D E F G H I J: the sphere x² + y² + z² = 4
//! 0.2 0.2 0.2   ambient
//! 2 2 2         diffuse
//! 0 0 0         specular
//! ```
//! The coefficients fill the symmetric matrix Q = [A B C D; B E F G; C F H I; D G I J].

use super::kernel::dd::{Dd, two_prod};
use super::kernel::{Kernel, Steps, Tangent};
use super::{HitNote, Invalid, Notes, Parameter, Ray, Verdict, unit};
use crate::error::MeaningError;
use glam::{DMat3, DMat4, DVec3, DVec4};

/// A general quadric surface, unbounded unless the quadric itself is closed.
#[derive(Debug, Clone, PartialEq)]
pub struct Quadric {
    /// A..J as written.
    pub coefficients: [f64; 10],
    /// The symmetric 4x4 matrix Q.
    pub q: DMat4,
    /// The same equation about a point near its centre, for the accurate kernel.
    pub(crate) centred: Centred,
}

/// f(x) = xᵀMx + 2 dᵀx + J rewritten about an anchor point x0, so that a ray near the
/// surface sees terms the size of the surface, not of its distance from the origin:
///
/// ```text
/// f(x0 + u) = uᵀ M u + 2 g0ᵀ u + f0,   g0 = M x0 + d,   f0 = f(x0)
/// ```
///
/// x0 is the centre (M x0 = -d) where there is one, and otherwise the point nearest it in
/// the least-squares sense: a point on a cylinder's axis, a paraboloid's vertex plane.
/// g0 and f0 are computed in double-double and rounded once.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Centred {
    /// x0.
    pub anchor: DVec3,
    /// M, the upper-left 3x3 block of Q.
    pub second_order: DMat3,
    /// |M|, element by element, for error estimates.
    pub second_order_abs: DMat3,
    /// g0 = M x0 + d.
    pub gradient: DVec3,
    /// f0 = f(x0).
    pub value: f64,
}

impl Centred {
    fn new(coefficients: [f64; 10]) -> Centred {
        let [a, b, c, d, e, f, g, h, i, j] = coefficients;
        let m = DMat3::from_cols(
            DVec3::new(a, b, c),
            DVec3::new(b, e, f),
            DVec3::new(c, f, h),
        );
        let linear = DVec3::new(d, g, i);
        // x0 = -(M² + μ I)⁻¹ M d: the centre when M is invertible, the least-squares
        // point when it is singular; μ only keeps the inverse finite.
        let size = m.abs().to_cols_array().into_iter().fold(0.0, f64::max);
        let normal = m * m + DMat3::from_diagonal(DVec3::splat(1e-12 * size * size));
        let anchor = -(normal.inverse() * (m * linear));
        let anchor = if anchor.is_finite() {
            anchor
        } else {
            DVec3::ZERO
        };
        let x = [anchor.x, anchor.y, anchor.z];
        let row = |k: usize| {
            let column = m.col(k);
            two_prod(column.x, x[0])
                + two_prod(column.y, x[1])
                + two_prod(column.z, x[2])
                + Dd::new(linear[k])
        };
        let g0 = [row(0), row(1), row(2)];
        let f0 = (0..3).fold(Dd::new(j), |sum, k| {
            sum + x[k] * (g0[k] + Dd::new(linear[k]))
        });
        Centred {
            anchor,
            second_order: m,
            second_order_abs: m.abs(),
            gradient: DVec3::new(g0[0].value(), g0[1].value(), g0[2].value()),
            value: f0.value(),
        }
    }
}

impl Quadric {
    /// Builds Q; all ten coefficients zero is an error.
    pub fn new(coefficients: [f64; 10]) -> Result<Quadric, Invalid> {
        if coefficients.iter().all(|&c| c == 0.0) {
            let (parameter, error) = (Parameter::Coefficients, MeaningError::ZeroQuadric);
            return Err(Invalid { parameter, error });
        }
        let [a, b, c, d, e, f, g, h, i, j] = coefficients;
        let q = DMat4::from_cols(
            DVec4::new(a, b, c, d),
            DVec4::new(b, e, f, g),
            DVec4::new(c, f, h, i),
            DVec4::new(d, g, i, j),
        );
        Ok(Quadric {
            coefficients,
            q,
            centred: Centred::new(coefficients),
        })
    }

    /// a = dᵀQd, b = 2 dᵀQp, c = pᵀQp with p = (B, 1), d = (D, 0) (note 004).
    #[inline]
    pub fn coefficients(&self, base: DVec3, dir: DVec3) -> (f64, f64, f64) {
        let p = base.extend(1.0);
        let d = dir.extend(0.0);
        let qp = self.q * p;
        (d.dot(self.q * d), 2.0 * d.dot(qp), p.dot(qp))
    }

    /// The smallest positive root along `ray` (spec §3.3; note 004), with kernel `K`
    /// doing the arithmetic: a, b, c of the quadratic, its roots, and the first in front
    /// of the base.
    #[inline(always)]
    pub fn hit<K: Kernel>(&self, ray: &Ray) -> Option<f64> {
        self.hit_noted::<K>(ray, &mut ())
    }

    /// [`Quadric::hit`], telling `notes` why it decided as it did.
    #[inline(always)]
    pub fn hit_noted<K: Kernel>(&self, ray: &Ray, notes: &mut impl Notes) -> Option<f64> {
        // The ray as P = (B, 1) + t (D, 0), moved next to the quadric where the kernel
        // does that.
        let local = K::quadric_ray(self, ray);
        // a = DᵀQD, b = 2 DᵀQP, c = PᵀQP.
        let abc = K::quadric_coefficients(self, &local);
        let steps = Steps::new(self, ray, &local, abc);
        let Some(roots) = K::roots(abc, Tangent::Counts) else {
            notes.note(HitNote::NoRealRoot);
            return None;
        };
        // The smallest positive root (a double root counts: a grazing ray touches).
        for (index, root) in roots.into_iter().enumerate() {
            match K::quadric_distance(&steps, root, index) {
                Ok(t) if t > 0.0 => {
                    notes.note(HitNote::QuadricRoot {
                        t,
                        verdict: Verdict::Counts,
                    });
                    return Some(t);
                }
                Ok(t) | Err(t) => notes.note(HitNote::QuadricRoot {
                    t,
                    verdict: Verdict::Behind,
                }),
            }
        }
        None
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
    use crate::shapes::testing::*;

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
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z);
        assert_eq!(sphere.hit::<Accurate>(&ray), Some(4.0));
        assert_eq!(sphere.normal(DVec3::Z), DVec3::Z);
        // From inside, the far side is hit (unlike code 13).
        let inside = Ray::new(DVec3::ZERO, DVec3::X);
        assert_eq!(sphere.hit::<Accurate>(&inside), Some(1.0));
    }

    #[test]
    fn no_real_points_renders_nothing_and_all_zero_is_an_error() {
        let empty = Quadric::new([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z);
        assert_eq!(empty.hit::<Accurate>(&ray), None);
        assert!(Quadric::new([0.0; 10]).is_err());
    }
}
