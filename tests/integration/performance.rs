//! What the speed work of issues 6 and 16 must not change: the image. Threads, the
//! bounding volume hierarchy and the camera rays' tiles (`accelerate: false` turns both
//! off) change only the order and number of tests, never a pixel.

#[path = "../support/generated.rs"]
mod generated;

use crate::common::{course_scenes, scene_files};
use legacy_rt::render::{Options, Variant, render};
use std::path::Path;

/// The PPM bytes of `scene` rendered with `options`.
fn bytes(scene: &legacy_rt::Scene, options: &Options) -> Vec<u8> {
    legacy_rt::image_output::ppm(&render(scene, options, |_| {}))
}

/// Whether a 96x72 render of `scene` walks a bounding volume hierarchy.
fn hierarchy(scene: &legacy_rt::Scene) -> bool {
    legacy_rt::render::acceleration(scene, &Options::new(96, 72)).0
}

/// The PPM of `scene` at `width` x `height` with the hierarchy and with the linear scan.
fn with_and_without_bvh(scene: &legacy_rt::Scene, width: usize, height: usize) -> [Vec<u8>; 2] {
    [true, false].map(|accelerate| {
        let options = Options {
            accelerate,
            ..Options::new(width, height)
        };
        bytes(scene, &options)
    })
}

/// Every example scene, every course scene and the generated family at 10 and 300
/// objects.
fn scenes() -> Vec<(String, legacy_rt::Scene)> {
    let mut files = scene_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples"));
    if let Some(dir) = course_scenes() {
        files.extend(scene_files(&dir));
    }
    let mut scenes: Vec<(String, legacy_rt::Scene)> = files
        .iter()
        .filter_map(|path| {
            let text = std::fs::read_to_string(path).ok()?;
            Some((path.display().to_string(), legacy_rt::load(&text).ok()?))
        })
        .collect();
    for count in [10, 300] {
        let scene = legacy_rt::load(&generated::many_objects(count)).unwrap();
        scenes.push((format!("generated {count}"), scene));
    }
    assert!(scenes.len() > 20, "{} scenes", scenes.len());
    scenes
}

#[test]
fn threads_1_and_4_give_identical_bytes() {
    for (name, scene) in scenes() {
        let one = Options {
            threads: 1,
            ..Options::new(96, 72)
        };
        let four = Options { threads: 4, ..one };
        assert!(bytes(&scene, &one) == bytes(&scene, &four), "{name}");
    }
}

#[test]
fn the_bvh_gives_the_linear_scan_s_image() {
    let mut accelerated = 0;
    for (name, scene) in scenes() {
        accelerated += usize::from(hierarchy(&scene));
        let [bvh, linear] = with_and_without_bvh(&scene, 96, 72);
        assert!(bvh == linear, "{name}");
    }
    // The comparison means something only where a tree is built.
    assert!(accelerated >= 2, "{accelerated} scenes with a BVH");
}

#[test]
fn the_generated_family_has_the_requested_objects_in_view() {
    let floor_only = legacy_rt::load(&generated::many_objects(0)).unwrap();
    let floor_only = render(&floor_only, &Options::new(160, 120), |_| {});
    for count in [10, 100] {
        let scene = legacy_rt::load(&generated::many_objects(count)).unwrap();
        assert_eq!(scene.objects.len(), count + 1); // and the floor
        let image = render(&scene, &Options::new(160, 120), |_| {});
        // The objects change a good part of the picture that the floor alone makes.
        let changed = (image.pixels.iter())
            .zip(&floor_only.pixels)
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            changed > image.pixels.len() / 10,
            "{count} objects change {changed} pixels"
        );
    }
}

