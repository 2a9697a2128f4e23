//! The hard cases: families of seeded rays, each aimed at what makes one kind of surface
//! hard (far, grazing, huge, translated, axis-parallel, apex, waist and rim rays), and
//! the table that draws them from one seeded stream, in a fixed order.

use super::{Case, Family, PER_FAMILY, SEED};
use glam::DVec3;
use legacy_rt::shapes::{
    AxisQuadric, Cone, Cylinder, Hyperboloid, Paraboloid, Plane, Quadric, Ray, Shape, Sphere, unit,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

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
        base: frame.centre + frame.irot() * base,
        dir: unit(frame.irot() * dir).expect("nonzero direction"),
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

fn sphere(centre: DVec3, radius: f64) -> Shape {
    Shape::Sphere(Sphere::new(centre, radius, "sphere").unwrap())
}

/// A general quadric written from an axis quadric: the same surface, unbounded.
pub fn as_general_quadric(equation: &AxisQuadric) -> Quadric {
    // f(P) = (P - C)ᵀ M (P - C) + β r·(P - C) + γ with M = Rᵀ diag(α) R and r the y row
    // of R (R = rotmat).
    let r = equation.frame.rotmat();
    let m = r.transpose() * glam::DMat3::from_diagonal(equation.alpha) * r;
    let row_y = equation.frame.irot().col(1);
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

/// Where a family's cases come from.
enum Source {
    /// Drawn from the seeded stream, [`PER_FAMILY`] rays in a row.
    Drawn(fn(&mut Gen) -> Case),
    /// The cases of an earlier family (shape, name), each surface rewritten as a
    /// `QUADRIC`: the same rays, no draws.
    Rewritten(&'static str, &'static str),
}

use Source::{Drawn, Rewritten};

/// Every family: surface, name, source. The order is the order of the draws, so it fixes
/// the rays: a new family goes at the end.
const FAMILIES: &[(&str, &str, Source)] = &[
    ("sphere", "far (d/r 10..1e5)", Drawn(sphere_far)),
    ("sphere", "grazing (0.999..1 of r)", Drawn(sphere_grazing)),
    (
        "sphere",
        "huge (r 1e4..1e6, eye just above)",
        Drawn(sphere_huge),
    ),
    ("sphere", "translated 1e4", Drawn(sphere_translated)),
    (
        "cylinder",
        "far (d/r 10..1e5)",
        Drawn(|g| cylinder_side(g, 0.0).case(g, FAR)),
    ),
    (
        "cylinder",
        "grazing (0.999..1 of r)",
        Drawn(|g| cylinder_side(g, 0.0).case(g, GRAZING)),
    ),
    (
        "cylinder",
        "nearly parallel to the axis",
        Drawn(cylinder_parallel),
    ),
    (
        "cylinder",
        "at the rims y = 0 and y = h",
        Drawn(cylinder_rims),
    ),
    (
        "cylinder",
        "translated 1e4",
        Drawn(|g| cylinder_side(g, 1e4).case(g, TRANSLATED)),
    ),
    (
        "cone",
        "far (d/r 10..1e5)",
        Drawn(|g| cone_side(g, 0.0).case(g, FAR)),
    ),
    (
        "cone",
        "grazing (0.999..1 of r)",
        Drawn(|g| cone_side(g, 0.0).case(g, GRAZING)),
    ),
    (
        "cone",
        "nearly parallel to a generator",
        Drawn(cone_generator),
    ),
    ("cone", "through and near the apex", Drawn(cone_apex)),
    (
        "cone",
        "translated 1e4",
        Drawn(|g| cone_side(g, 1e4).case(g, TRANSLATED)),
    ),
    (
        "paraboloid",
        "along and near the axis",
        Drawn(paraboloid_axis),
    ),
    (
        "paraboloid",
        "far (d/r 10..1e5)",
        Drawn(|g| paraboloid_side(g, 0.0).case(g, FAR)),
    ),
    (
        "paraboloid",
        "grazing (0.999..1 of r)",
        Drawn(|g| paraboloid_side(g, 0.0).case(g, GRAZING)),
    ),
    (
        "paraboloid",
        "translated 1e4",
        Drawn(|g| paraboloid_side(g, 1e4).case(g, TRANSLATED)),
    ),
    ("hyperboloid", "near the waist", Drawn(hyperboloid_waist)),
    (
        "hyperboloid",
        "far (d/r 10..1e5)",
        Drawn(|g| hyperboloid_side(g, 0.0).case(g, FAR)),
    ),
    (
        "hyperboloid",
        "translated 1e4",
        Drawn(|g| hyperboloid_side(g, 1e4).case(g, TRANSLATED)),
    ),
    (
        "quadric",
        "sphere, far",
        Rewritten("sphere", "far (d/r 10..1e5)"),
    ),
    (
        "quadric",
        "sphere, grazing",
        Rewritten("sphere", "grazing (0.999..1 of r)"),
    ),
    (
        "quadric",
        "sphere, translated 1e4",
        Rewritten("sphere", "translated 1e4"),
    ),
    (
        "quadric",
        "cylinder, nearly parallel",
        Rewritten("cylinder", "nearly parallel to the axis"),
    ),
    (
        "quadric",
        "cone, near the apex",
        Rewritten("cone", "through and near the apex"),
    ),
    (
        "quadric",
        "cylinder, translated 1e4",
        Rewritten("cylinder", "translated 1e4"),
    ),
    ("plane", "far (distance 10..1e5)", Drawn(plane_far)),
    ("plane", "grazing (1e-6..1e-2 rad)", Drawn(plane_grazing)),
    ("plane", "translated 1e4", Drawn(plane_translated)),
    ("plane", "hits near z = 0", Drawn(plane_near_screen)),
];

/// Every family of the suite, drawn from [`SEED`] in the order of the table.
pub fn suite() -> Vec<Family> {
    let mut g = Gen(ChaCha8Rng::seed_from_u64(SEED));
    let mut families: Vec<Family> = Vec::new();
    for (shape, name, source) in FAMILIES {
        let cases = match source {
            Drawn(draw) => (0..PER_FAMILY).map(|_| draw(&mut g)).collect(),
            Rewritten(from_shape, from_name) => {
                let source = families
                    .iter()
                    .find(|f| f.shape == *from_shape && f.name == *from_name)
                    .expect("the table names an earlier family");
                let rewrite = |case: &Case| Case {
                    shape: Shape::Quadric(Box::new(general_quadric_of(&case.shape))),
                    ray: case.ray,
                };
                source.cases.iter().map(rewrite).collect()
            }
        };
        families.push(Family { shape, name, cases });
    }
    families
}

/// A sphere, cylinder or cone written as a `QUADRIC`.
fn general_quadric_of(shape: &Shape) -> Quadric {
    match shape {
        Shape::Sphere(s) => as_general_quadric(&s.equation()),
        Shape::Cylinder(s) => as_general_quadric(&s.equation),
        Shape::Cone(s) => as_general_quadric(&s.equation),
        other => unreachable!("{other:?} is not rewritten"),
    }
}

// ----- spheres -----

/// A sphere of radius 0.5..2 near the origin and a ray past it at `impact` (a fraction
/// of r), starting `distance` radii before the closest point.
fn sphere_past(g: &mut Gen, centre: DVec3, impact: (f64, f64), distance: (f64, f64)) -> Case {
    let radius = g.uniform(0.5, 2.0);
    let dir = g.direction();
    let side = g.perpendicular(dir);
    let impact = radius * g.uniform(impact.0, impact.1);
    let ray = ray_past(
        centre,
        dir,
        side,
        impact,
        radius * g.log(distance.0, distance.1),
    );
    Case {
        shape: sphere(centre, radius),
        ray,
    }
}

fn sphere_far(g: &mut Gen) -> Case {
    let centre = g.point(5.0);
    sphere_past(g, centre, (0.0, 0.9), (10.0, 1e5))
}

fn sphere_grazing(g: &mut Gen) -> Case {
    let centre = g.point(5.0);
    sphere_past(g, centre, (0.999, 1.0), (2.0, 1e3))
}

fn sphere_huge(g: &mut Gen) -> Case {
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
}

fn sphere_translated(g: &mut Gen) -> Case {
    let centre = 1e4 * g.direction() + g.point(5.0);
    sphere_past(g, centre, (0.0, 0.95), (2.0, 50.0))
}

// ----- the course quadrics, with random centres and centre lines -----

fn cylinder(g: &mut Gen, far: f64) -> Cylinder {
    let (r, h) = (g.uniform(0.5, 2.0), g.uniform(1.0, 5.0));
    let centre = far * g.direction() + g.point(5.0);
    Cylinder::new(centre, centre_line(g), r, h).unwrap()
}

fn cylinder_side(g: &mut Gen, far: f64) -> Side {
    let s = cylinder(g, far);
    let y = g.uniform(0.1, 0.9) * s.size.height;
    Side::new(
        s.size.radius,
        y,
        s.size.radius,
        Shape::Cylinder(Box::new(s)),
    )
}

fn cylinder_parallel(g: &mut Gen) -> Case {
    let s = cylinder(g, 0.0);
    let (r, h) = (s.size.radius, s.size.height);
    let tilt = g.log(1e-9, 1e-3);
    let angle = g.uniform(0.0, std::f64::consts::TAU);
    let out = DVec3::new(angle.cos(), 0.0, angle.sin());
    // From below the base, drifting outward (from inside) or inward (from outside) so
    // that the wall is met at a height between 0 and h.
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
        shape: Shape::Cylinder(Box::new(s)),
        ray,
    }
}

fn cylinder_rims(g: &mut Gen) -> Case {
    let s = cylinder(g, 0.0);
    let (r, h) = (s.size.radius, s.size.height);
    let rim = if g.0.random::<bool>() { 0.0 } else { h };
    let y = rim + g.sign() * g.log(1e-12, 1e-3) * h;
    let (y, impact, distance) = (y, r * g.uniform(0.0, 0.9), r * g.log(2.0, 100.0));
    let (base, dir) = across_axis(g, y, impact, distance);
    let ray = from_local(&s.equation, base, dir);
    Case {
        shape: Shape::Cylinder(Box::new(s)),
        ray,
    }
}

fn cone(g: &mut Gen, far: f64) -> Cone {
    let (r, h) = (g.uniform(0.5, 2.0), g.uniform(1.0, 5.0));
    let centre = far * g.direction() + g.point(5.0);
    Cone::new(centre, centre_line(g), r, h).unwrap()
}

fn cone_side(g: &mut Gen, far: f64) -> Side {
    let s = cone(g, far);
    let y = g.uniform(0.2, 0.9) * s.size.height;
    Side::new(s.k().sqrt() * y, y, s.size.radius, Shape::Cone(Box::new(s)))
}

fn cone_generator(g: &mut Gen) -> Case {
    let s = cone(g, 0.0);
    let slope = s.k().sqrt();
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
        shape: Shape::Cone(Box::new(s)),
        ray,
    }
}

