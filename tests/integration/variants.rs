//! The variants of spec §7.3: each replaces its one rule, checked against the value that
//! rule's formula gives on a scene small enough to work out by hand.

use glam::DVec3;
use legacy_rt::compare::render_with_paths;
use legacy_rt::render::{self, Kind, Options, Variant};
use legacy_rt::shapes::{Ray, Shape};

/// The debug scene of spec §6: a plane z = -5 facing the eye, ambient 5 5 0, no lights.
const DEBUG_SCENE: &str = "8 6\n0 0 3\n14\n5 5 0\n0 0 0\n0 0 0\n0 0 -1\n0 0 -5\n";

fn render_as(
    text: &str,
    (width, height): (usize, usize),
    variants: &[Variant],
) -> legacy_rt::Image {
    let scene = legacy_rt::load(text).unwrap_or_else(|e| panic!("{e}"));
    let options = variants.iter().fold(Options::new(width, height), |o, &v| {
        o.with_variant(v).unwrap()
    });
    render::render(&scene, &options, |_| {})
}

/// The red byte of pixel (x, y), (0, 0) at the lower left, of an image in output order.
fn red(image: &legacy_rt::Image, x: usize, y: usize) -> u8 {
    image.pixels[(image.height - 1 - y) * image.width + x][0]
}

/// examples/quadrics_gallery.txt, loaded.
fn gallery() -> legacy_rt::Scene {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/quadrics_gallery.txt"
    ))
    .unwrap();
    legacy_rt::load(&text).unwrap()
}

/// The examples' scenes and the course's.
fn every_scene() -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = crate::common::scene_files(&root.join("examples"));
    if let Some(course) = crate::common::course_scenes() {
        files.extend(crate::common::scene_files(&course));
    }
    files
}

/// The distance from the eye (0, 0, 3) to the plane z = -5 through world point (x, y, 0).
fn to_the_wall(x: f64, y: f64) -> f64 {
    DVec3::new(x, y, -3.0).length() * 8.0 / 3.0
}

#[test]
fn pixel_centre_samples_the_middle_of_each_pixel() {
    let image = render_as(DEBUG_SCENE, (5, 3), &[Variant::of(Kind::PixelCentre)]);
    // Pixel (0, 0): (0.5 / 5 · 8 - 4, 0.5 / 3 · 6 - 3) = (-3.2, -2) instead of (-4, -3).
    let expected = (5.0 / to_the_wall(-3.2, -2.0) * 255.0).floor() as u8;
    assert_eq!(red(&image, 0, 0), expected);
    assert_eq!(expected, 99); // 5 / 12.855 = 0.389
    // The centre pixel (2, 1) is (0, 0) both ways: 5/8 → 159.
    assert_eq!(red(&image, 2, 1), 159);
}

#[test]
fn the_byte_rules_round_and_scale_by_256() {
    let corner = 5.0 / to_the_wall(-4.0, -3.0); // 0.3215: 81.99 → 81 truncated (spec §6)
    let round = render_as(DEBUG_SCENE, (5, 3), &[Variant::of(Kind::RoundBytes)]);
    assert_eq!(red(&round, 0, 0), (255.0 * corner + 0.5).floor() as u8);
    assert_eq!(red(&round, 0, 0), 82);
    let scaled = render_as(DEBUG_SCENE, (5, 3), &[Variant::of(Kind::Scale256)]);
    assert_eq!(red(&scaled, 0, 0), (256.0 * corner) as u8);
    assert_eq!(red(&scaled, 2, 1), 160); // 256 · 0.625
}

#[test]
fn no_distance_leaves_the_ambient_undivided() {
    let image = render_as(DEBUG_SCENE, (5, 3), &[Variant::of(Kind::NoDistance)]);
    // Ambient 5 5 0, clamped to 1: every pixel 255 255 0.
    assert!(image.pixels.iter().all(|&p| p == [255, 255, 0]));
}

#[test]
fn upside_down_writes_the_bottom_row_first() {
    let scene = "8 6\n0 0 3\n13\n9 9 9\n0 0 0\n0 0 0\n0 2 -4\n1.5\n"; // a sphere above centre
    let normal = render_as(scene, (16, 12), &[]);
    let flipped = render_as(scene, (16, 12), &[Variant::of(Kind::UpsideDown)]);
    let rows: Vec<_> = normal.pixels.chunks(16).rev().flatten().copied().collect();
    assert_eq!(flipped.pixels, rows);
    assert_ne!(flipped.pixels, normal.pixels);
}

