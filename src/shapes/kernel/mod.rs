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
mod stable;
mod textbook;
mod textbook_f32;

pub use accurate::Accurate;
pub use stable::StableRoots;
pub use textbook::Textbook;
pub use textbook_f32::TextbookF32;

use super::{AxisQuadric, Plane, Quadric, Ray, RootRule};

/// One way to compute the hit distance of each kind of surface.
pub trait Kernel: Copy + Default + Send + Sync + 'static {
    /// The name used by `--kernel` and the report.
    const NAME: &'static str;

    /// The hit of a sphere or a quadric 21-24 under its [`RootRule`].
    fn axis_quadric(quadric: &AxisQuadric, ray: &Ray) -> Option<f64>;

    /// The smallest positive root of a general `QUADRIC`.
    fn quadric(quadric: &Quadric, ray: &Ray) -> Option<f64>;

    /// The plane's t = N·(Q - B) / N·D under the z rule of spec §5.1.
    fn plane(plane: &Plane, ray: &Ray) -> Option<f64>;
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

    /// The kernel with this name.
    pub fn from_name(name: &str) -> Option<KernelChoice> {
        KernelChoice::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The legacy choice among two ascending roots t0 <= t1 of an f64 kernel, given the
/// local ray's y (base and direction) for the bounds.
#[inline]
pub(crate) fn choose(rule: RootRule, roots: [f64; 2], base_y: f64, dir_y: f64) -> Option<f64> {
    match rule {
        RootRule::Nearer => Some(roots[0]),
        RootRule::FirstPositiveWithin { low, high } => roots.into_iter().find(|&t| {
            let y = base_y + t * dir_y;
            t > 0.0 && low <= y && y <= high
        }),
    }
}

/// A root solver: a, b, c and whether a zero discriminant misses.
pub(crate) type Solver = fn(f64, f64, f64, bool) -> Option<[f64; 2]>;

/// An axis quadric solved the way note 003 does it: the local ray, the coefficients as
/// written, the roots by `solve`, the legacy choice. Only the solver differs between
/// [`Textbook`] and [`StableRoots`].
#[inline(always)]
pub(crate) fn axis_quadric_as_written(
    quadric: &AxisQuadric,
    ray: &Ray,
    solve: Solver,
) -> Option<f64> {
    let (base, dir) = quadric.frame.to_local(ray);
    let (a, b, c) = quadric.coefficients(base, dir);
    let roots = solve(a, b, c, strict(quadric.rule))?;
    choose(quadric.rule, roots, base.y, dir.y)
}

/// A general quadric solved from its f64 coefficients by `solve`.
#[inline(always)]
pub(crate) fn quadric_as_written(quadric: &Quadric, ray: &Ray, solve: Solver) -> Option<f64> {
    let (a, b, c) = quadric.coefficients(ray);
    first_positive(solve(a, b, c, false)?)
}

/// The legacy choice for a general quadric: the smallest positive root.
#[inline]
pub(crate) fn first_positive(roots: [f64; 2]) -> Option<f64> {
    roots.into_iter().find(|&t| t > 0.0)
}

/// The sphere rejects a zero discriminant (a tangent ray misses, spec §5.2).
#[inline]
pub(crate) fn strict(rule: RootRule) -> bool {
    matches!(rule, RootRule::Nearer)
}

/// The plane's legacy test on an f64 t: in front of the base and not beyond the screen.
#[inline]
pub(crate) fn plane_rule(ray: &Ray, t: f64) -> Option<f64> {
    (t >= 0.0 && ray.base.z + t * ray.dir.z <= 0.0).then_some(t)
}
