//! `legacy-rt trace X Y`: everything the renderer computes for one pixel, in order, in
//! two formats: readable, and the course's debug lines.
//!
//! The trace is not a second tracer. The renderer's own functions take a recorder
//! (`src/render/record.rs`): a plain render's is `()`, which compiles every recording
//! call away; [`trace`] passes a `Vec<Event>`, which collects what the same code computes
//! (every object tested in file order, with the shape's reasons). The formats below only
//! print those events.

use super::record::{Event, LightStep, Skip};
use super::tracer::Tracer;
use super::variant::Rules;
use super::{EveryObject, Options, Plain, Setup};
use crate::render::shading::PatternNote;
use crate::scene::Scene;
use crate::scene::dump::number;
use crate::shapes::kernel::with_kernel;
use crate::shapes::{HitNote, Verdict};
use glam::DVec3;
use std::fmt::Write;

/// Everything the renderer computed for one pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// The pixel, (0, 0) at the lower left.
    pub pixel: (usize, usize),
    /// The pixel's world point (spec §4.1).
    pub world: DVec3,
    /// The options rendered with.
    pub options: Options,
    /// What was computed, in order.
    pub events: Vec<Event>,
    /// The final colour, before clamping.
    pub colour: DVec3,
    /// The pixel's bytes.
    pub bytes: [u8; 3],
}

/// The trace of pixel (x, y) under `options`, or `None` if it lies outside the image.
/// Every object is tested in file order, as the course program did (the tiles and the
/// hierarchy change which objects are tested, never the bytes).
pub fn trace(scene: &Scene, options: &Options, x: usize, y: usize) -> Option<Trace> {
    tracing(scene, options, |frame| frame.trace(x, y))
}

/// A scene prepared once under `options` for the traces of many pixels (a student's
/// whole debug trace is read against one per block), lent to `body`.
pub fn tracing<T>(scene: &Scene, options: &Options, body: impl FnOnce(&Tracing<'_>) -> T) -> T {
    let setup = Setup::new(scene, options);
    // No tiles: a trace tests every object in file order whatever a render's lists hold.
    let tracer = Tracer::new(&setup.scene, &setup.rules, options, &setup.camera, None);
    body(&Tracing {
        setup: &setup,
        tracer,
        options: *options,
    })
}

/// A scene prepared for traces ([`tracing`]): each pixel's, or the camera ray's through
/// any point of the screen.
pub struct Tracing<'a> {
    setup: &'a Setup<'a>,
    tracer: Tracer<'a, &'a Rules>,
    options: Options,
}

impl Tracing<'_> {
    /// The options traced with.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// The world point of pixel (x, y) (spec §4.1, or §7.3's pixel-centre), (0, 0) at
    /// the lower left; x and y below the width and height.
    pub fn world(&self, x: usize, y: usize) -> DVec3 {
        self.setup.camera.world(x, y)
    }

    /// The bytes a colour is written as (spec §4.7, or a byte variant's rule).
    pub fn bytes(&self, colour: DVec3) -> [u8; 3] {
        self.setup.rules.bytes(colour)
    }

    /// The trace of pixel (x, y), or `None` if it lies outside the image.
    pub fn trace(&self, x: usize, y: usize) -> Option<Trace> {
        if x >= self.options.width || y >= self.options.height {
            return None;
        }
        Some(self.through((x, y), self.world(x, y)))
    }

    /// The bytes the camera ray through the point `world` of the screen (z = 0) gives,
    /// traced without recording: what a tracer that samples elsewhere in a pixel sees.
    pub fn bytes_through(&self, world: DVec3) -> [u8; 3] {
        let colour = match self.setup.camera.ray_through(world) {
            Some(ray) => {
                with_kernel!(self.options.kernel, K => self.tracer.through::<K>(ray, Plain, &mut ()))
            }
            None => DVec3::ZERO,
        };
        self.bytes(colour)
    }

    /// The trace of the camera ray through the point `world` of the screen (z = 0), named
    /// as pixel `pixel`'s: a program's ray through a point that is not its pixel's (a
    /// row off, jittered) followed as the reference follows its own.
    pub fn through(&self, pixel: (usize, usize), world: DVec3) -> Trace {
        let mut events = Vec::new();
        let kernel = self.options.kernel;
        let colour = match self.setup.camera.ray_through(world) {
            Some(ray) => {
                with_kernel!(kernel, K => self.tracer.through::<K>(ray, EveryObject, &mut events))
            }
            None => DVec3::ZERO,
        };
        Trace {
            pixel,
            world,
            options: self.options,
            events,
            colour,
            bytes: self.bytes(colour),
        }
    }
}

