//! The hard-case accuracy suite: seeded rays that the textbook root formula gets wrong,
//! for every kind of surface, and their exact roots computed in double-double (the
//! `twofloat` crate, about 106 bits, an implementation independent of the kernel's).
//!
//! Shared by the test `accuracy` (which asserts the goals of issue 4) and the report
//! `cargo run --release --example speed_vs_error` (which prints and charts them).

#![allow(dead_code)]

use glam::DVec3;
use legacy_rt::shapes::kernel::Kernel;
use legacy_rt::shapes::{
    AxisQuadric, Cone, Cylinder, Hyperboloid, Paraboloid, Plane, Quadric, Ray, RootRule, Shape,
    Sphere, unit,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
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

/// The answer of kernel `K`.
pub fn answer<K: Kernel>(case: &Case) -> Option<f64> {
    let t = case.shape.hit_with::<K>(&case.ray)?;
    // The sphere reports its nearer root even when negative; the caller keeps t > 0, and
    // so does the comparison.
    (t > 0.0 || matches!(case.shape, Shape::Sphere(_))).then_some(t)
}

// ---------------------------------------------------------------------------------------
// The reference.

type T = TwoFloat;

fn t(x: f64) -> T {
    T::from(x)
}

const EPS: f64 = f64::EPSILON;

/// The exact answer for a case.
pub fn reference(case: &Case) -> Reference {
    let ray = &case.ray;
    match &case.shape {
        Shape::Sphere(s) => axis_reference(&s.equation, ray),
        Shape::Paraboloid(s) => axis_reference(&s.equation, ray),
        Shape::Cylinder(s) => axis_reference(&s.equation, ray),
        Shape::Cone(s) => axis_reference(&s.equation, ray),
        Shape::Hyperboloid(s) => axis_reference(&s.equation, ray),
        Shape::Quadric(q) => quadric_reference(q, ray),
        Shape::Plane(p) => plane_reference(p, ray),
        other => panic!("no reference for {other:?}"),
    }
}

/// Ascending real roots of a t² + b t + c in double-double, and whether the discriminant
/// is within a few ulps of zero: of `size`, the magnitude of the terms it is made of.
fn roots(a: T, b: T, c: T, size: f64) -> (Option<[T; 2]>, bool) {
    if a == t(0.0) {
        if b == t(0.0) {
            return (None, false);
        }
        let root = -divide(c, b);
        return (Some([root, root]), false);
    }
    let discriminant = b * b - t(4.0) * a * c;
    let tie = discriminant.hi().abs() <= 8.0 * EPS * size;
    if discriminant < 0.0 {
        return (None, tie);
    }
    let root = discriminant.sqrt();
    let q = if b < 0.0 {
        (root - b) / t(2.0)
    } else {
        -(b + root) / t(2.0)
    };
    let (r1, r2) = (q / a, if q == t(0.0) { t(0.0) } else { c / q });
    let (r1, r2) = (polish(a, b, c, r1), polish(a, b, c, r2));
    (Some(if r1 <= r2 { [r1, r2] } else { [r2, r1] }), tie)
}

/// n / d with one correction step. twofloat's division alone can be off by more than
/// 1e-16 relative (1e10 + 1e5 over 1e5 + 1 comes out 7.5e-17 above 1e5), too coarse for
/// a reference; the remainder n - q d is computed from products and sums, which are
/// accurate, so the corrected quotient is good to about 1e-30.
fn divide(n: T, d: T) -> T {
    let q = n / d;
    q + (n - q * d) / d
}

/// Two Newton steps on a t² + b t + c from a root `r` (the root formula divides twice),
/// skipped where the slope vanishes (a double root, where Newton does not converge fast).
fn polish(a: T, b: T, c: T, mut r: T) -> T {
    for _ in 0..2 {
        let value = (a * r + b) * r + c;
        let slope = a * r * 2.0 + b;
        if slope == t(0.0) {
            break;
        }
        let step = value / slope;
        if step.hi().abs() > 1e-12 * r.hi().abs() {
            break;
        }
        r -= step;
    }
    r
}

fn axis_reference(quadric: &AxisQuadric, ray: &Ray) -> Reference {
    let frame = &quadric.frame;
    let offset: [T; 3] = [0, 1, 2].map(|i| t(ray.base[i]) - t(frame.centre[i]));
    let dir: [T; 3] = [0, 1, 2].map(|i| t(ray.dir[i]));
    let rotate = |v: [T; 3]| -> [T; 3] {
        if frame.identity {
            return v;
        }
        [0, 1, 2].map(|i| {
            let row = frame.irot.col(i);
            v[0] * row.x + v[1] * row.y + v[2] * row.z
        })
    };
    let (base, dir) = (rotate(offset), rotate(dir));
    let sq = quadric.alpha.to_array();
    let mut a = t(0.0);
    let mut b = t(0.0);
    let mut c = t(quadric.constant);
    for i in 0..3 {
        a += dir[i] * dir[i] * sq[i];
        b += base[i] * dir[i] * (2.0 * sq[i]);
        c += base[i] * base[i] * sq[i];
    }
    b += dir[1] * quadric.linear_y;
    c += base[1] * quadric.linear_y;
    let scale = offset.iter().map(|v| v.hi().abs()).fold(0.0, f64::max);
    // The discriminant b² - 4ac, measured against its two terms.
    let size = (b * b).hi().abs().max((t(4.0) * a * c).hi().abs());
    let (found, disc_tie) = roots(a, b, c, size);
    let mut tie = disc_tie;
    let chosen = found.and_then(|found| match quadric.rule {
        RootRule::Nearer => {
            // A zero discriminant misses the sphere (spec §5.2).
            (found[0] != found[1]).then_some(found[0])
        }
        RootRule::FirstPositiveWithin { low, high } => found.into_iter().find(|&root| {
            let y = base[1] + root * dir[1];
            let slack = 16.0 * EPS * (scale + root.hi().abs());
            let near_bound = (y - low).hi().abs() <= slack || (y - high).hi().abs() <= slack;
            let near_zero = root.hi().abs() <= 16.0 * EPS * scale;
            tie |= near_bound || near_zero;
            root > 0.0 && y >= low && y <= high
        }),
    });
    Reference {
        t: chosen.map(|x| x.hi() + x.lo()),
        exact: chosen,
        tie,
        scale,
    }
}

fn quadric_reference(quadric: &Quadric, ray: &Ray) -> Reference {
    let p: [T; 4] = [t(ray.base.x), t(ray.base.y), t(ray.base.z), t(1.0)];
    let d: [T; 4] = [t(ray.dir.x), t(ray.dir.y), t(ray.dir.z), t(0.0)];
    let q = quadric.q.to_cols_array_2d();
    let form = |u: &[T; 4], v: &[T; 4]| {
        let mut sum = t(0.0);
        for i in 0..4 {
            for j in 0..4 {
                sum += u[i] * v[j] * q[i][j];
            }
        }
        sum
    };
    let (a, b, c) = (form(&d, &d), form(&d, &p) * 2.0, form(&p, &p));
    let scale = ray.base.abs().max_element();
    // Here a, b and c are themselves sums of terms |Q| |p|² that cancel (a cone's apex
    // away from the origin makes J = CᵀMC): the discriminant is measured against the
    // magnitudes of those terms, b_mag² + 4 a_mag c_mag.
    let magnitude = |u: glam::DVec4, v: glam::DVec4| u.abs().dot(quadric.q.abs() * v.abs());
    let (pf, df) = (ray.base.extend(1.0), ray.dir.extend(0.0));
    let b_size = 2.0 * magnitude(df, pf);
    let size = b_size * b_size + 4.0 * magnitude(df, df) * magnitude(pf, pf);
    let (found, mut tie) = roots(a, b, c, size);
    let chosen = found.and_then(|found| {
        found.into_iter().find(|&root| {
            tie |= root.hi().abs() <= 16.0 * EPS * scale;
            root > 0.0
        })
    });
    Reference {
        t: chosen.map(|x| x.hi() + x.lo()),
        exact: chosen,
        tie,
        scale,
    }
}

fn plane_reference(plane: &Plane, ray: &Ray) -> Reference {
    let n = plane.normal;
    let mut numerator = t(0.0);
    let mut denominator = t(0.0);
    for i in 0..3 {
        numerator += (t(plane.point[i]) - t(ray.base[i])) * n[i];
        denominator += t(ray.dir[i]) * n[i];
    }
    let scale = (plane.point - ray.base).abs().max_element();
    if denominator == t(0.0) {
        return Reference {
            t: None,
            exact: None,
            tie: false,
            scale,
        };
    }
    let root = divide(numerator, denominator);
    let z = t(ray.base.z) + root * ray.dir.z;
    let tie = z.hi().abs() <= 16.0 * EPS * (ray.base.z.abs() + root.hi().abs())
        || root.hi().abs() <= 16.0 * EPS * scale;
    let chosen = (root >= 0.0 && z <= 0.0).then_some(root);
    Reference {
        t: chosen.map(|x| x.hi() + x.lo()),
        exact: chosen,
        tie,
        scale,
    }
}

// ---------------------------------------------------------------------------------------
// The cases.

struct Gen(ChaCha8Rng);

impl Gen {
    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.0.random::<f64>()
    }

    /// Log-uniform in [low, high].
    fn log(&mut self, low: f64, high: f64) -> f64 {
        (self.uniform(low.ln(), high.ln())).exp()
    }

    fn sign(&mut self) -> f64 {
        if self.0.random::<bool>() { 1.0 } else { -1.0 }
    }

    /// A uniformly distributed unit vector.
    fn direction(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.uniform(-1.0, 1.0),
                self.uniform(-1.0, 1.0),
                self.uniform(-1.0, 1.0),
            );
            let length = v.length();
            if length > 0.1 && length <= 1.0 {
                return v / length;
            }
        }
    }

    /// A unit vector perpendicular to the unit `v`.
    fn perpendicular(&mut self, v: DVec3) -> DVec3 {
        loop {
            let w = self.direction();
            if let Some(p) = unit(w - w.dot(v) * v)
                && w.cross(v).length() > 0.1
            {
                return p;
            }
        }
    }

    fn point(&mut self, size: f64) -> DVec3 {
        DVec3::new(
            self.uniform(-size, size),
            self.uniform(-size, size),
            self.uniform(-size, size),
        )
    }
}

