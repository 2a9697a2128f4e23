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
//! note 003 writes out shape by shape ([`coefficients`]). The kernels of
//! `src/shapes/kernel/` solve it, each in its own arithmetic; the rule that picks the
//! root (spec §5.2, §5.6) is [`RootRule`]'s, shared by them all.

use super::{AxisFrame, HitNote, Invalid, Notes, Parameter, Verdict, positive};
use glam::DVec3;
use num_traits::Float;

/// The size of a quadric 21-24 as its record gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    /// The radius at the open end (at y = ±h for the hyperboloid), > 0.
    pub radius: f64,
    /// The height h (the hyperboloid's half-height), > 0.
    pub height: f64,
}

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
    /// The variant nearer-root (spec §7.3): the smaller root only, if it is positive and
    /// within `[low, high]`; the other root is never tried.
    SmallerWithin {
        /// Lowest local y.
        low: f64,
        /// Highest local y.
        high: f64,
    },
    /// The variant behind-root (spec §7.5): the smaller root within `[low, high]` even
    /// when it is <= 0, which then is no hit (spec §4.6): a ray whose base is inside the
    /// surface misses it.
    SmallerEvenBehind {
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
    /// The coefficients (αx, αy, αz) of Lx², Ly², Lz².
    pub alpha: DVec3,
    /// β, the coefficient of Ly.
    pub linear_y: f64,
    /// γ, the constant term.
    pub constant: f64,
    /// Which root counts.
    pub rule: RootRule,
}

impl RootRule {
    /// The quadrics' rule with bounds `low <= y <= high`.
    pub fn within(low: f64, high: f64) -> RootRule {
        RootRule::FirstPositiveWithin { low, high }
    }

    /// The bounds of local y, (-∞, ∞) for the sphere.
    #[inline(always)]
    pub fn bounds(self) -> (f64, f64) {
        match self {
            RootRule::Nearer => (f64::NEG_INFINITY, f64::INFINITY),
            RootRule::FirstPositiveWithin { low, high }
            | RootRule::SmallerWithin { low, high }
            | RootRule::SmallerEvenBehind { low, high } => (low, high),
        }
    }

    /// Whether a root at distance `t` whose point has local y `y` counts: in front of the
    /// base and within the bounds, or within `slack()` of them (a kernel's allowance for
    /// the rounding of y, computed only when y is outside).
    #[inline(always)]
    pub fn accepts(self, t: f64, y: f64, slack: impl FnOnce() -> f64) -> bool {
        match self {
            RootRule::Nearer => true,
            RootRule::FirstPositiveWithin { low, high }
            | RootRule::SmallerWithin { low, high }
            | RootRule::SmallerEvenBehind { low, high } => {
                let within = |slack: f64| low - slack <= y && y <= high + slack;
                t > 0.0 && (within(0.0) || within(slack()))
            }
        }
    }

    /// Note 003's choice among the two real roots, ascending: "if the y of the hit is out
    /// of bounds, try the other root" (spec §5.6), and under nearer-root the smaller one
    /// only. `judge(index, root)` gives a root's t, local y and whether it counts, in the
    /// kernel's arithmetic; each is told to `notes` with its verdict.
    #[inline(always)]
    pub(crate) fn first_within<R>(
        self,
        roots: [R; 2],
        mut judge: impl FnMut(usize, R) -> (f64, f64, bool),
        notes: &mut impl Notes,
    ) -> Option<f64> {
        for (index, root) in roots.into_iter().enumerate() {
            let (t, y, counts) = judge(index, root);
            let verdict = match counts {
                true => Verdict::Counts,
                false if t <= 0.0 => Verdict::Behind,
                false => Verdict::OutOfBounds,
            };
            notes.note(HitNote::Root { t, y, verdict });
            if counts {
                return Some(t);
            }
            match self {
                RootRule::SmallerWithin { .. } => return None,
                // The first root in bounds is taken, and behind the base it is no hit.
                RootRule::SmallerEvenBehind { low, high } if low <= y && y <= high => return None,
                _ => {}
            }
        }
        None
    }
}

impl AxisQuadric {
    /// x² + αy y² + z² + β y + γ = 0 in `frame` under `rule`: every row of the table has
    /// αx = αz = 1.
    pub fn new(frame: AxisFrame, alpha_y: f64, beta: f64, gamma: f64, rule: RootRule) -> Self {
        AxisQuadric {
            frame,
            alpha: DVec3::new(1.0, alpha_y, 1.0),
            linear_y: beta,
            constant: gamma,
            rule,
        }
    }

    /// A quadric open at both ends between y = 0 and y = h (21, 22, 23), the `size`'s
    /// height.
    pub(crate) fn from_base(
        frame: AxisFrame,
        size: Size,
        alpha_y: f64,
        beta: f64,
        gamma: f64,
    ) -> Self {
        AxisQuadric::new(
            frame,
            alpha_y,
            beta,
            gamma,
            RootRule::within(0.0, size.height),
        )
    }

    /// The frame and size that every record 21-24 starts from: the frame from the first
    /// point and the centre line, and a radius and a height (the hyperboloid's
    /// half-height, named so by `height_name`) that must be positive.
    pub(crate) fn measure(
        record: &'static str,
        point: DVec3,
        centre_line: DVec3,
        (radius, height): (f64, f64),
        height_name: &'static str,
    ) -> Result<(AxisFrame, Size), Invalid> {
        let frame = AxisFrame::new(point, centre_line, record)?;
        let radius = positive(record, "radius", radius).map_err(Parameter::Radius.refuses())?;
        let height = positive(record, height_name, height).map_err(Parameter::Height.refuses())?;
        Ok((frame, Size { radius, height }))
    }

