//! The local frame of the course's quadrics 21-24: `rotmat` turns the unit centre line to
//! +y and `irot` (its transpose) turns back (spec §5.6, note 003).

use super::{Invalid, Ray, unit, unit_or_zero_error};
use crate::scene_file::layout::label;
use glam::{DMat3, DVec3};

/// Centre point and rotation of an axis-aligned quadric.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisFrame {
    /// The point that becomes the local origin (base centre, vertex, apex or waist centre).
    pub centre: DVec3,
    /// Rotation taking the unit centre line to +y.
    pub rotmat: DMat3,
    /// The inverse rotation, `rotmat` transposed.
    pub irot: DMat3,
}

impl AxisFrame {
    /// Builds `rotmat` and `irot` for a centre line (any nonzero length).
    pub fn new(
        centre: DVec3,
        centre_line: DVec3,
        record: &'static str,
    ) -> Result<AxisFrame, Invalid> {
        let c = unit_or_zero_error(centre_line, record, label::CENTRE_LINE)?;
        let rows = if c.x == 0.0 && c.z == 0.0 {
            if c.y > 0.0 {
                [DVec3::X, DVec3::Y, DVec3::Z]
            } else {
                // Upside down: any rotation taking -y to +y serves (spec §5.6).
                [DVec3::Z, DVec3::NEG_Y, DVec3::X]
            }
        } else {
            // Row 0 is the unit vector orthogonal to the centre line and +y, which the
            // rotation takes to +x (note 003); row 2 completes a right-handed frame.
            let row0 = unit(c.cross(DVec3::Y)).expect("c is not parallel to y");
            [row0, c, row0.cross(c)]
        };
        let irot = DMat3::from_cols(rows[0], rows[1], rows[2]);
        Ok(AxisFrame {
            centre,
            rotmat: irot.transpose(),
            irot,
        })
    }

    /// The ray in the local frame: B' = rotmat (B - C), D' = rotmat D.
    #[inline]
    pub fn to_local(&self, ray: &Ray) -> (DVec3, DVec3) {
        (
            self.rotmat * (ray.base - self.centre),
            self.rotmat * ray.dir,
        )
    }

    /// A world point in the local frame.
    #[inline]
    pub fn point_to_local(&self, point: DVec3) -> DVec3 {
        self.rotmat * (point - self.centre)
    }

    /// A local normal back in the world: unit(irot N'), or zero if N' is zero.
    #[inline]
    pub fn normal_to_world(&self, local_normal: DVec3) -> DVec3 {
        unit(self.irot * local_normal).unwrap_or(DVec3::ZERO)
    }

    /// a, b, c for the local ray (b, d) against x² + z² = k y² + rc²: the hyperboloid of
    /// note 003, and with rc² = 0 its cone.
    #[inline]
    pub fn cone_quadratic(b: DVec3, d: DVec3, k: f64, waist_sq: f64) -> (f64, f64, f64) {
        (
            d.x * d.x + d.z * d.z - k * d.y * d.y,
            2.0 * (b.x * d.x + b.z * d.z - k * b.y * d.y),
            b.x * b.x + b.z * b.z - k * b.y * b.y - waist_sq,
        )
    }

    /// The world normal of x² + z² = k y² + rc² at a world point: local (2x, -2k y, 2z)
    /// turned back by `irot` (zero at a cone's apex).
    #[inline]
    pub fn cone_normal(&self, point: DVec3, k: f64) -> DVec3 {
        let p = self.point_to_local(point);
        self.normal_to_world(DVec3::new(2.0 * p.x, -2.0 * k * p.y, 2.0 * p.z))
    }

    /// The smallest positive root whose local y lies in `[low, high]` (spec §5.6).
    #[inline]
    pub fn first_in_bounds(
        roots: super::Roots,
        base_y: f64,
        dir_y: f64,
        low: f64,
        high: f64,
    ) -> Option<f64> {
        let roots = roots?;
        roots.into_iter().find(|&t| {
            let y = base_y + t * dir_y;
            t > 0.0 && (low..=high).contains(&y)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_close(a: DVec3, b: DVec3) {
        assert!((a - b).length() < 1e-15, "{a} != {b}");
    }

    #[test]
    fn rotmat_takes_the_centre_line_to_plus_y_and_is_a_rotation() {
        for line in [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, -3.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, 2.0, -2.0),
            DVec3::new(-1e-200, 1.0, 0.0),
        ] {
            let frame = AxisFrame::new(DVec3::ZERO, line, "cylinder").unwrap();
            assert_close(frame.rotmat * (line / line.length()), DVec3::Y);
            assert!((frame.rotmat.determinant() - 1.0).abs() < 1e-15);
            let product = frame.rotmat * frame.irot;
            for (col, unit_col) in [product.x_axis, product.y_axis, product.z_axis]
                .into_iter()
                .zip([DVec3::X, DVec3::Y, DVec3::Z])
            {
                assert_close(col, unit_col);
            }
        }
    }

    #[test]
    fn note_003_rotates_the_orthogonal_vector_to_plus_x() {
        // Centre line +x: c × y = +z, so rotmat takes +z to +x.
        let frame = AxisFrame::new(DVec3::ZERO, DVec3::X, "cylinder").unwrap();
        assert_close(frame.rotmat * DVec3::Z, DVec3::X);
    }

    #[test]
    fn zero_centre_line_is_an_error() {
        assert!(AxisFrame::new(DVec3::ZERO, DVec3::ZERO, "cone").is_err());
    }
}
