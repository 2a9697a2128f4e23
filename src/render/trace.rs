//! `legacy-rt trace X Y`: everything the renderer computes for one pixel, in order, and
//! the stages and diagnostic images of spec §7.2.
//!
//! The trace is not a second tracer. The renderer's own functions take a [`Recorder`]:
//! for a normal render it is `()`, whose `record` does nothing and whose `ENABLED` is
//! false, so every recording call compiles away; `trace` passes a `Vec<Event>`, which
//! collects what the same code computes. The formats below only print those events.

use super::variant::Rules;
use super::{Camera, Options, Stats, Tracer, WithTracer, dispatch};
use crate::render::shading::PatternNote;
use crate::scene::dump::number;
use crate::scene::{Material, Scene};
use crate::shapes::kernel::Kernel;
use crate::shapes::{HitNote, Ray, Surface, Verdict};
use glam::DVec3;
use std::fmt::Write;

/// How much of spec §4 applies: the course's assignments, in the order it taught them
/// (spec §7.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stage {
    /// §4.2 without the lights (step 5) and the reflection (step 7).
    Ambient,
    /// Ambient and every light's §4.3 contribution, without the shadow test.
    Diffuse,
    /// Ambient and diffuse with the shadow test; no reflection.
    Shadows,
    /// §4 as written.
    #[default]
    Full,
}

impl Stage {
    /// Every stage, in the course's order.
    pub const ALL: [Stage; 4] = [Stage::Ambient, Stage::Diffuse, Stage::Shadows, Stage::Full];

    /// The name `--stage` takes.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Ambient => "ambient",
            Stage::Diffuse => "diffuse",
            Stage::Shadows => "shadows",
            Stage::Full => "full",
        }
    }

    /// Whether the lights' diffuse terms are added.
    #[inline(always)]
    pub fn lights(self) -> bool {
        self != Stage::Ambient
    }

    /// Whether a shadow ray can block a light.
    #[inline(always)]
    pub fn shadows(self) -> bool {
        matches!(self, Stage::Shadows | Stage::Full)
    }

    /// Whether mirrors reflect.
    #[inline(always)]
    pub fn reflects(self) -> bool {
        self == Stage::Full
    }
}

/// A diagnostic image instead of the stage's: what a student reaches for when stuck.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Show {
    /// The unit normal at the first hit as a colour, (N + 1) / 2.
    Normals,
    /// Each object in its own colour ([`super::object_colour`]).
    Objects,
    /// Grey 1 - t / MAX_DIST for the distance t to the first hit.
    Depth,
}

impl Show {
    /// Every diagnostic image.
    pub const ALL: [Show; 3] = [Show::Normals, Show::Objects, Show::Depth];

    /// The name `--show` takes.
    pub fn name(self) -> &'static str {
        match self {
            Show::Normals => "normals",
            Show::Objects => "objects",
            Show::Depth => "depth",
        }
    }
}

/// Where the renderer tells what it computes.
pub trait Recorder {
    /// Whether events are wanted.
    const ENABLED: bool;

    /// Whether every object's test is wanted, with the shape's reasons: the objects are
    /// then tested one by one in file order, as the course program did. When false the
    /// renderer takes the hierarchy and the kernel's compiled entry (the same numbers).
    const EVERY_TEST: bool = Self::ENABLED;

    /// Takes one event; `event` is called only by a recorder that keeps it.
    fn record(&mut self, event: impl FnOnce() -> Event);
}

impl Recorder for () {
    const ENABLED: bool = false;

    #[inline(always)]
    fn record(&mut self, _: impl FnOnce() -> Event) {}
}

impl Recorder for Vec<Event> {
    const ENABLED: bool = true;

    fn record(&mut self, event: impl FnOnce() -> Event) {
        self.push(event());
    }
}