#[test]
fn a_lopsided_hierarchy_renders_as_the_linear_scan() {
    // 700 spheres at x = 1.5^i: the surface area heuristic splits one sphere off at each
    // level, a chain 700 deep that overflowed the traversal's fixed stack (issue 12).
    let mut text = String::from("8 6\n0 0 3\n10\n9 9 9\n0 5 5\n");
    for i in 0..700 {
        let x = 1.5f64.powi(i);
        text.push_str(&format!("13\n1 1 1\n3 3 3\n0 0 0\n{x:e} 0 -10\n0.5\n"));
    }
    let scene = legacy_rt::load(&text).unwrap();
    assert!(hierarchy(&scene));
    let [image, linear] = with_and_without_bvh(&scene, 64, 48);
    assert!(image == linear);
    // The nearest spheres are in view: the image is not all black.
    assert!(image[b"P6 64 48 255\n".len()..].iter().any(|&b| b > 0));
}

#[test]
fn shapes_thinner_than_their_rounding_give_the_linear_scan_s_image() {
    // Found by the generated-scene property test (issue 12): a paraboloid 1e-21 high
    // (k = 1e17) and a hyperboloid 1e-15 high (k = 1e30) are thinner than the rounding of
    // their coordinates, so the kernel's t can put a hit far outside their boxes; the
    // hierarchy skipped those boxes while the scan took the hits. Eight spheres make the
    // scene big enough for a hierarchy.
    let spheres: String = (0..8)
        .map(|i| {
            format!(
                "13\n1 1 1\n1 1 1\n0.5 0.5 0.5\n{} 0 -6\n0.5\n",
                1.0 + 0.01 * f64::from(i)
            )
        })
        .collect();
    let thin = [
        "21\n0 0 0\n0 0 0\n1 1 1\n0 0 1e-8\n-16.7 0 0\n1e-2 1e-21\n\
         20\n0 1 0\n0 0 0\n1 1 1\n1 0 0\n-2 0 0\n0\n",
        "24\n0 0 1\n0 0 0\n0 0 0\n0 0 0\n1 0 0\n1 1e-15\n0\n",
    ];
    for shape in thin {
        let scene = legacy_rt::load(&format!("8 6\n0 0 3\n{spheres}{shape}")).unwrap();
        assert!(hierarchy(&scene));
        let [bvh, linear] = with_and_without_bvh(&scene, 32, 24);
        assert!(bvh == linear, "{shape}");
    }
}

/// A room (spec1's kind of scene, and a04's): walls, floor and ceiling as planes, a
/// tiled floor, spheres, quadrics and rectangles inside, some behind the back wall,
/// across the eye's plane z = 3 or behind the eye, one sphere around the eye.
fn room() -> legacy_rt::Scene {
    let mut text = String::from("8 6\n0 0 3\n10\n9 9 9\n1 2.5 1\n10\n4 4 4\n-3 2 -2\n");
    let material = "0.2 0.2 0.2\n2 2 2\n0.2 0.2 0.2\n";
    for (normal, point) in [
        ("0 0 1", "0 0 -6"),
        ("0 -1 0", "0 3 0"),
        ("1 0 0", "-5 0 0"),
        ("-0.7 0 0.7", "5 0 -3"),
    ] {
        text.push_str(&format!("14\n{material}{normal}\n{point}\n"));
    }
    text.push_str(&format!(
        "16\n{material}0 1 0\n0 -3 0\n1 0 0\n1 1\n1 1 1\n0 0 0\n0 0 0\n"
    ));
    for (i, centre) in [
        "-2 -2 -4", "2 -1 -3", "0 1 -8", "3 2 -10", "-1 0 2.5", "1 -1 5", "0 0 3",
    ]
    .iter()
    .enumerate()
    {
        let radius = [0.8, 1.0, 2.0, 1.5, 1.0, 0.7, 0.5][i];
        text.push_str(&format!("13\n{material}{centre}\n{radius}\n"));
    }
    text.push_str(&format!("22\n{material}-3 -3 -5\n0 1 0\n0.5 3\n"));
    text.push_str(&format!("23\n{material}3 -3 -7\n0 1 0.2\n1 2\n"));
    text.push_str(&format!("15\n{material}0 0 1\n-1 -1 -7\n1 0.3 0\n2 2\n"));
    legacy_rt::load(&text).expect("the room loads")
}

