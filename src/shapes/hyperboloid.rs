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
//!
//! Its hit is note 003's algorithm (`src/shapes/kernel/textbook.rs`, and the shipped
//! kernel's own arithmetic, under the rule [`RootRule`](super::RootRule)), on the hyperboloid's row:
//! a = dx² + dz² - k dy², b = 2(bx dx + bz dz - k by dy), c = bx² + bz² - k by² - rc²,
//! the smallest positive root with -h <= y <= h. Its normal ([`AxisQuadric::normal`]) is
//! the local (2x, -2k y, 2z), turned back by `irot`.

use super::{AxisQuadric, Invalid, Parameter, RootRule, Size};
use crate::error::MeaningError;
use glam::DVec3;

/// A hyperboloid with its frame, k and rc² precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct Hyperboloid {
    /// x² - k y² + z² - rc² = 0 for -h <= y <= h, with the frame (waist centre, `rotmat`,
    /// `irot`).
    pub equation: AxisQuadric,
    /// Radius at y = ±h, and the half-height h.
    pub size: Size,
    /// Waist radius rc, >= 0.
    pub waist: f64,
}

impl Hyperboloid {
    /// Validates the radii and half-height, builds the frame and k:
    /// x² - k y² + z² - rc² = 0 for -h <= y <= h.
    pub fn new(
        centre: DVec3,
        centre_line: DVec3,
        radius: f64,
        half_height: f64,
        waist: f64,
    ) -> Result<Self, Invalid> {
        let record = "hyperboloid";
        let measures = (radius, half_height);
        let (frame, size) =
            AxisQuadric::measure(record, centre, centre_line, measures, "half-height")?;
        if waist < 0.0 {
            let error = MeaningError::NegativeWaist { value: waist };
            return Err(Parameter::Waist.refuses()(error));
        }
        let (r, h) = (size.radius, size.height);
        let k = (r * r - waist * waist) / (h * h);
        let equation = AxisQuadric::new(frame, -k, 0.0, -(waist * waist), RootRule::within(-h, h));
        Ok(Hyperboloid {
            equation,
            size,
            waist,
        })
    }

    /// k = (r² - rc²)/h² (negative when the waist is wider than the ends), the -αy of
    /// its equation.
    pub fn k(&self) -> f64 {
        -self.equation.alpha.y
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::testing::*;

    fn hyperboloid() -> Hyperboloid {
        // Ends of radius √2 at y = ±1, waist 1: k = (2 - 1)/1 = 1, x² + z² = y² + 1.
        Hyperboloid::new(DVec3::ZERO, DVec3::Y, 2f64.sqrt(), 1.0, 1.0).unwrap()
    }

    #[test]
    fn waist_is_hit_at_its_radius() {
        let ray = Ray::new(DVec3::new(-4.0, 0.0, 0.0), DVec3::X);
        assert_eq!(hit(&hyperboloid().equation, &ray), Some(3.0));
        assert_eq!(
            hyperboloid().equation.normal(DVec3::new(-1.0, 0.0, 0.0)),
            DVec3::NEG_X
        );
    }

    #[test]
    fn at_height_one_the_radius_is_root_two_and_beyond_the_ends_it_misses() {
        let ray = Ray::new(DVec3::new(-4.0, -1.0, 0.0), DVec3::X);
        let t = hit(&hyperboloid().equation, &ray).unwrap();
        assert!((t - (4.0 - 2f64.sqrt())).abs() < 1e-15, "{t}");
        let beyond = Ray::new(DVec3::new(-4.0, 1.5, 0.0), DVec3::X);
        assert_eq!(hit(&hyperboloid().equation, &beyond), None);
    }

    #[test]
    fn negative_waist_is_an_error_and_zero_is_a_double_cone() {
        let error = Hyperboloid::new(DVec3::ZERO, DVec3::Y, 1.0, 1.0, -0.5).unwrap_err();
        assert_eq!(error.parameter, Parameter::Waist);
        let cone = Hyperboloid::new(DVec3::ZERO, DVec3::Y, 1.0, 1.0, 0.0).unwrap();
        assert_eq!(cone.k(), 1.0);
    }
}
