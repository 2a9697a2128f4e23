//! A pixel's path twice, grouped alike: the student's block as the course's `ray_trace`
//! printed it ([`student`]), and the reference's trace ([`reference()`]). Each is a list
//! of the path's rays (the camera ray, then each mirror's), and on each its objects'
//! tests, its hit, each light's term with its shadow ray, and the intensity divided by
//! the path's length.

use super::layout::Units;
use super::lex::{Item, Label, Num, Said};
use crate::render::{Event, LightStep, Trace};
use crate::shapes::Ray;
use glam::DVec3;

/// A vector as printed.
pub fn vector(v: &[Num]) -> DVec3 {
    DVec3::new(v[0].value, v[1].value, v[2].value)
}

/// Half a unit of the last digit of a printed vector's coarsest number.
pub fn slack(v: &[Num]) -> f64 {
    v.iter().map(|n| n.half_unit).fold(0.0, f64::max)
}

/// One `FND` line, with the three-line form's extra lines if printed.
#[derive(Debug, Clone)]
pub struct Found {
    /// The object's id.
    pub id: i64,
    /// Its t as printed.
    pub t: Num,
    /// The line, from 1.
    pub line: usize,
    /// The line's text.
    pub text: String,
    /// The ray's base, as the three-line form prints it.
    pub base: Option<[Num; 3]>,
    /// The ray's direction.
    pub dir: Option<[Num; 3]>,
    /// The point base + t·direction.
    pub hits: Option<[Num; 3]>,
}

impl Found {
    /// Whether the printed t says the ray hits: a positive number (a negative one, -1 or
    /// a NaN is a miss, spec §8).
    pub fn hits(&self) -> bool {
        self.t.value > 0.0
    }

    /// The units of t, where the line's point tells them: a hit along a direction that is
    /// not a unit vector, whose point is base + t·direction or base + t·unit(direction).
    pub fn units(&self) -> Option<Units> {
        let (base, dir, hits) = (self.base?, self.dir?, self.hits?);
        let t = self.t.value;
        let d = vector(&dir);
        let length = d.length();
        if !(t > 0.0 && t.is_finite() && length.is_finite() && length > 0.0) {
            return None;
        }
        if (length - 1.0).abs() <= 3.0 * slack(&dir) + 1e-6 {
            return Some(Units::Unit);
        }
        let tolerance = 3.0 * (slack(&hits) + slack(&base) + t * slack(&dir))
            + self.t.half_unit * length
            + 1e-6 * (1.0 + vector(&hits).length());
        let along_unit = (vector(&base) + t * d / length - vector(&hits)).length() <= tolerance;
        let along_printed = (vector(&base) + t * d - vector(&hits)).length() <= tolerance;
        match (along_unit, along_printed) {
            (true, false) => Some(Units::Unit),
            (false, true) => Some(Units::Printed),
            _ => None,
        }
    }
}

/// A label and its values.
#[derive(Debug, Clone)]
pub struct Field {
    /// The label.
    pub label: Label,
    /// Its values.
    pub values: Vec<Num>,
    /// The line, from 1.
    pub line: usize,
    /// The line's text.
    pub text: String,
}

/// One light's diffuse block, and the `FND` lines of its shadow ray.
#[derive(Debug, Clone, Default)]
pub struct LightBlock {
    /// Its labelled values, in the order printed.
    pub fields: Vec<Field>,
    /// Its shadow ray's tests.
    pub shadow: Vec<Found>,
    /// Whether the shadow ray came after the light's geometry (the course's own order).
    shadow_after: bool,
}

impl LightBlock {
    /// The field of `label`, if printed.
    pub fn get(&self, label: Label) -> Option<&Field> {
        self.fields.iter().find(|f| f.label == label)
    }

    /// Whether the block says the light was added (printed its contribution).
    pub fn adds(&self) -> bool {
        self.get(Label::Ivec).is_some() || self.get(Label::Emissivity).is_some()
    }

    /// Its first line.
    pub fn line(&self) -> usize {
        let fields = self.fields.iter().map(|f| f.line);
        let shadow = self.shadow.iter().map(|f| f.line);
        fields.chain(shadow).min().unwrap_or(0)
    }