/// A vector with the trace's fixed decimals.
fn vector(v: DVec3) -> String {
    format!("({}, {}, {})", number(v.x), number(v.y), number(v.z))
}

/// How an object is named in the readable trace: its kind and the line of its type code.
pub(crate) fn object_name(scene: &Scene, index: usize) -> String {
    let object = &scene.objects[index];
    format!("{} (line {})", object.kind(), object.line)
}

/// How a light is named: its number (from 1), kind and line.
pub(crate) fn light_name(scene: &Scene, index: usize) -> String {
    let light = &scene.lights[index];
    let kind = if light.beam.is_some() {
        "spotlight"
    } else {
        "point light"
    };
    format!("light {} ({kind}, line {})", index + 1, light.line)
}

/// What a root or a plane's t came to, in words.
fn verdict_words(verdict: Verdict) -> &'static str {
    match verdict {
        Verdict::Counts => "counts",
        Verdict::Behind => "behind the ray's base",
        Verdict::OutOfBounds => "out of bounds",
        Verdict::BeyondScreen => "behind the screen (z > 0)",
    }
}

/// Why a test came to what it did, in words.
fn reasons(notes: &[HitNote]) -> String {
    let reason = |note: &HitNote| match *note {
        HitNote::Discriminant { .. } => String::new(),
        HitNote::NoRealRoot => "no real root".to_string(),
        HitNote::Parallel => "parallel to the plane (N·D = 0)".to_string(),
        HitNote::Nearer { t: Some(t) } => format!("nearer root t = {}", number(t)),
        HitNote::Nearer { t: None } => "nearer root not a number".to_string(),
        HitNote::Root { t, y, verdict } => {
            let what = verdict_words(verdict);
            format!("root t = {}, local y {}: {what}", number(t), number(y))
        }
        HitNote::QuadricRoot { t, verdict } => {
            format!("root t = {}: {}", number(t), verdict_words(verdict))
        }
        HitNote::Plane { t, z, verdict } => {
            let what = verdict_words(verdict);
            format!("t = {}, z = {}: {what}", number(t), number(z))
        }
        HitNote::Rectangle { q, inside } => {
            let what = if inside {
                "inside the rectangle"
            } else {
                "outside the rectangle"
            };
            format!("q = ({}, {}): {what}", number(q.x), number(q.y))
        }
    };
    // How close a ray came to touching is for `compare`, not for the trace.
    let told = notes
        .iter()
        .filter(|note| !matches!(note, HitNote::Discriminant { .. }));
    told.map(reason).collect::<Vec<_>>().join("; ")
}

/// What chose the material, in words.
fn pattern_words(pattern: &PatternNote) -> String {
    match *pattern {
        PatternNote::Plain => "the object's material".to_string(),
        PatternNote::Tile {
            relx,
            rely,
            foreground,
        } => {
            let which = if foreground {
                "odd: foreground (first material)"
            } else {
                "even: background (second material)"
            };
            format!("tile relx {relx}, rely {rely}, sum {which}")
        }
        PatternNote::Texel { col, row, value } => {
            format!(
                "texel column {col}, row {row} from the bottom, value {}",
                vector(value)
            )
        }
        PatternNote::Shader { shader, value } => match shader {
            crate::scene::Shader::Stripes => format!("stripes shader, s = {value}"),
            crate::scene::Shader::ColourWheel => {
                format!("colour wheel shader, angle {} rad", number(value))
            }
        },
    }
}

