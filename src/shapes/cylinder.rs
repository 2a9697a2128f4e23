//! The finite open cylinder, code 22 (spec §5.6; note 003). Built by
//!
//! ```text
//! 22            cylinder
//! 0.2 0.2 0.2   ambient
//! 2.0 2.0 2.0   diffuse
//! 1.0 1.0 1.0   specular
//! 4 3 -4        centre of the base
//! 1 0 0         centre line
//! 2 5           radius and height
//! ```
//! Local frame: axis +y, base centre at the origin; surface x² + z² = r², 0 <= y <= h.

use super::kernel::{Accurate, Kernel};
use super::{AxisFrame, AxisQuadric, Invalid, Ray, RootRule, positive};
use crate::scene_file::layout::label;
use glam::DVec3;

/// A cylinder with its frame and r² precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct Cylinder {
    /// x² + z² - r² = 0 for 0 <= y <= h, with the frame (base centre, `rotmat`, `irot`).
    pub equation: AxisQuadric,
    /// Radius, > 0.
    pub radius: f64,
    /// Height, > 0.
    pub height: f64,
    /// r².
    pub radius_sq: f64,
}

impl Cylinder {
    /// Validates radius and height, builds the frame.
    pub fn new(base: DVec3, centre_line: DVec3, radius: f64, height: f64) -> Result<Self, Invalid> {
        const RECORD: &str = "cylinder";
        let frame = AxisFrame::new(base, centre_line, RECORD)?;
        let radius = positive(RECORD, "radius", label::RADIUS_HEIGHT, 0, radius)?;
        let height = positive(RECORD, "height", label::RADIUS_HEIGHT, 1, height)?;
        let radius_sq = radius * radius;
        let equation = AxisQuadric {
            frame,
            square: DVec3::new(1.0, 0.0, 1.0),
            linear_y: 0.0,
            constant: -radius_sq,
            rule: RootRule::FirstPositiveWithin {
                low: 0.0,
                high: height,
            },
        };
        Ok(Cylinder {
            equation,
            radius,
            height,
            radius_sq,
        })
    }

    /// a = dx² + dz², b = 2(bx dx + bz dz), c = bx² + bz² - r²; smallest positive root with
    /// 0 <= y <= h.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        Accurate::axis_quadric(&self.equation, ray)
    }

    /// Local normal (x, 0, z), turned back by `irot`.
    #[inline]
    pub fn normal(&self, point: DVec3) -> DVec3 {
        self.equation.normal(point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cylinder() -> Cylinder {
        // Note 003's example: base (4, 3, -4), axis +x, radius 2, height 5.
        Cylinder::new(DVec3::new(4.0, 3.0, -4.0), DVec3::X, 2.0, 5.0).unwrap()
    }

    #[test]
    fn ray_across_the_axis_hits_the_near_wall() {
        let ray = Ray {
            base: DVec3::new(6.0, 3.0, 0.0),
            dir: DVec3::NEG_Z,
        };
        // The wall is at z = -4 + 2 = -2.
        assert_eq!(cylinder().hit(&ray), Some(2.0));
        let normal = cylinder().normal(DVec3::new(6.0, 3.0, -2.0));
        assert!((normal - DVec3::Z).length() < 1e-15, "{normal}");
    }

    #[test]
    fn out_of_bounds_and_axis_parallel_rays_miss() {
        let beyond = Ray {
            base: DVec3::new(9.5, 3.0, 0.0),
            dir: DVec3::NEG_Z,
        };
        assert_eq!(cylinder().hit(&beyond), None);
        // Parallel to the axis: a = 0 and b = 0, no root and no division by zero.
        let inside_parallel = Ray {
            base: DVec3::new(0.0, 3.0, -4.0),
            dir: DVec3::X,
        };
        assert_eq!(cylinder().hit(&inside_parallel), None);
    }

    #[test]
    fn from_inside_the_far_wall_is_hit() {
        let ray = Ray {
            base: DVec3::new(5.0, 3.0, -4.0),
            dir: DVec3::Y,
        };
        assert_eq!(cylinder().hit(&ray), Some(2.0));
    }
}
