//! The student's path against the reference's, value by value in the order the
//! reference computes them, and for each difference the outcome it changes, if any: a
//! hit or a miss, the closest object, a blocked light, the pixel's bytes. Only a
//! difference that changes an outcome can be the first difference; one within what the
//! printing rounds is none; a value the reference never computes (a shadow ray toward a
//! light that adds nothing) is compared with nothing.

use super::layout::{Ids, Located, Units, show};
use super::lex::{Label, Num};
use super::path::{Field, Found, LightBlock, RefHit, RefSegment, Segment, Tested, vector};
use crate::render::trace::{light_name, object_name};
use crate::render::{Trace, Tracing};
use crate::scene::Scene;
use glam::DVec3;
use serde::Serialize;

/// One comparison of the student's trace with the reference's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// The step: `camera ray`, `reflected ray 1`, `shadow ray to light 2 (point light,
    /// line 61)`, `camera ray, light 1 (point light, line 3)`.
    pub event: String,
    /// The object or light it concerns, by kind and scene line, if one.
    pub object: Option<String>,
    /// What is compared: `hit or miss`, `t`, `closest object`, `normal`, ...
    pub quantity: String,
    /// The student's value, as printed.
    pub yours: String,
    /// The reference's value.
    pub reference: String,
    /// Whether they agree within the student's printed precision.
    pub agrees: bool,
    /// What the difference changes, where it changes an outcome: `hit or miss`,
    /// `closest object`, `blocked light`, `bytes`, `camera ray`; `None` where they agree
    /// or the difference changes nothing.
    pub outcome: Option<String>,
    /// The line of FILE the student's value is on (from 1).
    pub student_line: usize,
    /// The difference in a sentence (empty where they agree).
    pub sentence: String,
    /// The student's line as printed.
    #[serde(skip)]
    pub text: String,
    /// The reference's event the check is about (its index in the trace).
    #[serde(skip)]
    pub event_index: usize,
}

impl Check {
    /// The step and the object: `camera ray, light 1 (point light, line 42), sphere
    /// (line 11)`.
    pub fn place(&self) -> String {
        match &self.object {
            Some(object) => format!("{}, {object}", self.event),
            None => self.event.clone(),
        }
    }

    /// Whether it is a difference that changes an outcome.
    pub fn counts(&self) -> bool {
        !self.agrees && self.outcome.is_some()
    }
}

/// Whether a printed number is the reference's value, within what printing rounded away
/// and a relative 1e-6 for a student's own (correct) arithmetic.
pub fn close(printed: Num, reference: f64) -> bool {
    if printed.value.is_nan() || reference.is_nan() {
        return printed.value.is_nan() && reference.is_nan();
    }
    (printed.value - reference).abs() <= printed.half_unit + 1e-6 * reference.abs().max(1.0)
}

/// Whether a printed vector is the reference's.
pub fn close3(printed: &[Num], reference: DVec3) -> bool {
    printed.len() == 3 && (0..3).all(|k| close(printed[k], reference[k]))
}

/// A printed direction scaled to unit length, with its rounding scaled alike: as
/// printed where it is a unit vector as far as the printing tells (or has no length).
fn unit(printed: &[Num]) -> [Num; 3] {
    let length = vector(printed).length();
    let rounding: f64 = printed.iter().map(|n| n.half_unit).sum();
    let l = match length.is_finite() && length > 0.0 && (length - 1.0).abs() > rounding + 1e-6 {
        true => length,
        false => 1.0,
    };
    [0, 1, 2].map(|k| Num {
        value: printed[k].value / l,
        half_unit: printed[k].half_unit / l,
    })
}

fn show3(v: DVec3) -> String {
    format!("({}, {}, {})", show(v.x), show(v.y), show(v.z))
}

fn printed3(v: &[Num]) -> String {
    let parts: Vec<String> = v.iter().map(|n| show(n.value)).collect();
    format!("({})", parts.join(", "))
}

/// ", a root behind the ray's base" for a negative t.
fn behind(t: Num) -> &'static str {
    if t.value < 0.0 && t.value != -1.0 {
        ", a root behind the ray's base"
    } else {
        ""
    }
}

/// How a ray of the path is named.
pub fn ray_name(depth: usize) -> String {
    match depth {
        0 => "camera ray".into(),
        _ => format!("reflected ray {depth}"),
    }
}

/// Where a check is: the step, the object, the reference's event, the student's line.
#[derive(Clone)]
struct At {
    event: String,
    object: Option<String>,
    event_index: usize,
    line: usize,
    text: String,
}

/// What a ray's tests decide.
#[derive(Clone, Copy)]
enum Ray {
    /// A camera or mirror ray: which object is closest, and at what t (and the next).
    Path {
        closest: Option<(usize, f64)>,
        next: Option<f64>,
    },
    /// A shadow ray toward a light at `dist`: which objects block it. `printed` is the
    /// length of the direction the student printed for the ray, if not a unit one.
    Shadow { dist: f64, printed: Option<f64> },
}

/// The comparison of one pixel's paths.
pub struct Comparison<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The scene prepared for traces.
    pub frame: &'a Tracing<'a>,
    /// The reference's trace of the pixel.
    pub trace: &'a Trace,
    /// The student's ids.
    pub ids: &'a Ids,
    /// The units of the student's shadow rays' t, where a line does not tell.
    pub units: Units,
    /// The checks so far.
    pub checks: Vec<Check>,
}

