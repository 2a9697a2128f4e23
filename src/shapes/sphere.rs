//! The sphere (spec §5.2; notes 000 and 002). Built by
//!
//! ```text
//! 13            sphere
//! 0.2 0.2 5.2   ambient
//! 1.4 2.6 3.6   diffuse
//! 0.1 1.0 3.0   specular
//! 2 0 -3        centre
//! 2             radius
//! ```
//! (code 19, the procedural sphere, adds a shader index line).
//!
//! Its hit is note 003's algorithm (`src/shapes/kernel/textbook.rs`, and the shipped
//! kernel's own arithmetic, under the rule [`RootRule`](super::RootRule)), in the sphere's case: the
//! smaller root of |B - C + tD|² = r², even when negative, if the discriminant is
//! positive (spec §5.2: a tangent ray misses, a ray from inside finds t <= 0). Its normal
//! ([`AxisQuadric::normal`]) is the outward unit(P - C).

use super::{AxisFrame, AxisQuadric, Invalid, Parameter, RootRule, positive};
use glam::DVec3;

/// A sphere with its squared radius precomputed: 40 bytes, the smallest shape, since a
/// scene may hold a million of them. Its [`AxisQuadric`] is built when a kernel asks.
#[derive(Debug, Clone, PartialEq)]
pub struct Sphere {
    /// The centre C of spec §5.2.
    pub centre: DVec3,
    /// The radius r, greater than 0.
    pub radius: f64,
    /// r², the constant of the sphere's equation, exact.
    pub radius_sq: f64,
}

impl Sphere {
    /// Validates the radius (> 0) and precomputes r²: x² + y² + z² - r² = 0 about the
    /// centre, the nearer root.
    pub fn new(centre: DVec3, radius: f64, record: &'static str) -> Result<Sphere, Invalid> {
        let radius = positive(record, "radius", radius).map_err(Parameter::Radius.refuses())?;
        Ok(Sphere {
            centre,
            radius,
            radius_sq: radius * radius,
        })
    }

    /// The terms of `ray`'s quadratic a t² + b t + c about the centre, with w = B - C:
    /// (D·D, D·w, |w|²), whence a = D·D, b = 2 D·w and c = |w|² - r² (the notes'
    /// formula; the sphere's frame turns nothing).
    #[inline(always)]
    pub(crate) fn terms(&self, ray: &super::Ray) -> (f64, f64, f64) {
        let (w, d) = (ray.base - self.centre, ray.dir);
        (d.dot(d), d.dot(w), w.dot(w))
    }

    /// The quadratic (a, b, c) of [`Sphere::terms`].
    #[inline(always)]
    pub(crate) fn quadratic((dd, dw, ww): (f64, f64, f64), radius_sq: f64) -> (f64, f64, f64) {
        (dd, 2.0 * dw, ww - radius_sq)
    }

    /// The box `equation().bounds()` gives, C ∓ sqrt(r²), without its general steps: with
    /// αx = αy = αz = 1, β = 0 and no rotation, its widest radius is sqrt(r²) and its
    /// corners are C ∓ sqrt(r²) exactly (the rotation is the identity; the sum with zero
    /// terms is exact). A million spheres' boxes are computed before a render.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let r = self.radius_sq.sqrt();
        r.is_finite().then(|| (self.centre - r, self.centre + r))
    }

    /// |P - C|² - r² = 0 in the form every kernel solves: x² + y² + z² - r² about the
    /// centre, unrotated, the nearer root. Built from the three fields, so it is the same
    /// equation at every call and costs a scene of spheres nothing to hold.
    #[inline(always)]
    pub fn equation(&self) -> AxisQuadric {
        let frame = AxisFrame::unrotated(self.centre);
        AxisQuadric::new(frame, 1.0, 0.0, -self.radius_sq, RootRule::Nearer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::testing::*;

    fn sphere() -> Sphere {
        Sphere::new(DVec3::new(0.0, 0.0, -5.0), 2.0, "sphere").unwrap()
    }

    #[test]
    fn ray_through_the_centre_hits_the_near_side() {
        let ray = Ray::new(DVec3::ZERO, DVec3::NEG_Z);
        assert_eq!(hit(&sphere().equation(), &ray), Some(3.0));
        assert_eq!(
            sphere().equation().normal(DVec3::new(0.0, 0.0, -3.0)),
            DVec3::Z
        );
    }

    #[test]
    fn ray_from_inside_reports_the_negative_root() {
        let ray = Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::X);
        assert_eq!(hit(&sphere().equation(), &ray), Some(-2.0));
    }

    #[test]
    fn tangent_and_missing_rays_do_not_hit() {
        let tangent = Ray::new(DVec3::new(2.0, 0.0, 0.0), DVec3::NEG_Z);
        let away = Ray::new(DVec3::ZERO, DVec3::Y);
        assert_eq!(hit(&sphere().equation(), &tangent), None);
        assert_eq!(hit(&sphere().equation(), &away), None);
    }

    #[test]
    fn the_box_is_the_general_quadrics_box() {
        // Radii whose squares round (0.1, 1/3: sqrt(r²) need not be r), huge and tiny
        // ones (3e160: r² overflows, and there is no box), and centres far from the
        // origin.
        let radii = [0.1, 1.0 / 3.0, 2.0, 7e-155, 1e154, 3e160];
        let centres = [DVec3::ZERO, DVec3::new(-1e12, 0.3, 5e-9), DVec3::splat(7.1)];
        for (r, c) in radii.into_iter().flat_map(|r| centres.map(|c| (r, c))) {
            let sphere = Sphere::new(c, r, "sphere").unwrap();
            assert_eq!(
                sphere.bounds(),
                sphere.equation().bounds(),
                "r {r}, centre {c}"
            );
        }
    }

    #[test]
    fn radius_must_be_positive() {
        assert!(Sphere::new(DVec3::ZERO, 0.0, "sphere").is_err());
        assert!(Sphere::new(DVec3::ZERO, -1.0, "sphere").is_err());
    }
}
