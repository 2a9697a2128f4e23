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
    /// Rows: unit x direction in the plane, n × x, n; and what the x direction's
    /// projection kept. Boxed: a hit test reads only the plane, and the tiled plane's
    /// frame then takes 64 bytes in place, 8 more than a plane (boxing the whole frame
    /// instead cost spec1 1.6 % more instructions).
    pub local_from_world: Box<FrameRows>,
}

/// The rows of a plane frame's rotation, and the length that projecting the unit x
/// direction into the plane left it (spec §5.3): the scale of the frame a program gets
/// that uses unit(xdir) as given (`tile-unprojected`, spec §7.5).
#[derive(Debug, Clone, PartialEq)]
pub struct FrameRows {
    /// Rows: x, n × x, n (under tile-unprojected the first two times `in_plane`).
    pub rot: DMat3,
    /// |x - (n·x) n| for x = unit(xdir): 1 where the x direction lies in the plane.
    pub in_plane: f64,
    /// Whether the first two rows are scaled by `in_plane` (tile-unprojected).
    pub unprojected: bool,
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
        let length = in_plane.length();
        let x = unit(in_plane).ok_or(parallel)?;
        let rot = DMat3::from_cols(x, n.cross(x), n).transpose();
        Ok(PlaneFrame {
            plane,
            local_from_world: Box::new(FrameRows {
                rot,
                in_plane: length,
                unprojected: false,
            }),
        })
    }

    /// (q.x, q.y) of a point of the plane.
    #[inline]
    pub fn plane_xy(&self, point: DVec3) -> DVec2 {
        (self.local_from_world.rot * (point - self.plane.point)).truncate()
    }

    /// The frame of unit(xdir) used as given, not projected into the plane
    /// (`tile-unprojected`, spec §7.5): x·d = (x - (n·x) n)·d for d in the plane, so
    /// (q.x, q.y) are the projected frame's times |x - (n·x) n|.
    pub fn unproject(&mut self) {
        let rows = &mut *self.local_from_world;
        if !rows.unprojected {
            let [x, y, n] = [0, 1, 2].map(|k| rows.rot.row(k));
            let k = rows.in_plane;
            rows.rot = DMat3::from_cols(x * k, y * k, n).transpose();
            rows.unprojected = true;
        }
    }

    /// The world vectors from the origin along q.x and q.y by `size`: the rows times
    /// the size, or over the square of their scale when unprojected.
    pub fn edges(&self, size: DVec2) -> (DVec3, DVec3) {
        let rows = &*self.local_from_world;
        let [x, y] = [0, 1].map(|k| rows.rot.row(k));
        match rows.unprojected {
            false => (x * size.x, y * size.y),
            true => {
                let k2 = rows.in_plane * rows.in_plane;
                (x * (size.x / k2), y * (size.y / k2))
            }
        }
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
