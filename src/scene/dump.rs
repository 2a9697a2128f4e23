//! `--dump`: the typed scene as text, in file order, with fixed precision.
//!
//! Everything precomputed at load is shown (unit normals, frames, `rotmat`, `irot`, `k`,
//! spotlight cosines), so that a student can compare it with their own program's values
//! and so that snapshot tests see every number the tracer will use.

use super::{Light, Material, Object, Pattern, Scene, Shader, TextureMode};
use crate::shapes::{AxisFrame, Shape};
use glam::{DMat3, DVec3};
use std::fmt::Write;

/// Decimals printed for every real number.
const DECIMALS: usize = 6;

/// A number with `DECIMALS` decimals; in exponent form where that would print more than
/// 15 digits before the point or show a non-zero value as zero.
pub(crate) fn number(value: f64) -> String {
    let text = format!("{value:.DECIMALS$}");
    let zero = (text.trim_start_matches('-').bytes()).all(|b| b == b'0' || b == b'.');
    if value.abs() >= 1e15 || (zero && value != 0.0) {
        format!("{value:.DECIMALS$e}")
    } else if zero {
        // -0.0 and 0.0 are the same number to a reader; print one form.
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}

struct Dump(String);

impl Dump {
    fn row(&mut self, name: &str, values: &[f64]) {
        let values: Vec<String> = values.iter().map(|&v| number(v)).collect();
        let _ = writeln!(self.0, "  {name:<13} {}", values.join(" "));
    }

    fn vector(&mut self, name: &str, v: DVec3) {
        self.row(name, &v.to_array());
    }

    /// A matrix as three rows (row i is what the matrix dots with a vector for its i-th
    /// component, as the course's `rotmat[i]`).
    fn matrix(&mut self, name: &str, m: DMat3) {
        let rows = m.transpose();
        for (i, row) in [rows.x_axis, rows.y_axis, rows.z_axis]
            .into_iter()
            .enumerate()
        {
            self.vector(&format!("{name}[{i}]"), row);
        }
    }

    fn material(&mut self, prefix: &str, m: &Material) {
        self.vector(&format!("{prefix}ambient"), m.ambient);
        self.vector(&format!("{prefix}diffuse"), m.diffuse);
        self.vector(&format!("{prefix}specular"), m.specular);
    }

    fn axis(&mut self, origin: &str, frame: &AxisFrame) {
        self.vector(origin, frame.centre);
        self.matrix("rotmat", frame.rotmat());
        self.matrix("irot", frame.irot());
    }

    fn light(&mut self, light: &Light) {
        let kind = if light.beam.is_some() {
            "spotlight"
        } else {
            "light"
        };
        let _ = writeln!(self.0, "line {}: {kind}", light.line);
        self.vector("emissivity", light.emissivity);
        self.vector("location", light.location);
        if let Some(beam) = &light.beam {
            self.vector("direction", beam.direction);
            self.row("half-angle", &[beam.half_angle]);
            self.row("cos limit", &[beam.cos_limit]);
        }
    }

    fn object(&mut self, object: &Object) {
        let _ = writeln!(self.0, "line {}: {}", object.line, object.kind());
        self.material("", &object.look.material);
        match &object.shape {
            Shape::Sphere(s) => {
                self.vector("centre", s.centre);
                self.row("radius", &[s.radius]);
                self.row("radius²", &[s.radius_sq]);
            }
            Shape::Plane(s) => {
                self.vector("normal", s.normal);
                self.vector("point", s.point);
            }
            Shape::FinitePlane(s) => {
                self.vector("normal", s.frame.plane.normal);
                self.vector("point", s.frame.plane.point);
                self.matrix("frame", s.frame.local_from_world.rot);
                self.row("size", &s.size.to_array());
            }
            Shape::TiledPlane(s) => {
                self.vector("normal", s.plane.normal);
                self.vector("point", s.plane.point);
                self.matrix("frame", s.local_from_world.rot);
            }
            Shape::Paraboloid(s) => {
                self.axis("vertex", &s.equation.frame);
                self.row("radius", &[s.size.radius]);
                self.row("height", &[s.size.height]);
                self.row("k", &[s.k()]);
            }
            Shape::Cylinder(s) => {
                self.axis("base centre", &s.equation.frame);
                self.row("radius", &[s.size.radius]);
                self.row("height", &[s.size.height]);
            }
            Shape::Cone(s) => {
                self.axis("apex", &s.equation.frame);
                self.row("radius", &[s.size.radius]);
                self.row("height", &[s.size.height]);
                self.row("k", &[s.k()]);
            }
            Shape::Hyperboloid(s) => {
                self.axis("waist centre", &s.equation.frame);
                self.row("end radius", &[s.size.radius]);
                self.row("half-height", &[s.size.height]);
                self.row("waist", &[s.waist]);
                self.row("k", &[s.k()]);
            }
            Shape::Quadric(s) => {
                self.row("A B C D E", &s.coefficients[..5]);
                self.row("F G H I J", &s.coefficients[5..]);
                let q = s.q;
                for (i, row) in [q.x_axis, q.y_axis, q.z_axis, q.w_axis].iter().enumerate() {
                    self.row(&format!("Q[{i}]"), &row.to_array());
                }
            }
        }
        match &object.look.pattern {
            Pattern::Plain => {}
            Pattern::Tiles { tile, background } => {
                self.row("tile size", &tile.to_array());
                self.material("back ", background);
            }
            Pattern::Texture { texture, mode, .. } => {
                let mode = match mode {
                    TextureMode::Fit => "1 (fit)",
                    TextureMode::Tile => "2 (tile)",
                };
                // FNV-1a over the texels: enough to see that the right file was read.
                let hash = texture
                    .texels
                    .iter()
                    .flatten()
                    .fold(0xcbf29ce484222325u64, |h, &b| {
                        (h ^ u64::from(b)).wrapping_mul(0x100000001b3)
                    });
                let _ = writeln!(self.0, "  {:<13} {}", "texture", texture.path);
                let (w, h) = (texture.width, texture.height);
                let _ = writeln!(self.0, "  {:<13} {w}x{h}, fnv1a {hash:016x}", "texels");
                let _ = writeln!(self.0, "  {:<13} {mode}", "mode");
            }
            Pattern::Shader { shader, origin } => {
                let shader = match shader {
                    Shader::Stripes => "0 (stripes)",
                    Shader::ColourWheel => "1 (colour wheel)",
                };
                let _ = writeln!(self.0, "  {:<13} {shader}", "shader");
                self.vector("origin", *origin);
            }
        }
    }
}

/// The scene as text: header, then lights and objects interleaved in file order.
pub fn dump(scene: &Scene) -> String {
    let mut out = Dump(String::new());
    out.row("window", &scene.window.to_array());
    out.vector("viewpoint", scene.viewpoint);
    let (w, h) = scene.default_size();
    let _ = writeln!(out.0, "  {:<13} {w}x{h}", "default size");
    let (lights, objects) = (scene.lights.len(), scene.objects.len());
    let _ = writeln!(
        out.0,
        "  {:<13} {lights} lights, {objects} objects",
        "contents"
    );
    let (mut lights, mut objects) = (
        scene.lights.iter().peekable(),
        scene.objects.iter().peekable(),
    );
    loop {
        let light_first = match (lights.peek(), objects.peek()) {
            (Some(l), Some(o)) => l.line < o.line,
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (None, None) => break,
        };
        out.0.push('\n');
        if light_first {
            out.light(lights.next().unwrap());
        } else {
            out.object(objects.next().unwrap());
        }
    }
    out.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_fixed_decimals_and_no_negative_zero() {
        assert_eq!(number(1.0 / 3.0), "0.333333");
        assert_eq!(number(-0.0), "0.000000");
        assert_eq!(number(0.0), "0.000000");
        assert_eq!(number(-2.5), "-2.500000");
        assert_eq!(number(123456.5), "123456.500000");
    }

    #[test]
    fn numbers_that_fixed_decimals_would_lose_are_in_exponent_form() {
        // 1e308 in fixed form is 309 digits, and 1e-300 would read as zero.
        assert_eq!(number(1e308), "1.000000e308");
        assert_eq!(number(-2.5e15), "-2.500000e15");
        assert_eq!(number(1e-300), "1.000000e-300");
        assert_eq!(number(-1e-9), "-1.000000e-9");
        // Fixed decimals as long as they show the value as non-zero.
        assert_eq!(number(1e-6), "0.000001");
        assert_eq!(number(4e-7), "4.000000e-7");
    }
}
