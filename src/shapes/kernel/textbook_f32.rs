//! The notes' formula in single precision, for contrast: every input is rounded to f32
//! and every operation done in f32.

use super::{Kernel, choose, first_positive, plane_rule, strict};
use crate::shapes::{AxisQuadric, Plane, Quadric, Ray};
use glam::{DVec3, Vec3, Vec4};

/// The textbook formula in f32.
#[derive(Debug, Clone, Copy, Default)]
pub struct TextbookF32;

/// f32 roots, ascending (the same rules as [`super::textbook::textbook_roots`]).
#[inline]
fn roots_f32(a: f32, b: f32, c: f32, strict: bool) -> Option<[f64; 2]> {
    if a == 0.0 {
        return (b != 0.0).then(|| [f64::from(-c / b); 2]);
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 || (strict && discriminant == 0.0) || discriminant.is_nan() {
        return None;
    }
    let root = discriminant.sqrt();
    let (t0, t1) = ((-b - root) / (2.0 * a), (-b + root) / (2.0 * a));
    let (t0, t1) = (f64::from(t0), f64::from(t1));
    Some(if t0 <= t1 { [t0, t1] } else { [t1, t0] })
}

#[inline]
fn single(v: DVec3) -> Vec3 {
    v.as_vec3()
}

impl Kernel for TextbookF32 {
    const NAME: &'static str = "textbook-f32";

    #[inline]
    fn axis_quadric(quadric: &AxisQuadric, ray: &Ray) -> Option<f64> {
        let frame = &quadric.frame;
        let rotmat = frame.rotmat.as_mat3();
        let base = rotmat * (single(ray.base) - single(frame.centre));
        let dir = rotmat * single(ray.dir);
        let square = single(quadric.square);
        let (linear_y, constant) = (quadric.linear_y as f32, quadric.constant as f32);
        let weighted = square * dir;
        let a = weighted.dot(dir);
        let b = 2.0 * weighted.dot(base) + linear_y * dir.y;
        let c = (square * base).dot(base) + linear_y * base.y + constant;
        let roots = roots_f32(a, b, c, strict(quadric.rule))?;
        choose(quadric.rule, roots, f64::from(base.y), f64::from(dir.y))
    }

    #[inline]
    fn quadric(quadric: &Quadric, ray: &Ray) -> Option<f64> {
        let q = quadric.q.as_mat4();
        let p = single(ray.base).extend(1.0);
        let d: Vec4 = single(ray.dir).extend(0.0);
        let qp = q * p;
        let (a, b, c) = (d.dot(q * d), 2.0 * d.dot(qp), p.dot(qp));
        first_positive(roots_f32(a, b, c, false)?)
    }

    #[inline]
    fn plane(plane: &Plane, ray: &Ray) -> Option<f64> {
        let normal = single(plane.normal);
        let denominator = normal.dot(single(ray.dir));
        if denominator == 0.0 {
            return None;
        }
        let t = normal.dot(single(plane.point) - single(ray.base)) / denominator;
        plane_rule(ray, f64::from(t))
    }
}