fn cone_apex(g: &mut Gen) -> Case {
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
        shape: Shape::Cone(Box::new(s)),
        ray,
    }
}

fn paraboloid(g: &mut Gen, far: f64) -> Paraboloid {
    let (r, h) = (g.uniform(0.5, 2.0), g.uniform(1.0, 5.0));
    let centre = far * g.direction() + g.point(5.0);
    Paraboloid::new(centre, centre_line(g), r, h).unwrap()
}

fn paraboloid_side(g: &mut Gen, far: f64) -> Side {
    let s = paraboloid(g, far);
    let y = g.uniform(0.2, 0.9) * s.size.height;
    Side::new(
        (s.k() * y).sqrt(),
        y,
        s.size.radius,
        Shape::Paraboloid(Box::new(s)),
    )
}

fn paraboloid_axis(g: &mut Gen) -> Case {
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
        shape: Shape::Paraboloid(Box::new(s)),
        ray,
    }
}

fn hyperboloid(g: &mut Gen, far: f64) -> Hyperboloid {
    let (r, h) = (g.uniform(1.0, 2.0), g.uniform(1.0, 5.0));
    let waist = r * g.uniform(0.2, 0.9);
    let centre = far * g.direction() + g.point(5.0);
    Hyperboloid::new(centre, centre_line(g), r, h, waist).unwrap()
}

