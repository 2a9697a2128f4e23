//! `trace X Y --against FILE` (issue 27): a student's own debug trace read against the
//! reference's. The students' traces are written here, in the formats of spec §8, by a
//! writer of this test's own from the reference's events (what a correct program would
//! print), then one mistake is planted in them; the first difference must be the planted
//! one, named by object, light and line, and a trace without a mistake must agree.

use crate::common::{folder, run};
use glam::DVec3;
use legacy_rt::render::{Event, LightStep, Options, Trace, trace};
use legacy_rt::scene::Scene;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// How a copy of the course program prints (spec §8).
#[derive(Debug, Clone, Copy, Default)]
struct Dialect {
    /// `FND 3 -1.0`, `HIT 3 5.2 (...)`, and labels with their value on the next line.
    no_colon: bool,
    /// `%5.11f` instead of `%5.1lf`.
    eleven: bool,
    /// Ids from 100 instead of 0.
    from_100: bool,
    /// Each FND on its own line, followed by `base`, `dir` and `hits` lines.
    three_line: bool,
    /// How the pixel is printed.
    pix: Pix,
    /// WRL at the end of the pixel's lines, or before its PIX line.
    world: World,
    /// A miss printed as `-nan` instead of -1.
    nan_miss: bool,
    /// The direction to the light printed unnormalised; shadow rays' t in its units.
    unnormalised: bool,
    /// Shadow rays print their FND lines.
    shadow_fnd: bool,
    /// The light's geometry printed for every light before the cos test (else only for
    /// lights that add something, after the computation, as the course's own copy did).
    block_first: bool,
    /// Lines of other output: a model dump, matrices, bytes.
    junk: bool,
    /// Vectors as `%f %f %f` instead of `%8.3f`.
    long_vectors: bool,
}

#[derive(Debug, Clone, Copy, Default, PartialEq)]
enum Pix {
    #[default]
    XY,
    YX,
    RowCol,
}

#[derive(Debug, Clone, Copy, Default, PartialEq)]
enum World {
    #[default]
    AfterPix,
    AtTheEnd,
    BeforePix,
}

/// One mistake in the student's program.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Plant {
    None,
    /// The camera ray takes this object at this (negative) t: a root behind the ray.
    RootBehind(usize, f64),
    /// The normal is reversed (and so is cos θ).
    FlippedNormal,
    /// The light's distance squared, and the contribution divided by it.
    DistanceSquared,
    /// The shadow ray is not blocked where the reference's is: the blocker is a miss.
    NotBlocked,
    /// Ids from 1.
    IdsFrom1,
}

/// The course ids of the scene's records: one counter in file order, lights included.
fn course_ids(scene: &Scene, base: i64) -> (Vec<i64>, Vec<i64>) {
    let mut lines: Vec<usize> = scene.lights.iter().map(|l| l.line).collect();
    lines.extend(scene.objects.iter().map(|o| o.line));
    lines.sort_unstable();
    let id = |line: usize| base + lines.iter().position(|&l| l == line).unwrap() as i64;
    (
        scene.objects.iter().map(|o| id(o.line)).collect(),
        scene.lights.iter().map(|l| id(l.line)).collect(),
    )
}

