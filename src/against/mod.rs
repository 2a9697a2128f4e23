//! `legacy-rt trace X Y --against FILE`: a student's own debug trace (spec §8) read
//! against the reference's trace of the same pixel, to the first number that differs.
//!
//! [`read`] turns the student's text into tags and labels. Here they are found for the
//! pixel, grouped as the course's `ray_trace` printed them (a ray's `FND` lines, its
//! `HIT`, per light the shadow ray's `FND` lines and the diffuse block, `AMB`, then the
//! mirror's ray), and compared, in the order the reference computed them, with the
//! reference's events ([`crate::render::Trace`]): which objects each ray hits, the hit,
//! its point and normal, each light's direction, distance and cos θ, the shadow ray, the
//! intensities. Numbers agree within what the student's printing rounded away.

pub mod read;

use crate::render::{CourseIds, Event, LightStep, Trace, trace::light_name, trace::object_name};
use crate::scene::Scene;
use crate::shapes::Ray;
use glam::DVec3;
use read::{Label, Line, Num, Said};
use serde::Serialize;
use std::fmt::Write;

/// One comparison of the student's trace with the reference's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// The step: `camera ray`, `reflected ray 1`, `shadow ray to light 2 (point light,
    /// line 61)`, `light 1 (point light, line 3)`.
    pub event: String,
    /// The object or light it concerns, by kind and scene line, if one.
    pub object: Option<String>,
    /// What is compared: `id`, `hit or miss`, `t`, `closest object`, `hit point`, ...
    pub quantity: String,
    /// The student's value, as printed.
    pub yours: String,
    /// The reference's value.
    pub reference: String,
    /// Whether they agree within the student's printed precision.
    pub agrees: bool,
    /// The line of FILE the student's value is on (from 1).
    pub student_line: usize,
    /// The difference in a sentence (empty where they agree).
    pub sentence: String,
    /// The reference's event the check is about (its index in the trace).
    #[serde(skip)]
    pub event_index: usize,
}

/// The student's trace of one pixel, read against the reference's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The pixel, (0, 0) at the lower left.
    pub pixel: (usize, usize),
    /// The lines of FILE that hold the pixel's trace (from 1, inclusive).
    pub lines: (usize, usize),
    /// Where the student's ids start: 0 or 100 (spec §7.1), or what the trace used.
    pub id_base: i64,
    /// Notes on how the trace was read (the order of PIX's numbers, ...).
    pub notes: Vec<String>,
    /// Every comparison, in the reference's order.
    pub compared: Vec<Check>,
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
}

impl Report {
    /// The first comparison that disagrees.
    pub fn first_difference(&self) -> Option<&Check> {
        self.compared.iter().find(|c| !c.agrees)
    }

    /// The number of comparisons that disagree.
    pub fn differences(&self) -> usize {
        self.compared.iter().filter(|c| !c.agrees).count()
    }
}

/// What `trace --against --json` prints (and the page reads): the report with the
/// image's size and the student's file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary<'a> {
    /// The pixel, (0, 0) at the lower left.
    pub pixel: (usize, usize),
    /// The image's width and height.
    pub size: (usize, usize),
    /// The student's file, as named.
    pub file: &'a str,
    /// The lines of the file that hold the pixel's trace (from 1, inclusive).
    pub lines: (usize, usize),
    /// Where the student's ids start.
    pub id_base: i64,
    /// Notes on how the trace was read.
    pub notes: &'a [String],
    /// Whether every comparison agrees.
    pub agrees: bool,
    /// How many disagree.
    pub differences: usize,
    /// The first that disagrees.
    pub first_difference: Option<&'a Check>,
    /// Every comparison, in the reference's order.
    pub compared: &'a [Check],
}

impl Report {
    /// The report as `--json` gives it, for the pixel of `trace` and the file `file`.
    pub fn summary<'a>(&'a self, trace: &Trace, file: &'a str) -> Summary<'a> {
        Summary {
            pixel: self.pixel,
            size: (trace.options.width, trace.options.height),
            file,
            lines: self.lines,
            id_base: self.id_base,
            notes: &self.notes,
            agrees: self.first_difference().is_none(),
            differences: self.differences(),
            first_difference: self.first_difference(),
            compared: &self.compared,
        }
    }
}

/// Why a student's trace cannot be read against this pixel of this scene.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unreadable(pub String);

impl Unreadable {
    /// The message for the student's file shown as `file`, as the command line and the
    /// page give it (without the command line's `error: `).
    pub fn about(&self, file: &str) -> String {
        format!("cannot read {file} against the reference: {}", self.0)
    }
}

/// Reads the student's `text` against `trace`, the reference's trace of the same pixel.
pub fn against(scene: &Scene, trace: &Trace, text: &str) -> Result<Report, Unreadable> {
    let lines: Vec<&str> = text.lines().collect();
    let markers = read::read_lines(&lines, 0, |l| l.contains("PIX") || l.contains("WRL"));
    let (range, mut notes) = block(&markers, lines.len(), trace)?;
    let block = read::read_lines(&lines[range.0..range.1], range.0, |_| true);
    if !block.iter().any(|l| {
        matches!(
            l.said,
            Said::Found(..) | Said::Hit(..) | Said::Amb(_) | Said::Labelled(..)
        )
    }) {
        let (x, y) = trace.pixel;
        return Err(Unreadable(format!(
            "its trace of pixel ({x}, {y}) (lines {}-{}) has no line the course's DBG_ flags \
             print (FND, HIT, AMB or the diffuse block's labels, spec §8): is it the \
             standard error of the course program built with them?",
            range.0 + 1,
            range.1
        )));
    }
    let segments = segments(&block);
    let reference = reference(trace);
    same_scene(scene, &segments)?;
    let ids = Ids::new(scene, &segments)?;
    if ids.base != 0 {
        notes.push(format!("ids read from {}", ids.base));
    }
    let mut compare = Compare {
        scene,
        ids: &ids,
        checks: Vec::new(),
    };
    compare.path(&segments, &reference);
    Ok(Report {
        pixel: trace.pixel,
        lines: (range.0 + 1, range.1),
        id_base: ids.base,
        notes,
        compared: compare.checks,
    })
}

