//! The finite circular paraboloid, code 21 (spec §5.6; note 003). Built by
//!
//! ```text
//! 21            paraboloid
//! 0.2 0.2 0.2   ambient
//! 2.0 2.0 2.0   diffuse
//! 1.0 1.0 1.0   specular
//! 4 3 -4        vertex
//! 1 0 0         centre line
//! 2 5           radius at the top and height
//! ```
//! Local frame: axis +y, vertex at the origin; surface x² + z² = k y with k = r²/h.
//!
//! Its hit is note 003's algorithm (`src/shapes/kernel/textbook.rs`, and the shipped
//! kernel's own arithmetic, under the rule [`RootRule`](super::RootRule)), on the paraboloid's row:
//! a = dx² + dz², b = 2(bx dx + bz dz) - k dy, c = bx² + bz² - k by, the smallest
//! positive root with 0 <= y <= h; along the axis a = 0 and the equation is linear. Its
//! normal ([`AxisQuadric::normal`]) is the local (2x, -k, 2z), turned back by `irot`.

use super::{AxisQuadric, Invalid, Size};
use glam::DVec3;

/// A paraboloid with its frame and scale k = r²/h.
#[derive(Debug, Clone, PartialEq)]
pub struct Paraboloid {
    /// x² + z² - k y = 0 for 0 <= y <= h, with the frame (vertex, `rotmat`, `irot`).
    pub equation: AxisQuadric,
    /// Radius at y = h, and height.
    pub size: Size,
}

impl Paraboloid {
    /// Validates radius and height, builds the frame and k: x² + z² - k y = 0 for
    /// 0 <= y <= h.
    pub fn new(
        vertex: DVec3,
        centre_line: DVec3,
        radius: f64,
        height: f64,
    ) -> Result<Self, Invalid> {
        let (frame, size) = AxisQuadric::measure(
            "paraboloid",
            vertex,
            centre_line,
            (radius, height),
            "height",
        )?;
        let k = size.radius * size.radius / size.height;
        let equation = AxisQuadric::from_base(frame, size, 0.0, -k, 0.0);
        Ok(Paraboloid { equation, size })
    }

    /// k = r²/h (note 003's `parab->scale`), the -β of its equation.
    pub fn k(&self) -> f64 {
        -self.equation.linear_y
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::testing::*;

    fn bowl() -> Paraboloid {
        // Vertex at the origin opening up +y: k = 4 / 4 = 1, so x² + z² = y.
        Paraboloid::new(DVec3::ZERO, DVec3::Y, 2.0, 4.0).unwrap()
    }

    #[test]
    fn scale_is_r_squared_over_h() {
        assert_eq!(bowl().k(), 1.0);
    }

    #[test]
    fn ray_down_the_axis_meets_the_vertex_through_the_linear_case() {
        let ray = Ray::new(DVec3::new(0.0, 3.0, 0.0), DVec3::NEG_Y);
        assert_eq!(hit(&bowl().equation, &ray), Some(3.0));
        let normal = bowl().equation.normal(DVec3::ZERO);
        assert_eq!(normal, DVec3::NEG_Y);
    }

    #[test]
    fn horizontal_ray_hits_where_x_squared_is_y() {
        // At y = 1 the radius is 1: from x = -5 the wall is 4 away.
        let ray = Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::X);
        assert_eq!(hit(&bowl().equation, &ray), Some(4.0));
        // Above the rim (y = 4.5 > h) it misses.
        let high = Ray::new(DVec3::new(-5.0, 4.5, 0.0), DVec3::X);
        assert_eq!(hit(&bowl().equation, &high), None);
    }
}