/// A ray that passes at distance `impact` from `centre` with direction `dir`, starting
/// `distance` before the point of closest approach.
fn ray_past(centre: DVec3, dir: DVec3, sideways: DVec3, impact: f64, distance: f64) -> Ray {
    Ray {
        base: centre + impact * sideways - distance * dir,
        dir,
    }
}

/// The ray in a shape's local frame (axis +y from its centre) turned into the world.
fn from_local(equation: &AxisQuadric, base: DVec3, dir: DVec3) -> Ray {
    let frame = &equation.frame;
    Ray {
        base: frame.centre + frame.irot * base,
        dir: unit(frame.irot * dir).expect("nonzero direction"),
    }
}

/// A horizontal local ray that passes the axis at height `y`, distance `impact` from it,
/// starting `distance` before the closest point.
fn across_axis(g: &mut Gen, y: f64, impact: f64, distance: f64) -> (DVec3, DVec3) {
    let angle = g.uniform(0.0, std::f64::consts::TAU);
    let dir = DVec3::new(angle.cos(), 0.0, angle.sin());
    let sideways = DVec3::new(-angle.sin(), 0.0, angle.cos());
    (
        DVec3::new(0.0, y, 0.0) + impact * sideways - distance * dir,
        dir,
    )
}

/// Where a horizontal local ray crosses a surface of revolution: its radius at height
/// `y`, and the shape's size for the distance of the ray's start.
struct Side {
    radius: f64,
    y: f64,
    size: f64,
    shape: Shape,
}

