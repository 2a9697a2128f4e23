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
//!
//! Its hit is note 003's algorithm (`src/shapes/kernel/textbook.rs`, and the shipped
//! kernel's own arithmetic, under the rule [`RootRule`](super::RootRule)), on the cylinder's row:
//! a = dx² + dz², b = 2(bx dx + bz dz), c = bx² + bz² - r², the smallest positive root
//! with 0 <= y <= h. Its normal ([`AxisQuadric::normal`]) is the local (x, 0, z), turned
//! back by `irot`.

use super::{AxisQuadric, Invalid, Size};
use glam::DVec3;

/// A cylinder with its frame and r² precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct Cylinder {
    /// x² + z² - r² = 0 for 0 <= y <= h, with the frame (base centre, `rotmat`, `irot`).
    pub equation: AxisQuadric,
    /// Radius and height.
    pub size: Size,
}

impl Cylinder {
    /// Validates radius and height, builds the frame: x² + z² - r² = 0 for 0 <= y <= h.
    pub fn new(base: DVec3, centre_line: DVec3, radius: f64, height: f64) -> Result<Self, Invalid> {
        let (frame, size) =
            AxisQuadric::measure("cylinder", base, centre_line, (radius, height), "height")?;
        let equation = AxisQuadric::from_base(frame, size, 0.0, 0.0, -(size.radius * size.radius));
        Ok(Cylinder { equation, size })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::testing::*;

    fn cylinder() -> Cylinder {
        // Note 003's example: base (4, 3, -4), axis +x, radius 2, height 5.
        Cylinder::new(DVec3::new(4.0, 3.0, -4.0), DVec3::X, 2.0, 5.0).unwrap()
    }

    #[test]
    fn ray_across_the_axis_hits_the_near_wall() {
        let ray = Ray::new(DVec3::new(6.0, 3.0, 0.0), DVec3::NEG_Z);
        // The wall is at z = -4 + 2 = -2.
        assert_eq!(hit(&cylinder().equation, &ray), Some(2.0));
        let normal = cylinder().equation.normal(DVec3::new(6.0, 3.0, -2.0));
        assert!((normal - DVec3::Z).length() < 1e-15, "{normal}");
    }

    #[test]
    fn out_of_bounds_and_axis_parallel_rays_miss() {
        let beyond = Ray::new(DVec3::new(9.5, 3.0, 0.0), DVec3::NEG_Z);
        assert_eq!(hit(&cylinder().equation, &beyond), None);
        // Parallel to the axis: a = 0 and b = 0, no root and no division by zero.
        let inside_parallel = Ray::new(DVec3::new(0.0, 3.0, -4.0), DVec3::X);
        assert_eq!(hit(&cylinder().equation, &inside_parallel), None);
    }

    #[test]
    fn from_inside_the_far_wall_is_hit() {
        let ray = Ray::new(DVec3::new(5.0, 3.0, -4.0), DVec3::Y);
        assert_eq!(hit(&cylinder().equation, &ray), Some(2.0));
    }
}