/// A 45° mirror at the end of the centre ray sends it straight up to a ceiling 2 above:
/// the camera segment is 8 long, the reflected one 2.
const MIRROR_SCENE: &str = "8 6\n0 0 3\n\
    14 mirror\n0 0 0\n0 0 0\n1 1 1\n0 1 1\n0 0 -5\n\
    14 ceiling\n1 1 1\n0 0 0\n0 0 0\n0 -1 0\n0 2 0\n";

#[test]
fn segment_distance_divides_by_the_last_segment_only() {
    // Spec §4.2: the ceiling's ambient 1 over the path's 8 + 2 = 10; the variant: over 2.
    let reference = render_as(MIRROR_SCENE, (5, 3), &[]);
    assert_eq!(red(&reference, 2, 1), (255.0 / 10.0) as u8);
    let segment = render_as(MIRROR_SCENE, (5, 3), &[Variant::of(Kind::SegmentDistance)]);
    assert_eq!(red(&segment, 2, 1), (255.0 / 2.0) as u8);
    let one = render_as(MIRROR_SCENE, (5, 3), &[Variant::of(Kind::OneBounce)]);
    assert_eq!(red(&one, 2, 1), red(&reference, 2, 1)); // one bounce is all it takes
}

/// A wall z = -5 with diffuse 1, its normal as given, a light of emissivity 16 at
/// (0, 0, -1): the centre pixel's hit is 4 from the light, 8 from the eye.
fn lit_wall(normal_z: i32) -> String {
    format!("8 6\n0 0 3\n14\n0 0 0\n1 1 1\n0 0 0\n0 0 {normal_z}\n0 0 -5\n10\n16 16 16\n0 0 -1\n")
}

#[test]
fn square_falloff_divides_by_the_squared_distance() {
    // cos θ = 1, dist = 4: 16 / 4 / 8 = 0.5 as specified; 16 / 16 / 8 = 0.125 squared.
    let reference = render_as(&lit_wall(1), (5, 3), &[]);
    assert_eq!(red(&reference, 2, 1), 127);
    let squared = render_as(&lit_wall(1), (5, 3), &[Variant::of(Kind::SquareFalloff)]);
    assert_eq!(red(&squared, 2, 1), (0.125 * 255.0) as u8);
}

#[test]
fn facing_normals_light_the_back_of_a_surface() {
    // The normal (0, 0, -1) faces away from the eye and the light: cos θ = -1, unlit.
    let reference = render_as(&lit_wall(-1), (5, 3), &[]);
    assert_eq!(red(&reference, 2, 1), 0);
    let facing = render_as(&lit_wall(-1), (5, 3), &[Variant::of(Kind::FacingNormals)]);
    assert_eq!(red(&facing, 2, 1), 127);
}

#[test]
fn no_shadows_lets_a_blocked_light_through() {
    // The light at (0, 4, -1) is 4√2 from the hit (0, 0, -5), cos θ = 1/√2; a sphere on
    // the way blocks it. Unblocked: 32 · (1/√2) / (4√2) / 8 = 0.5.
    let scene = "8 6\n0 0 3\n14\n0 0 0\n1 1 1\n0 0 0\n0 0 1\n0 0 -5\n\
        13\n0 0 0\n0 0 0\n0 0 0\n0 2 -3\n0.5\n10\n32 32 32\n0 4 -1\n";
    assert_eq!(red(&render_as(scene, (5, 3), &[]), 2, 1), 0);
    let unshadowed = render_as(scene, (5, 3), &[Variant::of(Kind::NoShadows)]);
    assert_eq!(red(&unshadowed, 2, 1), 127);
}

#[test]
fn no_z_rule_keeps_a_plane_between_the_eye_and_the_screen() {
    // Plane z = 1 with ambient 1: 2 from the eye along the centre ray, but z > 0.
    let scene = "8 6\n0 0 3\n14\n1 1 1\n0 0 0\n0 0 0\n0 0 1\n0 0 1\n";
    assert_eq!(red(&render_as(scene, (5, 3), &[]), 2, 1), 0);
    assert_eq!(
        red(
            &render_as(scene, (5, 3), &[Variant::of(Kind::NoZRule)]),
            2,
            1
        ),
        127
    );
}

#[test]
fn tile_parity_swaps_which_tiles_are_the_foreground() {
    // At the centre hit q = (0, 0): relx + rely = 20000, even: the background tile.
    let scene = "8 6\n0 0 3\n16\n8 8 8\n0 0 0\n0 0 0\n0 0 1\n0 0 -5\n1 0 0\n1 1\n\
        0 0 0\n0 0 0\n0 0 0\n";
    assert_eq!(red(&render_as(scene, (5, 3), &[]), 2, 1), 0);
    assert_eq!(
        red(
            &render_as(scene, (5, 3), &[Variant::of(Kind::TileParity)]),
            2,
            1
        ),
        255
    );
}