impl Trace {
    /// The readable trace: an indented tree in the renderer's order, every number with
    /// six decimals, and as its last line `bytes: R G B`.
    pub fn readable(&self, scene: &Scene) -> String {
        self.readable_with_starts(scene).0
    }

    /// The readable trace, and for each event the number of the line (from 0) where its
    /// lines start.
    pub fn readable_with_starts(&self, scene: &Scene) -> (String, Vec<usize>) {
        let mut out = String::new();
        let mut starts = Vec::with_capacity(self.events.len());
        let mut lines = 2; // the pixel and the world point
        let (x, y) = self.pixel;
        let (w, h) = (self.options.width, self.options.height);
        let mut stage = match self.options.show {
            Some(show) => format!("--show {}", show.name()),
            None => format!("stage {}", self.options.stage.name()),
        };
        let mut variants: Vec<_> = self.options.variants.iter().collect();
        variants.sort_by_key(|v| (v.kind, v.line));
        if !variants.is_empty() {
            let ids: Vec<_> = variants.iter().map(|v| v.id()).collect();
            let _ = write!(stage, "; as if with --variant {}", ids.join(","));
        }
        let _ = writeln!(
            out,
            "pixel ({x}, {y}) of {w}x{h}, (0, 0) at the lower left; {stage}"
        );
        let _ = writeln!(out, "world point {}", vector(self.world));
        // Tests of a shadow ray sit one level deeper than those of a segment.
        let mut in_shadow_ray = false;
        for event in &self.events {
            match event {
                Event::Light(LightStep::ShadowRay { .. }) => in_shadow_ray = true,
                Event::Light(LightStep::Blocked { .. }) => in_shadow_ray = false,
                _ => {}
            }
            let indent = if in_shadow_ray { "      " } else { "  " };
            starts.push(lines);
            let before = out.len();
            self.readable_event(scene, event, indent, &mut out);
            lines += out[before..].bytes().filter(|&b| b == b'\n').count();
        }
        let _ = writeln!(out, "colour {}", vector(self.colour));
        let [r, g, b] = self.bytes;
        let _ = writeln!(out, "bytes: {r} {g} {b}");
        (out, starts)
    }

