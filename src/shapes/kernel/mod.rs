//! Ray-shape intersection kernels: the same legacy rules (spec §5: which root, tangent
//! rays, bounds, the plane's z rule) computed with different arithmetic.
//!
//! - [`Accurate`], the one `legacy-rt` ships: stable roots of a quadratic moved next to
//!   the shape, then, where a cheap error estimate says the f64 digits are not enough, one
//!   or two refinement steps whose residual is evaluated with error-free sums and
//!   products. Within 4 ulps of the exact root on every hard case of the test suite.
//! - [`StableRoots`]: the coefficients as the notes write them, solved with the
//!   cancellation-free root formula only.
//! - [`Textbook`]: the notes' formula (-b ± sqrt(b² - 4ac)) / 2a, in f64.
//! - [`TextbookF32`]: the same in f32, for contrast.
//!
//! `legacy-rt --kernel textbook` renders with the notes' formula, which shows a student
//! where their own tracer's speckles come from. `cargo run --release --example
//! speed_vs_error` measures all four (docs/speed-vs-error.md).

mod accurate;
pub(crate) mod dd;
mod quadratic;
mod textbook;
mod textbook_f32;

pub use accurate::Accurate;
pub use textbook::{
    AsWritten, Double, Formula, Named, Plain, Precision, StableFormula, StableRoots, Textbook,
    TextbookFormula,
};
pub use textbook_f32::{Single, TextbookF32};

pub(crate) use quadratic::{solve_quadratic, solve_quadratic_with_slope};

use super::{AxisFrame, AxisQuadric, Plane, Quadric, Ray, Sphere};

/// The arithmetic of one way to compute hit distances. The algorithms themselves, in the
/// order of the notes, are written once, in [`AxisQuadric::hit`], [`Plane::hit`] and
/// [`Quadric::hit`]; a kernel supplies only the steps that differ between kernels: how
/// the ray is moved into the shape's frame, how a, b and c are evaluated, how the roots
/// are computed, and whether and how a root is polished.
pub trait Kernel: Copy + Default + Send + Sync + 'static {
    /// The name used by `--kernel` and the report.
    const NAME: &'static str;

    /// The ray in a shape's local frame, as this kernel holds it (B' and D', and
    /// whatever its later steps need).
    type Local: Copy;

    /// The coefficients a, b, c, in this kernel's precision.
    type Coefficients: Copy;

    /// A root, with whatever the kernel needs to polish it.
    type Root: Copy;

    /// The hit of a sphere or a quadric 21-24: [`AxisQuadric::hit`] in this kernel's
    /// arithmetic. A kernel may run it from a copy of the code compiled for other
    /// instructions (the accurate kernel's fused multiply-add).
    #[inline(always)]
    fn axis_quadric(quadric: &AxisQuadric, ray: &Ray) -> Option<f64> {
        quadric.hit::<Self>(ray)
    }

    /// The hit of a sphere: [`AxisQuadric::hit`] on its equation. A kernel may first rule
    /// out, more cheaply, rays that certainly miss it.
    #[inline(always)]
    fn sphere(sphere: &Sphere, ray: &Ray) -> Option<f64> {
        Self::axis_quadric(&sphere.equation, ray)
    }

    /// The hit of a general `QUADRIC`: [`Quadric::hit`] in this kernel's arithmetic.
    #[inline(always)]
    fn quadric(quadric: &Quadric, ray: &Ray) -> Option<f64> {
        quadric.hit::<Self>(ray)
    }

    /// The hit of a plane: [`Plane::hit`] in this kernel's arithmetic.
    #[inline(always)]
    fn plane(plane: &Plane, ray: &Ray) -> Option<f64> {
        plane.hit::<Self>(ray)
    }

    /// Note 003's first step for the quadrics 21-24 and the sphere: the ray in the
    /// shape's frame, B' = rotmat (B - C), D' = rotmat D.
    fn local_ray(frame: &AxisFrame, ray: &Ray) -> Self::Local;

    /// a, b, c of a t² + b t + c = 0 along the local ray (note 003's table).
    fn coefficients(quadric: &AxisQuadric, local: &Self::Local) -> Self::Coefficients;

    /// The real roots, ascending, under `tangent`'s rule for a zero discriminant; `None`
    /// when there is none.
    fn roots(abc: Self::Coefficients, tangent: Tangent) -> Option<[Self::Root; 2]>;

    /// The nearer root alone (the sphere, where a tangent ray misses): by default the
    /// first of [`Kernel::roots`].
    #[inline(always)]
    fn nearer_root(abc: Self::Coefficients) -> Option<Self::Root> {
        Self::roots(abc, Tangent::Misses).map(|[nearer, _]| nearer)
    }

    /// The sphere's nearer root as a distance along the world ray; `None` if it is not a
    /// finite number.
    fn nearer_distance(steps: &Steps<AxisQuadric, Self>, root: Self::Root) -> Option<f64>;

    /// Root `index` (0 the smaller) of a bounded quadric as a distance along the world
    /// ray and the local y of its point, polished where the kernel does that; `Err`
    /// (with the unpolished values) where the root lies so far outside `bounds`
    /// (low, high) or behind the base that no polishing could bring it back.
    fn distance_and_height(
        steps: &Steps<AxisQuadric, Self>,
        root: Self::Root,
        index: usize,
        bounds: (f64, f64),
    ) -> Result<(f64, f64), (f64, f64)>;

    /// How far past a bound of local y a hit at `t` may lie and still count: the rounding
    /// of the coordinate, for a kernel that allows for it (0 for the others).
    #[inline(always)]
    fn bound_slack(_local: &Self::Local, _t: f64) -> f64 {
        0.0
    }

    /// The plane's t = N·(Q - B) / N·D, `None` if N·D = 0 (spec §5.1).
    fn plane_distance(plane: &Plane, ray: &Ray) -> Option<f64>;

    /// How far beyond the screen (z > 0) a plane hit at `t` may lie and still count: the
    /// rounding of z, for a kernel that allows for it.
    #[inline(always)]
    fn screen_slack(_ray: &Ray, _t: f64) -> f64 {
        0.0
    }

    /// The ray as a general `QUADRIC`'s coefficients need it (the world ray, or one
    /// moved next to the quadric's centre).
    fn quadric_ray(quadric: &Quadric, ray: &Ray) -> Self::Local;

    /// a = DᵀQD, b = 2 DᵀQP, c = PᵀQP of note 004 for P = (B, 1), D = (D, 0).
    fn quadric_coefficients(quadric: &Quadric, local: &Self::Local) -> Self::Coefficients;

    /// Root `index` of a `QUADRIC` as a distance along the world ray, polished where the
    /// kernel does that; `Err` (unpolished) where it lies so far behind the base that no
    /// polishing could bring it in front.
    fn quadric_distance(
        steps: &Steps<Quadric, Self>,
        root: Self::Root,
        index: usize,
    ) -> Result<f64, f64>;
}