    /// Whether the block has taken a value that comes after the shadow ray.
    fn past_geometry(&self) -> bool {
        self.shadow_after || self.fields.iter().any(|f| !f.label.geometry())
    }
}

/// A `HIT` line.
#[derive(Debug, Clone)]
pub struct HitLine {
    /// The object's id.
    pub id: i64,
    /// t.
    pub t: Num,
    /// The point.
    pub point: [Num; 3],
    /// The line, from 1.
    pub line: usize,
    /// The line's text.
    pub text: String,
}

/// A value printed on a line.
#[derive(Debug, Clone)]
pub struct Printed<T> {
    /// The value.
    pub value: T,
    /// The line, from 1.
    pub line: usize,
    /// The line's text.
    pub text: String,
}

/// One ray of the path as the student printed it.
#[derive(Debug, Clone, Default)]
pub struct Segment {
    /// Its objects' tests.
    pub tests: Vec<Found>,
    /// Its closest hit.
    pub hit: Option<HitLine>,
    /// `The total dist is`.
    pub total: Option<Printed<Num>>,
    /// Each light's block.
    pub blocks: Vec<LightBlock>,
    /// `AMB`.
    pub amb: Option<Printed<[Num; 3]>>,
}

/// What the grouping sees: a run of `FND` lines (one ray's tests) or another line.
enum Element<'a> {
    Run(Vec<Found>),
    Line(&'a Item),
}

/// `items` as runs of `FND` lines and the other lines. A run ends at any other line, and
/// where the printed ray changes (a copy that prints the three-line form for shadow rays
/// of several lights in a row).
fn elements(items: &[Item]) -> Vec<Element<'_>> {
    let mut out: Vec<Element> = Vec::new();
    let mut run: Vec<Found> = Vec::new();
    let close = |run: &mut Vec<Found>, out: &mut Vec<Element>| {
        if !run.is_empty() {
            out.push(Element::Run(std::mem::take(run)));
        }
    };
    for item in items {
        match &item.said {
            Said::Found(id, t) => {
                let found = Found {
                    id: *id,
                    t: *t,
                    line: item.line,
                    text: item.text.clone(),
                    base: None,
                    dir: None,
                    hits: None,
                };
                run.push(found);
            }
            Said::FoundBase(v) | Said::FoundDir(v) | Said::FoundHits(v) => {
                let Some(last) = run.last_mut() else { continue };
                let slot = match item.said {
                    Said::FoundBase(_) => &mut last.base,
                    Said::FoundDir(_) => &mut last.dir,
                    _ => &mut last.hits,
                };
                if slot.is_none() {
                    *slot = Some(*v);
                }
                // A new ray: this FND's base or direction is not the previous one's.
                if run.len() > 1 && matches!(item.said, Said::FoundDir(_)) {
                    let k = run.len() - 1;
                    let same = |a: Option<[Num; 3]>, b: Option<[Num; 3]>| match (a, b) {
                        (Some(a), Some(b)) => (0..3).all(|i| a[i].value == b[i].value),
                        _ => true,
                    };
                    if !same(run[k - 1].base, run[k].base) || !same(run[k - 1].dir, run[k].dir) {
                        let last = run.pop().expect("it has two");
                        close(&mut run, &mut out);
                        run.push(last);
                    }
                }
            }
            Said::Pix { .. } | Said::World(..) | Said::Diffuse(_) => {}
            _ => {
                close(&mut run, &mut out);
                out.push(Element::Line(item));
            }
        }
    }
    close(&mut run, &mut out);
    out
}

