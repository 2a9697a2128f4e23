//! The closed set of shapes a scene can hold, one file each, dispatched by `match`.
//!
//! Every shape is built once at load by a constructor that validates its numbers and
//! precomputes what its hit test needs (unit normals, frames, `rotmat`, `irot`, `k`).
//! Intersection is two-staged (`../shared/STYLE.md`): [`Shape::hit`] only finds the
//! distance `t` and drives the closest-hit loop; [`Shape::surface`] computes point and
//! normal for the winner. How `t` is computed is a kernel's (`src/shapes/kernel/`); the
//! rules that decide a hit (which root, the bounds, the z rule) are the shapes' own and
//! shared by every kernel ([`RootRule`], [`Plane`]).

mod axis_frame;
mod axis_quadric;
pub(crate) use axis_quadric::{clearly_no_root, discriminant_note};
mod cone;
mod cylinder;
mod finite_plane;
mod hyperboloid;
pub mod kernel;
mod paraboloid;
mod plane;
mod plane_frame;
pub(crate) mod quadric;
mod sphere;

pub use axis_frame::AxisFrame;
pub use axis_quadric::{AxisQuadric, RootRule, Size};
pub use cone::Cone;
pub use cylinder::Cylinder;
pub use finite_plane::FinitePlane;
pub use hyperboloid::Hyperboloid;
pub use paraboloid::Paraboloid;
pub use plane::Plane;
pub use plane_frame::{FrameRows, PlaneFrame};
pub use quadric::Quadric;
pub use sphere::Sphere;

use crate::error::MeaningError;
use glam::DVec3;
use kernel::{Kernel, KernelChoice, PlaneFrom, with_kernel};
use wide::f64x8;

/// A ray: a base point and a unit direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts (the eye, or a hit point for shadow and reflected rays).
    pub base: DVec3,
    /// Unit direction.
    pub dir: DVec3,
}

impl Ray {
    /// The ray from `base` along the unit direction `dir`.
    pub fn new(base: DVec3, dir: DVec3) -> Ray {
        Ray { base, dir }
    }
}

/// How many rays a span tests together ([`Dirs`]).
pub(crate) const LANES: usize = 8;

/// A span's directions by coordinate, lane i's (`x[i]`, `y[i]`, `z[i]`): the rays of a
/// span from one base, tested together in the processor's vector registers
/// ([`Kernel::planes_toward`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Dirs {
    pub(crate) x: [f64; LANES],
    pub(crate) y: [f64; LANES],
    pub(crate) z: [f64; LANES],
}

impl Dirs {
    /// Lane `i`'s direction.
    #[inline(always)]
    pub(crate) fn get(&self, i: usize) -> DVec3 {
        DVec3::new(self.x[i], self.y[i], self.z[i])
    }

    /// The three coordinates' lanes in vector registers.
    #[inline(always)]
    pub(crate) fn lanes(&self) -> [f64x8; 3] {
        [self.x, self.y, self.z].map(f64x8::from)
    }
}

/// A number a shape's constructor can refuse. Shapes know nothing of the scene file:
/// `src/scene/build.rs` maps a parameter to the group and column it came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parameter {
    /// A plane's normal.
    Normal,
    /// A framed plane's x direction.
    XDirection,
    /// A quadric's centre line (its axis).
    CentreLine,
    /// A radius (a sphere's; a quadric's at its open end).
    Radius,
    /// A quadric's height (half-height for the hyperboloid), or a finite plane's height.
    Height,
    /// A finite plane's width.
    Width,
    /// The hyperboloid's waist radius.
    Waist,
    /// The `QUADRIC` coefficients, as a whole.
    Coefficients,
}

impl Parameter {
    /// A refusal of this parameter, for `map_err`.
    pub(crate) fn refuses(self) -> impl Fn(MeaningError) -> Invalid {
        move |error| Invalid {
            parameter: self,
            error,
        }
    }

    /// How the parameter is named in messages.
    pub fn name(self) -> &'static str {
        match self {
            Parameter::Normal => "normal",
            Parameter::XDirection => "x direction",
            Parameter::CentreLine => "centre line",
            Parameter::Radius => "radius",
            Parameter::Height => "height",
            Parameter::Width => "width",
            Parameter::Waist => "waist radius",
            Parameter::Coefficients => "coefficients",
        }
    }
}