// ---------------------------------------------------------------------------------------
// Finding the pixel

/// The range of lines (from 0, end excluded) that hold the pixel's trace, found among the
/// `PIX` and `WRL` lines (`markers`) of a file of `count` lines, and notes on how.
fn block(
    markers: &[Line],
    count: usize,
    trace: &Trace,
) -> Result<((usize, usize), Vec<String>), Unreadable> {
    let (x, y) = (trace.pixel.0 as i64, trace.pixel.1 as i64);
    let pix: Vec<usize> = (0..markers.len())
        .filter(|&k| matches!(markers[k].said, Said::Pix(..)))
        .collect();
    let first_world = markers
        .iter()
        .position(|l| matches!(l.said, Said::World(..)));
    if pix.is_empty() {
        let world = first_world.and_then(|k| world_of(&markers[k]));
        check_world(world, trace, first_world.map_or(0, |k| markers[k].line))?;
        let note = "no PIX line: the whole file is read as this pixel's trace".to_string();
        return Ok(((0, count), vec![note]));
    }
    // Some copies print WRL before the pixel's other lines and before its PIX.
    let world_first = first_world.is_some_and(|w| w < pix[0]);
    let next = |k: usize| pix.get(k + 1).copied().unwrap_or(markers.len());
    let world_of_block = |k: usize| {
        let range = if world_first {
            (if k == 0 { 0 } else { pix[k - 1] + 1 }, pix[k])
        } else {
            (pix[k] + 1, next(k))
        };
        let mut worlds = markers[range.0..range.1].iter().filter_map(world_of);
        if world_first {
            worlds.next_back()
        } else {
            worlds.next()
        }
    };
    let mut mismatch = None;
    for swapped in [false, true] {
        for (k, &at) in pix.iter().enumerate() {
            let Said::Pix(a, b) = markers[at].said else {
                continue;
            };
            let printed = if swapped { (y, x) } else { (x, y) };
            if (a, b) != printed || (swapped && x == y) {
                continue;
            }
            let world = world_of_block(k);
            if world.is_none() && swapped {
                continue;
            }
            match check_world(world, trace, markers[at].line) {
                Ok(()) => {
                    let end = pix
                        .get(k + 1)
                        .map_or(count, |&n| markers[n].line - 1)
                        .max(markers[at].line);
                    let mut notes = Vec::new();
                    if swapped {
                        notes.push(format!(
                            "PIX prints y first (line {}: PIX {a} {b}), as one later copy did",
                            markers[at].line
                        ));
                    }
                    return Ok(((markers[at].line - 1, end), notes));
                }
                Err(error) => mismatch = mismatch.or(Some(error)),
            }
        }
    }
    if let Some(error) = mismatch {
        return Err(error);
    }
    let said = |k: usize| match markers[k].said {
        Said::Pix(a, b) => format!("PIX {a} {b} (line {})", markers[k].line),
        _ => String::new(),
    };
    let span = if pix.len() == 1 {
        format!("its one pixel is {}", said(pix[0]))
    } else {
        format!(
            "its {} PIX lines run from {} to {}",
            pix.len(),
            said(pix[0]),
            said(pix[pix.len() - 1])
        )
    };
    Err(Unreadable(format!(
        "it has no trace of pixel ({x}, {y}): {span}; trace the pixel it has, or print \
         the student's trace of this one"
    )))
}

/// The world point a `WRL` line says.
fn world_of(line: &Line) -> Option<(Num, Num)> {
    match line.said {
        Said::World(a, b) => Some((a, b)),
        _ => None,
    }
}

/// Whether the block's world point (if printed) is the reference's for this pixel.
fn check_world(world: Option<(Num, Num)>, trace: &Trace, line: usize) -> Result<(), Unreadable> {
    let Some((a, b)) = world else {
        return Ok(());
    };
    if close(a, trace.world.x) && close(b, trace.world.y) {
        return Ok(());
    }
    let (w, h) = (trace.options.width, trace.options.height);
    let (x, y) = trace.pixel;
    Err(Unreadable(format!(
        "its trace of pixel ({x}, {y}) (line {line}) has the world point ({}, {}), but this \
         scene at {w}x{h} puts the pixel at ({:.3}, {:.3}): the trace is of another scene, \
         or of another image size (give W H as the student's program rendered it)",
        a.value, b.value, trace.world.x, trace.world.y
    )))
}

// ---------------------------------------------------------------------------------------
// The student's trace, grouped as the course's ray_trace printed it

/// One `FND` line, with the three-line form's extra lines if printed.
#[derive(Debug, Clone)]
struct Found {
    id: i64,
    t: Num,
    line: usize,
    dir: Option<[Num; 3]>,
}

/// One light's diffuse block, and the shadow ray's `FND` lines printed before it.
#[derive(Debug, Clone, Default)]
struct Block {
    fields: Vec<(Label, Vec<Num>, usize)>,
    shadow: Vec<Found>,
    closed: bool,
}

impl Block {
    fn get(&self, label: Label) -> Option<(&[Num], usize)> {
        self.fields
            .iter()
            .find(|(l, _, _)| *l == label)
            .map(|(_, values, line)| (values.as_slice(), *line))
    }

    fn line(&self) -> usize {
        let first = self.shadow.first().map(|f| f.line);
        first.or(self.fields.first().map(|f| f.2)).unwrap_or(0)
    }
}

/// One ray of the path as the student printed it.
#[derive(Debug, Clone, Default)]
struct Segment {
    tests: Vec<Found>,
    hit: Option<(i64, Num, [Num; 3], usize)>,
    total: Option<(Num, usize)>,
    blocks: Vec<Block>,
    amb: Option<([Num; 3], usize)>,
}