/// What a student's program in `dialect`, with `plant`, prints for the traced pixel.
fn write(scene: &Scene, trace: &Trace, d: Dialect, plant: Plant) -> String {
    let base = match plant {
        Plant::IdsFrom1 => 1,
        _ if d.from_100 => 100,
        _ => 0,
    };
    let (objects, lights) = course_ids(scene, base);
    let one = |v: f64| match d.eleven {
        true => format!("{v:5.11}"),
        false => format!("{v:5.1}"),
    };
    let vector = |v: DVec3| match d.long_vectors {
        true => format!("{:.6} {:.6} {:.6}", v.x, v.y, v.z),
        false => format!("{:8.3} {:8.3} {:8.3}", v.x, v.y, v.z),
    };
    let colon = if d.no_colon { "" } else { ":" };
    let miss = || match d.nan_miss {
        true => "-nan".to_string(),
        false => one(-1.0),
    };
    let label = |out: &mut String, words: &str, value: String| match d.no_colon {
        true => {
            let _ = writeln!(out, "{words}\n{value}");
        }
        false => {
            let _ = writeln!(out, "{words:<24} :\t{value}");
        }
    };
    let (x, y) = trace.pixel;
    let mut out = String::new();
    if d.junk {
        out.push_str("window  8.0  6.0\nviewpoint 0.0 0.0 3.0\nrotmat:\n 1.0 0.0 0.0\n");
    }
    let world = format!("WRL ({}, {}) - ", one(trace.world.x), one(trace.world.y));
    if d.world == World::BeforePix {
        out.push_str(&world);
        out.push('\n');
    }
    match d.pix {
        Pix::XY => write!(out, "\nPIX {x:4} {y:4} - "),
        Pix::YX => write!(out, "\nPIX {y:4} {x:4} - "),
        Pix::RowCol => write!(out, "\nPIX:  ROW = {x} COL = {y} - "),
    }
    .unwrap();
    if d.world == World::AfterPix {
        out.push_str(&world);
    }
    out.push('\n');
    let mut ray = None;
    let mut in_shadow = false;
    let mut light = 0;
    let mut hit = (0, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO); // object, point, normal, diffuse
    let mut towards = (DVec3::ZERO, 0.0, 0.0);
    let mut extra = DVec3::ZERO; // what the planted mistake adds to the intensity
    let mut depth = 0;
    let geometry = |out: &mut String,
                    hit: (usize, DVec3, DVec3, DVec3),
                    light: usize,
                    towards: (DVec3, f64, f64)| {
        let (u, dist, cos) = towards;
        let (normal, cos) = match plant {
            Plant::FlippedNormal => (-hit.2, -cos),
            _ => (hit.2, cos),
        };
        let dist = if plant == Plant::DistanceSquared {
            dist * dist
        } else {
            dist
        };
        let u = if d.unnormalised { u * towards.1 } else { u };
        label(out, "hit object id was", objects[hit.0].to_string());
        label(out, "hit point was", vector(hit.1));
        label(out, "normal at hitpoint", vector(normal));
        label(out, "light object id was", lights[light].to_string());
        label(
            out,
            "light center was",
            vector(scene.lights[light].location),
        );
        label(out, "unit vector to light is", vector(u));
        label(out, "distance to light is", format!("{dist:8.3}"));
        label(out, "cos is", format!("{cos:8.3}"));
    };
    for event in &trace.events {
        match event {
            Event::Segment {
                depth: k, ray: r, ..
            } => {
                ray = Some(*r);
                depth = *k;
                extra = DVec3::ZERO;
            }
            Event::Tested { object, t, .. } if !in_shadow => {
                let r = ray.unwrap();
                let t = match plant {
                    Plant::RootBehind(o, behind) if o == *object && depth == 0 => Some(behind),
                    _ => *t,
                };
                let printed = t.map_or_else(miss, one);
                match d.three_line {
                    true => {
                        let at = t.map_or(DVec3::NAN, |t| r.base + t * r.dir);
                        let v = |v: DVec3| format!("X: {:.6} Y: {:.6} Z: {:.6}", v.x, v.y, v.z);
                        let _ = writeln!(out, "FND {:4}{colon} {printed} - ", objects[*object]);
                        let _ = writeln!(out, "base {}", v(r.base));
                        let _ = writeln!(out, "dir {}", v(r.dir));
                        let _ = writeln!(out, "hits: {}", v(at));
                    }
                    false => {
                        let _ = write!(out, "FND {:4}{colon} {printed} - ", objects[*object]);
                    }
                }
            }
            // A shadow ray's tests, in the units of the printed direction to the light.
            Event::Tested { object, t, .. } if d.shadow_fnd => {
                let scale = if d.unnormalised { towards.1 } else { 1.0 };
                let printed = t.map_or_else(miss, |t| format!("{:.4}", t / scale));
                let _ = writeln!(out, "FND {:4}{colon} {printed} - ", objects[*object]);
            }
            Event::Surface {
                object,
                t,
                surface,
                material,
                ..
            } => {
                if !d.three_line {
                    out.push('\n');
                }
                hit = (*object, surface.point, surface.normal, material.diffuse);
                let (object, t, p) = match plant {
                    Plant::RootBehind(o, behind) if depth == 0 => {
                        let r = ray.unwrap();
                        (o, behind, r.base + behind * r.dir)
                    }
                    _ => (*object, *t, surface.point),
                };
                let _ = writeln!(
                    out,
                    "HIT {:4}{colon} {} ({}, {}, {}) - ",
                    objects[object],
                    one(t),
                    one(p.x),
                    one(p.y),
                    one(p.z)
                );
                if d.junk {
                    out.push_str("byte:17\n");
                }
            }
            Event::Lamp { light: l } => light = *l,
            Event::Light(LightStep::Towards { u, dist, cos }) => {
                towards = (*u, *dist, *cos);
                if d.block_first {
                    geometry(&mut out, hit, light, towards);
                }
            }
            Event::Light(LightStep::ShadowRay { .. }) => in_shadow = true,
            Event::Light(LightStep::Blocked { blocker: b }) => {
                in_shadow = false;
                if let (Some((object, t)), false) = (b, plant == Plant::NotBlocked) {
                    let scale = if d.unnormalised { towards.1 } else { 1.0 };
                    label(
                        &mut out,
                        "hit object occluded by",
                        objects[*object].to_string(),
                    );
                    label(&mut out, "distance was", format!("{:8.3}", t / scale));
                }
            }
            Event::Lit {
                light: l,
                contribution,
                intensity,
            } => {
                let lamp = &scene.lights[*l];
                let (_, dist, cos) = towards;
                let unblocked = plant == Plant::NotBlocked
                    && *contribution == DVec3::ZERO
                    && cos > 0.0
                    && was_blocked(trace, *l, depth);
                if unblocked {
                    extra += hit.3 * lamp.emissivity * (cos / dist);
                }
                if plant == Plant::DistanceSquared {
                    extra += *contribution / dist - *contribution;
                }
                if *contribution != DVec3::ZERO || unblocked {
                    if !d.block_first {
                        geometry(&mut out, hit, light, towards);
                    }
                    label(&mut out, "Emissivity of the light", vector(lamp.emissivity));
                    label(&mut out, "Diffuse reflectivity", vector(hit.3));
                    label(&mut out, "Current ivec", vector(*intensity + extra));
                }
            }
            Event::Divided {
                seen, total_dist, ..
            } => {
                let s = *seen + extra / *total_dist;
                let _ = write!(out, "AMB ({}, {}, {}) - ", one(s.x), one(s.y), one(s.z));
                if d.junk {
                    out.push_str("\nrotmat 0.0 1.0 0.0");
                }
                out.push('\n');
            }
            _ => {}
        }
    }
    if d.world == World::AtTheEnd {
        out.push_str(&world);
        out.push('\n');
    }
    out
}

