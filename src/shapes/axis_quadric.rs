//! The one equation behind the sphere and the course quadrics 21-24: in the shape's local
//! frame (spec §5.6), with L = rotmat (P - C),
//!
//! ```text
//! f(L) = αx Lx² + αy Ly² + αz Lz² + β Ly + γ = 0
//! ```
//!
//! | shape                 | αx | αy | αz | β  | γ    | bounds on Ly       |
//! |-----------------------|----|----|----|----|------|--------------------|
//! | sphere (13, 19)       | 1  | 1  | 1  | 0  | -r²  | none, nearer root  |
//! | paraboloid (21)       | 1  | 0  | 1  | -k | 0    | 0 <= Ly <= h       |
//! | cylinder (22)         | 1  | 0  | 1  | 0  | -r²  | 0 <= Ly <= h       |
//! | cone (23)             | 1  | -k | 1  | 0  | 0    | 0 <= Ly <= h       |
//! | hyperboloid (24)      | 1  | -k | 1  | 0  | -rc² | -h <= Ly <= h      |
//!
//! A ray L = B' + t D' turns it into a t² + b t + c = 0 with
//! a = Σ αᵢ D'ᵢ², b = 2 Σ αᵢ B'ᵢ D'ᵢ + β D'y, c = f(B'): exactly the coefficients that
//! note 003 writes out shape by shape. The kernels in [`super::kernel`] solve it.

use super::AxisFrame;
use glam::DVec3;

/// How a root is chosen (spec §5.2 and §5.6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RootRule {
    /// The sphere: the smaller root, even when negative, if the discriminant is > 0.
    Nearer,
    /// The quadrics 21-24: the smallest positive root whose local y lies in
    /// `[low, high]`; a zero discriminant counts.
    FirstPositiveWithin {
        /// Lowest local y.
        low: f64,
        /// Highest local y.
        high: f64,
    },
}

/// A quadric of the form above, with its frame and root rule.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisQuadric {
    /// Centre point and rotation (the identity for a sphere).
    pub frame: AxisFrame,
    /// (αx, αy, αz).
    pub square: DVec3,
    /// β, the coefficient of Ly.
    pub linear_y: f64,
    /// γ.
    pub constant: f64,
    /// Which root counts.
    pub rule: RootRule,
}

impl AxisQuadric {
    /// f at a local point, in f64.
    #[inline]
    pub fn value(&self, local: DVec3) -> f64 {
        (self.square * local).dot(local) + self.linear_y * local.y + self.constant
    }

    /// a, b, c of the quadratic along the local ray B' + t D', written as note 003 does.
    #[inline]
    pub fn coefficients(&self, base: DVec3, dir: DVec3) -> (f64, f64, f64) {
        let weighted = self.square * dir;
        (
            weighted.dot(dir),
            2.0 * weighted.dot(base) + self.linear_y * dir.y,
            self.value(base),
        )
    }

    /// The unit world normal at a world point: ∇f in the local frame, turned back by
    /// `irot` and normalised (zero at a cone's apex, where ∇f = 0). For the sphere it is
    /// unit(P - C); for the cylinder unit(x, 0, z); the paraboloid (2x, -k, 2z); the cone
    /// and hyperboloid (2x, -2k y, 2z), all in local coordinates (note 003).
    #[inline]
    pub fn normal(&self, point: DVec3) -> DVec3 {
        let frame = &self.frame;
        frame.normal_to_world(self.gradient(frame.point_to_local(point)))
    }

    /// The local gradient ∇f = (2αx Lx, 2αy Ly + β, 2αz Lz).
    #[inline]
    pub fn gradient(&self, local: DVec3) -> DVec3 {
        let mut gradient = 2.0 * self.square * local;
        gradient.y += self.linear_y;
        gradient
    }

    /// An axis-aligned world box that holds every hit this shape can report, or `None`
    /// if the equation is not one of the closed forms above (for the BVH of
    /// `src/render/bvh.rs`). Locally the shape lies within y in its bounds (the sphere:
    /// ±r) and within the largest radius it reaches there; the box holds that cylinder's
    /// eight corners turned back to the world.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let DVec3 {
            x: ax,
            y: ay,
            z: az,
        } = self.square;
        if ax <= 0.0 || ax != az {
            return None;
        }
        let (low, high) = match self.rule {
            RootRule::Nearer if ay == ax && self.linear_y == 0.0 => {
                let r = (-self.constant / ax).sqrt();
                (-r, r)
            }
            RootRule::Nearer => return None,
            RootRule::FirstPositiveWithin { low, high } => (low, high),
        };
        // The squared radius at height y, x² + z² = -(αy y² + β y + γ) / αx, is largest
        // at an end of [low, high] or at its vertex.
        let radius_sq = |y: f64| -(ay * y * y + self.linear_y * y + self.constant) / ax;
        let mut largest = radius_sq(low).max(radius_sq(high));
        if ay != 0.0 {
            largest = largest.max(radius_sq((-self.linear_y / (2.0 * ay)).clamp(low, high)));
        }
        let r = largest.max(0.0).sqrt();
        if !(r.is_finite() && low.is_finite() && high.is_finite()) {
            return None;
        }
        let mut min = DVec3::splat(f64::INFINITY);
        let mut max = DVec3::splat(f64::NEG_INFINITY);
        for corner in 0..8 {
            let pick = |bit: usize, a: f64, b: f64| if corner & bit == 0 { a } else { b };
            let local = DVec3::new(pick(1, -r, r), pick(2, low, high), pick(4, -r, r));
            let world = self.frame.irot * local + self.frame.centre;
            min = min.min(world);
            max = max.max(world);
        }
        Some((min, max))
    }
}