/// The student's block grouped into the path's rays. A run of `FND` lines followed by a
/// label of the diffuse block is a shadow ray's: of the open light's block when the label
/// comes after the shadow ray (`Emissivity`, `occluded by`: the course's own copy prints
/// the ray after the light's geometry), else of the block the label starts (copies that
/// print the ray first). Any other run starts the next ray of the path (the mirror's).
/// `HIT` and `AMB` go to the latest ray without one, so that copies that print them
/// after the mirror's recursion are read as well as those that print them before.
pub fn student(items: &[Item]) -> Vec<Segment> {
    let elements = elements(items);
    let mut segments: Vec<Segment> = Vec::new();
    // A shadow ray printed before the block it belongs to.
    let mut waiting: Vec<Found> = Vec::new();
    for (k, element) in elements.iter().enumerate() {
        match element {
            Element::Run(run) => {
                let next_label = match elements.get(k + 1) {
                    Some(Element::Line(Item {
                        said: Said::Labelled(label, _),
                        ..
                    })) => Some(*label),
                    _ => None,
                };
                let started = !segments.is_empty();
                let open = segments
                    .last_mut()
                    .and_then(|s| s.blocks.last_mut())
                    .filter(|b| {
                        b.shadow.is_empty() && !b.fields.iter().any(|f| !f.label.geometry())
                    });
                match (next_label, open) {
                    (Some(label), Some(block)) if !label.geometry() => {
                        block.shadow = run.clone();
                        block.shadow_after = true;
                    }
                    (Some(_), _) if started => waiting = run.clone(),
                    _ => segments.push(Segment {
                        tests: run.clone(),
                        ..Segment::default()
                    }),
                }
            }
            Element::Line(item) => match &item.said {
                Said::Labelled(label, values) => {
                    if segments.is_empty() {
                        segments.push(Segment::default());
                    }
                    let segment = segments.last_mut().expect("one was pushed");
                    let field = Field {
                        label: *label,
                        values: values.clone(),
                        line: item.line,
                        text: item.text.clone(),
                    };
                    // A block ends with its intensity (`Current ivec`) or its occluder's
                    // distance; a label it already has, or one of the geometry after its
                    // shadow ray, starts the next.
                    let joins = segment.blocks.last().is_some_and(|b| {
                        b.get(*label).is_none()
                            && b.get(Label::Ivec).is_none()
                            && b.get(Label::DistanceWas).is_none()
                            && waiting.is_empty()
                            && (!label.geometry() || !b.past_geometry())
                    });
                    if !joins {
                        segment.blocks.push(LightBlock {
                            fields: Vec::new(),
                            shadow: std::mem::take(&mut waiting),
                            shadow_after: false,
                        });
                    }
                    let block = segment.blocks.last_mut().expect("one was pushed");
                    block.fields.push(field);
                }
                Said::Hit(id, t, point) => {
                    let at = match segments.iter().rposition(|s| s.hit.is_none()) {
                        Some(at) => at,
                        None => {
                            segments.push(Segment::default());
                            segments.len() - 1
                        }
                    };
                    segments[at].hit = Some(HitLine {
                        id: *id,
                        t: *t,
                        point: *point,
                        line: item.line,
                        text: item.text.clone(),
                    });
                }
                Said::TotalDist(total) => {
                    if let Some(s) = segments.iter_mut().rev().find(|s| s.hit.is_some()) {
                        s.total = Some(Printed {
                            value: *total,
                            line: item.line,
                            text: item.text.clone(),
                        });
                    }
                }
                Said::Amb(amb) => {
                    let at = match segments.iter().rposition(|s| s.amb.is_none()) {
                        Some(at) => at,
                        None => {
                            segments.push(Segment::default());
                            segments.len() - 1
                        }
                    };
                    segments[at].amb = Some(Printed {
                        value: *amb,
                        line: item.line,
                        text: item.text.clone(),
                    });
                }
                _ => {}
            },
        }
    }
    segments
}

/// Every `FND` of a block with its extra lines, wherever it is.
pub fn founds(items: &[Item]) -> Vec<Found> {
    elements(items)
        .into_iter()
        .filter_map(|e| match e {
            Element::Run(run) => Some(run),
            Element::Line(_) => None,
        })
        .flatten()
        .collect()
}

// ---------------------------------------------------------------------------------------
// The reference's trace, grouped the same way

/// One object tested by a reference ray, and the event that says so.
#[derive(Debug, Clone, Copy)]
pub struct Tested {
    /// The object's index.
    pub object: usize,
    /// Its t where it counts as a hit (t > 0, spec §4.6), `None` for a miss.
    pub t: Option<f64>,
    /// The event's index in the trace.
    pub event: usize,
}