/// Whether light `l`'s shadow ray is blocked at the hit of segment `depth`.
fn was_blocked(trace: &Trace, l: usize, depth: usize) -> bool {
    let mut k = 0;
    let mut light = usize::MAX;
    for event in &trace.events {
        match event {
            Event::Segment { depth: d, .. } => k = *d,
            Event::Lamp { light: i } => light = *i,
            Event::Light(LightStep::Blocked { blocker: Some(_) }) if k == depth && light == l => {
                return true;
            }
            _ => {}
        }
    }
    false
}

/// What the student's program prints with `plant`.
fn write_planted(scene: &Scene, trace: &Trace, d: Dialect, plant: Plant) -> String {
    match plant {
        Plant::NotBlocked => write_not_blocked(scene, trace, d),
        _ => write(scene, trace, d, plant),
    }
}

/// The NotBlocked plant: the events are rewritten so that each blocked shadow ray's
/// blocker is tested as a miss (its FND line is printed before the verdict that names
/// it), and the writer prints the blocked light's block as lit.
fn write_not_blocked(scene: &Scene, trace: &Trace, d: Dialect) -> String {
    let mut events = trace.events.clone();
    let mut blockers = Vec::new();
    for (k, event) in events.iter().enumerate() {
        if let Event::Light(LightStep::Blocked {
            blocker: Some((object, _)),
        }) = event
        {
            // The blocker's Tested event is the last one before this.
            let tested = (0..k)
                .rev()
                .find(|&j| matches!(events[j], Event::Tested { object: o, .. } if o == *object))
                .unwrap();
            blockers.push(tested);
        }
    }
    for k in blockers {
        if let Event::Tested { t, .. } = &mut events[k] {
            *t = None;
        }
    }
    let planted = Trace {
        events,
        ..trace.clone()
    };
    write(scene, &planted, d, Plant::NotBlocked)
}