impl Comparison<'_> {
    fn check(
        &mut self,
        at: &At,
        quantity: &str,
        yours: String,
        reference: String,
        difference: Option<(String, Option<&str>)>,
    ) {
        let agrees = difference.is_none();
        let (sentence, outcome) = difference.unwrap_or_default();
        self.checks.push(Check {
            event: at.event.clone(),
            object: at.object.clone(),
            quantity: quantity.into(),
            yours,
            reference,
            agrees,
            outcome: outcome.map(str::to_string),
            student_line: at.line,
            sentence,
            text: at.text.clone(),
            event_index: at.event_index,
        });
    }

    /// Whether the pixel's bytes change when its colour changes by `delta`.
    fn bytes_change(&self, delta: DVec3) -> bool {
        !delta.is_finite() || self.frame.bytes(self.trace.colour + delta) != self.trace.bytes
    }

    /// "bytes" where a change of `delta` in the colour changes them.
    fn by_bytes(&self, delta: DVec3) -> Option<&'static str> {
        self.bytes_change(delta).then_some("bytes")
    }

    /// The block's location finding: the first, where there is one.
    pub fn located(&mut self, located: &Located) {
        if let Some(finding) = &located.finding {
            let at = At {
                event: "camera ray".into(),
                object: None,
                event_index: 0,
                line: located.finding_line,
                text: located.finding_text.clone(),
            };
            let yours = show3(located.through);
            let own = self.frame.world(located.pixel.0, located.pixel.1);
            self.check(
                &at,
                "world point",
                yours,
                show3(own),
                Some((finding.clone(), Some("camera ray"))),
            );
        }
    }

    /// The student's path against the reference's.
    pub fn path(&mut self, theirs: &[Segment], ours: &[RefSegment]) {
        let prints_rays = theirs.iter().any(|s| !s.tests.is_empty());
        for (k, reference) in ours.iter().enumerate() {
            let event = ray_name(reference.depth);
            let Some(segment) = theirs.get(k) else {
                // The student's path ends before this ray: what it adds is lost.
                if k > 0 && prints_rays && reference.hit.is_some() {
                    let lost: DVec3 = ours[k..]
                        .iter()
                        .filter_map(|s| s.divided)
                        .map(|d| d.weight * d.seen)
                        .sum();
                    let at = At {
                        event: event.clone(),
                        object: reference.hit.map(|h| object_name(self.scene, h.object)),
                        event_index: reference.event,
                        line: theirs.last().map_or(0, last_line),
                        text: String::new(),
                    };
                    let sentence = format!(
                        "your trace has no {event}; the reference's reflects to {}",
                        reference
                            .hit
                            .map_or(String::new(), |h| object_name(self.scene, h.object))
                    );
                    let outcome = self.by_bytes(-lost).or(Some("mirror ray"));
                    self.check(
                        &at,
                        "mirror ray",
                        "none".into(),
                        "reflects".into(),
                        Some((sentence, outcome)),
                    );
                }
                break;
            };
            let ray = Ray::Path {
                closest: reference.hit.map(|h| (h.object, h.t)),
                next: next_t(reference),
            };
            let start = self.checks.len();
            self.tests(
                &event,
                &segment.tests,
                &reference.tests,
                &reference.skipped,
                ray,
            );
            if self.hit(
                &event,
                segment,
                reference,
                theirs.iter().any(|s| s.hit.is_some()),
            ) {
                // The two paths part at a tie: what follows is of other objects.
                return;
            }
            self.lights(&event, segment, reference);
            if self.amb(&event, segment, reference) {
                // What the program printed as its result agrees: the intensities and
                // lengths it printed before are not what it computed with.
                self.echoes(
                    start,
                    &[
                        "intensity (ivec)",
                        "path length",
                        "emissivity",
                        "diffuse reflectivity",
                    ],
                    "its AMB agrees",
                );
            }
        }
        for (k, extra) in theirs.iter().enumerate().skip(ours.len()) {
            // A ray the reference never casts: a difference only where it hits something
            // (a miss adds black).
            let Some(hit) = &extra.hit else { continue };
            let event = ray_name(k);
            let at = At {
                event: event.clone(),
                object: None,
                event_index: ours.last().map_or(0, |s| s.event),
                line: hit.line,
                text: hit.text.clone(),
            };
            let sentence = format!(
                "your trace has {event}, which hits id {}; the reference's path ends before it \
                 (no specular, or MAX_DIST)",
                hit.id
            );
            self.check(
                &at,
                "mirror ray",
                "reflects".into(),
                "none".into(),
                Some((sentence, Some("mirror ray"))),
            );
        }
    }

    /// Takes back the outcomes of the differences in `quantities` from check `start` on:
    /// values the program printed but, as a result printed after them shows (`why`), did
    /// not compute with.
    fn echoes(&mut self, start: usize, quantities: &[&str], why: &str) {
        for check in &mut self.checks[start..] {
            if check.outcome.is_some() && quantities.contains(&check.quantity.as_str()) {
                check.outcome = None;
                check.sentence = format!("{} (printed only: {why})", check.sentence);
            }
        }
    }

    /// A ray's `FND` lines against the reference's tests.
    fn tests(
        &mut self,
        event: &str,
        theirs: &[Found],
        ours: &[Tested],
        skipped: &[usize],
        ray: Ray,
    ) {
        if theirs.is_empty() {
            return;
        }
        // Copies that print only the winner's FND.
        let winner_only = theirs.len() == 1 && ours.len() > 1;
        for tested in ours {
            let object = tested.object;
            let name = object_name(self.scene, object);
            let found = theirs
                .iter()
                .find(|f| self.ids.object(f.id) == Some(object));
            let Some(found) = found else {
                if winner_only {
                    continue;
                }
                let at = At {
                    event: event.into(),
                    object: Some(name.clone()),
                    event_index: tested.event,
                    line: theirs[0].line,
                    text: theirs[0].text.clone(),
                };
                let Some(t) = tested.t else {
                    let sentence =
                        format!("your ray does not test {name}; the reference's misses it");
                    self.check(
                        &at,
                        "tested",
                        "not tested".into(),
                        "misses".into(),
                        Some((sentence, None)),
                    );
                    continue;
                };
                let outcome = self.hit_outcome(object, t, ray);
                let sentence = format!(
                    "your ray does not test {name}; the reference's hits it at t = {}{}",
                    show(t),
                    blocks_words(outcome)
                );
                self.check(
                    &at,
                    "hit or miss",
                    "not tested".into(),
                    format!("hits at t = {}", show(t)),
                    Some((sentence, Some(outcome.unwrap_or("hit or miss")))),
                );
                continue;
            };
            let at = At {
                event: event.into(),
                object: Some(name.clone()),
                event_index: tested.event,
                line: found.line,
                text: found.text.clone(),
            };
            let yours = match found.hits() {
                true => format!("hits at t = {}", show(found.t.value)),
                false => format!("misses (t = {}{})", show(found.t.value), behind(found.t)),
            };
            match (found.hits(), tested.t) {
                (false, None) => self.check(&at, "hit or miss", yours, "misses".into(), None),
                (true, None) => {
                    let sentence = format!("yours {yours}, the reference misses");
                    self.check(
                        &at,
                        "hit or miss",
                        yours,
                        "misses".into(),
                        Some((sentence, Some("hit or miss"))),
                    );
                }
                (false, Some(t)) => {
                    let blocks = match ray {
                        Ray::Shadow { dist, .. } if t < dist => " and blocks the light",
                        _ => "",
                    };
                    let reference = format!("hits at t = {}", show(t));
                    let sentence = format!(
                        "yours {yours}, the reference hits at t = {}{blocks}",
                        show(t)
                    );
                    self.check(
                        &at,
                        "hit or miss",
                        yours,
                        reference,
                        Some((sentence, Some("hit or miss"))),
                    );
                }
                (true, Some(t)) => self.t(&at, found, object, t, ray),
            }
        }
        // The student's tests of objects the reference's ray skips (the one it leaves).
        for found in theirs.iter().filter(|f| f.hits()) {
            let Some(object) = self.ids.object(found.id) else {
                continue;
            };
            if !skipped.contains(&object) || ours.iter().any(|t| t.object == object) {
                continue;
            }
            let t = self.unit_t(found, ray);
            let outcome = match ray {
                Ray::Shadow { dist, .. } => (t.value < dist).then_some("blocked light"),
                Ray::Path { closest, .. } => closest
                    .is_none_or(|(_, c)| t.value < c)
                    .then_some("closest object"),
            };
            let name = object_name(self.scene, object);
            let at = At {
                event: event.into(),
                object: Some(name.clone()),
                event_index: ours.first().map_or(0, |t| t.event),
                line: found.line,
                text: found.text.clone(),
            };
            let sentence = format!(
                "your ray hits {name}, the object it leaves, at t = {}; the reference's skips it (spec §4.2: last_hit){}",
                show(found.t.value),
                match outcome {
                    Some("blocked light") => ", and it blocks the light",
                    Some(_) => ", and it is the closest",
                    None => "",
                }
            );
            self.check(
                &at,
                "hit or miss",
                format!("hits at t = {}", show(found.t.value)),
                "skipped".into(),
                Some((sentence, outcome)),
            );
        }
    }

    /// What a hit at `t` on `object` decides: the closest object on a path ray, blocking
    /// the light on a shadow ray.
    fn hit_outcome(&self, object: usize, t: f64, ray: Ray) -> Option<&'static str> {
        match ray {
            Ray::Path { closest, .. } => {
                (closest.is_some_and(|(c, _)| c == object)).then_some("closest object")
            }
            Ray::Shadow { dist, .. } => (t < dist).then_some("blocked light"),
        }
    }

    /// The student's t in units of a unit direction: as printed on a path ray; on a
    /// shadow ray as its own line's point tells, or the file's units.
    fn unit_t(&self, found: &Found, ray: Ray) -> Num {
        let Ray::Shadow {
            printed: Some(length),
            ..
        } = ray
        else {
            return found.t;
        };
        let length = found.dir.map_or(length, |d| vector(&d).length());
        match found.units().unwrap_or(self.units) {
            Units::Printed => Num {
                value: found.t.value * length,
                half_unit: found.t.half_unit * length,
            },
            _ => found.t,
        }
    }

    /// A hit's t on both sides.
    fn t(&mut self, at: &At, found: &Found, object: usize, t: f64, ray: Ray) {
        let yours = show(found.t.value);
        let as_unit = self.unit_t(found, ray);
        // Where the file cannot tell the units, either reading agrees.
        let unknown = matches!(
            ray,
            Ray::Shadow {
                printed: Some(_),
                ..
            }
        ) && found.units().is_none()
            && self.units == Units::Unknown;
        let agrees = close(as_unit, t) || (unknown && close(found.t, t));
        if agrees {
            self.check(at, "t", yours, show(t), None);
            return;
        }
        let outcome = match ray {
            Ray::Path { closest, next } => match closest {
                // The closest hit moves past the next object's, or the path's length
                // changes the colour.
                Some((c, ct)) if c == object => {
                    let passes = next.is_some_and(|n| as_unit.value > n);
                    let delta = self.path_length_delta(as_unit.value - ct);
                    match passes {
                        true => Some("closest object"),
                        false => self.by_bytes(delta),
                    }
                }
                Some((_, ct)) => (as_unit.value < ct).then_some("closest object"),
                None => None,
            },
            Ray::Shadow { dist, .. } => {
                ((as_unit.value < dist) != (t < dist)).then_some("blocked light")
            }
        };
        let units = match as_unit.value != found.t.value {
            true => format!(" ({} along a unit direction)", show(as_unit.value)),
            false => String::new(),
        };
        let sentence = format!(
            "yours hits at t = {yours}{units}, the reference at t = {}",
            show(t)
        );
        self.check(at, "t", yours, show(t), Some((sentence, outcome)));
    }

    /// The change in the pixel's colour if the camera ray's path were `delta` longer
    /// (each segment's intensity divided by its path's length).
    fn path_length_delta(&self, delta: f64) -> DVec3 {
        let mut change = DVec3::ZERO;
        for segment in super::path::reference(self.trace) {
            if let Some(d) = segment.divided {
                change += d.weight * (d.intensity / (d.total_dist + delta) - d.seen);
            }
        }
        change
    }

    /// The `HIT` line against the closest hit; `true` where the two take different
    /// objects at a tie (equal t within the printed precision): the paths part there.
    fn hit(&mut self, event: &str, theirs: &Segment, ours: &RefSegment, prints_hits: bool) -> bool {
        let line = theirs.tests.first().map_or(0, |f| f.line);
        match (&theirs.hit, ours.hit) {
            (Some(printed), Some(hit)) => {
                let name = object_name(self.scene, hit.object);
                let at = At {
                    event: event.into(),
                    object: Some(name.clone()),
                    event_index: hit.event,
                    line: printed.line,
                    text: printed.text.clone(),
                };
                let object = self.ids.object(printed.id);
                if object != Some(hit.object) {
                    let yours =
                        object.map_or(format!("id {}", printed.id), |o| object_name(self.scene, o));
                    // The reference's t of the student's object: a tie where it is the
                    // winner's within what the student printed.
                    let theirs_t = object
                        .and_then(|o| ours.tests.iter().find(|t| t.object == o))
                        .and_then(|t| t.t);
                    let within = |t: f64| {
                        (t - hit.t).abs() <= printed.t.half_unit + 1e-9 * hit.t.abs().max(1.0)
                    };
                    if theirs_t.is_some_and(within) && close(printed.t, hit.t) {
                        let sentence = format!(
                            "a tie: {yours} and {name} are both hit at t = {} to the printed \
                             precision; the reference takes {name}, yours {yours} (a fragile \
                             pixel, as compare excuses it); the rest of the path is of another \
                             object and is not compared",
                            show(hit.t)
                        );
                        self.check(
                            &at,
                            "closest object (tie)",
                            yours,
                            name,
                            Some((sentence, None)),
                        );
                        return true;
                    }
                    let sentence = format!(
                        "your closest hit is {yours} (id {}) at t = {}{}, the reference's {name} at t = {}",
                        printed.id,
                        show(printed.t.value),
                        behind(printed.t),
                        show(hit.t)
                    );
                    // The check is of the object the student's ray took.
                    let at = At {
                        object: Some(yours.clone()),
                        ..at
                    };
                    self.check(
                        &at,
                        "closest object",
                        yours,
                        name,
                        Some((sentence, Some("closest object"))),
                    );
                    return false;
                }
                self.check(
                    &at,
                    "closest object",
                    name,
                    object_name(self.scene, hit.object),
                    None,
                );
                let delta = self.path_length_delta(printed.t.value - hit.t);
                let outcome = self.by_bytes(delta);
                self.value(&at, "t", "hit's t", printed.t, hit.t, outcome);
                self.vector(&at, "hit point", &printed.point, hit.point, None);
                if let Some(total) = &theirs.total {
                    let at = At {
                        line: total.line,
                        text: total.text.clone(),
                        ..at
                    };
                    let delta = self.path_length_delta(total.value.value - hit.total_dist);
                    let outcome = self.by_bytes(delta);
                    self.value(
                        &at,
                        "path length",
                        "path's length",
                        total.value,
                        hit.total_dist,
                        outcome,
                    );
                }
            }
            (Some(printed), None) => {
                let at = At {
                    event: event.into(),
                    object: None,
                    event_index: ours.event,
                    line: printed.line,
                    text: printed.text.clone(),
                };
                let yours = self
                    .ids
                    .object(printed.id)
                    .map_or(format!("id {}", printed.id), |o| object_name(self.scene, o));
                let sentence = format!(
                    "your ray hits {yours} at t = {}, the reference's hits nothing",
                    show(printed.t.value)
                );
                self.check(
                    &at,
                    "closest object",
                    yours,
                    "nothing".into(),
                    Some((sentence, Some("closest object"))),
                );
            }
            (None, Some(hit)) if prints_hits && !theirs.tests.is_empty() => {
                let name = object_name(self.scene, hit.object);
                let at = At {
                    event: event.into(),
                    object: Some(name.clone()),
                    event_index: hit.event,
                    line,
                    text: theirs.tests[0].text.clone(),
                };
                let sentence = format!(
                    "your ray hits nothing (no HIT line), the reference's hits {name} at t = {}",
                    show(hit.t)
                );
                self.check(
                    &at,
                    "closest object",
                    "nothing".into(),
                    name,
                    Some((sentence, Some("closest object"))),
                );
            }
            _ => {}
        }
        false
    }

    /// A printed vector against the reference's; `outcome` says what a difference changes.
    fn vector(
        &mut self,
        at: &At,
        quantity: &str,
        printed: &[Num],
        reference: DVec3,
        outcome: Option<&str>,
    ) {
        let (yours, ours) = (printed3(printed), show3(reference));
        let difference = (!close3(printed, reference)).then(|| {
            (
                format!("your {quantity} is {yours}, the reference's {ours}"),
                outcome,
            )
        });
        self.check(at, quantity, yours, ours, difference);
    }

    /// A printed number against the reference's; `outcome` says what a difference
    /// changes (worked out by the caller, used only where they differ).
    fn value(
        &mut self,
        at: &At,
        quantity: &str,
        words: &str,
        printed: Num,
        reference: f64,
        outcome: Option<&str>,
    ) {
        let (yours, ours) = (show(printed.value), show(reference));
        let difference = (!close(printed, reference)).then(|| {
            (
                format!("your {words} is {yours}, the reference's {ours}"),
                outcome,
            )
        });
        self.check(at, quantity, yours, ours, difference);
    }

    /// Each light's block against the reference's term of the light it is for.
    fn lights(&mut self, event: &str, theirs: &Segment, ours: &RefSegment) {
        let mut used = vec![false; ours.lights.len()];
        let mut next = 0;
        for block in &theirs.blocks {
            let by_id = block
                .get(Label::LightObject)
                .and_then(|f| self.ids.light(f.values[0].value as i64));
            let by_centre = block.get(Label::LightCenter).and_then(|f| {
                (0..self.scene.lights.len())
                    .find(|&l| close3(&f.values, self.scene.lights[l].location))
            });
            let by_direction = block.get(Label::ToLight).and_then(|f| {
                let u = unit(&f.values);
                ours.lights
                    .iter()
                    .find(|l| l.towards.is_some_and(|(v, ..)| close3(&u, v)))
                    .map(|l| l.light)
            });
            let term = match by_id.or(by_centre).or(by_direction) {
                Some(light) => ours.lights.iter().position(|l| l.light == light),
                None => (next..ours.lights.len()).find(|&k| !used[k]),
            };
            let Some(term) = term else { continue };
            used[term] = true;
            next = term + 1;
            self.light(event, block, term, ours);
        }
    }

    /// One light's block.
    fn light(&mut self, event: &str, block: &LightBlock, index: usize, ours: &RefSegment) {
        let term = &ours.lights[index];
        let Some(hit) = ours.hit else { return };
        let name = light_name(self.scene, term.light);
        let lamp = &self.scene.lights[term.light];
        let event_name = format!("{event}, {name}");
        let at = |field: &Field, event_index: usize| At {
            event: event_name.clone(),
            object: Some(object_name(self.scene, hit.object)),
            event_index,
            line: field.line,
            text: field.text.clone(),
        };
        let weight = ours.divided.map_or(DVec3::ONE, |d| d.weight);
        let total = ours.divided.map_or(hit.total_dist, |d| d.total_dist);
        let (contribution, intensity) = term
            .lit
            .map_or((DVec3::ZERO, DVec3::ZERO), |(c, i, _)| (c, i));
        // The colour's change if this light's contribution were `other`.
        let change = |other: DVec3| weight * (other - contribution) / total;
        let blocked = term.shadow.as_ref().is_some_and(|s| s.blocker.is_some());
        if let Some(field) = block.get(Label::HitObject) {
            let id = field.values[0].value as i64;
            let agrees = self.ids.object(id) == Some(hit.object);
            let yours = self
                .ids
                .object(id)
                .map_or(format!("id {id}"), |o| object_name(self.scene, o));
            let difference = (!agrees).then(|| {
                (
                    format!(
                        "your diffuse block is for {yours} (id {id}), the reference's hit is {}",
                        object_name(self.scene, hit.object)
                    ),
                    None,
                )
            });
            self.check(
                &at(field, term.event),
                "hit object",
                yours,
                object_name(self.scene, hit.object),
                difference,
            );
        }
        if let Some(field) = block.get(Label::HitPoint) {
            self.vector(
                &at(field, hit.event),
                "hit point",
                &field.values,
                hit.point,
                None,
            );
        }
        if let Some(field) = block.get(Label::LightCenter) {
            self.vector(
                &at(field, term.event),
                "light centre",
                &field.values,
                lamp.location,
                None,
            );
        }
        // What the reference computes of this light's geometry: nothing where the
        // material has no diffuse term or the light is switched off.
        let Some((u, dist, cos, towards)) = term.towards else {
            self.contribution(
                block,
                term.light,
                &hit,
                &at,
                change,
                contribution,
                intensity,
            );
            return;
        };
        // The term as the student's cos θ and distance would make it (the rest as the
        // reference's): 0 where the light faces away or is blocked.
        let term_with = |cos_: f64, dist_: f64| -> DVec3 {
            if cos_ <= 0.0 || blocked {
                return DVec3::ZERO;
            }
            match cos > 0.0 && contribution != DVec3::ZERO {
                true => contribution * (cos_ / cos) * (dist / dist_),
                false => hit.diffuse * lamp.emissivity * cos_ / dist_,
            }
        };
        if let Some(field) = block.get(Label::Normal) {
            let printed = unit(&field.values);
            let agrees = close3(&printed, hit.normal);
            let difference = (!agrees).then(|| {
                let flipped = close3(&printed, -hit.normal);
                let why = if flipped { ": it is flipped" } else { "" };
                let cos_ = vector(&printed).dot(u);
                let outcome = self.by_bytes(change(term_with(cos_, dist)));
                (
                    format!(
                        "your normal is {}, the reference's {}{why}",
                        printed3(&field.values),
                        show3(hit.normal)
                    ),
                    outcome,
                )
            });
            self.check(
                &at(field, hit.event),
                "normal",
                printed3(&field.values),
                show3(hit.normal),
                difference,
            );
        }
        if let Some(field) = block.get(Label::ToLight) {
            let printed = unit(&field.values);
            let agrees = close3(&printed, u);
            let difference = (!agrees).then(|| {
                let cos_ = hit.normal.dot(vector(&printed));
                let outcome = self.by_bytes(change(term_with(cos_, dist)));
                (
                    format!(
                        "your direction to the light is {}, the reference's {}",
                        printed3(&field.values),
                        show3(u)
                    ),
                    outcome,
                )
            });
            self.check(
                &at(field, towards),
                "direction to the light",
                printed3(&field.values),
                show3(u),
                difference,
            );
        }
        if let Some(field) = block.get(Label::Distance) {
            let printed = field.values[0];
            // A blocker between the two distances changes the verdict.
            let shadow = term.shadow.as_ref();
            let blocked_ = shadow.is_some_and(|s| {
                s.tests
                    .iter()
                    .any(|t| t.t.is_some_and(|t| t < printed.value))
            });
            let outcome = match (shadow.is_some(), blocked_ != blocked) {
                (true, true) => Some("blocked light"),
                _ => self.by_bytes(change(term_with(cos, printed.value))),
            };
            let at = at(field, towards);
            self.value(
                &at,
                "distance to the light",
                "distance to the light",
                printed,
                dist,
                outcome,
            );
        }
        if let Some(field) = block.get(Label::Cos) {
            let printed = field.values[0];
            let outcome = self.by_bytes(change(term_with(printed.value, dist)));
            self.value(&at(field, towards), "cos θ", "cos θ", printed, cos, outcome);
        }
        if let Some(shadow) = &term.shadow {
            // The student's shadow ray, if printed; where it runs along another light's
            // direction, it is that light's (a block read out of step).
            let printed_length = block
                .get(Label::ToLight)
                .map(|f| vector(&f.values).length());
            let ray = Ray::Shadow {
                dist,
                printed: printed_length.filter(|l| (l - 1.0).abs() > 1e-3),
            };
            let shadow_event = format!("shadow ray to {name}");
            self.tests(
                &shadow_event,
                &block.shadow,
                &shadow.tests,
                &shadow.skipped,
                ray,
            );
            self.occlusion(block, &shadow_event, shadow, printed_length);
        }
        self.contribution(
            block,
            term.light,
            &hit,
            &at,
            change,
            contribution,
            intensity,
        );
    }

    /// `occluded by` against the reference's shadow ray's verdict.
    fn occlusion(
        &mut self,
        block: &LightBlock,
        event: &str,
        shadow: &super::path::Shadow,
        printed_length: Option<f64>,
    ) {
        let at = |field: Option<&Field>, object: Option<String>| At {
            event: event.into(),
            object,
            event_index: shadow.verdict,
            line: field.map_or(block.line(), |f| f.line),
            text: field.map_or(String::new(), |f| f.text.clone()),
        };
        match (block.get(Label::OccludedBy), shadow.blocker) {
            (Some(field), Some((object, t))) => {
                let id = field.values[0].value as i64;
                let name = object_name(self.scene, object);
                let at = at(Some(field), Some(name.clone()));
                let yours = self
                    .ids
                    .object(id)
                    .map_or(format!("id {id}"), |o| object_name(self.scene, o));
                let agrees = self.ids.object(id) == Some(object);
                let difference = (!agrees).then(|| {
                    (
                        format!("yours is occluded by {yours}, the reference's by {name}"),
                        None,
                    )
                });
                self.check(&at, "occluded by", yours, name, difference);
                if let (true, Some(field)) = (agrees, block.get(Label::DistanceWas)) {
                    let at = At {
                        line: field.line,
                        text: field.text.clone(),
                        ..at
                    };
                    let printed = field.values[0];
                    let along_printed = printed_length.map(|l| Num {
                        value: printed.value * l,
                        half_unit: printed.half_unit * l,
                    });
                    let agrees = close(printed, t) || along_printed.is_some_and(|p| close(p, t));
                    let difference = (!agrees).then(|| {
                        (
                            format!(
                                "your distance to the occluding object is {}, the reference's {}",
                                show(printed.value),
                                show(t)
                            ),
                            None,
                        )
                    });
                    self.check(
                        &at,
                        "distance to the occluding object",
                        show(printed.value),
                        show(t),
                        difference,
                    );
                }
            }
            (Some(field), None) => {
                let id = field.values[0].value as i64;
                let yours = self
                    .ids
                    .object(id)
                    .map_or(format!("id {id}"), |o| object_name(self.scene, o));
                let at = at(Some(field), Some(yours.clone()));
                let sentence = format!(
                    "yours is occluded by {yours}; the reference's shadow ray is not blocked"
                );
                self.check(
                    &at,
                    "occluded by",
                    yours,
                    "not blocked".into(),
                    Some((sentence, Some("blocked light"))),
                );
            }
            (None, Some((object, t))) if block.adds() => {
                let name = object_name(self.scene, object);
                let field = block.get(Label::Emissivity).or(block.get(Label::Ivec));
                let at = at(field, Some(name.clone()));
                let sentence = format!(
                    "yours lights the point; the reference's shadow ray is blocked by {name} at t = {}",
                    show(t)
                );
                self.check(
                    &at,
                    "occluded by",
                    "not blocked".into(),
                    name,
                    Some((sentence, Some("blocked light"))),
                );
            }
            _ => {}
        }
    }

    /// The light's emissivity, the diffuse reflectivity and the intensity after it.
    #[allow(clippy::too_many_arguments)]
    fn contribution(
        &mut self,
        block: &LightBlock,
        light: usize,
        hit: &RefHit,
        at: &dyn Fn(&Field, usize) -> At,
        change: impl Fn(DVec3) -> DVec3,
        contribution: DVec3,
        intensity: DVec3,
    ) {
        let lamp = &self.scene.lights[light];
        let start = self.checks.len();
        let ratio = |printed: DVec3, reference: DVec3| -> DVec3 {
            DVec3::select(
                reference.cmpne(DVec3::ZERO),
                printed / reference,
                DVec3::ONE,
            )
        };
        // The light's emissivity and the diffuse reflectivity: the term scaled by each.
        let factors = [
            (Label::Emissivity, "emissivity", lamp.emissivity),
            (Label::Reflectivity, "diffuse reflectivity", hit.diffuse),
        ];
        for (label, quantity, reference) in factors {
            if let Some(field) = block.get(label) {
                let scaled = contribution * ratio(vector(&field.values), reference);
                let outcome = self.by_bytes(change(scaled));
                self.vector(
                    &at(field, hit.event),
                    quantity,
                    &field.values,
                    reference,
                    outcome,
                );
            }
        }
        if let Some(field) = block.get(Label::Ivec) {
            let printed = vector(&field.values);
            let outcome = self.by_bytes(change(contribution + printed - intensity));
            self.vector(
                &at(field, hit.event),
                "intensity (ivec)",
                &field.values,
                intensity,
                outcome,
            );
            if close3(&field.values, intensity) {
                self.echoes(
                    start,
                    &["emissivity", "diffuse reflectivity"],
                    "its ivec agrees",
                );
            }
        }
    }

    /// The segment's `AMB` against the intensity divided by the path's length; `true`
    /// where it is printed and agrees.
    fn amb(&mut self, event: &str, theirs: &Segment, ours: &RefSegment) -> bool {
        let (Some(amb), Some(divided)) = (&theirs.amb, ours.divided) else {
            return false;
        };
        let at = At {
            event: event.into(),
            object: ours.hit.map(|h| object_name(self.scene, h.object)),
            event_index: divided.event,
            line: amb.line,
            text: amb.text.clone(),
        };
        let outcome = self.by_bytes(divided.weight * (vector(&amb.value) - divided.seen));
        self.vector(
            &at,
            "intensity / path (AMB)",
            &amb.value,
            divided.seen,
            outcome,
        );
        close3(&amb.value, divided.seen)
    }
}