#[test]
fn cone_scale_takes_the_paraboloids_k() {
    // A cone with its apex at (0, -2, -6), axis +y, r = 2, h = 4: k = (r/h)² = 0.25, so
    // at the height of the eye (local y = 2) its radius is 1; with cone-scale's
    // k = r²/h = 1 it is 2. The ray towards (1.5, 0, -6) passes the axis at 1.48 at
    // that height: it misses the course's cone and hits the wider one.
    let scene = "8 6\n0 0 3\n23\n1 1 1\n0 0 0\n0 0 0\n0 -2 -6\n0 1 0\n2 4\n";
    let scene = legacy_rt::load(scene).unwrap();
    let k = match &scene.objects[0].shape {
        Shape::Cone(cone) => cone.k(),
        other => panic!("{other:?}"),
    };
    assert_eq!(k, (2.0f64 / 4.0).powi(2)); // (r/h)²
    let ray = Ray::new(
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(1.5, 0.0, -9.0).normalize(),
    );
    let options = Options::new(4, 3);
    assert_eq!(render::ray_trace(&scene, &options, ray), DVec3::ZERO);
    let scaled = options.with_variant(Variant::of(Kind::ConeScale)).unwrap();
    assert!(render::ray_trace(&scene, &scaled, ray).x > 0.0);
}

#[test]
fn nearer_root_misses_the_inside_of_an_open_cylinder() {
    // A tube along z from -9 to -6, radius 1. The ray towards (0.3, 0, 0) enters its open
    // end and meets the inner wall at (1, 0, -7), 10.05 from the eye; its smaller root
    // (x = -1) lies behind the eye.
    let scene = "8 6\n0 0 3\n22\n10 10 10\n0 0 0\n0 0 0\n0 0 -9\n0 0 1\n1 3\n";
    let scene = legacy_rt::load(scene).unwrap();
    let ray = Ray::new(
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(0.3, 0.0, -3.0).normalize(),
    );
    let options = Options::new(8, 6);
    let colour = render::ray_trace(&scene, &options, ray);
    let distance = DVec3::new(1.0, 0.0, -10.0).length();
    assert!((colour.x - 10.0 / distance).abs() < 1e-12, "{colour}");
    let nearer = options.with_variant(Variant::of(Kind::NearerRoot)).unwrap();
    assert_eq!(render::ray_trace(&scene, &nearer, ray), DVec3::ZERO);
}

#[test]
fn a_traced_pixel_has_the_bytes_of_the_variants_image() {
    let scene = gallery();
    for variant in Variant::all() {
        let options = Options::new(32, 24).with_variant(variant).unwrap();
        let image = render::render(&scene, &options, |_| {});
        for (x, y) in [(3, 4), (16, 12), (30, 2), (10, 20)] {
            let trace = render::trace(&scene, &options, x, y).unwrap();
            let row = options.row_of(y);
            assert_eq!(
                trace.bytes,
                image.pixels[row * 32 + x],
                "{} at ({x}, {y})",
                variant.id()
            );
            assert!(
                trace.readable(&scene).contains(&variant.id())
                    || matches!(
                        variant.kind,
                        Kind::MaxDist | Kind::Textbook | Kind::TextbookF32
                    )
            );
        }
    }
}

