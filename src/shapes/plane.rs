//! The infinite plane (spec §5.1). Built by
//!
//! ```text
//! 14            plane
//! 0 2 0         ambient
//! 0 0 0         diffuse
//! 0 0 0         specular
//! 0 1 0         normal
//! 0 -4 0        point
//! ```
//! (code 20, the procedural plane, adds a shader index line).

use super::{HitNote, Invalid, Notes, Parameter, Ray, Verdict, unit_or_zero_error};
use glam::DVec3;

/// A plane through `point` with unit `normal`, used as given (never flipped, spec §4.4).
#[derive(Debug, Clone, PartialEq)]
pub struct Plane {
    /// The unit normal, as the record gives its direction (never flipped).
    pub normal: DVec3,
    /// A point of the plane.
    pub point: DVec3,
    /// Spec §5.1's rule that a hit with z > this (behind the screen) is a miss: 0 as
    /// written, E under z-tolerance=E (spec §7.5), ∞ under no-z-rule (spec §7.3).
    pub z_limit: f64,
}

impl Plane {
    /// Normalises the normal; a zero normal is an error.
    pub fn new(normal: DVec3, point: DVec3, record: &'static str) -> Result<Plane, Invalid> {
        let normal = unit_or_zero_error(normal, record, Parameter::Normal)?;
        Ok(Plane {
            normal,
            point,
            z_limit: 0.0,
        })
    }

    /// Spec §5.1's rule on a plane hit at distance `t` along `ray` (the kernel's t): a
    /// miss when t < 0 (or not a number) or when the hit has z > 0, beyond the screen,
    /// unless within `slack()` of z = 0 (a kernel's allowance for the rounding of z,
    /// computed only when z > 0); the limit is E under z-tolerance, ∞ under no-z-rule.
    #[inline(always)]
    pub(crate) fn verdict(
        &self,
        ray: &Ray,
        t: f64,
        slack: impl FnOnce() -> f64,
        notes: &mut impl Notes,
    ) -> Option<f64> {
        let z = ray.base.z + t * ray.dir.z;
        // (A NaN t counts as behind.)
        let verdict = if t.is_nan() || t < 0.0 {
            Verdict::Behind
        } else if z <= self.z_limit || z - self.z_limit <= slack() {
            Verdict::Counts
        } else {
            Verdict::BeyondScreen
        };
        notes.note(HitNote::Plane { t, z, verdict });
        (verdict == Verdict::Counts).then_some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::kernel::Kernel;
    use crate::shapes::testing::*;

    #[test]
    fn ray_hits_the_floor_at_the_distance_of_the_formula() {
        let plane = Plane::new(
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(0.0, -4.0, 0.0),
            "plane",
        );
        let plane = plane.unwrap();
        assert_eq!(plane.normal, DVec3::Y);
        let dir = DVec3::new(0.0, -0.6, -0.8);
        let ray = Ray {
            base: DVec3::ZERO,
            dir,
        };
        // Descending 4 units at 0.6 per unit length takes t = 4 / 0.6.
        let t = Accurate::plane(&plane, &ray, &mut ()).unwrap();
        assert!((t - 4.0 / 0.6).abs() < 1e-14, "{t}");
    }

    #[test]
    fn parallel_backward_and_in_front_of_the_screen_rays_miss() {
        let wall = Plane::new(DVec3::Z, DVec3::new(0.0, 0.0, -5.0), "plane").unwrap();
        let from_eye = |dir| Ray {
            base: DVec3::new(0.0, 0.0, 3.0),
            dir,
        };
        assert_eq!(Accurate::plane(&wall, &from_eye(DVec3::X), &mut ()), None);
        assert_eq!(Accurate::plane(&wall, &from_eye(DVec3::Z), &mut ()), None);
        // A plane z = 1 lies between the eye and the screen: its hits have z > 0.
        let near = Plane::new(DVec3::Z, DVec3::new(0.0, 0.0, 1.0), "plane").unwrap();
        assert_eq!(
            Accurate::plane(&near, &from_eye(DVec3::NEG_Z), &mut ()),
            None
        );
        assert_eq!(
            Accurate::plane(&wall, &from_eye(DVec3::NEG_Z), &mut ()),
            Some(8.0)
        );
    }

    #[test]
    fn zero_normal_is_an_error() {
        assert!(Plane::new(DVec3::ZERO, DVec3::ZERO, "plane").is_err());
    }
}
