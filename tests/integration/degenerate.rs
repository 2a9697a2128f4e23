//! Rays the spec singles out (a = 0 in the quadratic, apex and vertex hits, grazing rays,
//! a light on the surface) never produce a NaN.

use glam::DVec3;
use legacy_rt::render::{Options, ray_trace, render};
use legacy_rt::shapes::Ray;

const SCENE: &str = "8 6\n0 0 3\n\
    22\n1 1 1\n1 1 1\n0.5 0.5 0.5\n0 -1 -5\n0 1 0\n1 2\n\
    23\n1 1 1\n1 1 1\n0.5 0.5 0.5\n3 0 -5\n0 1 0\n1 1\n\
    21\n1 1 1\n1 1 1\n0.5 0.5 0.5\n-3 0 -5\n0 1 0\n1 1\n\
    24\n1 1 1\n1 1 1\n0.5 0.5 0.5\n0 2 -8\n1 0 0\n1 1\n0\n\
    QUADRIC 1 0 0 0 -1 0 0 1 10 25   double cone with apex (0, 0, -10)\n1 1 1\n1 1 1\n0.5 0.5 0.5\n\
    13\n1 1 1\n1 1 1\n0.5 0.5 0.5\n0 3 -5\n1\n\
    14\n1 1 1\n1 1 1\n0 0 0\n0 1 0\n0 -3 0\n\
    10\n5 5 5\n0 2 -5\n\
    10\n5 5 5\n3 0 -5\n\
    11\n5 5 5\n-3 0 -5\n-3 -5 -5\n30\n";

fn ray(base: [f64; 3], dir: [f64; 3]) -> Ray {
    Ray {
        base: DVec3::from_array(base),
        dir: DVec3::from_array(dir).normalize(),
    }
}

#[test]
fn special_rays_give_finite_colours() {
    let scene = legacy_rt::load(SCENE).unwrap();
    let options = Options::new(64, 48);
    let rays = [
        // Along the cylinder's axis, inside it: a = b = 0.
        ray([0.0, 5.0, -5.0], [0.0, -1.0, 0.0]),
        // Parallel to the axis on its wall.
        ray([1.0, 5.0, -5.0], [0.0, -1.0, 0.0]),
        // Through the cone's apex, along its axis and along a generator (a = 0).
        ray([3.0, -2.0, -5.0], [0.0, 1.0, 0.0]),
        ray([2.0, -1.0, -5.0], [1.0, 1.0, 0.0]),
        // Down the paraboloid's axis to its vertex (a = 0, linear).
        ray([-3.0, 4.0, -5.0], [0.0, -1.0, 0.0]),
        // Through the waist-0 hyperboloid's apex and the general cone's apex.
        ray([-4.0, 2.0, -8.0], [1.0, 0.0, 0.0]),
        ray([0.0, 0.0, 3.0], [0.0, 0.0, -1.0]),
        // Tangent to the sphere, grazing the floor, and toward a light on a surface.
        ray([1.0, 3.0, 3.0], [0.0, 0.0, -1.0]),
        ray([0.0, -3.0, 3.0], [0.0, 0.0, -1.0]),
        ray([0.0, 0.0, 3.0], [0.0, 2.0, -8.0]),
    ];
    for r in rays {
        let colour = ray_trace(&scene, &options, r);
        assert!(colour.is_finite(), "{r:?} gave {colour}");
    }
    // And every camera ray of a 64 x 48 render (its bytes would show a NaN as 0, so the
    // colours are checked before conversion).
    for y in 0..48 {
        for x in 0..64 {
            let target = DVec3::new(
                x as f64 / 63.0 * 8.0 - 4.0,
                y as f64 / 47.0 * 6.0 - 3.0,
                0.0,
            );
            let r = Ray {
                base: scene.viewpoint,
                dir: (target - scene.viewpoint).normalize(),
            };
            let colour = ray_trace(&scene, &options, r);
            assert!(colour.is_finite(), "pixel ({x}, {y}) gave {colour}");
        }
    }
    let image = render(&scene, &options, |_| {});
    assert_eq!(
        legacy_rt::render::count_rays(&scene, &options).camera,
        64 * 48
    );
    assert_eq!(image.pixels.len(), 64 * 48);
}