#[test]
fn the_room_under_every_variant_renders_as_the_linear_scan() {
    // The camera rays' tiles leave out what a nearer wall hides and what lies behind
    // the eye; the shadow rays walk the hierarchy. Sizes that are not multiples of the
    // tiles' 8 pixels, and every variant (pixel-centre moves the pixels, upside-down the
    // rows, no-z-rule the planes' hits, textbook-f32 the arithmetic).
    let scene = room();
    assert!(hierarchy(&scene));
    for variant in Variant::all() {
        for (width, height) in [(64, 48), (53, 37)] {
            let options = Options::new(width, height).with_variant(variant).unwrap();
            let linear = Options {
                accelerate: false,
                ..options
            };
            let name = variant.id();
            assert!(
                bytes(&scene, &options) == bytes(&scene, &linear),
                "{name} {width}x{height}"
            );
        }
    }
    // Not all black: the room is in view.
    let image = bytes(&scene, &Options::new(64, 48));
    assert!(
        image[b"P6 64 48 255\n".len()..]
            .iter()
            .filter(|&&b| b > 0)
            .count()
            > 3000
    );
}

/// The renders that cast shadow rays trace a tile's span of pixels at a time, each step
/// across the span before the next (`Tracer::span`): `render`, and `render_pixels` (the
/// diagnosis's), which groups the pixels it is asked for into spans. The render with
/// margins (compare's reference) traces each pixel on its own with the scalar loop and a
/// recorder. All three give the same bytes on every example, course scene and generated
/// scene, at a size that leaves short spans at the right edge, in both stages with shadow
/// rays and under every variant: the whole image's, and each scoped edit on each record
/// it applies to. In the ambient stage `render` traces each span's rays without the
/// lights' and the mirror's steps (`Tracer::ambient_only`), and gives the same bytes too.
#[test]
fn spans_give_each_pixels_own_bytes() {
    use legacy_rt::compare::{render_pixels, render_with_margins};
    use legacy_rt::render::variant::{Scope, check_scopes};
    use legacy_rt::render::{Stage, VARIANTS};
    let (width, height) = (29, 22);
    let every: Vec<usize> = (0..width * height).collect();
    let mut checked = 0;
    let mut lit = 0;
    let mut ambient = 0;
    for (name, scene) in scenes() {
        let mut variants: Vec<Option<Variant>> = vec![None];
        variants.extend(Variant::all().map(Some));
        let lines =
            (scene.objects.iter().map(|o| o.line)).chain(scene.lights.iter().map(|l| l.line));
        for line in lines {
            for row in VARIANTS.iter().filter(|row| row.scope != Scope::Image) {
                if let Ok(variant) = Variant::parse(&format!("{}@{line}", row.id)) {
                    variants.push(Some(variant));
                }
            }
        }
        for stage in [Stage::Ambient, Stage::Shadows, Stage::Full] {
            for &variant in &variants {
                let plain = Options {
                    stage,
                    ..Options::new(width, height)
                };
                let options = match variant {
                    Some(variant) => match plain.with_variant(variant) {
                        Ok(options) => options,
                        Err(_) => continue,
                    },
                    None => plain,
                };
                if check_scopes(&options, &scene).is_err() {
                    continue;
                }
                let (each, _) = render_with_margins(&scene, &options, 1e-7);
                let whole = render(&scene, &options, |_| {});
                let sampled = render_pixels(&scene, &options, &every);
                let id = variant.map_or("none".to_string(), |v| v.id());
                assert!(
                    whole.pixels == each.pixels,
                    "{name}, {}, {id}",
                    stage.name()
                );
                assert!(sampled == each.pixels, "{name}, {}, {id}", stage.name());
                checked += 1;
                lit += usize::from(!scene.lights.is_empty() && stage != Stage::Ambient);
                ambient += usize::from(stage == Stage::Ambient);
            }
        }
    }
    // Not vacuous: most renders have a light, so they go by spans; a third are ambient.
    assert!(
        checked > 1000 && lit > checked / 2 && ambient > checked / 4,
        "{checked} renders, {lit} with lights, {ambient} ambient"
    );
}

