//! The finite open cone, code 23 (spec §5.6; note 003). Built by
//!
//! ```text
//! 23            cone
//! 0.2 0.2 0.2   ambient
//! 2.0 2.0 2.0   diffuse
//! 1.0 1.0 1.0   specular
//! 4 3 -4        apex (the course file says "center of base"; it is the apex)
//! 1 0 0         centre line
//! 2 5           radius at the open end and height
//! ```
//! Local frame: axis +y, apex at the origin; surface x² + z² = k y² with k = (r/h)².

use super::kernel::{Accurate, Kernel};
use super::{AxisFrame, AxisQuadric, Invalid, Ray, RootRule, positive};
use crate::scene_file::layout::label;
use glam::DVec3;

/// A cone with its frame and scale k = (r/h)².
#[derive(Debug, Clone, PartialEq)]
pub struct Cone {
    /// x² - k y² + z² = 0 for 0 <= y <= h, with the frame (apex, `rotmat`, `irot`).
    pub equation: AxisQuadric,
    /// Radius at y = h, > 0.
    pub radius: f64,
    /// Height, > 0.
    pub height: f64,
    /// k = (r/h)².
    pub k: f64,
}

impl Cone {
    /// Validates radius and height, builds the frame and k.
    pub fn new(apex: DVec3, centre_line: DVec3, radius: f64, height: f64) -> Result<Self, Invalid> {
        const RECORD: &str = "cone";
        let frame = AxisFrame::new(apex, centre_line, RECORD)?;
        let radius = positive(RECORD, "radius", label::RADIUS_HEIGHT, 0, radius)?;
        let height = positive(RECORD, "height", label::RADIUS_HEIGHT, 1, height)?;
        let slope = radius / height;
        let k = slope * slope;
        let equation = AxisQuadric {
            frame,
            square: DVec3::new(1.0, -k, 1.0),
            linear_y: 0.0,
            constant: 0.0,
            rule: RootRule::FirstPositiveWithin {
                low: 0.0,
                high: height,
            },
        };
        Ok(Cone {
            equation,
            radius,
            height,
            k,
        })
    }

    /// a = dx² + dz² - k dy², b = 2(bx dx + bz dz - k by dy), c = bx² + bz² - k by²;
    /// smallest positive root with 0 <= y <= h. Along a generator a = 0 (linear case).
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        Accurate::axis_quadric(&self.equation, ray)
    }

    /// Local normal (2x, -2k y, 2z), turned back by `irot`; zero at the apex.
    #[inline]
    pub fn normal(&self, point: DVec3) -> DVec3 {
        self.equation.normal(point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cone() -> Cone {
        // Apex at the origin, opening up +y, radius 1 at height 1: x² + z² = y², k = 1.
        Cone::new(DVec3::ZERO, DVec3::Y, 1.0, 1.0).unwrap()
    }

    #[test]
    fn horizontal_ray_hits_where_the_radius_equals_the_height() {
        let ray = Ray {
            base: DVec3::new(-3.0, 0.5, 0.0),
            dir: DVec3::X,
        };
        assert_eq!(cone().hit(&ray), Some(2.5));
        let n = cone().normal(DVec3::new(-0.5, 0.5, 0.0));
        let expected = DVec3::new(-1.0, -1.0, 0.0) / 2f64.sqrt();
        assert!((n - expected).length() < 1e-15, "{n}");
    }

    #[test]
    fn ray_along_a_generator_is_linear_and_does_not_divide_by_zero() {
        // Direction (1, 1, 0)/√2 is parallel to the generator x = y: a = 0.
        let dir = DVec3::new(1.0, 1.0, 0.0) / 2f64.sqrt();
        let ray = Ray {
            base: DVec3::new(-1.0, 0.0, 0.0),
            dir,
        };
        // Then b = 2(bx dx - k by dy) = -√2 and c = bx² = 1, so t = -c/b = 1/√2: the point
        // (-0.5, 0.5, 0) of the generator x = -y.
        let t = cone().hit(&ray).unwrap();
        assert!((t - 0.5f64.sqrt()).abs() < 1e-15, "{t}");
    }

    #[test]
    fn the_lower_nappe_is_out_of_bounds() {
        let ray = Ray {
            base: DVec3::new(-3.0, -0.5, 0.0),
            dir: DVec3::X,
        };
        assert_eq!(cone().hit(&ray), None);
    }
}
