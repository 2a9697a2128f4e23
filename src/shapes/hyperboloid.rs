//! The finite hyperboloid of one sheet, code 24 (spec §5.6; note 003, which prints code 21
//! by mistake). Built by
//!
//! ```text
//! 24            hyperboloid
//! 0.2 0.2 0.2   ambient
//! 2.0 2.0 2.0   diffuse
//! 1.0 1.0 1.0   specular
//! 4 3 -4        centre of the waist
//! 1 0 0         centre line
//! 2 5           radius at the ends and half-height
//! 0.5           radius at the waist
//! ```
//! Local frame: axis +y, waist centre at the origin; x² + z² = k y² + rc² with
//! k = (r² - rc²)/h², -h <= y <= h.

use super::kernel::{Accurate, Kernel};
use super::{AxisFrame, AxisQuadric, Invalid, Ray, RootRule, positive};
use crate::error::MeaningError;
use crate::scene_file::layout::label;
use glam::DVec3;

/// A hyperboloid with its frame, k and rc² precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct Hyperboloid {
    /// x² - k y² + z² - rc² = 0 for -h <= y <= h, with the frame (waist centre, `rotmat`,
    /// `irot`).
    pub equation: AxisQuadric,
    /// Radius at y = ±h, > 0.
    pub radius: f64,
    /// Half-height h, > 0.
    pub half_height: f64,
    /// Waist radius rc, >= 0.
    pub waist: f64,
    /// k = (r² - rc²)/h² (negative when the waist is wider than the ends).
    pub k: f64,
    /// rc².
    pub waist_sq: f64,
}

impl Hyperboloid {
    /// Validates the radii and half-height, builds the frame and k.
    pub fn new(
        centre: DVec3,
        centre_line: DVec3,
        radius: f64,
        half_height: f64,
        waist: f64,
    ) -> Result<Self, Invalid> {
        const RECORD: &str = "hyperboloid";
        let frame = AxisFrame::new(centre, centre_line, RECORD)?;
        let r = positive(RECORD, "radius", label::END_RADIUS_HALF_HEIGHT, 0, radius)?;
        let h = positive(
            RECORD,
            "half-height",
            label::END_RADIUS_HALF_HEIGHT,
            1,
            half_height,
        )?;
        if waist < 0.0 {
            let error = MeaningError::NegativeWaist { value: waist };
            let (label, index) = (label::WAIST_RADIUS, 0);
            return Err(Invalid {
                label,
                index,
                error,
            });
        }
        let k = (r * r - waist * waist) / (h * h);
        let waist_sq = waist * waist;
        let equation = AxisQuadric {
            frame,
            square: DVec3::new(1.0, -k, 1.0),
            linear_y: 0.0,
            constant: -waist_sq,
            rule: RootRule::FirstPositiveWithin { low: -h, high: h },
        };
        Ok(Hyperboloid {
            equation,
            radius: r,
            half_height: h,
            waist,
            k,
            waist_sq,
        })
    }

    /// a = dx² + dz² - k dy², b = 2(bx dx + bz dz - k by dy), c = bx² + bz² - k by² - rc²;
    /// smallest positive root with -h <= y <= h.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        Accurate::axis_quadric(&self.equation, ray)
    }

    /// Local normal (2x, -2k y, 2z), turned back by `irot`.
    #[inline]
    pub fn normal(&self, point: DVec3) -> DVec3 {
        self.equation.normal(point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hyperboloid() -> Hyperboloid {
        // Ends of radius √2 at y = ±1, waist 1: k = (2 - 1)/1 = 1, x² + z² = y² + 1.
        Hyperboloid::new(DVec3::ZERO, DVec3::Y, 2f64.sqrt(), 1.0, 1.0).unwrap()
    }

    #[test]
    fn waist_is_hit_at_its_radius() {
        let ray = Ray {
            base: DVec3::new(-4.0, 0.0, 0.0),
            dir: DVec3::X,
        };
        assert_eq!(hyperboloid().hit(&ray), Some(3.0));
        assert_eq!(
            hyperboloid().normal(DVec3::new(-1.0, 0.0, 0.0)),
            DVec3::NEG_X
        );
    }

    #[test]
    fn at_height_one_the_radius_is_root_two_and_beyond_the_ends_it_misses() {
        let ray = Ray {
            base: DVec3::new(-4.0, -1.0, 0.0),
            dir: DVec3::X,
        };
        let t = hyperboloid().hit(&ray).unwrap();
        assert!((t - (4.0 - 2f64.sqrt())).abs() < 1e-15, "{t}");
        let beyond = Ray {
            base: DVec3::new(-4.0, 1.5, 0.0),
            dir: DVec3::X,
        };
        assert_eq!(hyperboloid().hit(&beyond), None);
    }

    #[test]
    fn negative_waist_is_an_error_and_zero_is_a_double_cone() {
        let error = Hyperboloid::new(DVec3::ZERO, DVec3::Y, 1.0, 1.0, -0.5).unwrap_err();
        assert_eq!(error.label, label::WAIST_RADIUS);
        let cone = Hyperboloid::new(DVec3::ZERO, DVec3::Y, 1.0, 1.0, 0.0).unwrap();
        assert_eq!(cone.k, 1.0);
    }
}