    fn readable_event(&self, scene: &Scene, event: &Event, indent: &str, out: &mut String) {
        let mut line = |text: String| {
            let _ = writeln!(out, "{text}");
        };
        match event {
            Event::Segment {
                depth,
                ray,
                total_dist,
            } => {
                let what = if *depth == 0 {
                    "camera ray".to_string()
                } else {
                    format!("reflected ray {depth}")
                };
                line(format!(
                    "{what} from {} along {}, path so far {}",
                    vector(ray.base),
                    vector(ray.dir),
                    number(*total_dist)
                ));
            }
            Event::CutOff { total_dist } => line(format!(
                "  path {} > MAX_DIST {}: black from here",
                number(*total_dist),
                number(self.options.max_dist)
            )),
            Event::Skipped { object, reason } => {
                let why = match reason {
                    Skip::Leaves => "skipped, the ray leaves it",
                    Skip::Variant => "skipped by the variant",
                };
                line(format!("{indent}{}: {why}", object_name(scene, *object)));
            }
            Event::Tested { object, t, notes } => {
                let verdict = match t {
                    Some(t) => format!("hit at t = {}", number(*t)),
                    None => "miss".to_string(),
                };
                line(format!(
                    "{indent}{}: {verdict} ({})",
                    object_name(scene, *object),
                    reasons(notes)
                ));
            }
            Event::Closest { hit } => match hit {
                Some((object, t)) => line(format!(
                    "  closest: {} at t = {}",
                    object_name(scene, *object),
                    number(*t)
                )),
                None => line("  closest: nothing: black".to_string()),
            },
            Event::Surface {
                object,
                t: _,
                total_dist,
                surface,
                material,
                pattern,
            } => {
                line(format!(
                    "  hit point {}, normal {}, path {}",
                    vector(surface.point),
                    vector(surface.normal),
                    number(*total_dist)
                ));
                // The quadrics 21-24 in their own frame, where the bounds are tested.
                if let Some(frame) = scene.objects[*object].shape.axis_frame() {
                    let local = frame.point_to_local(surface.point);
                    line(format!(
                        "  local hit point {} (rotmat (H - C))",
                        vector(local)
                    ));
                }
                line(format!("  material: {}", pattern_words(pattern)));
                line(format!(
                    "    ambient {}, diffuse {}, specular {}",
                    vector(material.ambient),
                    vector(material.diffuse),
                    vector(material.specular)
                ));
            }
            Event::Lamp { light } => line(format!("  {}:", light_name(scene, *light))),
            Event::Light(step) => match *step {
                LightStep::NoDiffuse => line("    diffuse is zero: nothing to add".into()),
                LightStep::Off => line("    off under the variant: nothing to add".into()),
                LightStep::NoDirection { dist } => line(format!(
                    "    distance {}: no direction, nothing to add",
                    number(dist)
                )),
                LightStep::Towards { u, dist, cos } => {
                    let facing = if cos > 0.0 {
                        ""
                    } else {
                        ": faces away, nothing to add"
                    };
                    line(format!(
                        "    unit vector to the light {}, distance {}, cos θ {}{facing}",
                        vector(u),
                        number(dist),
                        number(cos)
                    ));
                }
                LightStep::Spot { along, lit } => {
                    let verdict = if lit {
                        "inside the beam"
                    } else {
                        "outside the beam: nothing to add"
                    };
                    line(format!(
                        "    spotlight: cos to the beam {}, {verdict}",
                        number(along)
                    ));
                }
                LightStep::ShadowRay { ray } => line(format!(
                    "    shadow ray from {} along {}:",
                    vector(ray.base),
                    vector(ray.dir)
                )),
                LightStep::Blocked { blocker } => match blocker {
                    Some((object, t)) => line(format!(
                        "    blocked by {} at t = {}: nothing to add",
                        object_name(scene, object),
                        number(t)
                    )),
                    None => line("    not blocked".into()),
                },
            },
            Event::Lit {
                light: _,
                contribution,
                intensity,
            } => line(format!(
                "    contribution diffuse × emissivity × cos θ / distance = {}; intensity {}",
                vector(*contribution),
                vector(*intensity)
            )),
            Event::Divided {
                intensity,
                total_dist,
                seen,
                weight,
                colour,
            } => {
                line(format!(
                    "  intensity {} / path {} = {}",
                    vector(*intensity),
                    number(*total_dist),
                    vector(*seen)
                ));
                line(format!(
                    "  colour += weight {} × that = {}",
                    vector(*weight),
                    vector(*colour)
                ));
            }
            Event::Shown { show, colour } => line(format!(
                "  --show {}: colour {}",
                show.name(),
                vector(*colour)
            )),
        }
    }

