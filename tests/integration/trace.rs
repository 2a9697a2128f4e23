//! `legacy-rt trace` and the stages (issue 14): a trace ends with the bytes the image has
//! at its pixel, everywhere; stage values follow from the formulas of spec §4; traces of
//! telling pixels are snapshots; the command line's errors are clean.

use super::common::{course_scenes, run, snapshots};
use legacy_rt::Scene;
use legacy_rt::render::{Options, Show, Stage, render, trace};
use std::path::Path;

fn example(name: &str) -> (String, Scene) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name);
    let text = std::fs::read_to_string(path).unwrap();
    let scene = legacy_rt::load(&text).unwrap();
    (text, scene)
}

/// The image's bytes at pixel (x, y), (0, 0) at the lower left.
fn at(image: &legacy_rt::Image, x: usize, y: usize) -> [u8; 3] {
    image.pixels[(image.height - 1 - y) * image.width + x]
}

/// Traces every pixel and checks its bytes against the render's.
fn every_pixel_agrees(name: &str, scene: &Scene, options: &Options) {
    let image = render(scene, options, |_| {});
    for y in 0..options.height {
        for x in 0..options.width {
            let traced = trace(scene, options, x, y).unwrap();
            assert_eq!(traced.bytes, at(&image, x, y), "{name} ({x}, {y})");
            let [r, g, b] = traced.bytes;
            let text = traced.readable(scene);
            assert!(text.ends_with(&format!("\nbytes: {r} {g} {b}\n")), "{name}");
        }
    }
}

#[test]
fn a_trace_ends_with_the_image_s_bytes_at_every_pixel() {
    // Mirrors (spec1's two spheres, or the gallery), a spotlight (lights), tiles and
    // quadrics (the gallery), a texture.
    let mut scenes: Vec<(String, Scene)> =
        ["lights.txt", "quadrics_gallery.txt", "textured_planes.txt"]
            .into_iter()
            .map(|name| (name.to_string(), example(name).1))
            .collect();
    if let Some(dir) = course_scenes() {
        let text = std::fs::read_to_string(dir.join("spec1.txt")).unwrap();
        scenes.push(("spec1".into(), legacy_rt::load(&text).unwrap()));
    }
    for (name, scene) in &scenes {
        every_pixel_agrees(name, scene, &Options::new(40, 30));
    }
    // Every stage and diagnostic image, on the gallery (tiles, mirrors, quadrics).
    let gallery = &scenes[1].1;
    for stage in Stage::ALL {
        let options = Options {
            stage,
            ..Options::new(24, 18)
        };
        every_pixel_agrees(stage.name(), gallery, &options);
    }
    for show in Show::ALL {
        let options = Options {
            show: Some(show),
            ..Options::new(24, 18)
        };
        every_pixel_agrees(show.name(), gallery, &options);
    }
}

/// Pixels of the examples that show one thing each, found by scanning the examples'
/// traces at 32x24; each is checked to still show it before its trace is kept.
const TELLING: [(&str, &str, usize, usize, &str); 7] = [
    ("shadowed", "procedural.txt", 14, 2, "blocked by"),
    ("spotlight_edge", "lights.txt", 22, 9, "outside the beam"),
    ("tile", "quadrics_gallery.txt", 2, 2, "tile relx"),
    ("texture", "textured_planes.txt", 11, 11, "texel column"),
    (
        "mirror_chain",
        "note003_records.txt",
        8,
        20,
        "reflected ray 2",
    ),
    (
        "quadric_second_root",
        "cones.txt",
        17,
        11,
        "out of bounds; root t =",
    ),
    ("nothing", "cones.txt", 2, 2, "closest: nothing: black"),
];

#[test]
fn traces_of_telling_pixels_are_reviewed() {
    snapshots().bind(|| {
        for (what, name, x, y, shows) in TELLING {
            let (_, scene) = example(name);
            let traced = trace(&scene, &Options::new(32, 24), x, y).unwrap();
            let text = traced.readable(&scene);
            assert!(text.contains(shows), "{what}: {name} ({x}, {y}):\n{text}");
            insta::assert_snapshot!(format!("trace_{what}"), text);
        }
    });
}

/// A floor y = -3 (ambient 0.5, specular 0.5) and a wall z = -10 (ambient 2). Pixel
/// (2, 1) of a 5x5 image looks at world point (0, -1.5): the ray from (0, 0, 3) along
/// (0, -1, -2)/√5 meets the floor at t = 3√5, point (0, -3, -3); the reflection
/// (0, 1, -2)/√5 meets the wall after 3.5√5 more, at (0, 0.5, -10).
const MIRROR_FLOOR: &str = "8 6\n0 0 3\n\
    14\n0.5 0.5 0.5\n0 0 0\n0.5 0.5 0.5\n0 1 0\n0 -3 0\n\
    14\n2 2 2\n0 0 0\n0 0 0\n0 0 1\n0 0 -10\n";