/// The block's lines grouped into the path's rays. A run of `FND` lines followed by a
/// diffuse label is a shadow ray's; any other run starts a ray of the path. `HIT` and
/// `AMB` go to the latest ray without one, so that copies printing them after the
/// mirror's recursion are read as well as those printing them before.
fn segments(block: &[Line]) -> Vec<Segment> {
    let mut segments: Vec<Segment> = Vec::new();
    let mut run: Vec<Found> = Vec::new();
    let flush = |run: &mut Vec<Found>, segments: &mut Vec<Segment>| {
        if !run.is_empty() {
            segments.push(Segment {
                tests: std::mem::take(run),
                ..Segment::default()
            });
        }
    };
    for line in block {
        match &line.said {
            Said::Found(id, t) => run.push(Found {
                id: *id,
                t: *t,
                line: line.line,
                dir: None,
            }),
            Said::FoundDir(dir) => {
                if let Some(found) = run.last_mut() {
                    found.dir = Some(*dir);
                }
            }
            Said::Labelled(label, values) => {
                let shadow = !run.is_empty()
                    && segments
                        .last()
                        .is_some_and(|s| !s.tests.is_empty() || s.hit.is_some());
                if !shadow {
                    flush(&mut run, &mut segments);
                }
                if segments.is_empty() {
                    segments.push(Segment::default());
                }
                let segment = segments.last_mut().expect("one was pushed");
                // A new light's block, unless this label continues the open one: the
                // shadow ray's verdict and the contribution after the light's geometry,
                // as copies that print the geometry before the shadow ray do.
                let continues = matches!(
                    label,
                    Label::OccludedBy
                        | Label::DistanceWas
                        | Label::Emissivity
                        | Label::Reflectivity
                        | Label::Ivec
                );
                let new = segment
                    .blocks
                    .last()
                    .is_none_or(|b| b.closed || b.get(*label).is_some() || (shadow && !continues));
                if new {
                    segment.blocks.push(Block::default());
                }
                let block = segment.blocks.last_mut().expect("one was pushed");
                if shadow {
                    block.shadow = std::mem::take(&mut run);
                }
                block.fields.push((*label, values.clone(), line.line));
                block.closed = matches!(label, Label::Ivec | Label::DistanceWas);
            }
            Said::Hit(id, t, point) => {
                flush(&mut run, &mut segments);
                let open = segments.iter().rposition(|s| s.hit.is_none());
                let at = open.unwrap_or_else(|| {
                    segments.push(Segment::default());
                    segments.len() - 1
                });
                segments[at].hit = Some((*id, *t, *point, line.line));
            }
            Said::TotalDist(total) => {
                if let Some(s) = segments.iter_mut().rev().find(|s| s.hit.is_some()) {
                    s.total = Some((*total, line.line));
                }
            }
            Said::Amb(amb) => {
                flush(&mut run, &mut segments);
                let open = segments.iter().rposition(|s| s.amb.is_none());
                let at = open.unwrap_or_else(|| {
                    segments.push(Segment::default());
                    segments.len() - 1
                });
                segments[at].amb = Some((*amb, line.line));
            }
            Said::Pix(..)
            | Said::World(..)
            | Said::FoundBase(_)
            | Said::FoundHits(_)
            | Said::Diffuse(_) => {}
        }
    }
    flush(&mut run, &mut segments);
    segments
}

// ---------------------------------------------------------------------------------------
// The reference's trace, grouped the same way

/// One object tested, and the event that says so.
#[derive(Debug, Clone, Copy)]
struct Tested {
    object: usize,
    t: Option<f64>,
    event: usize,
}

/// A shadow ray.
#[derive(Debug, Clone, Default)]
struct Shadow {
    tests: Vec<Tested>,
    blocker: Option<(usize, f64)>,
    /// The event of its verdict (blocked or not).
    blocked: usize,
}

/// One light's term.
#[derive(Debug, Clone)]
struct LightTerm {
    light: usize,
    event: usize,
    towards: Option<(DVec3, f64, f64, usize)>,
    shadow: Option<Shadow>,
    lit: Option<(DVec3, usize)>,
}

/// The hit of a segment.
#[derive(Debug, Clone, Copy)]
struct RefHit {
    object: usize,
    t: f64,
    point: DVec3,
    normal: DVec3,
    total_dist: f64,
    diffuse: DVec3,
    event: usize,
}

/// One ray of the reference's path.
#[derive(Debug, Clone)]
struct RefSegment {
    depth: usize,
    ray: Ray,
    event: usize,
    tests: Vec<Tested>,
    hit: Option<RefHit>,
    lights: Vec<LightTerm>,
    seen: Option<(DVec3, usize)>,
}

