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

/// A sphere with its squared radius precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct Sphere {
    /// The centre C of spec §5.2.
    pub centre: DVec3,
    /// The radius r, greater than 0.
    pub radius: f64,
    /// r², the constant of the sphere's equation, exact.
    pub radius_sq: f64,
    /// |P - C|² - r² = 0 in the form every kernel solves.
    pub equation: AxisQuadric,
}

impl Sphere {
    /// Validates the radius (> 0) and precomputes r²: x² + y² + z² - r² = 0 about the
    /// centre, the nearer root.
    pub fn new(centre: DVec3, radius: f64, record: &'static str) -> Result<Sphere, Invalid> {
        let radius = positive(record, "radius", radius).map_err(Parameter::Radius.refuses())?;
        let radius_sq = radius * radius;
        let frame = AxisFrame::unrotated(centre);
        let equation = AxisQuadric::new(frame, 1.0, 0.0, -radius_sq, RootRule::Nearer);
        Ok(Sphere {
            centre,
            radius,
            radius_sq,
            equation,
        })
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
        assert_eq!(hit(&sphere().equation, &ray), Some(3.0));
        assert_eq!(
            sphere().equation.normal(DVec3::new(0.0, 0.0, -3.0)),
            DVec3::Z
        );
    }

    #[test]
    fn ray_from_inside_reports_the_negative_root() {
        let ray = Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::X);
        assert_eq!(hit(&sphere().equation, &ray), Some(-2.0));
    }

    #[test]
    fn tangent_and_missing_rays_do_not_hit() {
        let tangent = Ray::new(DVec3::new(2.0, 0.0, 0.0), DVec3::NEG_Z);
        let away = Ray::new(DVec3::ZERO, DVec3::Y);
        assert_eq!(hit(&sphere().equation, &tangent), None);
        assert_eq!(hit(&sphere().equation, &away), None);
    }

    #[test]
    fn radius_must_be_positive() {
        assert!(Sphere::new(DVec3::ZERO, 0.0, "sphere").is_err());
        assert!(Sphere::new(DVec3::ZERO, -1.0, "sphere").is_err());
    }
}