/// A constructor's refusal: the parameter and what is wrong with it; no location.
#[derive(Debug, Clone, PartialEq)]
pub struct Invalid {
    /// The offending parameter.
    pub parameter: Parameter,
    /// What is wrong with the parameter's value.
    pub error: MeaningError,
}

/// Fails with `NotPositive` unless `value > 0`; `what` names the quantity in the message
/// ("radius", "half-height").
pub(crate) fn positive(
    record: &'static str,
    what: &'static str,
    value: f64,
) -> Result<f64, MeaningError> {
    if value > 0.0 {
        return Ok(value);
    }
    Err(MeaningError::NotPositive {
        record,
        what,
        value,
    })
}

/// `v / |v|` computed without overflow or underflow in `|v|`; `None` for the zero vector.
pub fn unit(v: DVec3) -> Option<DVec3> {
    let scale = v.abs().max_element();
    if scale == 0.0 || !scale.is_finite() {
        return None;
    }
    let w = v / scale;
    Some(w / w.length())
}

/// [`unit`] of a span's vectors, by coordinate: the same operations in the same order
/// on each lane, so the same bits, in the processor's vector registers. Bit i of the
/// mask is clear where [`unit`] gives `None` (that lane's direction is then
/// meaningless).
#[inline(always)]
pub(crate) fn units(v: Dirs) -> (Dirs, u32) {
    let [x, y, z] = v.lanes();
    // As glam's `max_element` and `length`: max(|x|, max(|y|, |z|)) where max(a, b) is
    // `if a > b { a } else { b }`, then √((x² + y²) + z²).
    let max = |a: f64x8, b: f64x8| a.simd_gt(b).select(a, b);
    let scale = max(x.abs(), max(y.abs(), z.abs()));
    let (wx, wy, wz) = (x / scale, y / scale, z / scale);
    let length = ((wx * wx + wy * wy) + wz * wz).sqrt();
    // unit's test: a scale (≥ 0 or NaN) neither 0 nor ∞ nor NaN. (A NaN coordinate
    // need not make the scale NaN, nor the test fail: unit then gives NaN directions.)
    let valid =
        (scale.simd_gt(f64x8::ZERO) & scale.simd_lt(f64x8::splat(f64::INFINITY))).to_bitmask();
    let dirs = Dirs {
        x: (wx / length).to_array(),
        y: (wy / length).to_array(),
        z: (wz / length).to_array(),
    };
    (dirs, valid)
}

/// Like [`unit`], but the error names the record's vector.
pub(crate) fn unit_or_zero_error(
    v: DVec3,
    record: &'static str,
    parameter: Parameter,
) -> Result<DVec3, Invalid> {
    let what = parameter.name();
    let error = MeaningError::ZeroVector { record, what };
    unit(v).ok_or(Invalid { parameter, error })
}

