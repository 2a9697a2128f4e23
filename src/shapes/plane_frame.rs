//! The frame of the finite, tiled and textured planes (spec §5.3): rows x, n × x, n, with
//! x the x direction projected into the plane. `q = rot (H - point)` gives in-plane
//! coordinates of a hit.

use super::{Invalid, Parameter, Plane, unit, unit_or_zero_error};
use crate::error::MeaningError;
use glam::{DMat3, DVec2, DVec3};

/// An infinite plane with an in-plane coordinate frame.
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneFrame {
    /// The plane (unit normal, point = the frame's origin, the lower-left corner).
    pub plane: Plane,
    /// Rows: unit x direction in the plane, n × x, n. Boxed: a hit test reads only the
    /// plane, and the tiled plane's frame then takes 64 bytes in place, 8 more than a
    /// plane (boxing the whole frame instead cost spec1 1.6 % more instructions).
    pub local_from_world: Box<DMat3>,
}

impl PlaneFrame {
    /// Normalises the normal, projects `xdir` into the plane; errors for zero vectors and
    /// for an x direction parallel to the normal.
    pub fn new(
        normal: DVec3,
        point: DVec3,
        xdir: DVec3,
        record: &'static str,
    ) -> Result<PlaneFrame, Invalid> {
        let plane = Plane::new(normal, point, record)?;
        let n = plane.normal;
        let x = unit_or_zero_error(xdir, record, Parameter::XDirection)?;
        let in_plane = x - n.dot(x) * n;
        // |in_plane| is the sine of the angle between x and n; below 1e-12 the direction
        // in the plane is rounding noise, so the pair is treated as parallel.
        let parallel = Invalid {
            parameter: Parameter::XDirection,
            error: MeaningError::XdirParallel { record },
        };
        if in_plane.length() < 1e-12 {
            return Err(parallel);
        }
        let x = unit(in_plane).ok_or(parallel)?;
        let rot = DMat3::from_cols(x, n.cross(x), n).transpose();
        Ok(PlaneFrame {
            plane,
            local_from_world: Box::new(rot),
        })
    }

    /// (q.x, q.y) of a point of the plane.
    #[inline]
    pub fn plane_xy(&self, point: DVec3) -> DVec2 {
        (*self.local_from_world * (point - self.plane.point)).truncate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn x_direction_is_projected_into_the_plane() {
        // spec1's floor: normal +y, grid direction (1, 0, 1).
        let frame = PlaneFrame::new(
            DVec3::Y,
            DVec3::new(0.0, -4.0, 0.0),
            DVec3::new(1.0, 0.0, 1.0),
            "tiled plane",
        )
        .unwrap();
        let s = 0.5f64.sqrt();
        let q = frame.plane_xy(DVec3::new(1.0, -4.0, 1.0));
        assert!((q - DVec2::new(2.0 * s, 0.0)).length() < 1e-15, "{q}");
        // n × x = y × (s, 0, s) = (s, 0, -s).
        let q = frame.plane_xy(DVec3::new(s, -4.0, -s));
        assert!((q - DVec2::new(0.0, 1.0)).length() < 1e-15, "{q}");
    }

    #[test]
    fn x_direction_along_the_normal_is_an_error() {
        let error = PlaneFrame::new(DVec3::Z, DVec3::ZERO, DVec3::new(0.0, 0.0, -2.0), "p");
        assert_eq!(error.unwrap_err().parameter, Parameter::XDirection);
        assert!(PlaneFrame::new(DVec3::Z, DVec3::ZERO, DVec3::ZERO, "p").is_err());
    }
}
