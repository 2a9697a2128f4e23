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
use super::{HitNote, Invalid, Notes, Parameter, Verdict, unit};
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
    /// x0, the centre or the least-squares point near it.
    pub anchor: DVec3,
    /// M, the upper-left 3x3 block of Q.
    pub second_order: DMat3,
    /// |M|, element by element, for error estimates.
    pub second_order_abs: DMat3,
    /// g0 = M x0 + d, the half-gradient at x0.
    pub gradient: DVec3,
    /// f0 = f(x0), the value at x0.
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

    /// A box that holds the whole surface when it is closed (an ellipsoid): when
    /// Gershgorin's circles put every eigenvalue of M above λ > 0, a surface point
    /// x0 + u has λ|u|² <= uᵀMu = -2 g0ᵀu - f0 <= 2|g0||u| + max(-f0, 0), so
    /// |u| <= (|g0| + sqrt(|g0|² + λ max(-f0, 0))) / λ. λ, |g0| and -f0 are each moved
    /// the safe way by far more than their rounding. `None` for the open quadrics, and
    /// for a closed one that Gershgorin's bound does not show to be closed by a clear
    /// margin (a thin or tilted ellipsoid may be left without a box).
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let Centred {
            anchor,
            second_order: m,
            second_order_abs: m_abs,
            gradient,
            value,
        } = &self.centred;
        let size = m_abs.to_cols_array().into_iter().fold(0.0, f64::max);
        let lambda = (0..3)
            .map(|i| {
                let row = m.row(i);
                row[i] - (m_abs.row(i).element_sum() - row[i].abs())
            })
            .fold(f64::INFINITY, f64::min)
            - 1e-12 * size;
        if lambda.is_nan() || lambda <= 1e-6 * size {
            return None;
        }
        // The sizes of the terms that gave g0 and f0 (rounded once from double-double).
        let reach = anchor.abs();
        let linear = DVec3::new(
            self.coefficients[3],
            self.coefficients[6],
            self.coefficients[8],
        );
        let g_terms = (*m_abs * reach + linear.abs()).max_element();
        let f_terms =
            reach.dot(*m_abs * reach) + 2.0 * linear.abs().dot(reach) + self.coefficients[9].abs();
        let g = gradient.length() * (1.0 + 1e-12) + 1e-15 * g_terms;
        let f = (-value).max(0.0) * (1.0 + 1e-12) + 1e-15 * f_terms;
        let radius = (g + (g * g + lambda * f).sqrt()) / lambda * (1.0 + 1e-9);
        let radius = DVec3::splat(radius);
        let (min, max) = (*anchor - radius, *anchor + radius);
        (min.is_finite() && max.is_finite()).then_some((min, max))
    }

    /// a = dᵀQd, b = 2 dᵀQp, c = pᵀQp with p = (B, 1), d = (D, 0) (note 004).
    #[inline]
    pub fn coefficients(&self, base: DVec3, dir: DVec3) -> (f64, f64, f64) {
        let p = base.extend(1.0);
        let d = dir.extend(0.0);
        let qp = self.q * p;
        (d.dot(self.q * d), 2.0 * d.dot(qp), p.dot(qp))
    }

    /// a, b, c along `ray` from its base, as the notes' formula computes them: note 004's
    /// in f64.
    pub(crate) fn quadratic(&self, ray: &super::Ray) -> (f64, f64, f64) {
        self.coefficients(ray.base, ray.dir)
    }

    /// Note 004's choice among the two real roots, ascending: the smallest in front of
    /// the base (a double root counts: a grazing ray touches). `judge(index, root)` gives
    /// a root's t in the kernel's arithmetic and whether it may count (a kernel may know a
    /// root to lie behind the base without polishing it); each is told to `notes`.
    #[inline(always)]
    pub(crate) fn first_in_front<R>(
        roots: [R; 2],
        mut judge: impl FnMut(usize, R) -> (f64, bool),
        notes: &mut impl Notes,
    ) -> Option<f64> {
        for (index, root) in roots.into_iter().enumerate() {
            let (t, may_count) = judge(index, root);
            let counts = may_count && t > 0.0;
            let verdict = match counts {
                true => Verdict::Counts,
                false => Verdict::Behind,
            };
            notes.note(HitNote::QuadricRoot { t, verdict });
            if counts {
                return Some(t);
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

    /// |∇²f| / |∇f| at `point`, bounded with M's Frobenius norm: the half-Hessian is M
    /// and the half-gradient M (x - x0) + g0 ([`super::Shape::curvature`]).
    pub(crate) fn curvature(&self, point: DVec3) -> f64 {
        let m = &self.centred.second_order;
        let frobenius =
            (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared())
                .sqrt();
        let gradient = *m * (point - self.centred.anchor) + self.centred.gradient;
        frobenius / gradient.length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::testing::*;

    /// The coefficients A..J of the ellipsoid with semi-axes `axes` along the columns of
    /// the rotation `turn`, centred at `centre`: (x - c)ᵀ Rᵀ diag(1/a²) R (x - c) = 1.
    fn ellipsoid(axes: DVec3, turn: DMat3, centre: DVec3) -> [f64; 10] {
        let m = turn * DMat3::from_diagonal(axes.powf(-2.0)) * turn.transpose();
        let d = -(m * centre);
        let j = centre.dot(m * centre) - 1.0;
        [
            m.x_axis.x, m.y_axis.x, m.z_axis.x, d.x, m.y_axis.y, m.z_axis.y, d.y, m.z_axis.z, d.z,
            j,
        ]
    }

    #[test]
    fn an_ellipsoid_s_box_holds_every_accurate_hit() {
        // A sphere of radius 0.5 at (0, 0, -4), as examples/quadrics_gallery.txt writes it:
        // its box is the sphere's own, to within the margins.
        let gallery = Quadric::new([4.0, 0.0, 0.0, 0.0, 4.0, 0.0, 0.0, 4.0, 16.0, 63.0]).unwrap();
        let (min, max) = gallery.bounds().unwrap();
        let exact = (DVec3::new(-0.5, -0.5, -4.5), DVec3::new(0.5, 0.5, -3.5));
        assert!((min - exact.0).abs().max_element() < 1e-6, "{min}");
        assert!((max - exact.1).abs().max_element() < 1e-6, "{max}");
        // Turned ellipsoids far from the origin, and rays through them from all sides:
        // every hit the accurate kernel finds lies in the box.
        let mut numbers = Numbers(0x2026_1122);
        let mut next = || numbers.next();
        let (mut boxed, mut hits) = (0, 0);
        for _ in 0..200 {
            let axes = DVec3::new(0.2 + 2.0 * next(), 0.2 + 2.0 * next(), 0.2 + 2.0 * next());
            let turn = DMat3::from_euler(
                glam::EulerRot::XYZ,
                6.0 * next(),
                6.0 * next(),
                6.0 * next(),
            );
            let centre = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 2e3;
            let quadric = Quadric::new(ellipsoid(axes, turn, centre)).unwrap();
            let Some((min, max)) = quadric.bounds() else {
                continue;
            };
            boxed += 1;
            for _ in 0..200 {
                let from = centre + DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 20.0;
                let towards = centre + DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 4.0;
                let ray = Ray::new(from, (towards - from).normalize());
                if let Some(t) = hit_quadric(&quadric, &ray) {
                    hits += 1;
                    let point = ray.base + t * ray.dir;
                    let slack = 1e-12 * centre.abs().max_element();
                    assert!(
                        point.cmpge(min - slack).all() && point.cmple(max + slack).all(),
                        "{point} outside {min} {max}"
                    );
                }
            }
        }
        assert!(boxed > 20 && hits > 2_000, "{boxed} boxes, {hits} hits");
    }

    #[test]
    fn open_quadrics_have_no_box() {
        // x² + y² - z² = 1 (one sheet), x² + y² = 1 (a cylinder), x² + y² - z = 0 (a
        // paraboloid), and x² + y² + z² = -1 (no point; still closed, so boxed).
        for open in [
            [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 0.0, -1.0],
            [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0],
            [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -0.5, 0.0],
        ] {
            assert_eq!(Quadric::new(open).unwrap().bounds(), None, "{open:?}");
        }
        let empty = Quadric::new([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
        assert!(empty.bounds().is_some());
    }

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
        assert_eq!(hit_quadric(&sphere, &ray), Some(4.0));
        assert_eq!(sphere.normal(DVec3::Z), DVec3::Z);
        // From inside, the far side is hit (unlike code 13).
        let inside = Ray::new(DVec3::ZERO, DVec3::X);
        assert_eq!(hit_quadric(&sphere, &inside), Some(1.0));
    }

    #[test]
    fn no_real_points_renders_nothing_and_all_zero_is_an_error() {
        let empty = Quadric::new([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z);
        assert_eq!(hit_quadric(&empty, &ray), None);
        assert!(Quadric::new([0.0; 10]).is_err());
    }
}