/// The reference's events grouped into the path's rays.
fn reference(trace: &Trace) -> Vec<RefSegment> {
    let mut segments: Vec<RefSegment> = Vec::new();
    let mut in_shadow = false;
    for (event, e) in trace.events.iter().enumerate() {
        if let Event::Segment { depth, ray, .. } = e {
            segments.push(RefSegment {
                depth: *depth,
                ray: *ray,
                event,
                tests: Vec::new(),
                hit: None,
                lights: Vec::new(),
                seen: None,
            });
            continue;
        }
        let Some(segment) = segments.last_mut() else {
            continue;
        };
        let light = segment.lights.last_mut();
        match e {
            Event::Tested { object, t, .. } => {
                let tested = Tested {
                    object: *object,
                    t: *t,
                    event,
                };
                match light.and_then(|l| l.shadow.as_mut()).filter(|_| in_shadow) {
                    Some(shadow) => shadow.tests.push(tested),
                    None => segment.tests.push(tested),
                }
            }
            Event::Surface {
                object,
                t,
                total_dist,
                surface,
                material,
                ..
            } => {
                segment.hit = Some(RefHit {
                    object: *object,
                    t: *t,
                    point: surface.point,
                    normal: surface.normal,
                    total_dist: *total_dist,
                    diffuse: material.diffuse,
                    event,
                })
            }
            Event::Lamp { light } => segment.lights.push(LightTerm {
                light: *light,
                event,
                towards: None,
                shadow: None,
                lit: None,
            }),
            Event::Light(step) => {
                let Some(light) = light else { continue };
                match *step {
                    LightStep::Towards { u, dist, cos } => {
                        light.towards = Some((u, dist, cos, event));
                    }
                    LightStep::ShadowRay { .. } => {
                        in_shadow = true;
                        light.shadow = Some(Shadow::default());
                    }
                    LightStep::Blocked { blocker } => {
                        in_shadow = false;
                        if let Some(shadow) = light.shadow.as_mut() {
                            shadow.blocker = blocker;
                            shadow.blocked = event;
                        }
                    }
                    _ => {}
                }
            }
            Event::Lit { intensity, .. } => {
                if let Some(light) = light {
                    light.lit = Some((*intensity, event));
                }
            }
            Event::Divided { seen, .. } => segment.seen = Some((*seen, event)),
            _ => {}
        }
    }
    segments
}

