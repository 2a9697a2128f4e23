//! The hard-case accuracy suite: seeded rays that the textbook root formula gets wrong,
//! for every kind of surface, and their exact roots computed in double-double (the
//! `twofloat` crate, about 106 bits, an implementation independent of the kernel's).
//!
//! Shared by the test `accuracy` (which asserts the goals of issue 4) and the report
//! `cargo run --release --example speed_vs_error` (which prints and charts them). The
//! rays are in `accuracy/families.rs` (a table of families drawn from one seeded
//! stream), their exact roots in `accuracy/reference.rs`.

#![allow(dead_code)]

#[path = "accuracy/families.rs"]
mod families;
#[path = "accuracy/reference.rs"]
mod reference;

pub use families::suite;
// The tests rewrite shapes as `QUADRIC` records; the report does not.
#[allow(unused_imports)]
pub use families::as_general_quadric;
pub use reference::reference;

use legacy_rt::shapes::kernel::KernelChoice;
use legacy_rt::shapes::{Ray, Shape};
use twofloat::TwoFloat;

/// The suite's seed: the same rays on every machine and run.
pub const SEED: u64 = 0x2026_1121;

/// Rays per family.
pub const PER_FAMILY: usize = 250;

/// The accuracy goal of issue 4, in ulps.
pub const GOAL_ULPS: f64 = 4.0;

/// One ray against one surface.
pub struct Case {
    /// The surface.
    pub shape: Shape,
    /// The ray (unit direction).
    pub ray: Ray,
}

/// A named group of hard cases for one kind of surface.
pub struct Family {
    /// The kind of surface ("sphere", "cylinder", ...).
    pub shape: &'static str,
    /// What makes these rays hard.
    pub name: &'static str,
    /// The cases.
    pub cases: Vec<Case>,
}

/// The kinds of surface, in report order.
pub const SHAPES: [&str; 7] = [
    "sphere",
    "paraboloid",
    "cylinder",
    "cone",
    "hyperboloid",
    "quadric",
    "plane",
];

/// The exact answer for one case.
#[derive(Debug, Clone, Copy)]
pub struct Reference {
    /// The exact t under the legacy rules, rounded to f64, or a miss.
    pub t: Option<f64>,
    /// The exact t itself (for the error, computed before rounding).
    pub exact: Option<TwoFloat>,
    /// Whether the case is a tie that rounding may decide either way: the exact
    /// discriminant, a bound (y = 0, y = h, z = 0) or t = 0 within a few ulps.
    pub tie: bool,
    /// The size of the problem (distance to the surface's reference point), for tiny t.
    pub scale: f64,
}

/// How one kernel did on one case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Outcome {
    /// Both hit; the error in ulps of the exact t (or of 1e-6 the scale, if larger).
    Hit(f64),
    /// Both missed.
    Miss,
    /// Hit and miss disagree, or the roots differ, on a tie: allowed, counted.
    Tie,
    /// Hit and miss disagree on a case that is not a tie: a failure.
    Disagree,
}

/// Compares a kernel's answer with the reference.
pub fn judge(answer: Option<f64>, reference: &Reference) -> Outcome {
    match (answer, reference.t, reference.exact) {
        (None, None, _) => Outcome::Miss,
        (Some(t), Some(_), Some(exact)) => {
            let error = ulps(t, exact, reference.scale);
            if error > GOAL_ULPS && reference.tie {
                Outcome::Tie
            } else {
                Outcome::Hit(error)
            }
        }
        _ if reference.tie => Outcome::Tie,
        _ => Outcome::Disagree,
    }
}

/// |t - exact| in ulps of max(|exact|, 1e-6 scale).
pub fn ulps(t: f64, exact: TwoFloat, scale: f64) -> f64 {
    let difference = (TwoFloat::from(t) - exact).hi().abs();
    let size = exact.hi().abs().max(1e-6 * scale);
    difference / ulp(size)
}

/// The spacing of f64 numbers at x > 0.
pub fn ulp(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1) - x
}

/// The answer of `kernel`.
pub fn answer(kernel: KernelChoice, case: &Case) -> Option<f64> {
    let t = case.shape.hit(&case.ray, kernel)?;
    // The sphere reports its nearer root even when negative; the caller keeps t > 0, and
    // so does the comparison.
    (t > 0.0 || matches!(case.shape, Shape::Sphere(_))).then_some(t)
}

/// Tallies for one kernel on one family.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    /// Errors of the hits, in ulps.
    pub errors: Vec<f64>,
    /// Hits counted as misses or misses as hits, outside the ties.
    pub disagreements: usize,
    /// Ties (either answer allowed).
    pub ties: usize,
    /// Agreed misses.
    pub misses: usize,
}

impl Tally {
    /// The largest error, 0 without hits.
    pub fn max(&self) -> f64 {
        self.errors.iter().copied().fold(0.0, f64::max)
    }

    /// The median error, 0 without hits.
    pub fn median(&self) -> f64 {
        if self.errors.is_empty() {
            return 0.0;
        }
        let mut sorted = self.errors.clone();
        sorted.sort_by(f64::total_cmp);
        sorted[sorted.len() / 2]
    }

    /// Adds another tally.
    pub fn merge(&mut self, other: &Tally) {
        self.errors.extend_from_slice(&other.errors);
        self.disagreements += other.disagreements;
        self.ties += other.ties;
        self.misses += other.misses;
    }
}

/// Runs `kernel` over a family against precomputed references.
pub fn tally(kernel: KernelChoice, family: &Family, references: &[Reference]) -> Tally {
    let mut tally = Tally::default();
    for (case, reference) in family.cases.iter().zip(references) {
        match judge(answer(kernel, case), reference) {
            Outcome::Hit(error) => tally.errors.push(error),
            Outcome::Miss => tally.misses += 1,
            Outcome::Tie => tally.ties += 1,
            Outcome::Disagree => tally.disagreements += 1,
        }
    }
    tally
}