fn scene_path(name: &str) -> Option<PathBuf> {
    let dir = crate::common::course_scenes()?;
    Some(dir.join(name))
}

fn load(path: &Path) -> Scene {
    legacy_rt::load(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Runs `trace X Y W H --against` on `student` and returns the exit code and output.
fn against(
    scene: &Path,
    (x, y): (usize, usize),
    (w, h): (usize, usize),
    student: &str,
    json: bool,
) -> (i32, String, String) {
    let dir = folder(&format!("against-{:x}", fnv(student)));
    let file = dir.join("dbg.txt");
    std::fs::write(&file, student).unwrap();
    let (xs, ys, ws, hs) = (x.to_string(), y.to_string(), w.to_string(), h.to_string());
    let mut args = vec![
        "trace",
        &xs,
        &ys,
        &ws,
        &hs,
        "--against",
        file.to_str().unwrap(),
    ];
    if json {
        args.push("--json");
    }
    let output = run(&args, &std::fs::read(scene).unwrap());
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

fn fnv(text: &str) -> u64 {
    text.bytes().fold(0xcbf29ce484222325, |h, b| {
        (h ^ b as u64).wrapping_mul(0x100000001b3)
    })
}

/// The dialects the tests write: together every form of spec §8.
fn dialects() -> Vec<(&'static str, Dialect)> {
    vec![
        ("the course's own copy", Dialect::default()),
        (
            "no colons, %5.11f, ids from 100, WRL at the end, -nan misses",
            Dialect {
                no_colon: true,
                eleven: true,
                from_100: true,
                world: World::AtTheEnd,
                nan_miss: true,
                ..Dialect::default()
            },
        ),
        (
            "three-line FND, shadow rays' FND, unnormalised direction, %f vectors, other output",
            Dialect {
                three_line: true,
                shadow_fnd: true,
                unnormalised: true,
                long_vectors: true,
                junk: true,
                ..Dialect::default()
            },
        ),
        (
            "PIX y x, the light's geometry before the cos test, -nan misses",
            Dialect {
                pix: Pix::YX,
                block_first: true,
                nan_miss: true,
                ..Dialect::default()
            },
        ),
        (
            "PIX: ROW = COL =, ids from 100, shadow FND, unnormalised, geometry first",
            Dialect {
                pix: Pix::RowCol,
                from_100: true,
                shadow_fnd: true,
                unnormalised: true,
                block_first: true,
                ..Dialect::default()
            },
        ),
        (
            "WRL before PIX, no colons, other output",
            Dialect {
                world: World::BeforePix,
                no_colon: true,
                junk: true,
                ..Dialect::default()
            },
        ),
    ]
}

/// spec1's pixel (300, 200) at 640x480: the camera ray hits the red sphere (line 11),
/// light 1 lights it, lights 2-4 face away; its mirror ray hits the tiled plane (line 18),
/// where the blue sphere (line 4) blocks light 2.
const PIXEL: (usize, usize) = (300, 200);
const SIZE: (usize, usize) = (640, 480);

fn spec1() -> Option<(PathBuf, Scene, Trace)> {
    let path = scene_path("spec1.txt")?;
    let scene = load(&path);
    let trace = trace(&scene, &Options::new(SIZE.0, SIZE.1), PIXEL.0, PIXEL.1).unwrap();
    Some((path, scene, trace))
}

#[test]
fn a_correct_trace_agrees_in_every_format() {
    let Some((path, scene, trace)) = spec1() else {
        return;
    };
    for (name, dialect) in dialects() {
        let student = write(&scene, &trace, dialect, Plant::None);
        let (code, out, err) = against(&path, PIXEL, SIZE, &student, false);
        assert_eq!(code, 0, "{name}:\n{student}\n{out}{err}");
        assert!(out.contains("agrees with the reference"), "{name}: {out}");
    }
}

/// The first difference of `student`, as `--json` gives it.
fn first(path: &Path, student: &str) -> serde_json::Value {
    let (code, out, err) = against(path, PIXEL, SIZE, student, true);
    assert_eq!(code, 1, "{student}\n{out}{err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    json["first_difference"].clone()
}

#[test]
fn a_light_s_distance_squared_is_the_first_difference() {
    let Some((path, scene, trace)) = spec1() else {
        return;
    };
    for (name, dialect) in dialects() {
        let student = write(&scene, &trace, dialect, Plant::DistanceSquared);
        let diff = first(&path, &student);
        assert_eq!(diff["quantity"], "distance to the light", "{name}: {diff}");
        assert_eq!(diff["object"], "sphere (line 11)", "{name}: {diff}");
        let event = diff["event"].as_str().unwrap();
        assert!(
            event.starts_with("camera ray, light 1 (point light, line 42)"),
            "{name}: {diff}"
        );
        // The student's line holds the squared distance.
        let line = student
            .lines()
            .nth(diff["student_line"].as_u64().unwrap() as usize - 1)
            .unwrap();
        let squared = 7.17876f64 * 7.17876;
        assert!(
            line.contains("distance to light") || line.trim() == format!("{squared:8.3}").trim(),
            "{name}: {line}"
        );
    }
}

#[test]
fn a_flipped_normal_is_the_first_difference() {
    let Some((path, scene, trace)) = spec1() else {
        return;
    };
    for (name, dialect) in dialects().into_iter().filter(|(_, d)| d.block_first) {
        let student = write(&scene, &trace, dialect, Plant::FlippedNormal);
        let diff = first(&path, &student);
        assert_eq!(diff["quantity"], "normal", "{name}: {diff}");
        assert_eq!(diff["object"], "sphere (line 11)", "{name}: {diff}");
        assert!(
            diff["sentence"].as_str().unwrap().contains("flipped"),
            "{name}: {diff}"
        );
    }
}

#[test]
fn a_shadow_ray_not_blocked_is_the_first_difference() {
    let Some((path, scene, trace)) = spec1() else {
        return;
    };
    assert!(
        was_blocked(&trace, 1, 1),
        "the pixel's mirror hit is in light 2's shadow"
    );
    for (name, dialect) in dialects() {
        let student = write_planted(&scene, &trace, dialect, Plant::NotBlocked);
        let diff = first(&path, &student);
        assert_eq!(
            diff["event"], "shadow ray to light 2 (point light, line 46)",
            "{name}: {diff}"
        );
        assert_eq!(diff["object"], "sphere (line 4)", "{name}: {diff}");
        let sentence = diff["sentence"].as_str().unwrap();
        if dialect.shadow_fnd {
            assert_eq!(diff["quantity"], "hit or miss", "{name}: {diff}");
            assert!(
                sentence.contains("yours misses") && sentence.contains("blocks the light"),
                "{name}: {diff}"
            );
        } else {
            assert_eq!(diff["quantity"], "occluded by", "{name}: {diff}");
            assert!(
                sentence.contains("blocked by sphere (line 4)"),
                "{name}: {diff}"
            );
        }
    }
}

#[test]
fn ids_from_1_are_read_as_the_file_numbers_them() {
    let Some((path, scene, trace)) = spec1() else {
        return;
    };
    for (name, dialect) in dialects().into_iter().filter(|(_, d)| !d.from_100) {
        let student = write(&scene, &trace, dialect, Plant::IdsFrom1);
        let (code, out, err) = against(&path, PIXEL, SIZE, &student, false);
        assert_eq!(code, 0, "{name}: {out}{err}");
        assert!(out.contains("note: ids from 1,"), "{name}: {out}");
    }
}

/// A scene with a sphere in front of the eye and one behind it: the camera ray's line
/// meets the one behind at negative t.
const BEHIND: &str = "8 6           world\n0 0 3         viewpoint\n\n\
13            sphere in front\n1 1 1  ambient\n2 2 2  diffuse\n0 0 0  specular\n0 0 -3  centre\n1  radius\n\n\
13            sphere behind the eye\n2 2 2  ambient\n2 2 2  diffuse\n0 0 0  specular\n0 0 6  centre\n1  radius\n\n\
10            light\n5 5 5  emissivity\n0 4 2  centre\n";

#[test]
fn a_root_behind_the_ray_taken_is_the_first_difference() {
    let dir = folder("against-behind");
    let path = dir.join("behind.txt");
    std::fs::write(&path, BEHIND).unwrap();
    let scene = legacy_rt::load(BEHIND).unwrap();
    let pixel = (40, 30);
    let size = (80, 60);
    let trace = trace(&scene, &Options::new(size.0, size.1), pixel.0, pixel.1).unwrap();
    // The roots of |base + t dir - c|² = r² for the sphere behind, from the camera ray.
    let Event::Segment { ray, .. } = trace.events[0] else {
        panic!()
    };
    let oc = ray.base - DVec3::new(0.0, 0.0, 6.0);
    let (b, c) = (oc.dot(ray.dir), oc.dot(oc) - 1.0);
    let disc = b * b - c;
    assert!(disc > 0.0, "the camera ray's line meets the sphere behind");
    let nearer = -b + disc.sqrt(); // the root nearer to the eye, behind it
    assert!(nearer < 0.0);
    for (name, dialect) in dialects() {
        let clean = write(&scene, &trace, dialect, Plant::None);
        let (code, out, err) = against(&path, pixel, size, &clean, false);
        assert_eq!(code, 0, "{name}: {out}{err}");
        let student = write(&scene, &trace, dialect, Plant::RootBehind(1, nearer));
        let (code, out, err) = against(&path, pixel, size, &student, true);
        assert_eq!(code, 1, "{name}: {student}\n{out}{err}");
        let json: serde_json::Value = serde_json::from_str(&out).unwrap();
        let diff = &json["first_difference"];
        assert_eq!(diff["quantity"], "closest object", "{name}: {diff}");
        assert_eq!(diff["object"], "sphere (line 11)", "{name}: {diff}");
        assert!(
            diff["sentence"].as_str().unwrap().contains("root behind"),
            "{name}: {diff}"
        );
    }
}

#[test]
fn the_text_report_names_the_line_and_shows_the_reference_around_it() {
    let Some((path, scene, trace)) = spec1() else {
        return;
    };
    let student = write(&scene, &trace, Dialect::default(), Plant::DistanceSquared);
    let (code, out, _) = against(&path, PIXEL, SIZE, &student, false);
    assert_eq!(code, 1);
    let first = out.lines().next().unwrap();
    assert!(
        first.starts_with("first difference: camera ray, light 1 (point light, line 42), sphere (line 11): your distance to the light is 51.535"),
        "{out}"
    );
    assert!(out.contains("the reference's trace around it"), "{out}");
    assert!(
        out.contains("> ") && out.contains("distance 7.178760"),
        "{out}"
    );
    assert!(out.contains("more differ"), "{out}");
}

/// A whole image's trace: every pixel of a 40x30 render, a few thousand lines.
fn whole_image(
    scene: &Scene,
    size: (usize, usize),
    d: Dialect,
    planted: (usize, usize),
    plant: Plant,
) -> String {
    let options = Options::new(size.0, size.1);
    let mut out = String::new();
    for y in 0..size.1 {
        for x in 0..size.0 {
            let trace = trace(scene, &options, x, y).unwrap();
            let plant = if (x, y) == planted {
                plant
            } else {
                Plant::None
            };
            out.push_str(&write(scene, &trace, d, plant));
        }
    }
    out
}

#[test]
fn a_whole_image_s_trace_finds_the_pixel() {
    let Some(path) = scene_path("spec1.txt") else {
        return;
    };
    let scene = load(&path);
    let size = (40, 30);
    let pixel = (19, 12);
    for (name, dialect) in [dialects()[0], dialects()[3]] {
        let clean = whole_image(&scene, size, dialect, pixel, Plant::None);
        assert!(clean.lines().count() > 2000, "{}", clean.lines().count());
        let planted = whole_image(&scene, size, dialect, pixel, Plant::DistanceSquared);
        assert_ne!(clean, planted, "the pixel has a lit light to plant in");
        let (code, out, err) = against(&path, pixel, size, &clean, false);
        assert_eq!(code, 0, "{name}: {out}{err}");
        let (code, out, err) = against(&path, pixel, size, &planted, true);
        assert_eq!(code, 1, "{name}: {out}{err}");
        let json: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(
            json["first_difference"]["quantity"], "distance to the light",
            "{name}"
        );
        // Its neighbours agree: the planted pixel is found, not another.
        let (code, _, err) = against(&path, (pixel.0 + 1, pixel.1), size, &planted, false);
        assert_eq!(code, 0, "{name}: {err}");
    }
}

#[test]
fn another_pixel_or_another_scene_is_exit_2() {
    let Some((path, scene, trace)) = spec1() else {
        return;
    };
    let student = write(&scene, &trace, Dialect::default(), Plant::None);
    // Another pixel.
    let (code, out, err) = against(&path, (10, 10), SIZE, &student, false);
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains("no trace of pixel (10, 10)") && err.contains("its one pixel is (300, 200)"),
        "{err}"
    );
    // Another scene at the same pixel and size: d04 has other objects and lights.
    let other = scene_path("d04.txt").unwrap();
    let (code, out, err) = against(&other, PIXEL, SIZE, &student, false);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.contains("another scene"), "{err}");
    // Another size: the world point differs.
    let (code, out, err) = against(&path, PIXEL, (800, 600), &student, false);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.contains("another image size"), "{err}");
    // No trace at all, and a file that cannot be read.
    let (code, _, err) = against(&path, PIXEL, SIZE, "hello\nworld\n", false);
    assert_eq!(code, 2);
    assert!(
        err.contains("no trace of pixel") || err.contains("no line"),
        "{err}"
    );
    let output = run(
        &[
            "trace",
            "300",
            "200",
            "640",
            "480",
            "--against",
            "/nonexistent/dbg.txt",
        ],
        &std::fs::read(&path).unwrap(),
    );
    assert_eq!(output.status.code(), Some(2));
    // A named pipe with no writer is refused at once, not waited on; binary garbage is
    // no trace.
    let dir = crate::common::folder("against-untrusted");
    let fifo = dir.join("dbg.txt");
    let name = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: mkfifo reads the NUL-terminated path and creates a FIFO; nothing else.
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o644) }, 0);
    let scene = std::fs::read(&path).unwrap();
    let output = run(
        &[
            "trace",
            "300",
            "200",
            "640",
            "480",
            "--against",
            fifo.to_str().unwrap(),
        ],
        &scene,
    );
    assert_eq!(output.status.code(), Some(2));
    let garbage: Vec<u8> = (0..=255u8).cycle().take(1 << 16).collect();
    std::fs::write(dir.join("garbage.txt"), garbage).unwrap();
    let garbage = dir.join("garbage.txt");
    let output = run(
        &[
            "trace",
            "300",
            "200",
            "640",
            "480",
            "--against",
            garbage.to_str().unwrap(),
        ],
        &scene,
    );
    assert_eq!(output.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}
