//! Images checked against numbers, not against themselves: the debug scene of spec §6, and
//! pixels whose value each test derives from the formulas of spec §4-§5.

use glam::DVec3;
use legacy_rt::render::{self, Options};

fn render_scene(text: &str, width: usize, height: usize) -> legacy_rt::Image {
    let scene = legacy_rt::load(text).unwrap_or_else(|e| panic!("{e}"));
    let options = Options::new(width, height);
    render::render(&scene, &options, |_| {})
}

/// Pixel (x, y) with (0, 0) at the lower left (spec §4.1).
fn pixel(image: &legacy_rt::Image, x: usize, y: usize) -> [u8; 3] {
    image.pixels[(image.height - 1 - y) * image.width + x]
}

/// clamp, times 255, truncate (spec §4.7), computed here on its own.
fn byte(value: f64) -> u8 {
    (value.clamp(0.0, 1.0) * 255.0).floor() as u8
}

/// World point of pixel (x, y) for window (ww, wh) and image (w, h) (spec §4.1).
fn world(x: usize, y: usize, (ww, wh): (f64, f64), (w, h): (usize, usize)) -> DVec3 {
    DVec3::new(
        x as f64 / (w - 1) as f64 * ww - ww / 2.0,
        y as f64 / (h - 1) as f64 * wh - wh / 2.0,
        0.0,
    )
}

const DEBUG_SCENE: &str = "8 6\n0 0 3\n14\n5 5 0\n0 0 0\n0 0 0\n0 0 -1\n0 0 -5\n";

#[test]
fn debug_scene_gives_exactly_the_bytes_of_spec_6() {
    let image = render_scene(DEBUG_SCENE, 5, 3);
    let expected_rg: [[u8; 5]; 3] = [
        [81, 101, 112, 101, 81],
        [95, 132, 159, 132, 95],
        [81, 101, 112, 101, 81],
    ];
    let expected: Vec<[u8; 3]> = expected_rg.iter().flatten().map(|&v| [v, v, 0]).collect();
    assert_eq!(image.pixels, expected);
    let ppm = legacy_rt::image_output::ppm(&image);
    assert!(ppm.starts_with(b"P6 5 3 255\n"));
    assert_eq!(ppm.len(), "P6 5 3 255\n".len() + 45);
}

#[test]
fn debug_scene_distances_are_those_the_notes_quote() {
    // Pixel (0, 0): world (-4, -3); the ray reaches z = -5 after 8/3 of |P - V|.
    let corner = DVec3::new(-4.0, -3.0, -3.0).length() * 8.0 / 3.0;
    assert!((corner - 15.55).abs() < 0.005, "{corner}");
    let image = render_scene(DEBUG_SCENE, 5, 3);
    assert_eq!(pixel(&image, 0, 0)[0], byte(5.0 / corner));
    assert_eq!(pixel(&image, 2, 1)[0], byte(5.0 / 8.0));
}

#[test]
fn sphere_centre_is_ambient_over_distance() {
    // The centre pixel looks straight down -z at a sphere of radius 1 centred at z = -5:
    // the hit is at z = -4, 7 from the eye, and without lights I = ambient / 7.
    let scene = "2 2\n0 0 3\n13\n5 2.5 1\n0 0 0\n0 0 0\n0 0 -5\n1\n";
    let image = render_scene(scene, 3, 3);
    assert_eq!(
        pixel(&image, 1, 1),
        [byte(5.0 / 7.0), byte(2.5 / 7.0), byte(1.0 / 7.0)]
    );
    // The corner rays miss: black background.
    assert_eq!(pixel(&image, 0, 0), [0, 0, 0]);
}

#[test]
fn lit_point_adds_diffuse_times_emissivity_times_cosine_over_light_distance() {
    // Same hit (0, 0, -4), normal +z. A light at (0, 3, 0): L = (0, 3, 4), |L| = 5,
    // cos = 4/5. I = (ambient + d e cos / 5) / 7.
    let scene = "2 2\n0 0 3\n13\n0.5 0.5 0.5\n3 2 1\n0 0 0\n0 0 -5\n1\n10\n4 4 4\n0 3 0\n";
    let image = render_scene(scene, 3, 3);
    let expected = [3.0, 2.0, 1.0].map(|d| byte((0.5 + d * 4.0 * 0.8 / 5.0) / 7.0));
    assert_eq!(pixel(&image, 1, 1), expected);
}

#[test]
fn shadowed_point_gets_ambient_only_and_an_unshadowed_one_gets_light() {
    // Floor y = -3 seen through pixel world (0, -1.5): the ray (0, -1.5, -3) reaches it at
    // twice its length, the point (0, -3, -3), 2 √11.25 from the eye. The light is straight
    // above at (0, 5, -3), 8 away, cos = 1. A small sphere at (0, 1, -3) blocks it; the
    // point one pixel to the right, (2, -3, -3), sees the light past the sphere.
    let floor = "14\n0.5 0.5 0.5\n1 1 1\n0 0 0\n0 1 0\n0 -3 0\n";
    let light = "10\n8 8 8\n0 5 -3\n";
    let blocker = "13\n0 0 0\n0 0 0\n0 0 0\n0 1 -3\n0.5\n";
    let scene = format!("8 6\n0 0 3\n{floor}{blocker}{light}");
    let image = render_scene(&scene, 5, 5);
    let eye = DVec3::new(0.0, 0.0, 3.0);
    let dist = 2.0 * DVec3::new(0.0, -1.5, -3.0).length();
    assert_eq!(pixel(&image, 2, 1), [byte(0.5 / dist); 3]);
    // Pixel (3, 1): world (2, -1.5); hit (4, -3, -3).
    let hit = eye + 2.0 * (world(3, 1, (8.0, 6.0), (5, 5)) - eye);
    assert_eq!(hit, DVec3::new(4.0, -3.0, -3.0));
    let to_light = DVec3::new(0.0, 5.0, -3.0) - hit;
    let cos = to_light.normalize().y;
    let lit = (0.5 + 8.0 * cos / to_light.length()) / (hit - eye).length();
    assert_eq!(pixel(&image, 3, 1), [byte(lit); 3]);
}