/// Why a shape's hit test decided as it did, for `legacy-rt trace`: every kernel's hit
/// ([`Shape::hit_noted`]) tells each decision of the shape's rule ([`RootRule`],
/// [`Plane`], [`FinitePlane`], [`Quadric`]) to a [`Notes`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HitNote {
    /// How close the quadratic of the sphere, a quadric 21-24 or a `QUADRIC` is to having
    /// a double root, as the notes' formula sees it from the ray's base: the discriminant
    /// b² - 4ac over the size of its terms, b² + 4|ac| (0 for a ray tangent to the
    /// surface, 1 far from it), and where the roots would meet, t = -b / 2a. For
    /// `compare`'s fragile pixels (docs/compare.md); the trace does not print it.
    Discriminant {
        /// |b² - 4ac| / (b² + 4|ac|).
        relative: f64,
        /// -b / 2a (-c / b for the linear equation).
        vertex: f64,
        /// How far a root moves when every term of the notes' formula is off by one part
        /// in 1 (to be multiplied by the arithmetic's precision): (|b| + √|Δ| + (b² +
        /// 4|ac|) / 2√|Δ|) / |2a|; infinite at a double root.
        spread: f64,
    },
    /// The quadratic has no real root (for the sphere: a discriminant not > 0).
    NoRealRoot,
    /// The sphere's nearer root, `None` if it is not a finite number.
    Nearer {
        /// The distance t along the ray.
        t: Option<f64>,
    },
    /// A root of a quadric 21-24, its point's local y, and whether it counts.
    Root {
        /// The distance t along the ray.
        t: f64,
        /// The local y of its point.
        y: f64,
        /// Counts, behind the base, or out of bounds.
        verdict: Verdict,
    },
    /// A root of a `QUADRIC`.
    QuadricRoot {
        /// The distance t along the ray.
        t: f64,
        /// Counts or behind the base.
        verdict: Verdict,
    },
    /// The ray is parallel to a plane (N·D = 0).
    Parallel,
    /// A plane's t and the z of its point.
    Plane {
        /// The distance t along the ray.
        t: f64,
        /// The z of the point.
        z: f64,
        /// Counts, behind the base, or beyond the screen.
        verdict: Verdict,
    },
    /// Where a finite plane's hit lies in its own frame, and whether that is inside the
    /// rectangle.
    Rectangle {
        /// (q.x, q.y) of spec §5.3.
        q: glam::DVec2,
        /// 0 <= q.x <= width and 0 <= q.y <= height.
        inside: bool,
    },
}

/// What a root or a plane's t came to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// It is the hit: in front of the base and within the bounds.
    Counts,
    /// t <= 0: behind the ray's base.
    Behind,
    /// Its local y lies outside the shape's bounds (spec §5.6).
    OutOfBounds,
    /// Its point has z > 0: behind the screen (spec §5.1).
    BeyondScreen,
}

/// Where the hit algorithms tell their decisions. `()` forgets them, and then they cost
/// nothing.
pub trait Notes {
    /// Whether the notes are kept: when false, a kernel may take a path that has none to
    /// give (the accurate kernel's early rejections and its FMA-compiled copy), with the
    /// same t.
    const KEPT: bool = true;

    /// Takes one decision of a hit test.
    fn note(&mut self, note: HitNote);
}

impl Notes for () {
    const KEPT: bool = false;

    #[inline(always)]
    fn note(&mut self, _: HitNote) {}
}

impl Notes for Vec<HitNote> {
    fn note(&mut self, note: HitNote) {
        self.push(note);
    }
}

/// Where a ray meets a shape, for shading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// The hit point, world coordinates.
    pub point: DVec3,
    /// Unit normal, world coordinates, never flipped toward the viewer (spec §4.4).
    pub normal: DVec3,
    /// Plane-frame coordinates (q.x, q.y) for tiles and textures (spec §5.3); zero otherwise.
    pub plane_xy: glam::DVec2,
}

/// A shape's test made ready for many rays from one base ([`Shape::for_base`]), a
/// span's camera rays: a plane's (or a tiled plane's) numerator computed once
/// ([`Kernel::plane_from`]); every other shape as it is.
pub(crate) enum ForBase<'s> {
    Plane(&'s Plane, PlaneFrom),
    Other(&'s Shape),
}

impl ForBase<'_> {
    /// [`Shape::hit_by`] without notes of the rays from `base` (the base this was made
    /// ready for) along `dirs`, for the lanes set in `lanes`: bit i of the mask set
    /// where lane i's ray hits, at `t[i]`. The same t as each ray's own test.
    #[inline(always)]
    pub(crate) fn hits<K: Kernel>(
        &self,
        base: DVec3,
        dirs: &Dirs,
        lanes: u32,
    ) -> ([f64; LANES], u32) {
        match self {
            ForBase::Plane(plane, from) => K::planes_toward(plane, from, base, dirs, lanes),
            ForBase::Other(shape) => each_lane(lanes, |i| {
                let ray = Ray::new(base, dirs.get(i));
                shape.hit_by::<K>(&ray, &mut ())
            }),
        }
    }
}