/// A family's ranges: the fraction of the radius the ray passes the axis at, and the
/// distance of its start in sizes (log-uniform).
struct Spread {
    impact: (f64, f64),
    distance: (f64, f64),
}

const FAR: Spread = Spread {
    impact: (0.0, 0.9),
    distance: (10.0, 1e5),
};
const GRAZING: Spread = Spread {
    impact: (0.999, 1.0),
    distance: (2.0, 1e3),
};
const TRANSLATED: Spread = Spread {
    impact: (0.0, 0.95),
    distance: (2.0, 50.0),
};

impl Side {
    fn new(radius: f64, y: f64, size: f64, shape: Shape) -> Side {
        Side {
            radius,
            y,
            size,
            shape,
        }
    }

    /// A horizontal local ray at height y, spread as `spread` says.
    fn case(self, g: &mut Gen, spread: Spread) -> Case {
        let impact = self.radius * g.uniform(spread.impact.0, spread.impact.1);
        let distance = self.size * g.log(spread.distance.0, spread.distance.1);
        let (base, dir) = across_axis(g, self.y, impact, distance);
        let equation = match &self.shape {
            Shape::Cylinder(s) => &s.equation,
            Shape::Cone(s) => &s.equation,
            Shape::Paraboloid(s) => &s.equation,
            Shape::Hyperboloid(s) => &s.equation,
            other => unreachable!("{other:?} is not a surface of revolution"),
        };
        let ray = from_local(equation, base, dir);
        Case {
            shape: self.shape,
            ray,
        }
    }
}