/// A reference shadow ray.
#[derive(Debug, Clone, Default)]
pub struct Shadow {
    /// Its objects' tests.
    pub tests: Vec<Tested>,
    /// The objects it skips (the one it leaves).
    pub skipped: Vec<usize>,
    /// What blocks it: the object and t.
    pub blocker: Option<(usize, f64)>,
    /// The event of its verdict.
    pub verdict: usize,
}

/// One light's term in the reference.
#[derive(Debug, Clone)]
pub struct LightTerm {
    /// The light's index.
    pub light: usize,
    /// The event that starts it.
    pub event: usize,
    /// The unit vector to the light, the distance, cos θ, and the event.
    pub towards: Option<(DVec3, f64, f64, usize)>,
    /// The shadow ray, if cast.
    pub shadow: Option<Shadow>,
    /// The contribution, the intensity after it, and the event.
    pub lit: Option<(DVec3, DVec3, usize)>,
}

/// The hit of a reference segment.
#[derive(Debug, Clone, Copy)]
pub struct RefHit {
    /// The object.
    pub object: usize,
    /// t.
    pub t: f64,
    /// The point.
    pub point: DVec3,
    /// The unit normal.
    pub normal: DVec3,
    /// The path's length with this segment.
    pub total_dist: f64,
    /// The material's diffuse triple there.
    pub diffuse: DVec3,
    /// The material's specular triple there.
    pub specular: DVec3,
    /// The event.
    pub event: usize,
}

/// The division of a reference segment.
#[derive(Debug, Clone, Copy)]
pub struct Divided {
    /// The intensity divided.
    pub intensity: DVec3,
    /// The intensity / the path's length.
    pub seen: DVec3,
    /// The weight of the mirrors before.
    pub weight: DVec3,
    /// The path's length.
    pub total_dist: f64,
    /// The event.
    pub event: usize,
}

/// One ray of the reference's path.
#[derive(Debug, Clone)]
pub struct RefSegment {
    /// 0 for the camera ray, k for the k-th mirror's.
    pub depth: usize,
    /// The ray.
    pub ray: Ray,
    /// The event that starts it.
    pub event: usize,
    /// Its objects' tests.
    pub tests: Vec<Tested>,
    /// The objects it skips (the one it leaves, hidden ones).
    pub skipped: Vec<usize>,
    /// Its closest hit.
    pub hit: Option<RefHit>,
    /// Each light's term.
    pub lights: Vec<LightTerm>,
    /// The division.
    pub divided: Option<Divided>,
}

/// The reference's events grouped into the path's rays.
pub fn reference(trace: &Trace) -> Vec<RefSegment> {
    let mut segments: Vec<RefSegment> = Vec::new();
    let mut in_shadow = false;
    for (event, e) in trace.events.iter().enumerate() {
        if let Event::Segment { depth, ray, .. } = e {
            segments.push(RefSegment {
                depth: *depth,
                ray: *ray,
                event,
                tests: Vec::new(),
                skipped: Vec::new(),
                hit: None,
                lights: Vec::new(),
                divided: None,
            });
            continue;
        }
        let Some(segment) = segments.last_mut() else {
            continue;
        };
        let shadow = match segment.lights.last_mut() {
            Some(light) if in_shadow => light.shadow.as_mut(),
            _ => None,
        };
        match e {
            Event::Tested { object, t, .. } => {
                let tested = Tested {
                    object: *object,
                    // A sphere's smaller root is its t even when negative (spec §5.2),
                    // and no hit (§4.6).
                    t: t.filter(|t| *t > 0.0),
                    event,
                };
                match shadow {
                    Some(shadow) => shadow.tests.push(tested),
                    None => segment.tests.push(tested),
                }
            }
            Event::Skipped { object, .. } => match shadow {
                Some(shadow) => shadow.skipped.push(*object),
                None => segment.skipped.push(*object),
            },
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
                    specular: material.specular,
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
                let Some(light) = segment.lights.last_mut() else {
                    continue;
                };
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
                            shadow.verdict = event;
                        }
                    }
                    _ => {}
                }
            }
            Event::Lit {
                contribution,
                intensity,
                ..
            } => {
                if let Some(light) = segment.lights.last_mut() {
                    light.lit = Some((*contribution, *intensity, event));
                }
            }
            Event::Divided {
                intensity,
                total_dist,
                seen,
                weight,
                ..
            } => {
                segment.divided = Some(Divided {
                    intensity: *intensity,
                    seen: *seen,
                    weight: *weight,
                    total_dist: *total_dist,
                    event,
                })
            }
            _ => {}
        }
    }
    segments
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::against::lex::read;

    /// The course's own copy: the light's geometry, its shadow ray, then its
    /// contribution; a light facing away has no shadow ray; the mirror's ray after AMB.
    const COURSE: &str = "\
FND  100: -1.0 - base X: 0 Y: 0 Z: 3
dir X: 0 Y: 0 Z: -1
hits: X: 0 Y: 0 Z: 0
FND  101: 4.5 - base X: 0 Y: 0 Z: 3
dir X: 0 Y: 0 Z: -1
hits: X: 0 Y: 0 Z: -1.5
HIT  101: 4.5 (0, 0, -1.5) - Thetotal dist is 4.5
hit object id was       101
light object id was      102
theta is                 0.87

