//! Ray-shape intersection kernels: the same legacy rules (spec §5: which root, tangent
//! rays, bounds, the plane's z rule) computed with different arithmetic.
//!
//! - `Accurate` (`accurate.rs`), the one `legacy-rt` ships, specialised: stable
//!   roots of a quadratic moved next to the shape, then, where a cheap error estimate says
//!   the f64 digits are not enough, one or two refinement steps whose residual is
//!   evaluated with error-free sums and products. Within 4 ulps of the exact root on
//!   every hard case of the test suite.
//! - `textbook.rs`: the notes' steps as written, one function per family over the float
//!   type a tracer computes in: `Textbook` (the notes' formula (-b ± sqrt(b² - 4ac)) / 2a
//!   in f64), `Stable` (the same coefficients, cancellation-free roots) and
//!   `TextbookF32` (the notes' formula in f32, for contrast).
//!
//! `legacy-rt --kernel textbook` renders with the notes' formula, which shows a student
//! where their own tracer's speckles come from. `cargo run --release --example
//! speed_vs_error` measures all four (docs/speed-vs-error.md).

pub(crate) mod accurate;
pub(crate) mod dd;
mod quadratic;
pub(crate) mod textbook;

pub(crate) use accurate::Accurate;
pub(crate) use quadratic::{solve_quadratic, solve_quadratic_with_slope};
pub(crate) use textbook::{Stable, Textbook, TextbookF32};

use super::{AxisQuadric, Dirs, LANES, Notes, Plane, Quadric, Ray, Sphere, each_lane};
use glam::DVec3;

/// One way of computing hit distances: the whole hit of each family of shapes, with the
/// decisions of spec §5 (shared through [`crate::shapes::RootRule`] and
/// [`Plane::verdict`]) told to `notes`. The renderer's aggregate is generic over it, so
/// that the choice costs nothing per test (`src/render/objects.rs`).
pub(crate) trait Kernel: Copy + Send + Sync + 'static {
    /// The sphere (spec §5.2): its nearer root, even when negative; `None` unless the
    /// discriminant is positive.
    fn sphere<N: Notes>(sphere: &Sphere, ray: &Ray, notes: &mut N) -> Option<f64>;

    /// A quadric 21-24 (spec §5.6): the smallest positive root whose local y is within
    /// bounds.
    fn axis_quadric<N: Notes>(quadric: &AxisQuadric, ray: &Ray, notes: &mut N) -> Option<f64>;

    /// A `QUADRIC` (spec §3.3): the smallest positive root.
    fn quadric<N: Notes>(quadric: &Quadric, ray: &Ray, notes: &mut N) -> Option<f64>;

    /// A plane (spec §5.1): t = N·(Q - B) / N·D, a miss when N·D = 0, t < 0 or z > 0.
    fn plane<N: Notes>(plane: &Plane, ray: &Ray, notes: &mut N) -> Option<f64>;

    /// What [`Kernel::plane_toward`] needs of `plane` for rays from `base`: the part of
    /// the test that the rays' base alone decides, computed once for many rays (a
    /// span's camera rays, which leave the eye). Nothing, unless the kernel says.
    #[inline(always)]
    fn plane_from(_plane: &Plane, _base: DVec3) -> PlaneFrom {
        PlaneFrom::default()
    }

    /// [`Kernel::plane`] without notes, for a `ray` from the base `from` was prepared
    /// for ([`Kernel::plane_from`]): the same t.
    #[inline(always)]
    fn plane_toward(plane: &Plane, _from: &PlaneFrom, ray: &Ray) -> Option<f64> {
        Self::plane(plane, ray, &mut ())
    }

    /// [`Kernel::plane_toward`] of the rays from `base` (the base `from` was prepared
    /// for) along `dirs`, for the lanes set in `lanes`: bit i of the mask set where lane
    /// i's ray hits, at `t[i]`. The same t as each ray's own test; one ray at a time,
    /// unless the kernel says.
    #[inline(always)]
    fn planes_toward(
        plane: &Plane,
        from: &PlaneFrom,
        base: DVec3,
        dirs: &Dirs,
        lanes: u32,
    ) -> ([f64; LANES], u32) {
        each_lane(lanes, |i| {
            Self::plane_toward(plane, from, &Ray::new(base, dirs.get(i)))
        })
    }

    /// Whether this kernel's [`Kernel::sphere`] surely finds no root, told from the
    /// terms [`Sphere::terms`] gives (D·D, D·w, |w|² with w = B - C) without computing
    /// them again; `false` where the kernel cannot tell so (its own test then decides).
    /// For `compare`'s margins, which compute those terms for the discriminant anyway.
    #[inline(always)]
    fn sphere_surely_misses(_sphere: &Sphere, _terms: (f64, f64, f64)) -> bool {
        false
    }
}

/// A plane's numerator N·(Q - B) for rays from one base B, and whether its terms cancel
/// ([`Kernel::plane_from`]); the kernels that do not split their test leave it unread.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct PlaneFrom {
    pub(crate) numerator: f64,
    pub(crate) cancels: bool,
}

/// What a zero discriminant (a ray tangent to the surface) means (spec §5.2, §5.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Tangent {
    /// The sphere: a hit only if the discriminant is > 0.
    Misses,
    /// The quadrics 21-24 and `QUADRIC`: the double root counts.
    Counts,
}

impl Tangent {
    /// Whether a discriminant `d` gives real roots under this rule (`false` for NaN).
    #[inline(always)]
    pub(crate) fn real<F: num_traits::Float>(self, d: F) -> bool {
        match self {
            Tangent::Misses => d > F::zero(),
            Tangent::Counts => d >= F::zero(),
        }
    }
}

/// The kernels, by the names `--kernel` takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KernelChoice {
    /// The shipped kernel: within 4 ulps of the exact root.
    #[default]
    Accurate,
    /// The notes' coefficients with cancellation-free roots.
    Stable,
    /// The notes' (-b ± sqrt(b² - 4ac)) / 2a in f64, as most students' tracers compute.
    Textbook,
    /// The notes' formula in f32, as a tracer written with `float` computes.
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

    /// The kernel's name, as `--kernel` takes it.
    pub fn name(self) -> &'static str {
        match self {
            KernelChoice::Accurate => "accurate",
            KernelChoice::Stable => "stable",
            KernelChoice::Textbook => "textbook",
            KernelChoice::TextbookF32 => "textbook-f32",
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

/// Runs `$body` with `$K` standing for the kernel type that `$choice` names: how the
/// aggregate and the shapes turn the run-time choice into a monomorphised loop.
macro_rules! with_kernel {
    ($choice:expr, $K:ident => $body:expr) => {
        match $choice {
            $crate::shapes::kernel::KernelChoice::Accurate => {
                type $K = $crate::shapes::kernel::Accurate;
                $body
            }
            $crate::shapes::kernel::KernelChoice::Stable => {
                type $K = $crate::shapes::kernel::Stable;
                $body
            }
            $crate::shapes::kernel::KernelChoice::Textbook => {
                type $K = $crate::shapes::kernel::Textbook;
                $body
            }
            $crate::shapes::kernel::KernelChoice::TextbookF32 => {
                type $K = $crate::shapes::kernel::TextbookF32;
                $body
            }
        }
    };
}
pub(crate) use with_kernel;