/// One thing the renderer computed, in the order it did.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// A ray of the path starts: the camera ray (depth 0) or a reflected one.
    Segment {
        /// 0 for the camera ray, k for the k-th reflection.
        depth: usize,
        /// The ray.
        ray: Ray,
        /// The path's length so far.
        total_dist: f64,
    },
    /// The path is longer than MAX_DIST: black from here (spec §4.2 step 1).
    CutOff {
        /// The path's length.
        total_dist: f64,
    },
    /// An object not tested because the ray leaves it (`last_hit`).
    Skipped {
        /// Its index among the scene's objects.
        object: usize,
    },
    /// An object tested: its t (`None`: no hit) and its shape's reasons.
    Tested {
        /// Its index.
        object: usize,
        /// The hit distance, if any.
        t: Option<f64>,
        /// Why.
        notes: Vec<HitNote>,
    },
    /// The closest hit (spec §4.6), if any.
    Closest {
        /// Object and t.
        hit: Option<(usize, f64)>,
    },
    /// The hit's point, normal and material.
    Surface {
        /// The object.
        object: usize,
        /// The distance from the segment's base.
        t: f64,
        /// The path's length including this segment.
        total_dist: f64,
        /// Point, normal, plane coordinates.
        surface: Surface,
        /// The material there.
        material: Material,
        /// What chose it.
        pattern: PatternNote,
    },
    /// A light's term starts.
    Lamp {
        /// The light's index.
        light: usize,
    },
    /// A step of one light's term (spec §4.3).
    Light(LightStep),
    /// A light's term is added.
    Lit {
        /// The light's index.
        light: usize,
        /// Its contribution.
        contribution: DVec3,
        /// The intensity with it.
        intensity: DVec3,
    },
    /// The division by the path's length and the addition to the colour (spec §4.2).
    Divided {
        /// Ambient plus the lights.
        intensity: DVec3,
        /// The path's length.
        total_dist: f64,
        /// intensity / total_dist.
        seen: DVec3,
        /// The product of the mirrors' specular triples so far.
        weight: DVec3,
        /// The colour so far.
        colour: DVec3,
    },
    /// A diagnostic image's colour.
    Shown {
        /// Which image.
        show: Show,
        /// Its colour.
        colour: DVec3,
    },
}

/// A step of one light's diffuse term.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightStep {
    /// The material's diffuse triple is zero: nothing to add.
    NoDiffuse,
    /// The light sits at the point (or infinitely far): no direction.
    NoDirection {
        /// |L|.
        dist: f64,
    },
    /// The unit vector to the light, the distance and cos θ = N·u.
    Towards {
        /// u.
        u: DVec3,
        /// |L|.
        dist: f64,
        /// N·u.
        cos: f64,
    },
    /// A spotlight's test: the cosine between the beam and the direction to the point.
    Spot {
        /// unit(hit - light)·beam.
        along: f64,
        /// along > cos(half-angle).
        lit: bool,
    },
    /// The shadow ray's start.
    ShadowRay {
        /// The ray from the hit point toward the light.
        ray: Ray,
    },
    /// What blocked the light, if anything (object, t).
    Blocked {
        /// The first object closer than the light.
        blocker: Option<(usize, f64)>,
    },
}

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
/// Every object is tested in file order, as the course program did (the hierarchy
/// changes which objects are tested, never the bytes).
pub fn trace(scene: &Scene, options: &Options, x: usize, y: usize) -> Option<Trace> {
    if x >= options.width || y >= options.height {
        return None;
    }
    struct Job<'a>(&'a Scene, &'a Options, usize, usize);
    impl WithTracer for Job<'_> {
        type Output = Trace;
        fn run<K: Kernel, V: Rules>(self) -> Trace {
            let Job(scene, options, x, y) = self;
            let scene = options.deviations.scene(scene);
            let camera = Camera::new(&scene, options);
            let tracer = Tracer::<K, V>::new(&scene, options);
            let mut events = Vec::new();
            let colour = match camera.ray(x, y) {
                Some(ray) => {
                    tracer.pixel(ray, None, options.show, &mut Stats::default(), &mut events)
                }
                None => DVec3::ZERO,
            };
            Trace {
                pixel: (x, y),
                world: camera.world(x, y),
                options: *options,
                events,
                colour,
                bytes: tracer.bytes(colour),
            }
        }
    }
    Some(dispatch(options, Job(scene, options, x, y)))
}

/// A vector with the trace's fixed decimals.
fn vector(v: DVec3) -> String {
    format!("({}, {}, {})", number(v.x), number(v.y), number(v.z))
}

/// How an object is named in the readable trace: its kind and the line of its type code.
fn object_name(scene: &Scene, index: usize) -> String {
    let object = &scene.objects[index];
    format!("{} (line {})", object.kind, object.line)
}

/// How a light is named: its number (from 1), kind and line.
fn light_name(scene: &Scene, index: usize) -> String {
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
    notes.iter().map(reason).collect::<Vec<_>>().join("; ")
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
        let mut out = String::new();
        let (x, y) = self.pixel;
        let (w, h) = (self.options.width, self.options.height);
        let mut stage = match self.options.show {
            Some(show) => format!("--show {}", show.name()),
            None => format!("stage {}", self.options.stage.name()),
        };
        let variants = self.options.deviations.variants();
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
            self.readable_event(scene, event, indent, &mut out);
        }
        let _ = writeln!(out, "colour {}", vector(self.colour));
        let [r, g, b] = self.bytes;
        let _ = writeln!(out, "bytes: {r} {g} {b}");
        out
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
            Event::Skipped { object } => line(format!(
                "{indent}{}: skipped, the ray leaves it",
                object_name(scene, *object)
            )),
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
