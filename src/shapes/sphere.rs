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

use super::kernel::{Accurate, Kernel};
use super::{AxisFrame, AxisQuadric, Invalid, Ray, RootRule, positive};
use crate::scene_file::layout::label;
use glam::DVec3;

/// A sphere with its squared radius precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub centre: DVec3,
    /// Radius, > 0.
    pub radius: f64,
    /// r².
    pub radius_sq: f64,
    /// |P - C|² - r² = 0 in the form every kernel solves.
    pub equation: AxisQuadric,
}

impl Sphere {
    /// Validates the radius (> 0) and precomputes r².
    pub fn new(centre: DVec3, radius: f64, record: &'static str) -> Result<Sphere, Invalid> {
        let radius = positive(record, "radius", label::RADIUS, 0, radius)?;
        let radius_sq = radius * radius;
        let equation = AxisQuadric {
            frame: AxisFrame::unrotated(centre),
            square: DVec3::ONE,
            linear_y: 0.0,
            constant: -radius_sq,
            rule: RootRule::Nearer,
        };
        Ok(Sphere {
            centre,
            radius,
            radius_sq,
            equation,
        })
    }

    /// The smaller root of |B - C + tD|² = r², even when negative, if the discriminant is
    /// positive (spec §5.2: a tangent ray misses, a ray from inside finds t <= 0).
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        Accurate::axis_quadric(&self.equation, ray)
    }

    /// Unit outward normal unit(P - C).
    #[inline]
    pub fn normal(&self, point: DVec3) -> DVec3 {
        self.equation.normal(point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere() -> Sphere {
        Sphere::new(DVec3::new(0.0, 0.0, -5.0), 2.0, "sphere").unwrap()
    }

    #[test]
    fn ray_through_the_centre_hits_the_near_side() {
        let ray = Ray {
            base: DVec3::ZERO,
            dir: DVec3::NEG_Z,
        };
        assert_eq!(sphere().hit(&ray), Some(3.0));
        assert_eq!(sphere().normal(DVec3::new(0.0, 0.0, -3.0)), DVec3::Z);
    }

    #[test]
    fn ray_from_inside_reports_the_negative_root() {
        let ray = Ray {
            base: DVec3::new(0.0, 0.0, -5.0),
            dir: DVec3::X,
        };
        assert_eq!(sphere().hit(&ray), Some(-2.0));
    }

    #[test]
    fn tangent_and_missing_rays_do_not_hit() {
        let tangent = Ray {
            base: DVec3::new(2.0, 0.0, 0.0),
            dir: DVec3::NEG_Z,
        };
        let away = Ray {
            base: DVec3::ZERO,
            dir: DVec3::Y,
        };
        assert_eq!(sphere().hit(&tangent), None);
        assert_eq!(sphere().hit(&away), None);
    }

    #[test]
    fn radius_must_be_positive() {
        assert!(Sphere::new(DVec3::ZERO, 0.0, "sphere").is_err());
        assert!(Sphere::new(DVec3::ZERO, -1.0, "sphere").is_err());
    }
}
