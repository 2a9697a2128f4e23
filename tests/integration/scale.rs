//! Issue 4's scale test: a whole scene scaled by 10^-3 and 10^3 (positions, sizes, world
//! window, viewpoint, lights, MAX_DIST) renders the same image. Without a scene-scale
//! epsilon there is nothing that could depend on the unit, except the legacy 1/distance
//! factors (spec §4.2-§4.3): ambient / path length goes as 1/s and the diffuse light's
//! emissivity · cos / distance, divided by the path length, as 1/s². The test scales the
//! ambient colours by s and the emissivities by s² to compensate.

use legacy_rt::render::{DEFAULT_MAX_DIST, Options, render};
use legacy_rt::scene::{Look, Object, Pattern, Scene, load};
use legacy_rt::shapes::{
    Cone, Cylinder, FinitePlane, Hyperboloid, Paraboloid, Plane, PlaneFrame, Quadric, Shape, Sphere,
};
use std::sync::Arc;

fn scale_shape(shape: &Shape, s: f64) -> Shape {
    let line = |irot: glam::DMat3| irot.col(1);
    match shape {
        Shape::Sphere(x) => Shape::Sphere(Sphere::new(x.centre * s, x.radius * s, "s").unwrap()),
        Shape::Plane(x) => Shape::Plane(Plane::new(x.normal, x.point * s, "p").unwrap()),
        Shape::FinitePlane(x) => {
            let f = &x.frame;
            Shape::FinitePlane(Box::new(
                FinitePlane::new(
                    f.plane.normal,
                    f.plane.point * s,
                    f.local_from_world.rot.row(0),
                    x.size * s,
                    "f",
                )
                .unwrap(),
            ))
        }
        Shape::TiledPlane(f) => Shape::TiledPlane(
            PlaneFrame::new(
                f.plane.normal,
                f.plane.point * s,
                f.local_from_world.rot.row(0),
                "t",
            )
            .unwrap(),
        ),
        Shape::Paraboloid(x) => {
            let f = &x.equation.frame;
            let shape = Paraboloid::new(
                f.centre * s,
                line(f.irot()),
                x.size.radius * s,
                x.size.height * s,
            );
            Shape::Paraboloid(Box::new(shape.unwrap()))
        }
        Shape::Cylinder(x) => {
            let f = &x.equation.frame;
            let shape = Cylinder::new(
                f.centre * s,
                line(f.irot()),
                x.size.radius * s,
                x.size.height * s,
            );
            Shape::Cylinder(Box::new(shape.unwrap()))
        }
        Shape::Cone(x) => {
            let f = &x.equation.frame;
            Shape::Cone(Box::new(
                Cone::new(
                    f.centre * s,
                    line(f.irot()),
                    x.size.radius * s,
                    x.size.height * s,
                )
                .unwrap(),
            ))
        }
        Shape::Hyperboloid(x) => {
            let f = &x.equation.frame;
            let (r, h, w) = (x.size.radius * s, x.size.height * s, x.waist * s);
            Shape::Hyperboloid(Box::new(
                Hyperboloid::new(f.centre * s, line(f.irot()), r, h, w).unwrap(),
            ))
        }
        Shape::Quadric(x) => {
            // f(P / s) s²: the quadratic terms stay, the linear ones gain s, J gains s².
            let [a, b, c, d, e, f, g, h, i, j] = x.coefficients;
            let coefficients = [a, b, c, d * s, e, f, g * s, h, i * s, j * s * s];
            Shape::Quadric(Box::new(Quadric::new(coefficients).unwrap()))
        }
    }
}

/// The scene scaled by `s`, with the 1/distance factors compensated; `None` for a scene
/// with procedural or texture patterns (their frequencies are in world units).
fn scaled(scene: &Scene, s: f64) -> Option<Scene> {
    let mut out = scene.clone();
    out.window *= s;
    out.viewpoint *= s;
    for light in &mut out.lights {
        light.location *= s;
        light.emissivity *= s * s;
    }
    out.objects = scene
        .objects
        .iter()
        .map(|object| {
            let mut material = object.look.material;
            material.ambient *= s;
            let pattern = match &object.look.pattern {
                Pattern::Plain => Pattern::Plain,
                Pattern::Tiles { tile, background } => {
                    let mut background = background.clone();
                    background.ambient *= s;
                    Pattern::Tiles {
                        tile: *tile * s,
                        background,
                    }
                }
                _ => return None,
            };
            Some(Object {
                shape: scale_shape(&object.shape, s),
                look: Arc::new(Look { material, pattern }),
                ..object.clone()
            })
        })
        .collect::<Option<Vec<_>>>()?;
    Some(out)
}

#[test]
fn scaling_a_scene_by_1e_minus_3_and_1e3_keeps_its_image() {
    let examples = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut compared = 0;
    for path in crate::common::scene_files(&examples) {
        let scene = load(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let render_at = |scene: &Scene, s: f64| {
            let options = Options {
                max_dist: DEFAULT_MAX_DIST * s,
                ..Options::new(160, 120)
            };
            render(scene, &options, |_| {})
        };
        let base = render_at(&scene, 1.0);
        for s in [1e-3, 1e3] {
            let Some(small_or_large) = scaled(&scene, s) else {
                continue;
            };
            let image = render_at(&small_or_large, s);
            let differing = base
                .pixels
                .iter()
                .zip(&image.pixels)
                .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 1))
                .count();
            let allowed = base.pixels.len() / 1000;
            assert!(
                differing <= allowed,
                "{} scaled by {s}: {differing} of {} pixels differ by more than 1/255",
                path.display(),
                base.pixels.len()
            );
            compared += 1;
        }
    }
    assert!(compared >= 20, "only {compared} scaled renders compared");
}
