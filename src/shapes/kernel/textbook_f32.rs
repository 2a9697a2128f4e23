//! The notes' formula in single precision, for contrast: every input is rounded to f32
//! and every operation done in f32, as a tracer written with `float` does. Only the
//! [`Precision`] differs from [`Textbook`](super::Textbook).

use super::textbook::{AsWritten, Named, Plain, Precision, TextbookFormula};
use crate::shapes::axis_quadric::coefficients;
use crate::shapes::{AxisFrame, AxisQuadric, Plane, Quadric, Ray};
use glam::{DVec3, Vec3, Vec4};

/// The textbook formula in f32.
pub type TextbookF32 = AsWritten<TextbookFormula, Single>;

impl Named for TextbookF32 {
    const LABEL: &'static str = "textbook-f32";
}

/// Single precision: every input rounded to f32.
#[derive(Debug, Clone, Copy, Default)]
pub struct Single;

#[inline(always)]
fn single(v: DVec3) -> Vec3 {
    v.as_vec3()
}

impl Precision for Single {
    type Vector = Vec3;
    type Real = f32;

    #[inline(always)]
    fn local_ray(frame: &AxisFrame, ray: &Ray) -> Plain<Vec3> {
        let rotmat = frame.rotmat.as_mat3();
        Plain {
            base: rotmat * (single(ray.base) - single(frame.centre)),
            dir: rotmat * single(ray.dir),
        }
    }

    #[inline(always)]
    fn coefficients(quadric: &AxisQuadric, local: &Plain<Vec3>) -> (f32, f32, f32) {
        let square = single(quadric.alpha).to_array();
        let (linear_y, constant) = (quadric.linear_y as f32, quadric.constant as f32);
        let [base, dir] = [local.base, local.dir].map(|v| v.to_array());
        coefficients(square, linear_y, constant, base, dir)
    }

    /// The local y in f64 from the f32 ray, as the f64 kernels compute it.
    #[inline(always)]
    fn height(local: &Plain<Vec3>, t: f64) -> f64 {
        f64::from(local.base.y) + t * f64::from(local.dir.y)
    }

    #[inline(always)]
    fn plane_distance(plane: &Plane, ray: &Ray) -> Option<f64> {
        let normal = single(plane.normal);
        let denominator = normal.dot(single(ray.dir));
        if denominator == 0.0 {
            return None;
        }
        let t = normal.dot(single(plane.point) - single(ray.base)) / denominator;
        Some(f64::from(t))
    }

    #[inline(always)]
    fn world_ray(ray: &Ray) -> Plain<Vec3> {
        Plain {
            base: single(ray.base),
            dir: single(ray.dir),
        }
    }

    #[inline(always)]
    fn quadric_coefficients(quadric: &Quadric, local: &Plain<Vec3>) -> (f32, f32, f32) {
        let q = quadric.q.as_mat4();
        let p = local.base.extend(1.0);
        let d: Vec4 = local.dir.extend(0.0);
        let qp = q * p;
        (d.dot(q * d), 2.0 * d.dot(qp), p.dot(qp))
    }
}
