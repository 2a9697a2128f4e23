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

use super::kernel::Kernel;
use super::{HitNote, Invalid, Notes, Parameter, PlaneFrame, Ray, positive};
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
        positive(record, "width", size.x).map_err(Parameter::Width.refuses())?;
        positive(record, "height", size.y).map_err(Parameter::Height.refuses())?;
        Ok(FinitePlane { frame, size })
    }

    /// The box around the rectangle's four corners.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let origin = self.frame.plane.point;
        let (x, y) = self.frame.edges(self.size);
        let corners = [origin, origin + x, origin + y, origin + x + y];
        let min = corners.into_iter().fold(DVec3::INFINITY, DVec3::min);
        let max = corners.into_iter().fold(DVec3::NEG_INFINITY, DVec3::max);
        (min, max)
    }

    /// The plane's hit (spec §5.1) with kernel `K`, if q = rot (H - point) lies in the
    /// rectangle, edges included (spec §5.3); `notes` are told why.
    #[inline(always)]
    pub(crate) fn hit<K: Kernel>(&self, ray: &Ray, notes: &mut impl Notes) -> Option<f64> {
        let t = K::plane(&self.frame.plane, ray, notes)?;
        let q = self.frame.plane_xy(ray.base + t * ray.dir);
        let inside = (0.0..=self.size.x).contains(&q.x) && (0.0..=self.size.y).contains(&q.y);
        notes.note(HitNote::Rectangle { q, inside });
        inside.then_some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::testing::*;

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
        let towards = |x: f64, y: f64| Ray::new(DVec3::new(x, y, 0.0), DVec3::NEG_Z);
        assert_eq!(
            plane.hit::<Accurate>(&towards(0.0, -0.5), &mut ()),
            Some(4.0)
        );
        assert_eq!(
            plane.hit::<Accurate>(&towards(1.0, 0.0), &mut ()),
            Some(4.0)
        );
        assert_eq!(plane.hit::<Accurate>(&towards(1.5, -0.5), &mut ()), None);
        assert_eq!(plane.hit::<Accurate>(&towards(0.0, 0.5), &mut ()), None);
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
        assert_eq!(make(0.0, 1.0).unwrap_err().parameter, Parameter::Width);
        assert_eq!(make(1.0, -1.0).unwrap_err().parameter, Parameter::Height);
    }
}