/// " and blocks the light" for a shadow ray's blocker.
fn blocks_words(outcome: Option<&str>) -> &'static str {
    match outcome {
        Some("blocked light") => " and blocks the light",
        _ => "",
    }
}

/// The t of the second-closest hit of a path ray.
fn next_t(segment: &RefSegment) -> Option<f64> {
    let closest = segment.hit.map(|h| h.object);
    segment
        .tests
        .iter()
        .filter(|t| Some(t.object) != closest)
        .filter_map(|t| t.t)
        .fold(None, |best: Option<f64>, t| {
            Some(best.map_or(t, |b| b.min(t)))
        })
}

/// The last line of a student's segment.
fn last_line(segment: &Segment) -> usize {
    let lines = [
        segment.tests.last().map(|f| f.line),
        segment.hit.as_ref().map(|h| h.line),
        segment.amb.as_ref().map(|a| a.line),
        segment
            .blocks
            .last()
            .map(|b| b.fields.last().map_or(b.line(), |f| f.line)),
    ];
    lines.into_iter().flatten().max().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Options;

    /// A number as printed with `decimals` digits after the point.
    fn printed(value: f64, decimals: i32) -> Num {
        let scale = 10f64.powi(decimals);
        Num {
            value: (value * scale).round() / scale,
            half_unit: 0.5 / scale,
        }
    }

    /// A value agrees with its printing, rounded to the printed digits; beyond that
    /// rounding (half a unit of the last digit) a relative 1e-6 is granted for a
    /// student's own arithmetic, and no more. NaN agrees with NaN only.
    #[test]
    fn a_printed_number_is_close_within_its_rounding() {
        let exact = 2.0f64.sqrt();
        for decimals in [2, 4, 6] {
            let shown = printed(exact, decimals);
            assert!(close(shown, exact), "{decimals} decimals");
            let tolerance = shown.half_unit + 1e-6 * exact;
            let at = |k: f64| Num {
                value: exact + k * tolerance,
                ..shown
            };
            assert!(close(at(0.99), exact) && close(at(-0.99), exact));
            assert!(!close(at(1.01), exact) && !close(at(-1.01), exact));
        }
        // 1e-6 of 1e6 is 1: printed exactly (no rounding), 1e6 + 0.9 agrees, + 1.1 not.
        let whole = |value| Num {
            value,
            half_unit: 0.0,
        };
        assert!(close(whole(1e6 + 0.9), 1e6));
        assert!(!close(whole(1e6 + 1.1), 1e6));
        // Below 1 the grant is 1e-6 absolute.
        assert!(close(whole(0.5 + 0.9e-6), 0.5));
        assert!(!close(whole(0.5 + 1.1e-6), 0.5));
        let nan = whole(f64::NAN);
        assert!(close(nan, f64::NAN) && !close(nan, 0.0) && !close(whole(0.0), f64::NAN));
    }

    /// A vector is close when each of exactly three components is.
    #[test]
    fn a_printed_vector_is_close_component_by_component() {
        let v = DVec3::new(0.25, -1.5, 3.125);
        let shown: Vec<Num> = v.to_array().iter().map(|&c| printed(c, 3)).collect();
        assert!(close3(&shown, v));
        assert!(!close3(&shown[..2], v));
        let mut off = shown.clone();
        off[2].value += 0.01;
        assert!(!close3(&off, v));
    }

    /// A printed direction of length 2 is scaled to unit length, its rounding with it;
    /// one that is a unit vector as far as its digits tell is kept as printed.
    #[test]
    fn a_printed_direction_is_made_unit_with_its_rounding() {
        let long = [printed(0.0, 3), printed(2.0, 3), printed(0.0, 3)];
        let [x, y, z] = unit(&long);
        assert_eq!((x.value, y.value, z.value), (0.0, 1.0, 0.0));
        assert_eq!(y.half_unit, 0.0005 / 2.0);
        // (0.6, 0.8, 0) printed to one decimal: length 1 exactly, kept.
        let kept = [printed(0.6, 1), printed(0.8, 1), printed(0.0, 1)];
        assert_eq!(unit(&kept).map(|n| n.value), [0.6, 0.8, 0.0]);
        // (0.577, 0.577, 0.577): length 0.99937, within the rounding of 3 decimals
        // (3 x 0.0005): kept as printed rather than stretched.
        let diagonal = [printed(0.57735, 3); 3];
        assert_eq!(unit(&diagonal).map(|n| n.value), [0.577; 3]);
    }

    /// "A root behind the ray's base" is said of a negative t, but not of -1, the value
    /// the course's programs print for "no hit".
    #[test]
    fn only_a_negative_root_other_than_minus_one_is_behind() {
        let t = |value| Num {
            value,
            half_unit: 0.0,
        };
        assert_eq!(behind(t(-0.5)), ", a root behind the ray's base");
        assert_eq!(behind(t(-1.0)), "");
        assert_eq!(behind(t(2.0)), "");
        assert_eq!(ray_name(0), "camera ray");
        assert_eq!(ray_name(2), "reflected ray 2");
    }

    /// A real trace of a correct program (../shared/student-traces, 64x48, MAX_DIST 70)
    /// and its scene; `None` where ../shared is absent (under `CI=true` that fails).
    fn real_trace(scene: &str) -> Option<(Scene, String)> {
        use std::io::Read;
        let shared = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared");
        if !shared.is_dir() {
            let ci = std::env::var("CI").is_ok_and(|value| value == "true");
            assert!(!ci, "{} is absent, and CI must have it", shared.display());
            return None;
        }
        let text = std::fs::read_to_string(shared.join(format!("course-scenes/{scene}.txt")));
        let gz = std::fs::File::open(shared.join(format!("student-traces/{scene}.dbg.txt.gz")));
        let mut trace = String::new();
        flate2::read::GzDecoder::new(gz.unwrap())
            .read_to_string(&mut trace)
            .unwrap();
        Some((crate::load(&text.unwrap()).unwrap(), trace))
    }

    /// Pixel `pixel`'s block of a real trace, with its `nth` line (from the block's
    /// `PIX` line) that starts with `start` passed through `edit` (a labelled value is
    /// on the next line that is not blank), read against the reference: the checks that
    /// disagree and did not before the edit.
    fn edited(
        (scene, trace): &(Scene, String),
        pixel: (usize, usize),
        start: &str,
        nth: usize,
        edit: impl Fn(&str) -> String,
    ) -> Vec<Check> {
        let label = format!("PIX {:4} {:4} - ", pixel.0, pixel.1);
        let lines: Vec<&str> = trace.lines().collect();
        let first = lines.iter().position(|l| *l == label).unwrap();
        let last = (first + 1..lines.len())
            .find(|&k| lines[k].starts_with("PIX "))
            .unwrap_or(lines.len());
        let block: Vec<String> = lines[first..last].iter().map(|l| l.to_string()).collect();
        let mut at = (block.iter().enumerate())
            .filter(|(_, l)| l.starts_with(start))
            .nth(nth)
            .map(|(k, _)| k)
            .unwrap_or_else(|| panic!("no line {nth} starting {start:?}"));
        if block[at].trim_end() == start {
            at = (at + 1..block.len())
                .find(|&k| !block[k].trim().is_empty())
                .unwrap();
        }
        let mut changed = block.clone();
        changed[at] = edit(&block[at]);
        assert_ne!(changed[at], block[at], "the edit changes the line");
        // The model dump the dialect is learnt from, then the one block.
        let dump = &lines[..lines.iter().position(|l| l.starts_with("PIX ")).unwrap()];
        let options = Options {
            max_dist: 70.0,
            ..Options::new(64, 48)
        };
        let disagree = |block: &[String]| -> Vec<Check> {
            let text = dump.join("\n") + "\n" + &block.join("\n") + "\n";
            crate::render::tracing(scene, &options, |frame| {
                let (report, _) = crate::against::against(scene, frame, pixel, text.as_bytes())
                    .unwrap_or_else(|e| panic!("{}", e.0));
                report.compared.into_iter().filter(|c| !c.agrees).collect()
            })
        };
        let before: Vec<(String, String)> = (disagree(&block).into_iter())
            .map(|c| (c.event, c.quantity))
            .collect();
        (disagree(&changed).into_iter())
            .filter(|c| !before.contains(&(c.event.clone(), c.quantity.clone())))
            .collect()
    }

    /// The one check that disagrees.
    fn only(checks: Vec<Check>) -> Check {
        assert_eq!(checks.len(), 1, "{checks:#?}");
        checks.into_iter().next().unwrap()
    }

    /// spec1's pixel (20, 20) sees the red sphere (line 11), lit by light 1 (line 42,
    /// id 104: distance 6.441930, cos θ 0.873245) and light 4 (line 54, id 107); lights 2
    /// and 3 face away from it.
    const RED: (usize, usize) = (20, 20);

    #[test]
    fn a_light_block_for_another_object_is_its_hit_object_that_differs() {
        let Some(spec1) = real_trace("spec1") else {
            return;
        };
        let check = only(edited(&spec1, RED, "hit object id was", 0, |l| {
            l.replace("101", "102")
        }));
        assert_eq!(check.quantity, "hit object");
        assert_eq!(check.event, "camera ray, light 1 (point light, line 42)");
        assert!(
            check
                .sentence
                .starts_with("your diffuse block is for tiled plane (line 18) (id 102)"),
            "{}",
            check.sentence
        );
        assert!(
            check
                .sentence
                .contains("the reference's hit is sphere (line 11)")
        );
    }

    #[test]
    fn a_direction_to_the_light_that_turns_cos_changes_the_bytes() {
        let Some(spec1) = real_trace("spec1") else {
            return;
        };
        // Printed unnormalised: (1.993473, 0.609936, 6.095286). With its z negated it
        // points behind the surface (the normal is (0.003264, -0.304968, 0.952357)):
        // cos θ turns negative and the light's term, which the bytes hold, is lost.
        let check = only(edited(&spec1, RED, "unit vector to light is", 0, |l| {
            l.replace("6.095286", "-6.095286")
        }));
        assert_eq!(check.quantity, "direction to the light");
        assert_eq!(check.outcome.as_deref(), Some("bytes"), "{check:#?}");
        assert!(check.sentence.starts_with("your direction to the light is"));
    }

    #[test]
    fn a_cos_theta_off_changes_the_bytes_and_one_within_its_digits_agrees() {
        let Some(spec1) = real_trace("spec1") else {
            return;
        };
        let check = only(edited(&spec1, RED, "theta is", 0, |l| {
            l.replace("0.873245", "0.5")
        }));
        assert_eq!(check.quantity, "cos θ");
        assert_eq!(check.outcome.as_deref(), Some("bytes"), "{check:#?}");
        // The last digit moved by less than half a unit of it is the same cos θ.
        let same = edited(&spec1, RED, "theta is", 0, |l| {
            l.replace("0.873245", "0.8732454")
        });
        assert!(same.is_empty(), "{same:#?}");
    }

    #[test]
    fn a_light_block_is_read_against_the_light_its_id_names_or_else_its_own() {
        let Some(spec1) = real_trace("spec1") else {
            return;
        };
        // Light 1's block (id 104) with light 2's id (105): read against light 2, whose
        // centre (0, 5, -3) is not the printed (0, 0, 5).
        let other = edited(&spec1, RED, "light object id was", 0, |l| {
            l.replace("104", "105")
        });
        assert!(
            other.iter().any(|c| c.quantity == "light centre"
                && c.event == "camera ray, light 2 (point light, line 46)"),
            "{other:#?}"
        );
        // With an id no record has, the block is still light 1's (its centre, its
        // direction and its place all say so): every value agrees.
        let unknown = edited(&spec1, RED, "light object id was", 0, |l| {
            l.replace("104", "999")
        });
        assert!(unknown.is_empty(), "{unknown:#?}");
    }

    #[test]
    fn a_distance_to_the_light_short_of_the_blocker_unblocks_it() {
        let Some(spec1) = real_trace("spec1") else {
            return;
        };
        // Pixel (40, 10): the tiled floor (line 18), blocked from light 2 (line 46, id 105) by
        // the blue sphere (line 4) at t = 2.23491; light 2 is 9.391661 away. Printed as
        // 2.0, the blocker lies beyond the student's light: the verdict changes.
        let check = only(edited(&spec1, (40, 10), "distance to light is", 1, |l| {
            l.replace("9.391661", "2.000000")
        }));
        assert_eq!(check.quantity, "distance to the light");
        assert_eq!(check.event, "camera ray, light 2 (point light, line 46)");
        assert_eq!(
            check.outcome.as_deref(),
            Some("blocked light"),
            "{check:#?}"
        );
        // Printed as 9.0 the blocker still blocks: only the bytes could change, and a
        // blocked light adds nothing, so nothing does.
        let check = only(edited(&spec1, (40, 10), "distance to light is", 1, |l| {
            l.replace("9.391661", "9.000000")
        }));
        assert_eq!(check.outcome, None, "{check:#?}");
    }
}