#[test]
fn mirror_bounce_adds_specular_times_what_the_reflection_sees() {
    // A mirror floor y = -3 (ambient 0.5, specular 0.25 0.5 1) reflects the ray of pixel
    // world (0, -1.5) at (0, -3, -3) into the direction (0, 1.5, -3), which meets the wall
    // z = -9 at (0, 0, -9): another 2 √11.25, so total_dist = 4 √11.25 there.
    let mirror = "14\n0.5 0.5 0.5\n0 0 0\n0.25 0.5 1\n0 1 0\n0 -3 0\n";
    let wall = "14\n6 3 0\n0 0 0\n0 0 0\n0 0 1\n0 0 -9\n";
    let scene = format!("8 6\n0 0 3\n{mirror}{wall}");
    let image = render_scene(&scene, 5, 5);
    let leg = DVec3::new(0.0, 1.5, -3.0).length();
    let expected = [(0.25, 6.0), (0.5, 3.0), (1.0, 0.0)]
        .map(|(s, wall_ambient)| byte(0.5 / (2.0 * leg) + s * wall_ambient / (4.0 * leg)));
    assert_eq!(pixel(&image, 2, 1), expected);
}

#[test]
fn tile_parity_follows_the_truncation_rule() {
    // Tiled floor y = -3, grid direction +x, tiles 0.7 x 0.7: the frame is x = +x,
    // n × x = -z, so q = (hit.x, -hit.z). Every pixel of the bottom half is checked but
    // the bottom row, whose floor points lie on z = 0 exactly, where rounding decides the
    // z > 0 rule of spec §5.1.
    let tiles = "16\n0.8 0.4 0.2\n0 0 0\n0 0 0\n0 1 0\n0 -3 0\n1 0 0\n0.7 0.7\n\
                 0.1 0.3 0.9\n0 0 0\n0 0 0\n";
    let scene = format!("8 6\n0 0 3\n{tiles}");
    let (w, h) = (41, 31);
    let image = render_scene(&scene, w, h);
    let eye = DVec3::new(0.0, 0.0, 3.0);
    let (mut odd, mut even) = (0, 0);
    for y in 1..h / 2 {
        for x in 0..w {
            let d = world(x, y, (8.0, 6.0), (w, h)) - eye;
            let hit = eye + (-3.0 / d.y) * d;
            let relx = (10000.0 + hit.x / 0.7).trunc() as i64;
            let rely = (10000.0 - hit.z / 0.7).trunc() as i64;
            let ambient = if (relx + rely) % 2 == 1 {
                odd += 1;
                [0.8, 0.4, 0.2]
            } else {
                even += 1;
                [0.1, 0.3, 0.9]
            };
            let dist = (hit - eye).length();
            assert_eq!(
                pixel(&image, x, y),
                ambient.map(|a| byte(a / dist)),
                "({x}, {y})"
            );
        }
    }
    assert!(odd > 50 && even > 50, "{odd} {even}");
}

#[test]
fn spotlight_lights_only_inside_its_cone() {
    // A spotlight at (0, 5, -3) aimed straight down, half-angle 20°, over the floor y = -3.
    // A floor point is lit iff the angle between (hit - light) and -y is below 20°.
    let floor = "14\n0 0 0\n1 1 1\n0 0 0\n0 1 0\n0 -3 0\n";
    let spot = "11\n10 10 10\n0 5 -3\n0 -3 -3\n20\n";
    let scene = format!("8 6\n0 0 3\n{floor}{spot}");
    let (w, h) = (81, 61);
    let image = render_scene(&scene, w, h);
    let eye = DVec3::new(0.0, 0.0, 3.0);
    let light = DVec3::new(0.0, 5.0, -3.0);
    let limit = 20f64.to_radians().cos();
    let (mut lit, mut dark) = (0, 0);
    for y in 1..h / 2 {
        for x in 0..w {
            let d = world(x, y, (8.0, 6.0), (w, h)) - eye;
            let hit = eye + (-3.0 / d.y) * d;
            let to_light = light - hit;
            let inside = (-to_light).normalize().dot(DVec3::NEG_Y) > limit;
            let value = if inside {
                lit += 1;
                let dist = to_light.length();
                10.0 * (to_light.y / dist) / dist / (hit - eye).length()
            } else {
                dark += 1;
                0.0
            };
            assert_eq!(pixel(&image, x, y), [byte(value); 3], "({x}, {y})");
        }
    }
    assert!(lit > 20 && dark > 20, "{lit} {dark}");
}