    /// The trace as the course's `-DDBG_PIX -DDBG_WRL -DDBG_FND -DDBG_HIT -DDBG_AMB` and
    /// diffuse debug output printed it (`%4d`, `%5.1lf`, `%8.3f`), with the course's
    /// object ids: one counter over lights and objects in file order, from 0 (spec §7.1);
    /// then, as every trace ends, `bytes: R G B`.
    pub fn course(&self, scene: &Scene) -> String {
        let ids = CourseIds::new(scene);
        let mut out = String::new();
        let (x, y) = self.pixel;
        let _ = write!(out, "PIX {x:4} {y:4} - ");
        let _ = write!(out, "WRL ({:5.1}, {:5.1}) - ", self.world.x, self.world.y);
        let v3 = |v: DVec3| format!("{:8.3} {:8.3} {:8.3}", v.x, v.y, v.z);
        let mut hit_object = None;
        let mut point = DVec3::ZERO;
        let mut normal = DVec3::ZERO;
        let mut diffuse = DVec3::ZERO;
        let mut light = 0;
        let mut in_shadow_ray = false;
        for event in &self.events {
            match event {
                Event::Light(LightStep::ShadowRay { .. }) => in_shadow_ray = true,
                Event::Light(LightStep::Blocked { blocker }) => {
                    in_shadow_ray = false;
                    if let Some((object, t)) = blocker {
                        let _ = writeln!(out, "hit object occluded by {}", ids.object(*object));
                        let _ = writeln!(out, "distance was {:8.3}", t);
                    }
                }
                Event::Tested { object, t, .. } if !in_shadow_ray => {
                    let _ = write!(
                        out,
                        "FND {:4}: {:5.1} - ",
                        ids.object(*object),
                        t.unwrap_or(-1.0)
                    );
                }
                Event::Closest {
                    hit: Some((object, _)),
                } => hit_object = Some(*object),
                Event::Surface {
                    object,
                    t,
                    surface,
                    material,
                    ..
                } => {
                    point = surface.point;
                    normal = surface.normal;
                    diffuse = material.diffuse;
                    let p = surface.point;
                    let _ = writeln!(
                        out,
                        "HIT {:4}: {:5.1} ({:5.1}, {:5.1}, {:5.1}) - ",
                        ids.object(*object),
                        t,
                        p.x,
                        p.y,
                        p.z
                    );
                }
                Event::Lamp { light: index } => light = *index,
                Event::Light(LightStep::Towards { u, dist, cos }) => {
                    let object = hit_object.map_or(0, |o| ids.object(o));
                    let lamp = &scene.lights[light];
                    let _ = writeln!(out, "hit object id was {object}");
                    let _ = writeln!(out, "hit point was {}", v3(point));
                    let _ = writeln!(out, "normal at hitpoint {}", v3(normal));
                    let _ = writeln!(out, "light object id was {}", ids.light(light));
                    let _ = writeln!(out, "light center was {}", v3(lamp.location));
                    let _ = writeln!(out, "unit vector to light is {}", v3(*u));
                    let _ = writeln!(out, "distance to light is {:8.3}", dist);
                    let _ = writeln!(out, "cos is {:8.3}", cos);
                }
                Event::Lit {
                    light: index,
                    contribution,
                    intensity,
                } if *contribution != DVec3::ZERO => {
                    let lamp = &scene.lights[*index];
                    let _ = writeln!(out, "emissivity of the light {}", v3(lamp.emissivity));
                    let _ = writeln!(out, "diffuse reflectivity {}", v3(diffuse));
                    let _ = writeln!(out, "current ivec {}", v3(*intensity));
                }
                Event::Divided { seen, .. } => {
                    let _ = write!(
                        out,
                        "AMB ({:5.1}, {:5.1}, {:5.1}) - ",
                        seen.x, seen.y, seen.z
                    );
                }
                _ => {}
            }
        }
        out.push('\n');
        // Not a line the course printed: the bytes that every trace ends with, so that
        // both formats end on the pixel's bytes in the image.
        let [r, g, b] = self.bytes;
        let _ = writeln!(out, "bytes: {r} {g} {b}");
        out
    }
}

/// The course's object ids: one counter over every record, lights and objects alike, in
/// file order, from 0 (spec §7.1).
pub struct CourseIds {
    lights: Vec<usize>,
    objects: Vec<usize>,
}

impl CourseIds {
    /// The ids of `scene`'s records.
    pub fn new(scene: &Scene) -> CourseIds {
        let mut lines: Vec<usize> = scene.lights.iter().map(|l| l.line).collect();
        lines.extend(scene.objects.iter().map(|o| o.line));
        lines.sort_unstable();
        let id = |line: usize| lines.partition_point(|&l| l < line);
        CourseIds {
            lights: scene.lights.iter().map(|l| id(l.line)).collect(),
            objects: scene.objects.iter().map(|o| id(o.line)).collect(),
        }
    }

    /// The id of object `index`.
    pub fn object(&self, index: usize) -> usize {
        self.objects[index]
    }

    /// The id of light `index`.
    pub fn light(&self, index: usize) -> usize {
        self.lights[index]
    }
}
