//! The local frame of the course's quadrics 21-24: `rotmat` turns the unit centre line to
//! +y and `irot` (its transpose) turns back (spec §5.6, note 003).

use super::{Invalid, Parameter, Ray, unit, unit_or_zero_error};
use glam::{DMat3, DVec3};

/// Centre point and rotation of an axis-aligned quadric.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisFrame {
    /// The point that becomes the local origin (base centre, vertex, apex or waist centre).
    pub centre: DVec3,
    /// The rotation, `None` when it is the identity (every sphere, and a centre line
    /// along +y): the hit test then skips the matrix products, and an unrotated frame
    /// takes 32 bytes instead of 176 (a million unrotated cylinders, 144 MB less).
    pub rotation: Option<Box<Rotation>>,
}

/// A frame's rotation and its inverse.
#[derive(Debug, Clone, PartialEq)]
pub struct Rotation {
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
        let c = unit_or_zero_error(centre_line, record, Parameter::CentreLine)?;
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
        let rotation = (irot != DMat3::IDENTITY).then(|| {
            Box::new(Rotation {
                rotmat: irot.transpose(),
                irot,
            })
        });
        Ok(AxisFrame { centre, rotation })
    }

    /// The frame of a sphere: its centre and no rotation.
    pub fn unrotated(centre: DVec3) -> AxisFrame {
        AxisFrame {
            centre,
            rotation: None,
        }
    }

    /// Rotation taking the unit centre line to +y (the identity for an unrotated frame).
    pub fn rotmat(&self) -> DMat3 {
        self.rotation.as_ref().map_or(DMat3::IDENTITY, |r| r.rotmat)
    }

    /// The inverse rotation (the identity for an unrotated frame).
    pub fn irot(&self) -> DMat3 {
        self.rotation.as_ref().map_or(DMat3::IDENTITY, |r| r.irot)
    }

    /// The ray in the local frame: B' = rotmat (B - C), D' = rotmat D.
    #[inline]
    pub fn to_local(&self, ray: &Ray) -> (DVec3, DVec3) {
        (self.point_to_local(ray.base), self.rotate(ray.dir))
    }

    /// A world point in the local frame.
    #[inline]
    pub fn point_to_local(&self, point: DVec3) -> DVec3 {
        self.rotate(point - self.centre)
    }

    /// rotmat v (v itself when the frame is unrotated).
    #[inline]
    pub fn rotate(&self, v: DVec3) -> DVec3 {
        match &self.rotation {
            None => v,
            Some(rotation) => rotation.rotmat * v,
        }
    }

    /// A local normal back in the world: unit(irot N'), or zero if N' is zero.
    #[inline]
    pub fn normal_to_world(&self, local_normal: DVec3) -> DVec3 {
        let world = match &self.rotation {
            None => local_normal,
            Some(rotation) => rotation.irot * local_normal,
        };
        unit(world).unwrap_or(DVec3::ZERO)
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
            assert_close(frame.rotmat() * (line / line.length()), DVec3::Y);
            assert!((frame.rotmat().determinant() - 1.0).abs() < 1e-15);
            let product = frame.rotmat() * frame.irot();
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
        assert_close(frame.rotmat() * DVec3::Z, DVec3::X);
    }

    #[test]
    fn zero_centre_line_is_an_error() {
        assert!(AxisFrame::new(DVec3::ZERO, DVec3::ZERO, "cone").is_err());
    }
}