/// Memory per object (issue 30): a million records must fit a laptop's memory, so an
/// object holds in place only what the common kinds need. The sphere keeps its centre and
/// radius (its equation is built when a kernel asks), the rarer shapes are boxed, and the
/// material and pattern are one shared look for a run of records with the same plain
/// material. Measured 280 bytes before (472 the round before that); the sizes per kind
/// are in docs/performance.md.
#[test]
fn an_object_takes_at_most_88_bytes() {
    use legacy_rt::scene::{Object, Pattern};
    use legacy_rt::shapes::{AxisFrame, Shape, Sphere};
    use std::mem::size_of;
    use std::sync::Arc;
    assert!(size_of::<Object>() <= 88, "{}", size_of::<Object>());
    assert!(size_of::<Shape>() <= 72, "{}", size_of::<Shape>());
    assert!(size_of::<Sphere>() <= 40, "{}", size_of::<Sphere>());
    // A sphere's frame is its centre: no rotation is stored for it.
    let two = "8 6\n0 0 3\n13\n1 1 1\n0 0 0\n0 0 0\n0 0 -5\n1\n\
               13\n1 1 1\n0 0 0\n0 0 0\n2 0 -5\n1\n\
               13\n1 1 2\n0 0 0\n0 0 0\n-2 0 -5\n1\n\
               19\n1 1 2\n0 0 0\n0 0 0\n0 2 -5\n1\n0\n\
               19\n1 1 2\n0 0 0\n0 0 0\n0 -2 -5\n1\n0\n";
    let scene = legacy_rt::load(two).unwrap();
    let Shape::Sphere(s) = &scene.objects[0].shape else {
        panic!("a sphere")
    };
    assert_eq!(s.equation().frame, AxisFrame::unrotated(s.centre));
    assert!(s.equation().frame.rotation.is_none());
    // The first two records have one material: one look. The third differs; the shaded
    // spheres' patterns (each with its own origin) are never shared.
    let looks = |i: usize, j: usize| Arc::ptr_eq(&scene.objects[i].look, &scene.objects[j].look);
    assert!(looks(0, 1));
    assert!(!looks(1, 2) && !looks(2, 3) && !looks(3, 4));
    assert!(matches!(
        scene.objects[4].look.pattern,
        Pattern::Shader { .. }
    ));
    assert_eq!(scene.objects[4].kind(), "procedural sphere");
}

/// A scene over a megabyte is read in chunks on several threads, and its hierarchy is
/// built there (issue 47): the command line gives the same image on 1 and 3 threads,
/// and for the same scene with an error near its end (a zero axis, or a word for a
/// number), the same message and status.
#[test]
fn a_large_scene_is_read_and_rendered_alike_on_any_threads() {
    let text = generated::many_objects(30_000);
    assert!(
        text.len() > 1 << 20,
        "{} bytes: not read in chunks",
        text.len()
    );
    // The first line labelled `label` in the last fiftieth of the text, replaced.
    let broken = |label: &str, with: &str| {
        let at = text.len() - text.len() / 50;
        let end = at + text[at..].find(label).unwrap();
        let start = text[..end].rfind('\n').unwrap() + 1;
        format!("{}{with}{}", &text[..start], &text[end..])
    };
    let scenes = [
        (text.clone(), 0),
        (broken("   axis", "0 0 0"), 1),
        (broken("   centre", "one two three"), 1),
    ];
    for (scene, status) in scenes {
        let [one, three] = ["1", "3"].map(|threads| {
            crate::common::run(&["--threads", threads, "64", "48"], scene.as_bytes())
        });
        let message = String::from_utf8_lossy(&one.stderr);
        assert_eq!(one.status.code(), Some(status), "{message}");
        assert_eq!(one.status.code(), three.status.code());
        assert_eq!(one.stdout, three.stdout);
        assert_eq!(message, String::from_utf8_lossy(&three.stderr));
    }
}