fn hyperboloid_side(g: &mut Gen, far: f64) -> Side {
    let s = hyperboloid(g, far);
    let y = g.uniform(-0.9, 0.9) * s.size.height;
    let radius = (s.k() * y * y + s.waist * s.waist).sqrt();
    Side::new(radius, y, s.size.radius, Shape::Hyperboloid(Box::new(s)))
}

fn hyperboloid_waist(g: &mut Gen) -> Case {
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
        shape: Shape::Hyperboloid(Box::new(s)),
        ray,
    }
}

// ----- the plane, under the z rule: the eye in front of the screen, the plane behind -----

fn plane_case(g: &mut Gen, distance: f64, grazing: bool, shift: DVec3) -> Case {
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
}

fn plane_far(g: &mut Gen) -> Case {
    let d = g.log(10.0, 1e5);
    plane_case(g, d, false, DVec3::ZERO)
}

fn plane_grazing(g: &mut Gen) -> Case {
    let d = g.log(2.0, 100.0);
    plane_case(g, d, true, DVec3::ZERO)
}

fn plane_translated(g: &mut Gen) -> Case {
    let d = g.log(2.0, 50.0);
    let shift = DVec3::new(1e4 * g.sign(), 1e4 * g.sign(), -1e4);
    plane_case(g, d, false, shift)
}

fn plane_near_screen(g: &mut Gen) -> Case {
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
}