/// The lanes set in `mask` (below [`LANES`]), lowest first: a loop over them takes
/// the set bits only, for masks that are mostly empty (the lanes a plane's quick test
/// leaves: a loop over every lane cost the ambient plane 16 instructions a pixel).
#[inline(always)]
pub(crate) fn set_lanes(mask: u32) -> impl Iterator<Item = usize> {
    let mut left = mask & ((1 << LANES) - 1);
    std::iter::from_fn(move || {
        let lane = (left != 0).then(|| left.trailing_zeros() as usize);
        left &= left.wrapping_sub(1);
        lane
    })
}

/// `hit(i)` of the lanes set in `lanes`, as [`ForBase::hits`] gives them.
#[inline(always)]
pub(crate) fn each_lane(lanes: u32, hit: impl Fn(usize) -> Option<f64>) -> ([f64; LANES], u32) {
    let (mut ts, mut hits) = ([0.0; LANES], 0);
    for i in set_lanes(lanes) {
        if let Some(hit) = hit(i) {
            (ts[i], hits) = (hit, hits | 1 << i);
        }
    }
    (ts, hits)
}

/// What a query of margins learns of a test before the kernel's ([`Shape::ahead`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Ahead {
    /// The ray clearly misses the quadric, and the kernel finds no root: nothing to tell.
    Clear,
    /// The test's quadratic (a, b, c), whose discriminant its notes start with.
    Quadratic((f64, f64, f64)),
    /// A plane-based shape: no quadratic.
    Flat,
}

/// Every shape of spec §3.2-§3.3 that can be hit.
///
/// An enum is as large as its largest variant, so only the shapes a scene may hold by the
/// thousand are held in place: the sphere (40 bytes), the plane (56) and the tiled plane
/// (64, its frame's rows boxed). Every other shape is boxed (80-408 bytes). A shape
/// takes 72 bytes, not the 152 that the finite plane would make it.
#[derive(Debug, Clone, PartialEq)]
// A tag of its own: left to itself the compiler hides the kind in a spare value of a
// field inside the shapes, and every hit test's dispatch pays to decode it (2.8 % more
// instructions on spec1).
#[repr(u8)]
pub enum Shape {
    /// 13 and 19: a sphere.
    Sphere(Sphere),
    /// 14 and 20: an infinite plane.
    Plane(Plane),
    /// 15 and 17: a rectangle of a plane.
    FinitePlane(Box<FinitePlane>),
    /// 16: an infinite plane with a frame for the tile grid.
    TiledPlane(PlaneFrame),
    /// 21: a finite circular paraboloid.
    Paraboloid(Box<Paraboloid>),
    /// 22: a finite open cylinder.
    Cylinder(Box<Cylinder>),
    /// 23: a finite open cone.
    Cone(Box<Cone>),
    /// 24: a finite hyperboloid of one sheet.
    Hyperboloid(Box<Hyperboloid>),
    /// `QUADRIC`: the general quadric x^T Q x = 0.
    Quadric(Box<Quadric>),
}

impl Shape {
    /// The distance along `ray` to this shape under the legacy rules of spec §5, computed
    /// by `kernel`, if any. The caller keeps only `t > 0` (spec §4.6): a sphere may report
    /// a negative `t`.
    pub fn hit(&self, ray: &Ray, kernel: KernelChoice) -> Option<f64> {
        with_kernel!(kernel, K => self.hit_by::<K>(ray, &mut ()))
    }

    /// [`Shape::hit`], telling `notes` why it decided as it did; the same t.
    pub fn hit_noted(
        &self,
        ray: &Ray,
        kernel: KernelChoice,
        notes: &mut impl Notes,
    ) -> Option<f64> {
        with_kernel!(kernel, K => self.hit_by::<K>(ray, notes))
    }