FND  100: -1.0 - base X: 0 Y: 0 Z: -1.5
dir X: 1 Y: 1 Z: 6
hits: X: 0 Y: 0 Z: 0
Emissivity of the light

   4.0 4.0 4.0
Current ivec

   7.6 0.9 1.6
hit object id was       101
light object id was      103
theta is                 -0.5
AMB (1.6, 0.2, 0.3) -

FND  100: -1.0 - base X: 0 Y: 0 Z: -1.5
dir X: 0 Y: 0 Z: 1
hits: X: 0 Y: 0 Z: 0
";

    #[test]
    fn the_course_s_own_layout() {
        let segments = student(&read(COURSE));
        assert_eq!(segments.len(), 2);
        let camera = &segments[0];
        assert_eq!(camera.tests.len(), 2);
        assert!(camera.hit.as_ref().is_some_and(|h| h.id == 101));
        assert_eq!(camera.total.as_ref().map(|t| t.value.value), Some(4.5));
        assert_eq!(camera.blocks.len(), 2);
        let first = &camera.blocks[0];
        assert_eq!(first.shadow.len(), 1);
        assert!(first.adds() && first.get(Label::Cos).is_some());
        assert!(camera.blocks[1].shadow.is_empty() && !camera.blocks[1].adds());
        assert!(camera.amb.is_some());
        assert_eq!(segments[1].tests.len(), 1);
        assert!(segments[1].hit.is_none());
    }

    #[test]
    fn a_shadow_ray_printed_before_its_block() {
        let text = "FND 0: 5.0 -\nFND 1: -1 -\nHIT 0: 5.0 (0, 0, -2) -\nFND 1: 2.0 -\n\
                    hit object id was 0\nlight object id was 2\ncos is 0.5\n\
                    hit object occluded by 1\ndistance was 2.0\nFND 1: -1 -\n\
                    hit object id was 0\nlight object id was 3\ncos is 0.5\nAMB (1, 1, 1) -";
        let segments = student(&read(text));
        assert_eq!(segments.len(), 1);
        let blocks = &segments[0].blocks;
        assert_eq!(blocks.len(), 2);
        assert!(blocks[0].shadow[0].hits() && blocks[0].get(Label::OccludedBy).is_some());
        assert!(!blocks[1].shadow[0].hits());
    }

    #[test]
    fn the_units_of_t_from_the_point() {
        // base (0, 0, 0) along (3, 4, 0), |dir| 5: t = 1 along a unit direction ends at
        // (0.6, 0.8, 0); along the printed one at (3, 4, 0).
        let along = |hits: &str| {
            let text = format!(
                "FND 1: 1.000000 - base X: 0.000000 Y: 0.000000 Z: 0.000000\n\
                 dir X: 3.000000 Y: 4.000000 Z: 0.000000\nhits: X: {hits} Z: 0.000000"
            );
            founds(&read(&text))[0].units()
        };
        assert_eq!(along("0.600000 Y: 0.800000"), Some(Units::Unit));
        assert_eq!(along("3.000000 Y: 4.000000"), Some(Units::Printed));
        assert_eq!(along("9.000000 Y: 4.000000"), None);
    }
}