/// A floor z = -5 (ambient 1, diffuse 2), a light at (3, 0, -1) (emissivity 3) and a
/// small sphere halfway between them. Pixel (2, 1) of 5x3 looks straight down the axis:
/// t = 8 to (0, 0, -5); to the light L = (3, 0, 4), distance 5, cos θ = 4/5.
const LIT_FLOOR: &str = "8 6\n0 0 3\n\
    14\n1 1 1\n2 2 2\n0 0 0\n0 0 1\n0 0 -5\n\
    10\n3 3 3\n3 0 -1\n\
    13\n0 0 0\n0 0 0\n0 0 0\n1.5 0 -3\n0.5\n";

fn channel(text: &str, options: Options, x: usize, y: usize) -> u8 {
    let scene = legacy_rt::load(text).unwrap();
    let traced = trace(&scene, &options, x, y).unwrap();
    assert_eq!(traced.bytes[0], traced.bytes[1]);
    traced.bytes[0]
}

#[test]
fn each_stage_gives_the_value_of_its_formula() {
    let byte = |value: f64| (value.clamp(0.0, 1.0) * 255.0) as u8;
    let lit = |stage| {
        let options = Options {
            stage,
            ..Options::new(5, 3)
        };
        channel(LIT_FLOOR, options, 2, 1)
    };
    // Ambient only: ambient / distance.
    assert_eq!(lit(Stage::Ambient), byte(1.0 / 8.0));
    // Diffuse without shadows: (ambient + diffuse × emissivity × cos θ / dist) / distance.
    let lit_value = (1.0 + 2.0 * 3.0 * 0.8 / 5.0) / 8.0;
    assert_eq!(lit(Stage::Diffuse), byte(lit_value));
    // With shadows the sphere blocks the light: ambient only again.
    assert_eq!(lit(Stage::Shadows), byte(1.0 / 8.0));
    assert_eq!(lit(Stage::Full), byte(1.0 / 8.0));

    let mirror = |stage| {
        let options = Options {
            stage,
            ..Options::new(5, 5)
        };
        channel(MIRROR_FLOOR, options, 2, 1)
    };
    let first = 3.0 * 5f64.sqrt();
    let floor = 0.5 / first;
    // Without reflection: the floor's ambient over its distance.
    assert_eq!(mirror(Stage::Shadows), byte(floor));
    // Full: plus specular × the wall's ambient over the whole path, 6.5√5.
    let wall = 0.5 * 2.0 / (first + 3.5 * 5f64.sqrt());
    assert_eq!(mirror(Stage::Full), byte(floor + wall));
}

#[test]
fn the_diagnostic_images_follow_their_mappings() {
    let scene = legacy_rt::load(LIT_FLOOR).unwrap();
    let show = |show| {
        let options = Options {
            show: Some(show),
            ..Options::new(5, 3)
        };
        trace(&scene, &options, 2, 1).unwrap().bytes
    };
    // The floor's normal (0, 0, 1) as (N + 1) / 2 = (0.5, 0.5, 1).
    assert_eq!(show(Show::Normals), [127, 127, 255]);
    // Distance 8 of MAX_DIST 32: grey 1 - 8/32 = 0.75.
    assert_eq!(show(Show::Depth), [191, 191, 191]);
    // The floor is object 0, hue 0: channels 0.55 + 0.45 cos(0, 2π/3, 4π/3) =
    // (1, 0.325, 0.325), bytes 255, trunc(82.875), trunc(82.875).
    assert_eq!(show(Show::Objects), [255, 82, 82]);
    // The first objects of a file all get clearly different colours.
    let colours: Vec<_> = (0..12).map(legacy_rt::render::object_colour).collect();
    for (i, a) in colours.iter().enumerate() {
        let apart = |b: &glam::DVec3| (*a - *b).abs().max_element() > 0.05;
        assert!(colours[..i].iter().all(apart), "object {i}");
    }
}