    /// [`Shape::hit_noted`] with the kernel as a type: what the renderer's loops call.
    #[inline]
    pub(crate) fn hit_by<K: Kernel>(&self, ray: &Ray, notes: &mut impl Notes) -> Option<f64> {
        match self {
            Shape::Sphere(s) => K::sphere(s, ray, notes),
            Shape::Plane(s) => K::plane(s, ray, notes),
            Shape::FinitePlane(s) => s.hit::<K>(ray, notes),
            Shape::TiledPlane(s) => K::plane(&s.plane, ray, notes),
            Shape::Paraboloid(s) => K::axis_quadric(&s.equation, ray, notes),
            Shape::Cylinder(s) => K::axis_quadric(&s.equation, ray, notes),
            Shape::Cone(s) => K::axis_quadric(&s.equation, ray, notes),
            Shape::Hyperboloid(s) => K::axis_quadric(&s.equation, ray, notes),
            Shape::Quadric(s) => K::quadric(s, ray, notes),
        }
    }

    /// This shape's test made ready for many rays from `base` ([`ForBase`]).
    #[inline(always)]
    pub(crate) fn for_base<K: Kernel>(&self, base: DVec3) -> ForBase<'_> {
        match self {
            Shape::Plane(p) | Shape::TiledPlane(PlaneFrame { plane: p, .. }) => {
                ForBase::Plane(p, K::plane_from(p, base))
            }
            shape => ForBase::Other(shape),
        }
    }

    /// What a query of `compare`'s margins learns of `ray`'s test before the kernel's:
    /// the quadratic a t² + b t + c along the ray from its base, as the notes' formula
    /// computes it, for the sphere, the quadrics 21-24 and `QUADRIC`, whose discriminant
    /// the test's notes start with ([`HitNote::Discriminant`]); or that the ray clearly
    /// misses, by more than `reach` ([`clearly_no_root`]), and kernel `K` finds no root
    /// either, so that there is nothing to tell. The sphere's terms are computed once,
    /// for its discriminant and the kernel's quick test.
    #[inline(always)]
    pub(crate) fn ahead<K: Kernel>(&self, ray: &Ray, reach: f64) -> Ahead {
        let clearly = |(a, b, c): (f64, f64, f64)| clearly_no_root(a, b, c, reach);
        let quadratic = match self {
            Shape::Sphere(s) => {
                let terms = s.terms(ray);
                let quadratic = Sphere::quadratic(terms, s.radius_sq);
                if clearly(quadratic) && K::sphere_surely_misses(s, terms) {
                    return Ahead::Clear;
                }
                quadratic
            }
            Shape::Paraboloid(s) => s.equation.quadratic(ray),
            Shape::Cylinder(s) => s.equation.quadratic(ray),
            Shape::Cone(s) => s.equation.quadratic(ray),
            Shape::Hyperboloid(s) => s.equation.quadratic(ray),
            Shape::Quadric(s) => s.quadratic(ray),
            Shape::Plane(_) | Shape::FinitePlane(_) | Shape::TiledPlane(_) => return Ahead::Flat,
        };
        match clearly(quadratic) && self.hit_by::<K>(ray, &mut ()).is_none() {
            true => Ahead::Clear,
            false => Ahead::Quadratic(quadratic),
        }
    }

    /// The equation of a quadric 21-24, for the variant nearer-root to change its root
    /// rule ([`AxisQuadric::smaller_root_only`]).
    pub(crate) fn bounded_axis_quadric_mut(&mut self) -> Option<&mut AxisQuadric> {
        match self {
            Shape::Paraboloid(s) => Some(&mut s.equation),
            Shape::Cylinder(s) => Some(&mut s.equation),
            Shape::Cone(s) => Some(&mut s.equation),
            Shape::Hyperboloid(s) => Some(&mut s.equation),
            _ => None,
        }
    }

    /// The plane of a plane-based shape (14-17, 20): every hit of the shape lies on it.
    pub fn plane(&self) -> Option<&Plane> {
        match self {
            Shape::Plane(s) => Some(s),
            Shape::FinitePlane(s) => Some(&s.frame.plane),
            Shape::TiledPlane(s) => Some(&s.plane),
            _ => None,
        }
    }

    /// The plane of a plane-based shape (14-17, 20), to drop its z rule (the variant
    /// no-z-rule).
    /// The frame of a finite, textured or tiled plane (15-17, spec §5.3), `None` for the
    /// other shapes.
    pub(crate) fn frame_mut(&mut self) -> Option<&mut PlaneFrame> {
        match self {
            Shape::FinitePlane(s) => Some(&mut s.frame),
            Shape::TiledPlane(s) => Some(s),
            _ => None,
        }
    }

    pub(crate) fn plane_mut(&mut self) -> Option<&mut Plane> {
        match self {
            Shape::Plane(s) => Some(s),
            Shape::FinitePlane(s) => Some(&mut s.frame.plane),
            Shape::TiledPlane(s) => Some(&mut s.plane),
            _ => None,
        }
    }

    /// The local frame of a quadric 21-24 (spec §5.6), `None` for the other shapes.
    pub fn axis_frame(&self) -> Option<&AxisFrame> {
        match self {
            Shape::Paraboloid(s) => Some(&s.equation.frame),
            Shape::Cylinder(s) => Some(&s.equation.frame),
            Shape::Cone(s) => Some(&s.equation.frame),
            Shape::Hyperboloid(s) => Some(&s.equation.frame),
            _ => None,
        }
    }

    /// An axis-aligned box (min, max) that holds every hit this shape can report, or
    /// `None` for the unbounded ones: planes, tiled and procedural planes, and a `QUADRIC`
    /// that is not an ellipsoid ([`Quadric::bounds`]).
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Paraboloid(s) => s.equation.bounds(),
            Shape::Cylinder(s) => s.equation.bounds(),
            Shape::Cone(s) => s.equation.bounds(),
            Shape::Hyperboloid(s) => s.equation.bounds(),
            Shape::FinitePlane(s) => Some(s.bounds()),
            Shape::Quadric(s) => s.bounds(),
            Shape::Plane(_) | Shape::TiledPlane(_) => None,
        }
    }

    /// How fast the unit normal turns at `point` per unit of distance along the surface,
    /// at most: |∇²f| / |∇f| (a sphere's 1/r, a plane's 0; infinite at a cone's apex).
    /// A point found a distance δ off has its normal off by about δ times this: what a
    /// mirror makes of the error its hit point carries (`compare`'s margins).
    pub(crate) fn curvature(&self, point: DVec3) -> f64 {
        match self {
            Shape::Sphere(s) => 1.0 / s.radius,
            Shape::Plane(_) | Shape::FinitePlane(_) | Shape::TiledPlane(_) => 0.0,
            Shape::Paraboloid(s) => s.equation.curvature(point),
            Shape::Cylinder(s) => s.equation.curvature(point),
            Shape::Cone(s) => s.equation.curvature(point),
            Shape::Hyperboloid(s) => s.equation.curvature(point),
            Shape::Quadric(s) => s.curvature(point),
        }
    }

    /// Point and normal where `ray` meets this shape at distance `t` (from [`Shape::hit`]).
    #[inline(always)]
    pub fn surface(&self, ray: &Ray, t: f64) -> Surface {
        let point = ray.base + t * ray.dir;
        let (normal, plane_xy) = match self {
            Shape::Sphere(s) => (s.equation().normal(point), glam::DVec2::ZERO),
            Shape::Plane(s) => (s.normal, glam::DVec2::ZERO),
            Shape::FinitePlane(s) => (s.frame.plane.normal, s.frame.plane_xy(point)),
            Shape::TiledPlane(s) => (s.plane.normal, s.plane_xy(point)),
            Shape::Paraboloid(s) => (s.equation.normal(point), glam::DVec2::ZERO),
            Shape::Cylinder(s) => (s.equation.normal(point), glam::DVec2::ZERO),
            Shape::Cone(s) => (s.equation.normal(point), glam::DVec2::ZERO),
            Shape::Hyperboloid(s) => (s.equation.normal(point), glam::DVec2::ZERO),
            Shape::Quadric(s) => (s.normal(point), glam::DVec2::ZERO),
        };
        // A zero gradient (a cone's apex, a degenerate quadric) has no direction; face the
        // ray so that the point is shaded as seen from the front instead of turning to NaN.
        let normal = if normal.is_finite() && normal != DVec3::ZERO {
            normal
        } else {
            -ray.dir
        };
        Surface {
            point,
            normal,
            plane_xy,
        }
    }
}