    /// a, b, c along `ray` from its base, as the notes' formula computes them:
    /// B' = rotmat (B - C), D' = rotmat D, the coefficients of note 003 in f64.
    pub(crate) fn quadratic(&self, ray: &crate::shapes::Ray) -> (f64, f64, f64) {
        let (base, dir) = self.frame.to_local(ray);
        self.coefficients(base, dir)
    }

    /// f at a local point, in f64.
    #[inline]
    pub fn value(&self, local: DVec3) -> f64 {
        self.coefficients(local, DVec3::ZERO).2
    }

    /// a, b, c of the quadratic along the local ray B' + t D', written as note 003 does.
    #[inline(always)]
    pub fn coefficients(&self, base: DVec3, dir: DVec3) -> (f64, f64, f64) {
        let (square, linear_y, constant) = (self.alpha, self.linear_y, self.constant);
        let [base, dir] = [base, dir].map(|v| v.to_array());
        coefficients(square.to_array(), linear_y, constant, base, dir)
    }

    /// The same quadric under the variant nearer-root (spec §7.3): only the smaller root
    /// is tried. The sphere's rule is already the nearer root.
    pub(crate) fn smaller_root_only(&mut self) {
        if let RootRule::FirstPositiveWithin { low, high } = self.rule {
            self.rule = RootRule::SmallerWithin { low, high };
        }
    }

    /// The same quadric under the variant behind-root (spec §7.5): the smaller root in
    /// bounds even when it is behind the base.
    pub(crate) fn smaller_root_even_behind(&mut self) {
        if let RootRule::FirstPositiveWithin { low, high } = self.rule {
            self.rule = RootRule::SmallerEvenBehind { low, high };
        }
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

    /// |∇²f| / |∇f| at a world point: the Hessian is 2 diag(α), whose norm is 2 max |αi|
    /// ([`super::Shape::curvature`]).
    pub(crate) fn curvature(&self, point: DVec3) -> f64 {
        let gradient = self.gradient(self.frame.point_to_local(point));
        2.0 * self.alpha.abs().max_element() / gradient.length()
    }

    /// The local gradient ∇f = (2αx Lx, 2αy Ly + β, 2αz Lz).
    #[inline]
    pub fn gradient(&self, local: DVec3) -> DVec3 {
        let mut gradient = 2.0 * self.alpha * local;
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
        } = self.alpha;
        if ax <= 0.0 || ax != az {
            return None;
        }
        let (low, high) = match self.rule {
            RootRule::Nearer if ay == ax && self.linear_y == 0.0 => {
                let r = (-self.constant / ax).sqrt();
                (-r, r)
            }
            RootRule::Nearer => return None,
            rule => rule.bounds(),
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
            let world = self.frame.irot() * local + self.frame.centre;
            min = min.min(world);
            max = max.max(world);
        }
        Some((min, max))
    }
}

/// Whether a t² + b t + c = 0 has no real root by a relative margin of at least `reach`:
/// b² - 4ac < 0 with |b² - 4ac| >= reach (b² + 4|ac|).
pub(crate) fn clearly_no_root(a: f64, b: f64, c: f64, reach: f64) -> bool {
    let (square, product) = (b * b, 4.0 * a * c);
    let size = square + product.abs();
    size.is_finite() && square < product && product - square >= reach * size
}

/// [`HitNote::Discriminant`] of a t² + b t + c = 0.
pub(crate) fn discriminant_note(a: f64, b: f64, c: f64) -> HitNote {
    let (square, product) = (b * b, 4.0 * a * c);
    let size = square + product.abs();
    let relative = match size > 0.0 {
        true => (square - product).abs() / size,
        false => 1.0,
    };
    let vertex = match a != 0.0 {
        true => -b / (2.0 * a),
        false => -c / b,
    };
    // The notes' root (-b ± √Δ) / 2a with every term rounded once: the numerator's terms,
    // and Δ's through the square root, whose slope is 1 / 2√Δ.
    let root = (square - product).abs().sqrt();
    let spread = match a != 0.0 {
        true => (b.abs() + root + size / (2.0 * root)) / (2.0 * a).abs(),
        false => 2.0 * vertex.abs(),
    };
    HitNote::Discriminant {
        relative,
        vertex,
        spread,
    }
}

/// a = Σ αᵢ dᵢ², b = 2 Σ αᵢ bᵢ dᵢ + β dy, c = Σ αᵢ bᵢ² + β by + γ in any precision (the
/// f32 kernel rounds everything to f32 first).
#[inline(always)]
pub(crate) fn coefficients<F: Float>(
    square: [F; 3],
    linear_y: F,
    constant: F,
    base: [F; 3],
    dir: [F; 3],
) -> (F, F, F) {
    let dot = |u: [F; 3], v: [F; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let times = |u: [F; 3], v: [F; 3]| [u[0] * v[0], u[1] * v[1], u[2] * v[2]];
    let weighted = times(square, dir);
    let two = F::one() + F::one();
    (
        dot(weighted, dir),
        two * dot(weighted, base) + linear_y * dir[1],
        dot(times(square, base), base) + linear_y * base[1] + constant,
    )
}