#[test]
fn the_command_prints_the_trace_and_its_bytes() {
    let output = run(&["trace", "2", "1", "5", "5"], MIRROR_FLOOR.as_bytes());
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8(output.stdout).unwrap();
    let image = run(&["5", "5"], MIRROR_FLOOR.as_bytes()).stdout;
    // Row 5 - 1 - 1 = 3 of the image, column 2.
    let pixel = &image["P6 5 5 255\n".len() + (3 * 5 + 2) * 3..][..3];
    let last = format!("bytes: {} {} {}\n", pixel[0], pixel[1], pixel[2]);
    assert!(text.ends_with(&last), "{text}");
    assert!(text.contains("reflected ray 1"), "{text}");
    // The course's format: PIX, WRL, one FND per object tested, HIT, AMB.
    let output = run(
        &["trace", "2", "1", "5", "5", "--format", "course"],
        MIRROR_FLOOR.as_bytes(),
    );
    let course = String::from_utf8(output.stdout).unwrap();
    assert!(
        course.starts_with("PIX    2    1 - WRL (  0.0,  -1.5) - FND    0:   6.7 - "),
        "{course}"
    );
    assert!(
        course.contains("HIT    0:   6.7 (  0.0,  -3.0,  -3.0) - "),
        "{course}"
    );
    assert!(
        course.contains("HIT    1:   7.8 (  0.0,   0.5, -10.0) - "),
        "{course}"
    );
    assert_eq!(course.matches("AMB (").count(), 2, "{course}");
    // Every trace ends with the image's bytes, the course's format too.
    assert!(course.ends_with(&last), "{course}");
}

#[test]
fn course_ids_count_lights_and_objects_together_in_file_order() {
    // lights.txt: floor (0), sphere (1), then two lights (2, 3).
    let (text, _) = example("lights.txt");
    let output = run(
        &["trace", "16", "6", "32", "24", "--format", "course"],
        text.as_bytes(),
    );
    let course = String::from_utf8(output.stdout).unwrap();
    assert!(
        course.contains("FND    0: ") && course.contains("FND    1: "),
        "{course}"
    );
    assert!(course.contains("light object id was 2"), "{course}");
}

#[test]
fn trace_with_output_writes_the_image_with_the_pixel_marked() {
    let dir = std::env::temp_dir().join(format!("legacy-rt-trace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let marked = dir.join("traced.ppm");
    let output = run(
        &["trace", "1", "2", "5", "3", "-o", marked.to_str().unwrap()],
        LIT_FLOOR.as_bytes(),
    );
    assert!(output.status.success());
    let image = run(&["5", "3"], LIT_FLOOR.as_bytes()).stdout;
    let mut expected = image.clone();
    // Pixel (1, 2) is in output row 3 - 1 - 2 = 0.
    let at = "P6 5 3 255\n".len() + 3;
    expected[at..at + 3].copy_from_slice(&[0, 255, 0]);
    assert_eq!(std::fs::read(&marked).unwrap(), expected);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn trace_errors_are_one_clear_line_with_status_2_and_nothing_on_stdout() {
    for (args, says) in [
        (&["trace", "5", "0", "5", "3"][..], "outside the 5x3 image"),
        (&["trace", "0", "3", "5", "3"][..], "outside the 5x3 image"),
        (&["trace", "0", "0", "1", "3"][..], "at least 2x2"),
        (
            &["trace", "0", "0", "--stage", "ambient", "--show", "normals"][..],
            "cannot be used with",
        ),
        (
            &["--stage", "ambient", "--show", "depth"][..],
            "cannot be used with",
        ),
        (&["trace", "0", "0", "--format", "json"][..], "readable"),
    ] {
        let output = run(args, LIT_FLOOR.as_bytes());
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        assert!(output.stdout.is_empty(), "{args:?}");
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert!(
            stderr.starts_with("error: ") && stderr.contains(says),
            "{args:?}: {stderr}"
        );
    }
}

#[test]
fn help_shows_rendering_and_trace() {
    let help = String::from_utf8(run(&["--help"], b"").stdout).unwrap();
    for needle in [
        "trace",
        "--stage",
        "--show",
        "legacy-rt < scene.txt > image.ppm",
    ] {
        assert!(help.contains(needle), "{needle}:\n{help}");
    }
    let help = String::from_utf8(run(&["trace", "--help"], b"").stdout).unwrap();
    assert!(
        help.contains("--format") && help.contains("bytes: R G B"),
        "{help}"
    );
}

#[test]
fn every_stage_renders_every_course_scene() {
    let Some(dir) = course_scenes() else { return };
    for path in super::common::scene_files(&dir) {
        let scene = legacy_rt::load(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let mut images = Vec::new();
        for stage in Stage::ALL {
            let options = Options {
                stage,
                ..Options::new(32, 24)
            };
            images.push(render(&scene, &options, |_| {}));
        }
        // The full image is the default render, and the ambient stage is never brighter
        // than the diffuse one (lights only add).
        assert_eq!(images[3], render(&scene, &Options::new(32, 24), |_| {}));
        for (a, d) in images[0].pixels.iter().zip(&images[1].pixels) {
            assert!(a.iter().zip(d).all(|(a, d)| a <= d), "{}", path.display());
        }
    }
}