/// What the shapes' tests use besides their own module: a ray and the shipped kernel.
#[cfg(test)]
pub(crate) mod testing {
    pub(crate) use super::Ray;
    pub(crate) use super::kernel::Accurate;
    use super::kernel::Kernel;

    /// The shipped kernel's t on a sphere or a quadric 21-24.
    pub fn hit(quadric: &super::AxisQuadric, ray: &Ray) -> Option<f64> {
        Accurate::axis_quadric(quadric, ray, &mut ())
    }

    /// The shipped kernel's t on a `QUADRIC`.
    pub fn hit_quadric(quadric: &super::Quadric, ray: &Ray) -> Option<f64> {
        Accurate::quadric(quadric, ray, &mut ())
    }

    /// Numbers in [0, 1) from a fixed seed (xorshift64), so that a test's random cases
    /// are the same on every run.
    pub struct Numbers(pub u64);

    impl Numbers {
        /// The next number.
        pub fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }

        /// The next number scaled to [low, high).
        pub fn within(&mut self, low: f64, high: f64) -> f64 {
            low + (high - low) * self.next()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_has_no_direction_for_zero_and_survives_extreme_lengths() {
        assert_eq!(unit(DVec3::ZERO), None);
        // |v|² overflows (1e200²) or underflows (1e-200²) in f64: a plain normalise loses
        // the direction, the scaled form gives the exact unit vector.
        assert_eq!(
            unit(DVec3::new(0.0, 3e200, 4e200)),
            Some(DVec3::new(0.0, 0.6, 0.8))
        );
        assert_eq!(
            unit(DVec3::new(3e-200, 0.0, 4e-200)),
            Some(DVec3::new(0.6, 0.0, 0.8))
        );
        assert!(!DVec3::new(0.0, 3e200, 4e200).normalize().is_normalized());
    }

    #[test]
    fn units_are_unit_s_bits_lane_by_lane() {
        // Random vectors over 600 binary orders of magnitude, and the cases unit refuses
        // or scales: zero, ∞, NaN, subnormal coordinates, one coordinate alone, -0.
        let mut numbers = testing::Numbers(0x2545_f491_4f6c_dd1d);
        let mut next = || numbers.next();
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NAN,
            5e-324,
            -1e-310,
            1e300,
            3.0,
        ];
        let mut cases = Vec::new();
        for i in 0..4_000 {
            let mut v = [0.0; 3].map(|_| (next() - 0.5) * 2f64.powf(600.0 * next() - 300.0));
            if i % 4 == 0 {
                v[i / 4 % 3] = special[i / 12 % special.len()];
            }
            if i % 16 == 1 {
                v = [0.0, 0.0, 0.0];
                v[i / 16 % 3] = special[i / 48 % special.len()];
            }
            cases.push(DVec3::from(v));
        }
        let (mut some, mut none) = (0, 0);
        for span in cases.chunks(LANES) {
            let v = Dirs {
                x: std::array::from_fn(|i| span[i].x),
                y: std::array::from_fn(|i| span[i].y),
                z: std::array::from_fn(|i| span[i].z),
            };
            let (dirs, valid) = units(v);
            for (i, v) in span.iter().enumerate() {
                match unit(*v) {
                    Some(own) => {
                        assert!(valid & 1 << i != 0, "{v:?}");
                        assert_eq!(
                            dirs.get(i).to_array().map(f64::to_bits),
                            own.to_array().map(f64::to_bits),
                            "{v:?}"
                        );
                        some += 1;
                    }
                    None => {
                        assert!(valid & 1 << i == 0, "{v:?}");
                        none += 1;
                    }
                }
            }
        }
        assert!(some > 3_000 && none > 100, "{some} {none}");
    }

    #[test]
    fn set_lanes_are_the_mask_s_bits_below_lanes() {
        let lanes = |mask| set_lanes(mask).collect::<Vec<_>>();
        assert_eq!(lanes(0), Vec::<usize>::new());
        assert_eq!(lanes(0b1010_0001), vec![0, 5, 7]);
        assert_eq!(lanes(u32::MAX), (0..LANES).collect::<Vec<_>>());
    }
}
