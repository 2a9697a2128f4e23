//! The finite plane (spec §5.3), a rectangle: code 15, and the geometry of the textured
//! plane (17). Built by
//!
//! ```text
//! 15            finite plane
//! 2 2 2         ambient
//! 7 6 0         diffuse
//! 0 0 0         specular
//! 1 0 1         normal
//! 4 -1 -4       point (lower-left corner)
//! 1 0.4 0       x direction
//! 7 3           size (width height)
//! ```

use super::kernel::{Accurate, Kernel};
use super::{Invalid, PlaneFrame, Ray, positive};
use crate::scene_file::layout::label;
use glam::{DVec2, DVec3};

/// A rectangle [0, width] x [0, height] of a plane frame, edges included.
#[derive(Debug, Clone, PartialEq)]
pub struct FinitePlane {
    /// The frame; its point is the lower-left corner.
    pub frame: PlaneFrame,
    /// Width and height, both > 0.
    pub size: DVec2,
}

impl FinitePlane {
    /// Builds the frame and validates the size.
    pub fn new(
        normal: DVec3,
        point: DVec3,
        xdir: DVec3,
        size: DVec2,
        record: &'static str,
    ) -> Result<FinitePlane, Invalid> {
        let frame = PlaneFrame::new(normal, point, xdir, record)?;
        positive(record, "width", label::SIZE, 0, size.x)?;
        positive(record, "height", label::SIZE, 1, size.y)?;
        Ok(FinitePlane { frame, size })
    }

    /// The box around the rectangle's four corners.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let origin = self.frame.plane.point;
        let x = self.frame.rot.row(0) * self.size.x;
        let y = self.frame.rot.row(1) * self.size.y;
        let corners = [origin, origin + x, origin + y, origin + x + y];
        let min = corners.into_iter().fold(DVec3::INFINITY, DVec3::min);
        let max = corners.into_iter().fold(DVec3::NEG_INFINITY, DVec3::max);
        (min, max)
    }

    /// The plane's hit, if q = rot (H - point) lies in the rectangle.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        self.hit_with::<Accurate>(ray)
    }

    /// [`FinitePlane::hit`] with the plane's t from kernel `K`.
    #[inline]
    pub fn hit_with<K: Kernel>(&self, ray: &Ray) -> Option<f64> {
        let t = K::plane(&self.frame.plane, ray)?;
        let q = self.frame.plane_xy(ray.base + t * ray.dir);
        let inside = (0.0..=self.size.x).contains(&q.x) && (0.0..=self.size.y).contains(&q.y);
        inside.then_some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_inside_the_rectangle_and_on_its_edge_only() {
        let plane = FinitePlane::new(
            DVec3::Z,
            DVec3::new(-1.0, -1.0, -4.0),
            DVec3::X,
            DVec2::new(2.0, 1.0),
            "finite plane",
        )
        .unwrap();
        let towards = |x: f64, y: f64| Ray {
            base: DVec3::new(x, y, 0.0),
            dir: DVec3::NEG_Z,
        };
        assert_eq!(plane.hit(&towards(0.0, -0.5)), Some(4.0));
        assert_eq!(plane.hit(&towards(1.0, 0.0)), Some(4.0));
        assert_eq!(plane.hit(&towards(1.5, -0.5)), None);
        assert_eq!(plane.hit(&towards(0.0, 0.5)), None);
    }

    #[test]
    fn size_must_be_positive() {
        let make = |w, h| {
            FinitePlane::new(
                DVec3::Z,
                DVec3::ZERO,
                DVec3::X,
                DVec2::new(w, h),
                "finite plane",
            )
        };
        assert_eq!(make(0.0, 1.0).unwrap_err().index, 0);
        assert_eq!(make(1.0, -1.0).unwrap_err().index, 1);
    }
}
