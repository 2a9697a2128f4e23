//! What the tracer tells as it works: one [`Event`] per step of spec §4, to a
//! [`Recorder`]. The plain render's recorder is `()`, whose `record` does nothing and is
//! inlined, so every recording call compiles away and the render pays nothing for them
//! (the recorder is a type parameter rather than a run-time flag: docs/architecture.md
//! says what that saves). Which objects a query tests is not the recorder's to say: the
//! caller gives the query ([`Query`](super::objects::Query)). `legacy-rt trace`
//! keeps every event (`Vec<Event>`), and `compare` keeps what it needs of them.

use super::shading::PatternNote;
use super::stage::Show;
use crate::scene::Material;
use crate::shapes::{HitNote, Ray, Surface};
use glam::DVec3;

/// Where the tracer tells what it computes.
pub(crate) trait Recorder {
    /// Takes one event; `event` is called only by a recorder that keeps it.
    fn record(&mut self, event: impl FnOnce() -> Event);

    /// Takes one object's test: its t and the shape's decisions (told where the query
    /// wants them, [`Query::NOTES`](super::objects::Query::NOTES)).
    fn tested(&mut self, object: usize, t: Option<f64>, notes: &[HitNote]) {
        self.record(|| Event::Tested {
            object,
            t,
            notes: notes.to_vec(),
        });
    }
}

/// The largest reach of a recorder of margins, as a share of the distance: the largest
/// precision `compare` takes (`--precision`).
pub(crate) const MARGIN_REACH: f64 = 1e-2;

impl Recorder for () {
    #[inline(always)]
    fn record(&mut self, _: impl FnOnce() -> Event) {}
}

impl Recorder for Vec<Event> {
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
        /// Its base and unit direction.
        ray: Ray,
        /// The path's length so far.
        total_dist: f64,
    },
    /// The path is longer than MAX_DIST: black from here (spec §4.2 step 1).
    CutOff {
        /// The path's length.
        total_dist: f64,
    },
    /// An object not tested, and why.
    Skipped {
        /// Its index among the scene's objects.
        object: usize,
        /// Why it was not tested.
        reason: Skip,
    },
    /// An object tested: its t (`None`: no hit) and its shape's reasons.
    Tested {
        /// The object's index among the scene's objects.
        object: usize,
        /// The hit distance, if any.
        t: Option<f64>,
        /// The shape's decisions, in order.
        notes: Vec<HitNote>,
    },
    /// The closest hit (spec §4.6), if any: the object and its t.
    Closest {
        /// The winning object's index and its t; `None` when nothing is hit.
        hit: Option<(usize, f64)>,
    },
    /// The hit's point, normal and material.
    Surface {
        /// The index of the object hit.
        object: usize,
        /// The distance from the segment's base.
        t: f64,
        /// The path's length including this segment.
        total_dist: f64,
        /// Point, normal, plane coordinates.
        surface: Surface,
        /// The material there.
        material: Material,
        /// What chose the material: a tile, a texel, a shader, or nothing.
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
        /// The diagnostic image of `--show`.
        show: Show,
        /// The colour it gives the pixel, before the conversion to bytes.
        colour: DVec3,
    },
}

/// Why an object was not tested.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Skip {
    /// The ray leaves it (spec §4.2 step 2, §4.3: `last_hit`).
    Leaves,
    /// A variant takes it out of this test: hidden (camera and mirror rays) or no-shadow
    /// (shadow rays).
    Variant,
}

/// A step of one light's diffuse term.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightStep {
    /// The material's diffuse triple is zero: nothing to add.
    NoDiffuse,
    /// A variant switches the light off for this point (no-light, unlit).
    Off,
    /// The light sits at the point (or infinitely far): no direction.
    NoDirection {
        /// The distance to the light, |L|.
        dist: f64,
    },
    /// The unit vector to the light, the distance and cos θ = N·u.
    Towards {
        /// The unit vector to the light, u = L / |L|.
        u: DVec3,
        /// The distance to the light, |L|.
        dist: f64,
        /// cos θ = N·u; the light adds nothing unless it is positive.
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

/// The rays of a render: one camera ray per pixel, one reflected ray per mirror bounce,
/// one shadow ray per light test that got past the cosine and spotlight checks. As a
/// recorder it counts the reflected and shadow rays; the camera rays are the pixels.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Camera rays: one per pixel.
    pub camera: u64,
    /// Shadow rays: one per light that faces a hit and whose beam reaches it.
    pub shadow: u64,
    /// Reflected rays.
    pub reflected: u64,
}

impl Stats {
    /// Every ray: camera, shadow and reflected.
    pub fn total(&self) -> u64 {
        self.camera + self.shadow + self.reflected
    }
}

impl std::ops::Add for Stats {
    type Output = Stats;
    fn add(self, other: Stats) -> Stats {
        Stats {
            camera: self.camera + other.camera,
            shadow: self.shadow + other.shadow,
            reflected: self.reflected + other.reflected,
        }
    }
}

impl Recorder for Stats {
    fn record(&mut self, event: impl FnOnce() -> Event) {
        match event() {
            Event::Segment { depth, .. } if depth > 0 => self.reflected += 1,
            Event::Light(LightStep::ShadowRay { .. }) => self.shadow += 1,
            _ => {}
        }
    }
}