/// Where a hit algorithm has got to, for a kernel's later steps: the shape, the world
/// ray, and what the earlier steps gave (the local ray, the coefficients).
pub struct Steps<'a, S, K: Kernel> {
    /// The shape being hit.
    pub shape: &'a S,
    /// The ray, in world coordinates.
    pub ray: &'a Ray,
    /// The ray in the shape's frame, as the kernel holds it.
    pub local: &'a K::Local,
    /// a, b, c.
    pub abc: K::Coefficients,
}

impl<'a, S, K: Kernel> Steps<'a, S, K> {
    /// The steps so far.
    #[inline(always)]
    pub fn new(shape: &'a S, ray: &'a Ray, local: &'a K::Local, abc: K::Coefficients) -> Self {
        Steps {
            shape,
            ray,
            local,
            abc,
        }
    }
}

/// What a zero discriminant (a ray tangent to the surface) means (spec §5.2, §5.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tangent {
    /// The sphere: a hit only if the discriminant is > 0.
    Misses,
    /// The quadrics 21-24 and `QUADRIC`: the double root counts.
    Counts,
}

impl Tangent {
    /// Whether a discriminant `d` gives real roots under this rule (`false` for NaN).
    #[inline(always)]
    pub fn real<F: num_traits::Float>(self, d: F) -> bool {
        match self {
            Tangent::Misses => d > F::zero(),
            Tangent::Counts => d >= F::zero(),
        }
    }
}

/// The kernels by name, for the command line and the report.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KernelChoice {
    /// [`Accurate`].
    #[default]
    Accurate,
    /// [`StableRoots`].
    Stable,
    /// [`Textbook`].
    Textbook,
    /// [`TextbookF32`].
    TextbookF32,
}

impl KernelChoice {
    /// All kernels, shipped one first.
    pub const ALL: [KernelChoice; 4] = [
        KernelChoice::Accurate,
        KernelChoice::Stable,
        KernelChoice::Textbook,
        KernelChoice::TextbookF32,
    ];

    /// The kernel's name.
    pub fn name(self) -> &'static str {
        match self {
            KernelChoice::Accurate => Accurate::NAME,
            KernelChoice::Stable => StableRoots::NAME,
            KernelChoice::Textbook => Textbook::NAME,
            KernelChoice::TextbookF32 => TextbookF32::NAME,
        }
    }

    /// How much the boxes of the bounding volume hierarchy and the tiles are grown, as a
    /// share of a box's size plus its distance from the origin, so that they hold every
    /// hit this kernel reports on their object (a hit outside its object's box does not
    /// count: `src/render/bvh.rs::Boxes::admits`). The f64 kernels' hits lie within a
    /// few ulps (10⁻¹⁵) of the surface, 10⁻⁹ is far beyond that. The f32 kernel rounds
    /// every input to 24 bits and computes t in f32: its hit on a rectangle lying in a
    /// box of zero thickness is off the plane by some 10⁻⁷ of the coordinates involved,
    /// so its boxes grow by 10⁻⁴, a thousand times that (tested in
    /// `src/render/bvh.rs`, `every_kernel_s_hits_lie_in_their_boxes`).
    pub fn box_padding(self) -> f64 {
        match self {
            KernelChoice::TextbookF32 => 1e-4,
            _ => 1e-9,
        }
    }

    /// The kernel with this name.
    pub fn from_name(name: &str) -> Option<KernelChoice> {
        KernelChoice::ALL.into_iter().find(|k| k.name() == name)
    }
}
