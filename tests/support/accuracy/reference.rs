//! The exact answer for a case: the roots of the same quadratic in double-double (the
//! `twofloat` crate, about 106 bits, an implementation independent of the kernel's own
//! error-free arithmetic), polished by Newton's method.

use super::{Case, Reference};
use legacy_rt::shapes::{AxisQuadric, Plane, Quadric, Ray, RootRule, Shape};
use twofloat::TwoFloat;

type T = TwoFloat;

fn t(x: f64) -> T {
    T::from(x)
}

const EPS: f64 = f64::EPSILON;

/// The exact answer for a case.
pub fn reference(case: &Case) -> Reference {
    let ray = &case.ray;
    match &case.shape {
        Shape::Sphere(s) => axis_reference(&s.equation(), ray),
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
        let Some(rotation) = &frame.rotation else {
            return v;
        };
        [0, 1, 2].map(|i| {
            let row = rotation.irot.col(i);
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
        // The variants nearer-root and behind-root: the suite's shapes follow the spec's
        // rule.
        RootRule::SmallerWithin { .. } | RootRule::SmallerEvenBehind { .. } => {
            unreachable!("the suite has no variants")
        }
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