fn family(
    shape: &'static str,
    name: &'static str,
    g: &mut Gen,
    mut make: impl FnMut(&mut Gen) -> Case,
) -> Family {
    Family {
        shape,
        name,
        cases: (0..PER_FAMILY).map(|_| make(g)).collect(),
    }
}

fn sphere(centre: DVec3, radius: f64) -> Shape {
    Shape::Sphere(Sphere::new(centre, radius, "sphere").unwrap())
}

/// A general quadric written from an axis quadric: the same surface, unbounded.
pub fn as_general_quadric(equation: &AxisQuadric) -> Quadric {
    // f(P) = (P - C)ᵀ M (P - C) + β r·(P - C) + γ with M = Rᵀ diag(α) R and r the y row
    // of R (R = rotmat).
    let r = equation.frame.rotmat;
    let m = r.transpose() * glam::DMat3::from_diagonal(equation.alpha) * r;
    let row_y = equation.frame.irot.col(1);
    let c = equation.frame.centre;
    let beta = equation.linear_y;
    let g = -(m * c) + 0.5 * beta * row_y;
    let j = c.dot(m * c) - beta * row_y.dot(c) + equation.constant;
    Quadric::new([
        m.x_axis.x, m.y_axis.x, m.z_axis.x, g.x, m.y_axis.y, m.z_axis.y, g.y, m.z_axis.z, g.z, j,
    ])
    .unwrap()
}

/// A random orientation for a shape's centre line.
fn centre_line(g: &mut Gen) -> DVec3 {
    g.direction()
}

