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
//!
//! Its hit is note 003's algorithm (`src/shapes/kernel/textbook.rs`, and the shipped
//! kernel's own arithmetic, under the rule [`RootRule`](super::RootRule)), on the cone's row:
//! a = dx² + dz² - k dy², b = 2(bx dx + bz dz - k by dy), c = bx² + bz² - k by², the
//! smallest positive root with 0 <= y <= h; along a generator a = 0 (the linear case).
//! Its normal ([`AxisQuadric::normal`]) is the local (2x, -2k y, 2z), turned back by
//! `irot`; zero at the apex.

use super::{AxisFrame, AxisQuadric, Invalid, Size};
use glam::DVec3;

/// A cone with its frame and scale k = (r/h)².
#[derive(Debug, Clone, PartialEq)]
pub struct Cone {
    /// x² - k y² + z² = 0 for 0 <= y <= h, with the frame (apex, `rotmat`, `irot`).
    pub equation: AxisQuadric,
    /// Radius at y = h, and height.
    pub size: Size,
}

impl Cone {
    /// Validates radius and height, builds the frame and k: x² - k y² + z² = 0 for
    /// 0 <= y <= h.
    pub fn new(apex: DVec3, centre_line: DVec3, radius: f64, height: f64) -> Result<Self, Invalid> {
        let (frame, size) =
            AxisQuadric::measure("cone", apex, centre_line, (radius, height), "height")?;
        let slope = size.radius / size.height;
        Ok(Cone::with_k(frame, size, slope * slope))
    }

    /// The cone x² - k y² + z² = 0 for 0 <= y <= h with a given k: (r/h)² for the course's
    /// cone, r²/h under the variant cone-scale (spec §7.3).
    pub fn with_k(frame: AxisFrame, size: Size, k: f64) -> Self {
        let equation = AxisQuadric::from_base(frame, size, -k, 0.0, 0.0);
        Cone { equation, size }
    }

    /// k = (r/h)², the -αy of its equation.
    pub fn k(&self) -> f64 {
        -self.equation.alpha.y
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::testing::*;

    fn cone() -> Cone {
        // Apex at the origin, opening up +y, radius 1 at height 1: x² + z² = y², k = 1.
        Cone::new(DVec3::ZERO, DVec3::Y, 1.0, 1.0).unwrap()
    }

    #[test]
    fn horizontal_ray_hits_where_the_radius_equals_the_height() {
        let ray = Ray::new(DVec3::new(-3.0, 0.5, 0.0), DVec3::X);
        assert_eq!(hit(&cone().equation, &ray), Some(2.5));
        let n = cone().equation.normal(DVec3::new(-0.5, 0.5, 0.0));
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
        let t = hit(&cone().equation, &ray).unwrap();
        assert!((t - 0.5f64.sqrt()).abs() < 1e-15, "{t}");
    }

    #[test]
    fn the_lower_nappe_is_out_of_bounds() {
        let ray = Ray::new(DVec3::new(-3.0, -0.5, 0.0), DVec3::X);
        assert_eq!(hit(&cone().equation, &ray), None);
    }
}