/// hidden@LINE on a plane: camera rays pass through it to what lies behind, as the
/// course's loop (the trace tests every object in file order) finds it. The tiles once
/// took a hidden plane for a wall that hides everything behind it and left those objects
/// out of their lists: the back wall of a04 hidden showed the wall's own colour.
#[test]
fn a_hidden_plane_hides_nothing_behind_it() {
    let files = every_scene();
    let mut planes = 0;
    for path in files {
        let scene = legacy_rt::load(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let lines = (scene.objects.iter())
            .filter(|o| matches!(o.shape, Shape::Plane(_) | Shape::TiledPlane(_)))
            .map(|o| o.line);
        for line in lines {
            planes += 1;
            let hidden = Variant::parse(&format!("hidden@{line}")).unwrap();
            let options = Options::new(48, 36).with_variant(hidden).unwrap();
            let image = render::render(&scene, &options, |_| {});
            for (x, y) in (0..36)
                .step_by(3)
                .flat_map(|y| (0..48).step_by(3).map(move |x| (x, y)))
            {
                let trace = render::trace(&scene, &options, x, y).unwrap();
                assert_eq!(
                    trace.bytes,
                    image.pixels[options.row_of(y) * 48 + x],
                    "{} hidden@{line} at ({x}, {y})",
                    path.display()
                );
            }
        }
    }
    assert!(planes > 10, "{planes} planes");
}

/// What `compare --diagnose` relies on to score a candidate without a whole render
/// (src/render/reach.rs): a variant of one record changes only the pixels whose paths in
/// the reference name that record, a byte rule only by the steps the paths hold, and
/// one-bounce only the pixels whose paths took a second mirror bounce, far-clip=D only
/// those whose paths met something at D or beyond, a reader stopped at a record only
/// those whose paths met that record or a later one. For every localisable edit of the
/// first objects and of every light of each scene (and with round-bytes or scale-256
/// besides), a reader stopped at each of those records, and for one-bounce and far clips
/// of 2 to 20 alone and beside the first edit,
/// the image put together from the reference (the
/// pixels not touched) and from [`compare::render_pixels`] (the touched ones) is the
/// image rendered whole under the variants.
#[test]
fn a_variant_of_one_record_changes_only_the_pixels_whose_paths_name_it() {
    let files = every_scene();
    let object_edits = [
        "hidden",
        "no-shadow",
        "unlit",
        "no-mirror",
        "flipped-normal",
        "facing-normals",
        "shadow-epsilon",
    ];
    let light_edits = ["no-light", "unshadowed", "square-falloff"];
    let (mut checked, mut touched_somewhere, mut untouched_somewhere) = (0, 0, 0);
    for path in files {
        let scene = legacy_rt::load(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let options = Options::new(40, 30);
        let (reference, _, paths) = render_with_paths(&scene, &options, legacy_rt::compare::F32);
        let mut sets: Vec<Vec<Variant>> = Vec::new();
        for object in scene.objects.iter().take(5) {
            for edit in object_edits {
                sets.push(vec![
                    Variant::parse(&format!("{edit}@{}", object.line)).unwrap(),
                ]);
            }
            sets.push(vec![
                Variant::parse(&format!("stopped-at@{}", object.line)).unwrap(),
            ]);
            if matches!(object.shape, Shape::TiledPlane(_)) {
                sets.push(vec![
                    Variant::parse(&format!("tile-parity@{}", object.line)).unwrap(),
                ]);
            }
        }
        for light in &scene.lights {
            sets.push(vec![
                Variant::parse(&format!("stopped-at@{}", light.line)).unwrap(),
            ]);
            for edit in light_edits {
                sets.push(vec![
                    Variant::parse(&format!("{edit}@{}", light.line)).unwrap(),
                ]);
            }
        }
        let bytes = [
            Variant::parse("round-bytes").unwrap(),
            Variant::parse("scale-256").unwrap(),
        ];
        let one_bounce = Variant::parse("one-bounce").unwrap();
        let clips = [
            "far-clip=2",
            "far-clip=8",
            "far-clip=1",
            "far-clip=3",
            "far-clip=5",
            "far-clip=12",
            "far-clip=20",
        ]
        .map(|id| Variant::parse(id).unwrap());
        if let Some(first) = sets.first().cloned() {
            sets.push(vec![bytes[0], first[0]]);
            sets.push(vec![first[0], bytes[1]]);
            sets.push(vec![first[0], one_bounce]);
            sets.push(vec![first[0], clips[2]]);
        }
        sets.extend(bytes.map(|b| vec![b]));
        sets.push(vec![one_bounce]);
        sets.extend(clips.map(|c| vec![c]));
        for variants in sets {
            let what = format!("{}", path.display());
            let rendered = (&reference, &paths[..]);
            let traced = assembled_is_whole(&scene, options, rendered, &variants, &what);
            checked += 1;
            touched_somewhere += usize::from(traced > 0);
            untouched_somewhere += usize::from(traced < options.width * options.height);
        }
    }
    // Not vacuous: the edits touch some pixels and leave others to the reference.
    assert!(checked > 200, "{checked}");
    assert!(touched_somewhere > checked / 2 && untouched_somewhere > checked / 2);
}

/// The image put together from `scene`'s reference under `options` and its paths (the pixels
/// `variants`' [`Reach`] does not touch, stepped under their byte rule) and from
/// [`compare::render_pixels`] (the touched ones) is the whole render under `variants`;
/// how many pixels were touched.
///
/// [`Reach`]: legacy_rt::compare::Reach
fn assembled_is_whole(
    scene: &legacy_rt::scene::Scene,
    options: Options,
    (reference, paths): (&render::Image, &[legacy_rt::compare::Paths]),
    variants: &[Variant],
    what: &str,
) -> usize {
    use legacy_rt::compare::{Reach, render_pixels};
    let ids: Vec<String> = variants.iter().map(|v| v.id()).collect();
    let what = format!("{what} --variant {}", ids.join(","));
    let edited = (variants.iter()).fold(options, |o, &v| o.with_variant(v).unwrap());
    let whole = render::render(scene, &edited, |_| {});
    let reach = Reach::of(scene, &[], variants).unwrap_or_else(|| panic!("{what}"));
    let traced: Vec<usize> = (0..paths.len())
        .filter(|&i| reach.touches(paths[i]))
        .collect();
    let mut bytes = render_pixels(scene, &edited, &traced).into_iter();
    for (i, &path) in paths.iter().enumerate() {
        let pixel = match reach.touches(path) {
            true => bytes.next().unwrap(),
            false => reach.untouched(path, reference.pixels[i]),
        };
        assert_eq!(pixel, whole.pixels[i], "{what}: pixel {i}");
    }
    traced.len()
}

/// A far clip that frees a shadow ray where the camera ray's hit lies nearer than the
/// clip: a floor seen from close by (camera hits from t = 3.2 on, at z <= 0), lit from
/// above past a sphere (shadow rays blocked at t of about 15). far-clip=9 frees those
/// shadows where the camera's hit lies nearer than 8, which only the blocker's t, kept in
/// the path, says.
#[test]
fn a_far_clip_that_frees_a_shadow_ray_is_within_its_reach() {
    let text = "8 6\n0 0 3\n\n14\n0.1 0.1 0.1\n5 5 5\n0 0 0\n0 1 0\n0 -1 0\n\n\
                13\n0.2 0.2 0.2\n1 1 1\n0 0 0\n0 20 2\n6\n\n10\n100 100 100\n0 50 2\n";
    let scene = legacy_rt::load(text).unwrap();
    let options = Options::new(40, 30);
    let clip = Variant::parse("far-clip=9").unwrap();
    let (reference, _, paths) = render_with_paths(&scene, &options, legacy_rt::compare::F32);
    let rendered = (&reference, &paths[..]);
    let touched = assembled_is_whole(&scene, options, rendered, &[clip], "floor under a sphere");
    // Not vacuous: the clip frees shadows on pixels it leaves lit.
    let [plain, clipped] = [vec![], vec![clip]].map(|v| {
        let edited = (v.iter()).fold(options, |o, &v| o.with_variant(v).unwrap());
        render::render(&scene, &edited, |_| {})
    });
    let near_changed = (0..plain.pixels.len())
        .filter(|&i| plain.pixels[i] != clipped.pixels[i] && plain.pixels[i] != [0; 3])
        .filter(|&i| clipped.pixels[i] != [0; 3])
        .count();
    assert!(
        near_changed > 0 && touched < plain.pixels.len(),
        "{near_changed} {touched}"
    );
}

/// A reader stopped at a blocker that no camera ray sees, after the light: the floor
/// under a sphere above the view, lit from above it (the light first in the file).
/// stopped-at@15 drops the sphere alone and frees its shadow on pixels whose paths hit
/// only the floor and met the light: the blocker, kept in the path, says so.
#[test]
fn a_reader_stopped_at_a_blocker_out_of_view_is_within_its_reach() {
    let text = "8 6\n0 0 3\n\n10\n100 100 100\n0 50 2\n\n\
                14\n0.1 0.1 0.1\n5 5 5\n0 0 0\n0 1 0\n0 -1 0\n\n\
                13\n0.2 0.2 0.2\n1 1 1\n0 0 0\n0 20 2\n6\n";
    let scene = legacy_rt::load(text).unwrap();
    assert_eq!(scene.objects[1].line, 15);
    let options = Options::new(40, 30);
    let stopped = Variant::parse("stopped-at@15").unwrap();
    let (reference, _, paths) = render_with_paths(&scene, &options, legacy_rt::compare::F32);
    let rendered = (&reference, &paths[..]);
    let touched = assembled_is_whole(&scene, options, rendered, &[stopped], "a blocker");
    // Not vacuous: the shadow goes, and some pixels are left to the reference.
    let edited = options.with_variant(stopped).unwrap();
    let freed = render::render(&scene, &edited, |_| {});
    let changed = (0..freed.pixels.len())
        .filter(|&i| freed.pixels[i] != reference.pixels[i])
        .count();
    assert!(
        changed > 0 && touched < freed.pixels.len(),
        "{changed} {touched}"
    );
}

/// [`compare::render_pixels`] gives the whole render's bytes at whichever pixels it is
/// asked for: a block (the tiles it covers get their lists, the others none), pixels
/// scattered one to a tile (no lists), every pixel; upside down too (rows counted the
/// other way) and with the first object hidden (a hidden plane hides nothing).
#[test]
fn render_pixels_gives_the_renders_bytes_at_any_pixels() {
    let (width, height) = (64, 48);
    let block: Vec<usize> = (0..width * height)
        .filter(|i| (5..27).contains(&(i % width)) && (9..30).contains(&(i / width)))
        .collect();
    let scattered: Vec<usize> = (0..width * height).step_by(37).collect();
    let every: Vec<usize> = (0..width * height).collect();
    for path in every_scene() {
        let scene = legacy_rt::load(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let plain = Options::new(width, height);
        let mut variants = vec![Variant::parse("upside-down").unwrap()];
        if let Some(first) = scene.objects.first() {
            variants.push(Variant::parse(&format!("hidden@{}", first.line)).unwrap());
        }
        let options =
            std::iter::once(plain).chain(variants.iter().map(|&v| plain.with_variant(v).unwrap()));
        for options in options {
            let whole = render::render(&scene, &options, |_| {});
            for pixels in [&block, &scattered, &every] {
                let bytes = legacy_rt::compare::render_pixels(&scene, &options, pixels);
                for (&i, &b) in pixels.iter().zip(&bytes) {
                    assert_eq!(b, whole.pixels[i], "{}: pixel {i}", path.display());
                }
            }
        }
    }
}

/// The edits whose record may be hit where it was not (geometry) can change any pixel:
/// no reach is claimed for them, nor for the whole image's variants but the byte rules,
/// one-bounce and far-clip.
#[test]
fn geometry_variants_claim_no_reach() {
    let scene = gallery();
    for object in &scene.objects {
        for edit in ["nearer-root", "cone-scale", "no-z-rule"] {
            if let Ok(variant) = Variant::parse(&format!("{edit}@{}", object.line)) {
                assert_eq!(legacy_rt::compare::Reach::of(&scene, &[], &[variant]), None);
            }
        }
    }
    let claimed = |v: &Variant| {
        v.row().site == render::variant::Site::Bytes
            || matches!(v.kind, Kind::OneBounce | Kind::FarClip)
    };
    for variant in Variant::all().filter(|v| !claimed(v)) {
        assert_eq!(
            legacy_rt::compare::Reach::of(&scene, &[], &[variant]),
            None,
            "{}",
            variant.id()
        );
    }
}

// The mistakes of spec §7.5.

/// A variant with its value.
fn valued(kind: Kind, value: f64) -> Variant {
    Variant {
        value: Some(value),
        ..Variant::of(kind)
    }
}

/// The red byte a pixel of the debug scene shows when its ray goes through world point
/// (x, y): 5 / the distance to the wall, truncated.
fn debug_red(x: f64, y: f64) -> u8 {
    (5.0 / to_the_wall(x, y) * 255.0) as u8
}

#[test]
fn row_and_column_offsets_trace_the_neighbouring_pixel() {
    // 5x3 of the debug scene: pixel (x, y) is at (2x - 4, 3y - 3). Under row-offset=1
    // pixel row y traces row y + 1: the top row (y = 2) traces y = 3, the point (x, 6),
    // beyond the window.
    let image = render_as(DEBUG_SCENE, (5, 3), &[valued(Kind::RowOffset, 1.0)]);
    for (x, y) in [(0, 0), (2, 1), (4, 2)] {
        let (wx, wy) = (2.0 * x as f64 - 4.0, 3.0 * (y + 1) as f64 - 3.0);
        assert_eq!(red(&image, x, y), debug_red(wx, wy), "({x}, {y})");
    }
    // Two rows down.
    let image = render_as(DEBUG_SCENE, (5, 3), &[valued(Kind::RowOffset, -2.0)]);
    assert_eq!(red(&image, 0, 2), debug_red(-4.0, -3.0));
    assert_eq!(red(&image, 1, 0), debug_red(-2.0, -9.0));
    // One column right.
    let image = render_as(DEBUG_SCENE, (5, 3), &[valued(Kind::ColumnOffset, 1.0)]);
    assert_eq!(red(&image, 1, 1), debug_red(0.0, 0.0));
    assert_eq!(red(&image, 4, 1), debug_red(6.0, 0.0));
}

#[test]
fn jitter_moves_each_ray_within_half_a_pixel_the_same_way_every_time() {
    let jittered = || render_as(DEBUG_SCENE, (5, 3), &[Variant::of(Kind::Jitter)]);
    let (a, b) = (jittered(), jittered());
    assert_eq!(a, b, "a seed gives one image");
    let other = render_as(DEBUG_SCENE, (5, 3), &[valued(Kind::Jitter, 2.0)]);
    assert_ne!(a, other, "another seed, other points");
    // Each pixel's byte lies between those of the farthest and the nearest point of its
    // square (half a pixel is 1 in x and 1.5 in y here): the wall's distance grows away
    // from the centre.
    for y in 0..3 {
        for x in 0..5 {
            let (cx, cy) = (2.0 * x as f64 - 4.0, 3.0 * y as f64 - 3.0);
            let far = (cx.abs() + 1.0, cy.abs() + 1.5);
            let near = ((cx.abs() - 1.0).max(0.0), (cy.abs() - 1.5).max(0.0));
            let byte = red(&a, x, y);
            assert!(
                byte >= debug_red(far.0, far.1) && byte <= debug_red(near.0, near.1),
                "({x}, {y}): {byte}"
            );
        }
    }
}

#[test]
fn behind_root_lets_a_shadow_ray_from_inside_a_tube_through() {
    // examples/tube.txt: the floor inside the tube is in the tube's shadow; under
    // behind-root the shadow ray from inside takes the tube's root behind its base (in
    // bounds) and misses, so the floor there is lit.
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/tube.txt")).unwrap();
    let scene = legacy_rt::load(&text).unwrap();
    // The ray from the eye to the floor inside the tube, at (0.3, -2, -2.8).
    let eye = scene.viewpoint;
    let inside = DVec3::new(0.3, -2.0, -2.8);
    let ray = Ray::new(eye, (inside - eye).normalize());
    let options = Options::new(8, 6);
    let plain = render::ray_trace(&scene, &options, ray);
    let behind = options.with_variant(Variant::of(Kind::BehindRoot)).unwrap();
    let lit = render::ray_trace(&scene, &behind, ray);
    // Unlit: the ambient 0.5 over the path; lit: plus diffuse 4 × emissivity 8 × cos θ /
    // dist, all over the path.
    let path = (inside - eye).length();
    assert!((plain.x - 0.5 / path).abs() < 1e-12, "{plain}");
    let to_light = DVec3::new(3.0, -1.6, -3.0) - inside;
    let (dist, cos) = (to_light.length(), to_light.normalize().y);
    let expected = (0.5 + 4.0 * 8.0 * cos / dist) / path;
    assert!((lit.x - expected).abs() < 1e-12, "{lit} against {expected}");
}

#[test]
fn z_tolerance_moves_the_z_rule_and_far_clip_cuts_far_hits() {
    // The plane z = 1 of no-z-rule's test: its hits have z = 1 > 0, a miss; under
    // z-tolerance=2 they count, under z-tolerance=0.5 not.
    let scene = "8 6\n0 0 3\n14\n1 1 1\n0 0 0\n0 0 0\n0 0 1\n0 0 1\n";
    assert_eq!(
        red(
            &render_as(scene, (5, 3), &[valued(Kind::ZTolerance, 2.0)]),
            2,
            1
        ),
        127
    );
    assert_eq!(
        red(
            &render_as(scene, (5, 3), &[valued(Kind::ZTolerance, 0.5)]),
            2,
            1
        ),
        0
    );
    // The debug scene's wall is 8 from the eye along the centre ray: far-clip=8.5 keeps
    // it, far-clip=7.5 cuts it (black).
    assert_eq!(
        red(
            &render_as(DEBUG_SCENE, (5, 3), &[valued(Kind::FarClip, 8.5)]),
            2,
            1
        ),
        159
    );
    assert_eq!(
        red(
            &render_as(DEBUG_SCENE, (5, 3), &[valued(Kind::FarClip, 7.5)]),
            2,
            1
        ),
        0
    );
}

#[test]
fn stopped_at_drops_that_record_and_every_later_one() {
    // A wall (line 3) and, nearer, a small white sphere (line 9) at the centre: stopped at
    // the sphere, the centre shows the wall; stopped at the wall, nothing.
    let scene = format!("{DEBUG_SCENE}13\n10 10 10\n0 0 0\n0 0 0\n0 0 -3\n1\n");
    assert_eq!(red(&render_as(&scene, (5, 3), &[]), 2, 1), 255);
    let stopped = |line: usize| render_as(&scene, (5, 3), &[Variant::of(Kind::StoppedAt).at(line)]);
    assert_eq!(red(&stopped(9), 2, 1), 159);
    assert!(stopped(3).pixels.iter().all(|p| *p == [0, 0, 0]));
}

#[test]
fn tile_unprojected_takes_the_x_direction_as_given() {
    // A 1 x 1 finite plane in z = -5 from (-1, -1, -5), x direction (1, 0, 1): projected
    // into the plane, x = (1, 0, 0) and the rectangle spans x, y in [-1, 0]. Used as
    // given, x = (1, 0, 1)/√2, so q.x = (H - point)·x = d_x/√2 (and q.y = d_y/√2): the
    // rectangle spans [-1, -1 + √2] = [-1, 0.414] each way.
    let scene = "8 6\n0 0 3\n15\n1 1 1\n0 0 0\n0 0 0\n0 0 1\n-1 -1 -5\n1 0 1\n1 1\n";
    let scene = legacy_rt::load(scene).unwrap();
    let options = Options::new(4, 3);
    let unprojected = (options.with_variant(Variant::of(Kind::TileUnprojected))).unwrap();
    let eye = DVec3::new(0.0, 0.0, 3.0);
    let towards = |x: f64, y: f64| Ray::new(eye, (DVec3::new(x, y, -5.0) - eye).normalize());
    // (-0.5, -0.5): inside both; (0.3, 0.3): only the unprojected one; (0.5, 0.5): neither.
    for ((x, y), (as_written, as_given)) in [
        ((-0.5, -0.5), (true, true)),
        ((0.3, 0.3), (false, true)),
        ((0.5, 0.5), (false, false)),
    ] {
        let lit = |options: &Options| render::ray_trace(&scene, options, towards(x, y)).x > 0.0;
        assert_eq!(lit(&options), as_written, "({x}, {y}) as written");
        assert_eq!(lit(&unprojected), as_given, "({x}, {y}) unprojected");
    }
    // The same record with its x direction in the plane: nothing changes.
    let flat = "8 6\n0 0 3\n15\n1 1 1\n0 0 0\n0 0 0\n0 0 1\n-1 -1 -5\n2 0 0\n1 1\n";
    let flat = legacy_rt::load(flat).unwrap();
    let plain = Options::new(40, 30);
    let given = plain
        .with_variant(Variant::of(Kind::TileUnprojected))
        .unwrap();
    let image = |options: &Options| render::render(&flat, options, |_| {}).pixels;
    assert_eq!(image(&plain), image(&given));
}

/// A decision forced on every pixel's path (`compare::render_forced`) gives the image of
/// the edit of one record that makes the same decision, on every example and course
/// scene: an object missed by camera and mirror rays is `hidden@LINE`, by shadow rays
/// `no-shadow@LINE`; a light's shadow test forced open is `unshadowed@LINE`, forced shut
/// (where the stage casts shadow rays, which then adds nothing) `no-light@LINE`.
#[test]
fn a_forced_decision_gives_the_image_of_the_edit_that_makes_it() {
    use legacy_rt::compare::render_forced;
    use legacy_rt::render::{Override, Rays};
    let (width, height) = (40, 30);
    let every: Vec<usize> = (0..width * height).collect();
    let (mut compared, mut changed) = (0, 0);
    for path in every_scene() {
        let text = std::fs::read_to_string(&path).unwrap();
        let scene = legacy_rt::load(&text).unwrap();
        let options = Options::new(width, height);
        let plain = render::render(&scene, &options, |_| {}).pixels;
        // Each case: the decisions forced, and the edit of the record on `line`.
        let mut cases: Vec<(Vec<Override>, &str, usize)> = Vec::new();
        // The first eight objects and every light: enough of each kind of record.
        for (object, record) in scene.objects.iter().enumerate().take(8) {
            let missed = |rays| Override::Miss { object, rays };
            let hidden = vec![missed(Rays::Camera), missed(Rays::Mirror)];
            cases.push((hidden, "hidden", record.line));
            cases.push((vec![missed(Rays::Shadow)], "no-shadow", record.line));
        }
        for (light, record) in scene.lights.iter().enumerate() {
            let decided = |blocked| vec![Override::Shadow { light, blocked }];
            cases.push((decided(false), "unshadowed", record.line));
            cases.push((decided(true), "no-light", record.line));
        }
        for (overrides, edit, line) in cases {
            let variant = Variant::parse(&format!("{edit}@{line}")).unwrap();
            let with = options.with_variant(variant).unwrap();
            let edited = render::render(&scene, &with, |_| {}).pixels;
            let forced = render_forced(&scene, &options, &every, &overrides);
            assert_eq!(forced, edited, "{} {edit}@{line}", path.display());
            compared += 1;
            changed += usize::from(edited != plain);
        }
    }
    // Not vacuous: most of the edits change their scene's image.
    assert!(
        2 * changed > compared,
        "{changed} of {compared} edits change the image"
    );
    assert!(compared > 100, "only {compared} images compared");
}