/// Every family of the suite, generated from [`SEED`].
pub fn suite() -> Vec<Family> {
    let mut g = Gen(ChaCha8Rng::seed_from_u64(SEED));
    let g = &mut g;
    let mut families = Vec::new();

    // Sphere.
    families.push(family("sphere", "far (d/r 10..1e5)", g, |g| {
        let (centre, radius) = (g.point(5.0), g.uniform(0.5, 2.0));
        let dir = g.direction();
        let side = g.perpendicular(dir);
        let impact = radius * g.uniform(0.0, 0.9);
        let ray = ray_past(centre, dir, side, impact, radius * g.log(10.0, 1e5));
        Case {
            shape: sphere(centre, radius),
            ray,
        }
    }));
    families.push(family("sphere", "grazing (0.999..1 of r)", g, |g| {
        let (centre, radius) = (g.point(5.0), g.uniform(0.5, 2.0));
        let dir = g.direction();
        let side = g.perpendicular(dir);
        let impact = radius * g.uniform(0.999, 1.0);
        let ray = ray_past(centre, dir, side, impact, radius * g.log(2.0, 1e3));
        Case {
            shape: sphere(centre, radius),
            ray,
        }
    }));
    families.push(family(
        "sphere",
        "huge (r 1e4..1e6, eye just above)",
        g,
        |g| {
            let radius = g.log(1e4, 1e6);
            let centre = g.point(5.0);
            let up = g.direction();
            let eye = centre + (radius + g.log(0.01, 10.0)) * up;
            let side = g.perpendicular(up);
            let down = g.uniform(0.05, 1.0);
            let dir = unit(-down * up + (1.0 - down * down).sqrt() * side).unwrap();
            Case {
                shape: sphere(centre, radius),
                ray: Ray { base: eye, dir },
            }
        },
    ));
    families.push(family("sphere", "translated 1e4", g, |g| {
        let centre = 1e4 * g.direction() + g.point(5.0);
        let radius = g.uniform(0.5, 2.0);
        let dir = g.direction();
        let side = g.perpendicular(dir);
        let impact = radius * g.uniform(0.0, 0.95);
        let ray = ray_past(centre, dir, side, impact, radius * g.log(2.0, 50.0));
        Case {
            shape: sphere(centre, radius),
            ray,
        }
    }));

    // The course quadrics, with random centres and centre lines.
    let cylinder = |g: &mut Gen, far: f64| {
        let (r, h) = (g.uniform(0.5, 2.0), g.uniform(1.0, 5.0));
        let centre = far * g.direction() + g.point(5.0);
        Cylinder::new(centre, centre_line(g), r, h).unwrap()
    };
    let cylinder_side = |g: &mut Gen, far: f64| {
        let s = cylinder(g, far);
        let y = g.uniform(0.1, 0.9) * s.size.height;
        Side::new(s.size.radius, y, s.size.radius, Shape::Cylinder(s))
    };
    families.push(family("cylinder", "far (d/r 10..1e5)", g, |g| {
        let side = cylinder_side(g, 0.0);
        side.case(g, FAR)
    }));
    families.push(family("cylinder", "grazing (0.999..1 of r)", g, |g| {
        let side = cylinder_side(g, 0.0);
        side.case(g, GRAZING)
    }));
    families.push(family("cylinder", "nearly parallel to the axis", g, |g| {
        let s = cylinder(g, 0.0);
        let (r, h) = (s.size.radius, s.size.height);
        let tilt = g.log(1e-9, 1e-3);
        let angle = g.uniform(0.0, std::f64::consts::TAU);
        let out = DVec3::new(angle.cos(), 0.0, angle.sin());
        // From below the base, drifting outward (from inside) or inward (from outside)
        // so that the wall is met at a height between 0 and h.
        let rise = g.uniform(0.1, 0.9) * h + 1.0;
        let (start, drift) = if g.0.random::<bool>() {
            (r - tilt * rise, out)
        } else {
            (r + tilt * rise, -out)
        };
        let base = DVec3::new(0.0, -1.0, 0.0) + start * out;
        let dir = DVec3::new(0.0, 1.0, 0.0) + tilt * drift;
        let ray = from_local(&s.equation, base, dir);
        Case {
            shape: Shape::Cylinder(s),
            ray,
        }
    }));
    families.push(family("cylinder", "at the rims y = 0 and y = h", g, |g| {
        let s = cylinder(g, 0.0);
        let (r, h) = (s.size.radius, s.size.height);
        let rim = if g.0.random::<bool>() { 0.0 } else { h };
        let y = rim + g.sign() * g.log(1e-12, 1e-3) * h;
        let (y, impact, distance) = (y, r * g.uniform(0.0, 0.9), r * g.log(2.0, 100.0));
        let (base, dir) = across_axis(g, y, impact, distance);
        let ray = from_local(&s.equation, base, dir);
        Case {
            shape: Shape::Cylinder(s),
            ray,
        }
    }));
    families.push(family("cylinder", "translated 1e4", g, |g| {
        let side = cylinder_side(g, 1e4);
        side.case(g, TRANSLATED)
    }));

    let cone = |g: &mut Gen, far: f64| {
        let (r, h) = (g.uniform(0.5, 2.0), g.uniform(1.0, 5.0));
        let centre = far * g.direction() + g.point(5.0);
        Cone::new(centre, centre_line(g), r, h).unwrap()
    };
    let cone_side = |g: &mut Gen, far: f64| {
        let s = cone(g, far);
        let y = g.uniform(0.2, 0.9) * s.size.height;
        Side::new(s.k.sqrt() * y, y, s.size.radius, Shape::Cone(s))
    };
    families.push(family("cone", "far (d/r 10..1e5)", g, |g| {
        let side = cone_side(g, 0.0);
        side.case(g, FAR)
    }));
    families.push(family("cone", "grazing (0.999..1 of r)", g, |g| {
        let side = cone_side(g, 0.0);
        side.case(g, GRAZING)
    }));
    families.push(family("cone", "nearly parallel to a generator", g, |g| {
        let s = cone(g, 0.0);
        let slope = s.k.sqrt();
        let around = |angle: f64| DVec3::new(angle.cos(), 0.0, angle.sin());
        let angle = g.uniform(0.0, std::f64::consts::TAU);
        // A point P of the wall on the side w, reached along the generator direction of
        // another side w' (so a = 0 but for the tilt), which arrives from outside.
        let y = g.uniform(0.2, 0.9) * s.size.height;
        let target = slope * y * around(angle) + DVec3::new(0.0, y, 0.0);
        let other = around(angle + g.uniform(0.5, 1.0) * std::f64::consts::PI);
        let generator = DVec3::new(0.0, 1.0, 0.0) + slope * other;
        let dir = generator + g.log(1e-9, 1e-3) * g.direction();
        let base = target - g.uniform(0.5, 5.0) * s.size.height * dir;
        let ray = from_local(&s.equation, base, dir);
        Case {
            shape: Shape::Cone(s),
            ray,
        }
    }));
    families.push(family("cone", "through and near the apex", g, |g| {
        let s = cone(g, 0.0);
        let miss = g.log(1e-12, 1e-2) * s.size.height * g.direction();
        let from = s.size.height
            * g.log(1.0, 100.0)
            * DVec3::new(g.uniform(-1.0, 1.0), 1.0, g.uniform(-1.0, 1.0));
        let target = if g.0.random::<bool>() {
            DVec3::ZERO
        } else {
            miss
        };
        let ray = from_local(&s.equation, from, target - from);
        Case {
            shape: Shape::Cone(s),
            ray,
        }
    }));
    families.push(family("cone", "translated 1e4", g, |g| {
        let side = cone_side(g, 1e4);
        side.case(g, TRANSLATED)
    }));

    let paraboloid = |g: &mut Gen, far: f64| {
        let (r, h) = (g.uniform(0.5, 2.0), g.uniform(1.0, 5.0));
        let centre = far * g.direction() + g.point(5.0);
        Paraboloid::new(centre, centre_line(g), r, h).unwrap()
    };
    let paraboloid_side = |g: &mut Gen, far: f64| {
        let s = paraboloid(g, far);
        let y = g.uniform(0.2, 0.9) * s.size.height;
        Side::new((s.k * y).sqrt(), y, s.size.radius, Shape::Paraboloid(s))
    };
    families.push(family("paraboloid", "along and near the axis", g, |g| {
        let s = paraboloid(g, 0.0);
        let offset = if g.0.random::<bool>() {
            0.0
        } else {
            g.log(1e-12, 1e-3) * s.size.radius
        };
        let angle = g.uniform(0.0, std::f64::consts::TAU);
        let out = DVec3::new(angle.cos(), 0.0, angle.sin());
        let base = DVec3::new(0.0, s.size.height * g.uniform(1.0, 10.0), 0.0) + offset * out;
        let dir = DVec3::new(0.0, -1.0, 0.0) + g.log(1e-12, 1e-6) * g.sign() * out;
        let ray = from_local(&s.equation, base, dir);
        Case {
            shape: Shape::Paraboloid(s),
            ray,
        }
    }));
    families.push(family("paraboloid", "far (d/r 10..1e5)", g, |g| {
        let side = paraboloid_side(g, 0.0);
        side.case(g, FAR)
    }));
    families.push(family("paraboloid", "grazing (0.999..1 of r)", g, |g| {
        let side = paraboloid_side(g, 0.0);
        side.case(g, GRAZING)
    }));
    families.push(family("paraboloid", "translated 1e4", g, |g| {
        let side = paraboloid_side(g, 1e4);
        side.case(g, TRANSLATED)
    }));

    let hyperboloid = |g: &mut Gen, far: f64| {
        let (r, h) = (g.uniform(1.0, 2.0), g.uniform(1.0, 5.0));
        let waist = r * g.uniform(0.2, 0.9);
        let centre = far * g.direction() + g.point(5.0);
        Hyperboloid::new(centre, centre_line(g), r, h, waist).unwrap()
    };
    let hyperboloid_side = |g: &mut Gen, far: f64| {
        let s = hyperboloid(g, far);
        let y = g.uniform(-0.9, 0.9) * s.size.height;
        let radius = (s.k * y * y + s.waist * s.waist).sqrt();
        Side::new(radius, y, s.size.radius, Shape::Hyperboloid(s))
    };
    families.push(family("hyperboloid", "near the waist", g, |g| {
        let s = hyperboloid(g, 0.0);
        let y = g.sign() * g.log(1e-9, 1e-3) * s.size.height;
        let fraction = if g.0.random::<bool>() {
            g.uniform(0.999, 1.0)
        } else {
            g.uniform(0.0, 0.9)
        };
        let (y, impact, distance) = (y, s.waist * fraction, s.size.radius * g.log(2.0, 1e3));
        let (base, dir) = across_axis(g, y, impact, distance);
        let ray = from_local(&s.equation, base, dir);
        Case {
            shape: Shape::Hyperboloid(s),
            ray,
        }
    }));
    families.push(family("hyperboloid", "far (d/r 10..1e5)", g, |g| {
        let side = hyperboloid_side(g, 0.0);
        side.case(g, FAR)
    }));
    families.push(family("hyperboloid", "translated 1e4", g, |g| {
        let side = hyperboloid_side(g, 1e4);
        side.case(g, TRANSLATED)
    }));

    // The general quadric: spheres, cylinders and cones written as QUADRIC records.
    let quadric_of = |shape: &Shape| match shape {
        Shape::Sphere(s) => as_general_quadric(&s.equation),
        Shape::Cylinder(s) => as_general_quadric(&s.equation),
        Shape::Cone(s) => as_general_quadric(&s.equation),
        _ => unreachable!(),
    };
    let rewritten = |families: &Vec<Family>, shape: &str, name: &str| -> Vec<Case> {
        let source = families
            .iter()
            .find(|f| f.shape == shape && f.name == name)
            .expect("family exists");
        source
            .cases
            .iter()
            .map(|case| Case {
                shape: Shape::Quadric(quadric_of(&case.shape)),
                ray: case.ray,
            })
            .collect()
    };
    for (shape, name, label) in [
        ("sphere", "far (d/r 10..1e5)", "sphere, far"),
        ("sphere", "grazing (0.999..1 of r)", "sphere, grazing"),
        ("sphere", "translated 1e4", "sphere, translated 1e4"),
        (
            "cylinder",
            "nearly parallel to the axis",
            "cylinder, nearly parallel",
        ),
        ("cone", "through and near the apex", "cone, near the apex"),
        ("cylinder", "translated 1e4", "cylinder, translated 1e4"),
    ] {
        let cases = rewritten(&families, shape, name);
        families.push(Family {
            shape: "quadric",
            name: label,
            cases,
        });
    }

    // The plane, under the z rule: the eye in front of the screen, the plane behind it.
    let plane_case = |g: &mut Gen, distance: f64, grazing: bool, shift: DVec3| {
        let eye = shift
            + DVec3::new(
                g.uniform(-2.0, 2.0),
                g.uniform(-2.0, 2.0),
                g.uniform(0.5, 5.0),
            );
        let dir = if grazing {
            unit(DVec3::new(
                g.uniform(-1.0, 1.0),
                g.uniform(-1.0, 1.0),
                -g.uniform(0.2, 1.0),
            ))
            .unwrap()
        } else {
            unit(DVec3::new(g.uniform(-0.5, 0.5), g.uniform(-0.5, 0.5), -1.0)).unwrap()
        };
        let hit = eye + distance * dir;
        let normal = if grazing {
            // Nearly perpendicular to the ray: the ray meets the plane at a shallow angle.
            let side = g.perpendicular(dir);
            unit(side + g.sign() * g.log(1e-6, 1e-2) * dir).unwrap()
        } else {
            let n = g.direction();
            if n.dot(dir).abs() < 0.2 { -dir } else { n }
        };
        let point = hit + g.uniform(1.0, 10.0) * g.perpendicular(normal);
        Case {
            shape: Shape::Plane(Plane::new(normal, point, "plane").unwrap()),
            ray: Ray { base: eye, dir },
        }
    };
    families.push(family("plane", "far (distance 10..1e5)", g, |g| {
        let d = g.log(10.0, 1e5);
        plane_case(g, d, false, DVec3::ZERO)
    }));
    families.push(family("plane", "grazing (1e-6..1e-2 rad)", g, |g| {
        let d = g.log(2.0, 100.0);
        plane_case(g, d, true, DVec3::ZERO)
    }));
    families.push(family("plane", "translated 1e4", g, |g| {
        let d = g.log(2.0, 50.0);
        let shift = DVec3::new(1e4 * g.sign(), 1e4 * g.sign(), -1e4);
        plane_case(g, d, false, shift)
    }));
    families.push(family("plane", "hits near z = 0", g, |g| {
        // A floor through the bottom edge of a window: camera rays to the edge's points.
        let eye = DVec3::new(0.0, 0.0, g.uniform(1.0, 10.0));
        let edge = -g.uniform(1.0, 5.0);
        let x = g.uniform(-5.0, 5.0);
        let dir = unit(DVec3::new(x, edge + g.sign() * g.log(1e-12, 1e-3), 0.0) - eye).unwrap();
        let normal = unit(DVec3::new(0.0, 1.0, g.uniform(-1.0, 1.0))).unwrap();
        let point = DVec3::new(0.0, edge, 0.0);
        Case {
            shape: Shape::Plane(Plane::new(normal, point, "plane").unwrap()),
            ray: Ray { base: eye, dir },
        }
    }));
    families
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

/// Runs kernel `K` over a family against precomputed references.
pub fn tally<K: Kernel>(family: &Family, references: &[Reference]) -> Tally {
    let mut tally = Tally::default();
    for (case, reference) in family.cases.iter().zip(references) {
        match judge(answer::<K>(case), reference) {
            Outcome::Hit(error) => tally.errors.push(error),
            Outcome::Miss => tally.misses += 1,
            Outcome::Tie => tally.ties += 1,
            Outcome::Disagree => tally.disagreements += 1,
        }
    }
    tally
}