/// Fails when the trace cannot be of this scene: its camera ray tests another number of
/// objects than the scene has (one `FND`, for the winner, as some copies print, is
/// allowed), or a light block's centre is none of the scene's lights.
fn same_scene(scene: &Scene, segments: &[Segment]) -> Result<(), Unreadable> {
    let another = |why: String| {
        Err(Unreadable(format!(
            "{why}: the trace is of another scene (or the scene was changed since)"
        )))
    };
    let camera = segments.first().map_or(&[][..], |s| &s.tests[..]);
    let objects = scene.objects.len();
    if camera.len() > 1 && camera.len() != objects {
        return another(format!(
            "its camera ray tests {} objects (FND lines from line {}), and this scene has {objects}",
            camera.len(),
            camera[0].line
        ));
    }
    for block in segments.iter().flat_map(|s| &s.blocks) {
        let Some((centre, line)) = block.get(Label::LightCenter) else {
            continue;
        };
        if !scene.lights.iter().any(|l| close3(centre, l.location)) {
            return another(format!(
                "its light centre {} (line {line}) is none of this scene's lights",
                printed3(centre)
            ));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Ids

/// What a course id names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Named {
    Object(usize),
    Light(usize),
}

/// The student's ids: where they start, and what each names.
struct Ids {
    base: i64,
    /// By course id from 0: what it names.
    records: Vec<Named>,
    /// The course id (from 0) of each object.
    course: CourseIds,
    /// The first `FND` whose id is not this scene's under base 0 or 100, if the ids
    /// had to be read from another base: (the student's id, the object it is at).
    wrong: Option<(i64, usize, usize)>,
}

impl Ids {
    fn new(scene: &Scene, segments: &[Segment]) -> Result<Ids, Unreadable> {
        let course = CourseIds::new(scene);
        let mut records = vec![Named::Object(0); scene.objects.len() + scene.lights.len()];
        for index in 0..scene.objects.len() {
            records[course.object(index)] = Named::Object(index);
        }
        for index in 0..scene.lights.len() {
            records[course.light(index)] = Named::Light(index);
        }
        let mut objects = Vec::new();
        let mut lights = Vec::new();
        for segment in segments {
            objects.extend(segment.tests.iter().map(|f| f.id));
            objects.extend(segment.hit.map(|h| h.0));
            for block in &segment.blocks {
                objects.extend(block.shadow.iter().map(|f| f.id));
                for (label, values, _) in &block.fields {
                    let id = values[0].value as i64;
                    match label {
                        Label::HitObject | Label::OccludedBy => objects.push(id),
                        Label::LightObject => lights.push(id),
                        _ => {}
                    }
                }
            }
        }
        let mut ids = Ids {
            base: 0,
            records,
            course,
            wrong: None,
        };
        let fits = |ids: &Ids| {
            objects
                .iter()
                .all(|&id| matches!(ids.named(id), Some(Named::Object(_))))
                && lights
                    .iter()
                    .all(|&id| matches!(ids.named(id), Some(Named::Light(_))))
        };
        for base in [0, 100] {
            ids.base = base;
            if fits(&ids) {
                return Ok(ids);
            }
        }
        // Neither base: if the camera ray tests every object, its n-th FND is the n-th
        // object, and the ids are read from where that puts them.
        let camera = segments.first().map_or(&[][..], |s| &s.tests[..]);
        if !camera.is_empty() && camera.len() == scene.objects.len() {
            let base = camera[0].id - ids.course.object(0) as i64;
            ids.base = base;
            let in_order = camera
                .iter()
                .enumerate()
                .all(|(k, f)| f.id - base == ids.course.object(k) as i64);
            if in_order && fits(&ids) {
                ids.wrong = Some((camera[0].id, 0, camera[0].line));
                return Ok(ids);
            }
        }
        let mut seen: Vec<i64> = objects.iter().chain(&lights).copied().collect();
        seen.sort_unstable();
        seen.dedup();
        let shown: Vec<String> = seen.iter().take(12).map(i64::to_string).collect();
        let more = if seen.len() > 12 { ", ..." } else { "" };
        Err(Unreadable(format!(
            "its ids ({}{more}) are not this scene's: the scene's {} lights and objects are \
             numbered in file order from 0 or 100 (spec §7.1), and its camera ray tests {} \
             objects where the scene has {}: the trace is of another scene",
            shown.join(", "),
            ids.records.len(),
            camera.len(),
            scene.objects.len()
        )))
    }

    /// What the student's `id` names.
    fn named(&self, id: i64) -> Option<Named> {
        let k = usize::try_from(id - self.base).ok()?;
        self.records.get(k).copied()
    }

    fn object(&self, id: i64) -> Option<usize> {
        match self.named(id)? {
            Named::Object(index) => Some(index),
            Named::Light(_) => None,
        }
    }

    fn light(&self, id: i64) -> Option<usize> {
        match self.named(id)? {
            Named::Light(index) => Some(index),
            Named::Object(_) => None,
        }
    }
}

// ---------------------------------------------------------------------------------------
// Comparing

/// Whether a printed number is the reference's value, within what printing rounded away
/// and a relative 1e-6 for a student's own (correct) arithmetic.
fn close(printed: Num, reference: f64) -> bool {
    if printed.value.is_nan() || reference.is_nan() {
        return printed.value.is_nan() && reference.is_nan();
    }
    (printed.value - reference).abs() <= printed.half_unit + 1e-6 * reference.abs().max(1.0)
}

/// Whether a printed vector is the reference's.
fn close3(printed: &[Num], reference: DVec3) -> bool {
    printed.len() == 3 && (0..3).all(|k| close(printed[k], reference[k]))
}

/// The printed vector's length: 1 when it is a unit vector as far as the printing tells
/// (or when it has no length).
fn length(printed: &[Num]) -> f64 {
    let v = DVec3::new(printed[0].value, printed[1].value, printed[2].value);
    let length = v.length();
    let rounding: f64 = printed.iter().map(|n| n.half_unit).sum();
    if length.is_finite() && length > 0.0 && (length - 1.0).abs() > rounding + 1e-6 {
        length
    } else {
        1.0
    }
}

/// A printed vector scaled to unit length, with its rounding scaled alike.
fn unit(printed: &[Num]) -> [Num; 3] {
    let l = length(printed);
    [0, 1, 2].map(|k| Num {
        value: printed[k].value / l,
        half_unit: printed[k].half_unit / l,
    })
}

/// A number as the reports print it: six decimals at most.
fn show(v: f64) -> String {
    if v.is_nan() {
        return "nan".into();
    }
    let text = format!("{v:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

fn show3(v: DVec3) -> String {
    format!("({}, {}, {})", show(v.x), show(v.y), show(v.z))
}

fn printed3(v: &[Num]) -> String {
    let parts: Vec<String> = v.iter().map(|n| show(n.value)).collect();
    format!("({})", parts.join(", "))
}

/// Whether a printed t says the ray hits: a positive number (a negative one, -1 or a NaN
/// is a miss, spec §8).
fn hits(t: Num) -> bool {
    t.value > 0.0
}

struct Compare<'a> {
    scene: &'a Scene,
    ids: &'a Ids,
    checks: Vec<Check>,
}

/// Where a check is: the step, the object, the reference's event, the student's line.
#[derive(Clone)]
struct At {
    event: String,
    object: Option<String>,
    event_index: usize,
    line: usize,
}

impl Compare<'_> {
    fn check(
        &mut self,
        at: &At,
        quantity: &str,
        yours: String,
        reference: String,
        sentence: Option<String>,
    ) {
        self.checks.push(Check {
            event: at.event.clone(),
            object: at.object.clone(),
            quantity: quantity.into(),
            yours,
            reference,
            agrees: sentence.is_none(),
            student_line: at.line,
            sentence: sentence.unwrap_or_default(),
            event_index: at.event_index,
        });
    }

    /// Compares a value: `printed` against `reference`.
    fn value(&mut self, at: &At, quantity: &str, printed: Num, reference: f64) {
        let agrees = close(printed, reference);
        let sentence = (!agrees).then(|| {
            format!(
                "your {quantity} is {}, the reference's {}",
                show(printed.value),
                show(reference)
            )
        });
        self.check(at, quantity, show(printed.value), show(reference), sentence);
    }

    /// Compares a vector.
    fn vector(&mut self, at: &At, quantity: &str, printed: &[Num], reference: DVec3) {
        let agrees = close3(printed, reference);
        let sentence = (!agrees).then(|| {
            format!(
                "your {quantity} is {}, the reference's {}",
                printed3(printed),
                show3(reference)
            )
        });
        self.check(at, quantity, printed3(printed), show3(reference), sentence);
    }

    fn object_name(&self, index: usize) -> String {
        object_name(self.scene, index)
    }

    /// The whole path, ray by ray.
    fn path(&mut self, segments: &[Segment], reference: &[RefSegment]) {
        if let Some((id, object, line)) = self.ids.wrong {
            let at = At {
                event: "camera ray".into(),
                object: Some(self.object_name(object)),
                event_index: reference.first().map_or(0, |s| s.event),
                line,
            };
            let course = self.ids.course.object(object);
            self.check(
                &at,
                "id",
                id.to_string(),
                format!("{course} (or {})", course + 100),
                Some(format!(
                    "yours numbers it {id}; one counter over lights and objects in file \
                     order, from 0 (or 100), makes it {course} (spec §7.1): every id after \
                     it is off by {}",
                    id - course as i64
                )),
            );
        }
        let printed_rays = segments
            .iter()
            .any(|s| !s.tests.is_empty() || s.hit.is_some());
        let count = segments.len().max(reference.len());
        for k in 0..count {
            let ours = reference.get(k);
            let theirs = segments.get(k);
            match (ours, theirs) {
                (Some(ours), Some(theirs)) => self.segment(theirs, ours),
                (Some(ours), None)
                    if printed_rays && (!ours.tests.is_empty() || ours.hit.is_some()) =>
                {
                    let at = At {
                        event: ray_name(ours.depth),
                        object: None,
                        event_index: ours.event,
                        line: segments.last().map_or(0, last_line),
                    };
                    let what = match ours.hit {
                        Some(hit) => format!("hits {}", self.object_name(hit.object)),
                        None => "hits nothing".into(),
                    };
                    self.check(
                        &at,
                        "ray",
                        "none".into(),
                        what.clone(),
                        Some(format!(
                            "the reference traces {} (it {what}); your trace has no such ray",
                            ray_name(ours.depth)
                        )),
                    );
                }
                (None, Some(theirs)) => {
                    let depth = reference.len();
                    let at = At {
                        event: ray_name(k),
                        object: None,
                        event_index: reference.last().map_or(0, |s| s.event),
                        line: first_line(theirs),
                    };
                    let why = if depth == 0 {
                        "the pixel has no camera ray".to_string()
                    } else {
                        "the reference's path ends before it (no specular, or MAX_DIST)".into()
                    };
                    self.check(
                        &at,
                        "ray",
                        "traced".into(),
                        "none".into(),
                        Some(format!("your trace has {}; {why}", ray_name(k))),
                    );
                }
                _ => {}
            }
        }
    }

    /// One ray: its tests, its hit, its lights, its intensity.
    fn segment(&mut self, theirs: &Segment, ours: &RefSegment) {
        let event = ray_name(ours.depth);
        self.tests(
            &event,
            &theirs.tests,
            &ours.tests,
            Some(1.0),
            None,
            ours.ray.dir,
        );
        let Some((id, t, point, line)) = theirs.hit else {
            self.lights(&event, theirs, ours);
            self.amb(&event, theirs, ours);
            return;
        };
        let at = At {
            event: event.clone(),
            object: self.ids.object(id).map(|o| self.object_name(o)),
            event_index: ours.hit.map_or(ours.event, |h| h.event),
            line,
        };
        let Some(hit) = ours.hit else {
            let name = at.object.clone().unwrap_or_else(|| format!("id {id}"));
            self.check(
                &at,
                "closest object",
                format!("{name} at t = {}", show(t.value)),
                "nothing".into(),
                Some(format!(
                    "yours hits {name} at t = {}{}; the reference's ray hits nothing",
                    show(t.value),
                    behind(t)
                )),
            );
            return;
        };
        let same = self.ids.object(id) == Some(hit.object);
        let theirs_name = at.object.clone().unwrap_or_else(|| format!("id {id}"));
        let ours_name = self.object_name(hit.object);
        let sentence = (!same).then(|| {
            format!(
                "your closest hit is {theirs_name} at t = {}{}; the reference's is {ours_name} at t = {}",
                show(t.value),
                behind(t),
                show(hit.t)
            )
        });
        self.check(&at, "closest object", theirs_name, ours_name, sentence);
        if !same {
            return;
        }
        self.value(&at, "t of the hit", t, hit.t);
        self.vector(&at, "hit point", &point, hit.point);
        if let Some((total, line)) = theirs.total {
            let at = At { line, ..at.clone() };
            self.value(&at, "path length", total, hit.total_dist);
        }
        self.lights(&event, theirs, ours);
        self.amb(&event, theirs, ours);
    }

    /// A ray's `FND` lines against the reference's tests of the same objects. `scale` is
    /// the length of the ray's printed direction where it was not a unit vector; `None`
    /// where the student's direction is not known (a shadow ray whose direction to the
    /// light was not printed): then hits and misses are compared, not t (spec §8).
    fn tests(
        &mut self,
        event: &str,
        theirs: &[Found],
        ours: &[Tested],
        scale: Option<f64>,
        blocker: Option<(usize, f64)>,
        dir: DVec3,
    ) {
        for found in theirs {
            let Some(object) = self.ids.object(found.id) else {
                let at = At {
                    event: event.into(),
                    object: None,
                    event_index: ours.first().map_or(0, |t| t.event),
                    line: found.line,
                };
                self.check(
                    &at,
                    "id",
                    found.id.to_string(),
                    "an object's id".into(),
                    Some(format!(
                        "your FND names id {}, which is not an object of the scene (ids from {})",
                        found.id, self.ids.base
                    )),
                );
                continue;
            };
            let Some(tested) = ours.iter().find(|t| t.object == object) else {
                continue;
            };
            let at = At {
                event: event.into(),
                object: Some(self.object_name(object)),
                event_index: tested.event,
                line: found.line,
            };
            // The ray's printed direction, if the three-line form gave it.
            let scale = match &found.dir {
                Some(printed) => {
                    let unit = unit(printed);
                    if !close3(&unit, dir) {
                        self.vector(&at, "ray direction", &unit, dir);
                    }
                    Some(length(printed))
                }
                None => scale,
            };
            let yours = if hits(found.t) {
                format!("hits at t = {}", show(found.t.value))
            } else {
                format!("misses (t = {})", show(found.t.value))
            };
            // The course's sphere returns its nearer root whatever its sign; the closest
            // hit takes only t > 0 (spec §4.6), and so does this comparison.
            match (hits(found.t), tested.t.filter(|&t| t > 0.0)) {
                (true, Some(t)) if scale.is_none() => {
                    let reference = format!("hits at t = {}", show(t));
                    self.check(&at, "hit or miss", yours, reference, None);
                }
                (true, Some(t)) => {
                    let scale = scale.unwrap_or(1.0);
                    let unit_t = Num {
                        value: found.t.value * scale,
                        half_unit: found.t.half_unit * scale,
                    };
                    let agrees = close(unit_t, t);
                    let sentence = (!agrees).then(|| {
                        let units = if scale != 1.0 {
                            format!(" ({} along a unit direction)", show(unit_t.value))
                        } else {
                            String::new()
                        };
                        format!(
                            "yours hits at t = {}{units}, the reference at t = {}",
                            show(found.t.value),
                            show(t)
                        )
                    });
                    self.check(&at, "t", show(found.t.value), show(t), sentence);
                }
                (false, None) => self.check(&at, "hit or miss", yours, "misses".into(), None),
                (true, None) => {
                    let sentence = format!("{yours}, the reference misses");
                    self.check(&at, "hit or miss", yours, "misses".into(), Some(sentence));
                }
                (false, Some(t)) => {
                    let blocks = if blocker.is_some_and(|(b, _)| b == object) {
                        " and blocks the light"
                    } else {
                        ""
                    };
                    let reference = format!("hits at t = {}", show(t));
                    let sentence = format!(
                        "yours {yours}, the reference hits at t = {}{blocks}",
                        show(t)
                    );
                    self.check(&at, "hit or miss", yours, reference, Some(sentence));
                }
            }
        }
    }

    /// Each light's block against the reference's term of the light.
    fn lights(&mut self, event: &str, theirs: &Segment, ours: &RefSegment) {
        let mut next = 0;
        for block in &theirs.blocks {
            let by_id = block
                .get(Label::LightObject)
                .and_then(|(v, _)| self.ids.light(v[0].value as i64));
            let term = match by_id {
                Some(light) => ours.lights.iter().position(|l| l.light == light),
                None => {
                    let printed = |l: &LightTerm| {
                        l.towards.is_some_and(|(_, _, cos, _)| cos > 0.0)
                            || block.get(Label::Cos).is_some() && l.towards.is_some()
                    };
                    (next..ours.lights.len()).find(|&k| printed(&ours.lights[k]))
                }
            };
            let Some(term) = term else { continue };
            next = term + 1;
            self.light(event, block, &ours.lights[term], ours.hit);
        }
    }

    /// One light's block.
    fn light(&mut self, event: &str, block: &Block, term: &LightTerm, hit: Option<RefHit>) {
        let name = light_name(self.scene, term.light);
        let at = |line: usize, event_index: usize| At {
            event: format!("{event}, {name}"),
            object: hit.map(|h| object_name(self.scene, h.object)),
            event_index,
            line,
        };
        if let (Some(hit), Some((v, line))) = (hit, block.get(Label::HitObject)) {
            let at = at(line, term.event);
            let id = v[0].value as i64;
            let agrees = self.ids.object(id) == Some(hit.object);
            let sentence = (!agrees).then(|| {
                format!(
                    "your diffuse block is for id {id}, the reference's hit is {} (id {})",
                    object_name(self.scene, hit.object),
                    self.ids.course.object(hit.object) as i64 + self.ids.base
                )
            });
            self.check(
                &at,
                "hit object id",
                id.to_string(),
                hit.object.to_string(),
                sentence,
            );
        }
        if let Some(hit) = hit {
            if let Some((v, line)) = block.get(Label::HitPoint) {
                self.vector(&at(line, hit.event), "hit point", v, hit.point);
            }
            if let Some((v, line)) = block.get(Label::Normal) {
                let unit = unit(v);
                let at = at(line, hit.event);
                let agrees = close3(&unit, hit.normal);
                let flipped = close3(&unit, -hit.normal);
                let sentence = (!agrees).then(|| {
                    let why = if flipped { ": it is flipped" } else { "" };
                    format!(
                        "your normal is {}, the reference's {}{why}",
                        printed3(v),
                        show3(hit.normal)
                    )
                });
                self.check(&at, "normal", printed3(v), show3(hit.normal), sentence);
            }
        }
        let lamp = &self.scene.lights[term.light];
        if let Some((v, line)) = block.get(Label::LightCenter) {
            self.vector(&at(line, term.event), "light centre", v, lamp.location);
        }
        // The length of the student's direction to the light, if printed: some copies
        // print it before normalising it, and their shadow ray's t is in its units.
        let mut scale = None;
        if let Some((u, dist, cos, event_index)) = term.towards {
            if let Some((v, line)) = block.get(Label::ToLight) {
                scale = Some(length(v));
                let unit = unit(v);
                let at = at(line, event_index);
                let agrees = close3(&unit, u);
                let sentence = (!agrees).then(|| {
                    format!(
                        "your direction to the light is {}, the reference's {}",
                        printed3(v),
                        show3(u)
                    )
                });
                self.check(
                    &at,
                    "direction to the light",
                    printed3(v),
                    show3(u),
                    sentence,
                );
            }
            if let Some((v, line)) = block.get(Label::Distance) {
                self.value(&at(line, event_index), "distance to the light", v[0], dist);
            }
            if let Some((v, line)) = block.get(Label::Cos) {
                self.value(&at(line, event_index), "cos θ", v[0], cos);
            }
        }
        let shadow_event = format!("shadow ray to {name}");
        if let Some(shadow) = &term.shadow {
            let dir = term.towards.map_or(DVec3::ZERO, |t| t.0);
            self.tests(
                &shadow_event,
                &block.shadow,
                &shadow.tests,
                scale,
                shadow.blocker,
                dir,
            );
        }
        let blocker = term.shadow.as_ref().and_then(|s| s.blocker);
        let shadow_at = |line: usize| At {
            event: shadow_event.clone(),
            object: None,
            event_index: term.shadow.as_ref().map_or(term.event, |s| s.blocked),
            line,
        };
        match (block.get(Label::OccludedBy), blocker) {
            (Some((v, line)), Some((object, t))) => {
                let id = v[0].value as i64;
                let mut at = shadow_at(line);
                at.object = Some(object_name(self.scene, object));
                let agrees = self.ids.object(id) == Some(object);
                let sentence = (!agrees).then(|| {
                    format!(
                        "yours is occluded by id {id}, the reference's by {}",
                        object_name(self.scene, object)
                    )
                });
                self.check(
                    &at,
                    "occluded by",
                    id.to_string(),
                    object_name(self.scene, object),
                    sentence,
                );
                if let (true, Some((v, line)), Some(scale)) =
                    (agrees, block.get(Label::DistanceWas), scale)
                {
                    let at = At { line, ..at };
                    let scaled = Num {
                        value: v[0].value * scale,
                        half_unit: v[0].half_unit * scale,
                    };
                    self.value(&at, "distance to the occluding object", scaled, t);
                }
            }
            (Some((v, line)), None) => {
                let id = v[0].value as i64;
                let at = shadow_at(line);
                let name = self
                    .ids
                    .object(id)
                    .map_or(format!("id {id}"), |o| object_name(self.scene, o));
                self.check(
                    &at,
                    "occluded by",
                    name.clone(),
                    "not blocked".into(),
                    Some(format!(
                        "yours is occluded by {name}; the reference's shadow ray is not blocked"
                    )),
                );
            }
            (None, Some((object, t))) if lit_block(block) => {
                let line = block
                    .get(Label::Ivec)
                    .or(block.get(Label::Emissivity))
                    .map_or(block.line(), |f| f.1);
                let mut at = shadow_at(line);
                at.object = Some(object_name(self.scene, object));
                self.check(
                    &at,
                    "occluded by",
                    "not blocked".into(),
                    object_name(self.scene, object),
                    Some(format!(
                        "yours lights the point; the reference's shadow ray is blocked by {} at t = {}",
                        object_name(self.scene, object),
                        show(t)
                    )),
                );
            }
            _ => {}
        }
        if let Some((v, line)) = block.get(Label::Emissivity) {
            self.vector(&at(line, term.event), "emissivity", v, lamp.emissivity);
        }
        if let (Some((v, line)), Some(hit)) = (block.get(Label::Reflectivity), hit) {
            self.vector(&at(line, hit.event), "diffuse reflectivity", v, hit.diffuse);
        }
        if let (Some((v, line)), Some((intensity, event_index))) =
            (block.get(Label::Ivec), term.lit)
        {
            self.vector(&at(line, event_index), "intensity (ivec)", v, intensity);
        }
    }

    /// The segment's `AMB` against the intensity divided by the path's length.
    fn amb(&mut self, event: &str, theirs: &Segment, ours: &RefSegment) {
        if let (Some((v, line)), Some((seen, event_index))) = (theirs.amb, ours.seen) {
            let at = At {
                event: event.into(),
                object: ours.hit.map(|h| self.object_name(h.object)),
                event_index,
                line,
            };
            self.vector(&at, "intensity / path (AMB)", &v, seen);
        }
    }
}

/// Whether a block says the light was added (not occluded).
fn lit_block(block: &Block) -> bool {
    block.get(Label::Ivec).is_some() || block.get(Label::Emissivity).is_some()
}

/// " (behind the ray's base)" for a negative t.
fn behind(t: Num) -> &'static str {
    if t.value < 0.0 {
        ", a root behind the ray's base"
    } else {
        ""
    }
}

fn ray_name(depth: usize) -> String {
    if depth == 0 {
        "camera ray".into()
    } else {
        format!("reflected ray {depth}")
    }
}

fn first_line(segment: &Segment) -> usize {
    let test = segment.tests.first().map(|f| f.line);
    test.or(segment.hit.map(|h| h.3)).unwrap_or(0)
}

fn last_line(segment: &Segment) -> usize {
    let lines = [
        segment.tests.last().map(|f| f.line),
        segment.hit.map(|h| h.3),
        segment.amb.map(|a| a.1),
        segment
            .blocks
            .last()
            .and_then(|b| b.fields.last())
            .map(|f| f.2),
    ];
    lines.into_iter().flatten().max().unwrap_or(0)
}

// ---------------------------------------------------------------------------------------
// The report

impl Report {
    /// The text report: agreement in a line, or the first difference with both values,
    /// the student's line, the reference's trace around it, and what differs after it.
    pub fn text(&self, scene: &Scene, trace: &Trace, file: &str, student: &str) -> String {
        let mut out = String::new();
        let (x, y) = self.pixel;
        let compared = self.compared.len();
        for note in &self.notes {
            let _ = writeln!(out, "note: {note}");
        }
        let Some(first) = self.first_difference() else {
            let _ = writeln!(
                out,
                "your trace of pixel ({x}, {y}) ({file}, lines {}-{}) agrees with the \
                 reference: {compared} values compared within their printed precision",
                self.lines.0, self.lines.1
            );
            return out;
        };
        let _ = writeln!(
            out,
            "first difference: {}: {}",
            first.place(),
            first.sentence
        );
        let line = student
            .lines()
            .nth(first.student_line.saturating_sub(1))
            .unwrap_or("");
        let _ = writeln!(
            out,
            "  yours ({file} line {}): {}",
            first.student_line,
            line.trim()
        );
        let _ = writeln!(out, "  the reference: {}", first.reference);
        let (readable, starts) = trace.readable_with_starts(scene);
        let lines: Vec<&str> = readable.lines().collect();
        let at = starts.get(first.event_index).copied().unwrap_or(0);
        let from = at.saturating_sub(3);
        let to = (at + 4).min(lines.len());
        let (w, h) = (trace.options.width, trace.options.height);
        let _ = writeln!(
            out,
            "the reference's trace around it (legacy-rt trace {x} {y} {w} {h}):"
        );
        for (k, text) in lines.iter().enumerate().take(to).skip(from) {
            let mark = if k == at { ">" } else { " " };
            let _ = writeln!(out, "{mark} {text}");
        }
        let rest: Vec<&Check> = self.compared.iter().filter(|c| !c.agrees).skip(1).collect();
        if rest.is_empty() {
            let _ = writeln!(out, "nothing else differs ({compared} values compared)");
        } else {
            let _ = writeln!(
                out,
                "after it, {} more differ (a first difference often explains the rest):",
                rest.len()
            );
            for check in rest.iter().take(5) {
                let _ = writeln!(
                    out,
                    "  line {}: {}: {}",
                    check.student_line,
                    check.place(),
                    check.sentence
                );
            }
            if rest.len() > 5 {
                let _ = writeln!(
                    out,
                    "  ... and {} more (--json lists them all)",
                    rest.len() - 5
                );
            }
        }
        out
    }
}
