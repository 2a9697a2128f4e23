//! `compare --diagnose`'s decision flips: what no catalogue names, told by the decisions
//! on the differing pixels' paths.
//!
//! Each differing pixel's path in the reference takes decisions: the camera ray hits an
//! object, a mirror ray hits another, a shadow ray toward a light is blocked by a third
//! or reaches the light. Each decision is forced the other way on that pixel
//! ([`Override`], on the renderer's own frame, as [`render_forced`](super::render_forced)
//! does), one and then two together, and those whose change gives the student's bytes
//! explain the pixel. The pixels are grouped by the decision that explains the most of them
//! (the object's before a light's where both do), and each group is described by what
//! its decisions share: the kind of ray, the lights toward which it was cast, and the
//! geometry where the reference took it (the ray's base inside the surface: its nearer
//! root behind the base; a ray that grazes it). A group also counts the agreeing pixels
//! whose path takes the same decision in the same geometry and would change were it
//! forced: what the same mistake would break.

use super::causes::{BREAKS_PER_FIX, Case, HALF};
use super::retrace::{recorded, render_forced_each};
use super::{for_each_set, is_set, light_name, pixel_at, within};
use crate::render::PatternNote;
use crate::render::record::{Event, LightStep, Recorder};
use crate::render::trace::object_name;
use crate::render::{Override, Rays, Variant};
use crate::scene::Scene;
use crate::shapes::{HitNote, Verdict};
use serde::Serialize;
use std::collections::BTreeMap;

/// A group of differing pixels that one decision forced the other way (or two) explains.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Flip {
    /// The decision, as the student's program takes it: "cylinder (line 11) does not
    /// block shadow rays".
    pub decision: String,
    /// The geometry the group's decisions share in the reference, where nearly all do:
    /// "whose base is inside it (the nearer root is behind the base)".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub condition: Option<String>,
    /// Of the pixels it explains, how many share the condition.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub condition_holds: Option<usize>,
    /// For shadow rays: toward which lights ("both lights", "light (line 19)").
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lights: Option<String>,
    /// How many of the differing pixels examined it explains.
    pub explains: usize,
    /// Of how many examined.
    pub of: usize,
    /// How many differing pixels there were, where `of` is an even sample of them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sampled_from: Option<usize>,
    /// How many agreeing pixels whose path takes the same decision in the same geometry
    /// it would make differ (an estimate where `breaks_sampled` says so).
    pub breaks: usize,
    /// Whether `breaks` was scaled up from an even sample of those pixels.
    pub breaks_sampled: bool,
    /// Where to look in the student's program.
    pub advice: String,
    /// A pixel it explains (x, y from the lower left, as `trace` takes them).
    pub pixel: [usize; 2],
    /// The whole-image causes the decisions were found under (in JSON their ids, as
    /// `--variant` takes them): `pixel` is traced with them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub under: Vec<Variant>,
    /// The command that traces `pixel` in the reference, when the command line knows the
    /// scene's file name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trace: Option<String>,
}

/// What spec §5.4 adds to a tile's coordinates before it truncates them: relx or rely
/// below it is a negative coordinate in the plane.
const TILE_ORIGIN: i64 = 10000;

/// The most differing pixels examined; more are sampled evenly down to it.
const EXAMINED: usize = 4096;

/// The differing pixels every decision is tried on ([`Examined::try_singles`]); on the
/// others, only those that explained one of them.
const PROBE: usize = 512;

/// The most agreeing pixels traced for a group's breaks; more are sampled evenly.
const BREAK_SAMPLE: usize = 4096;

/// How many groups are told, at most.
const GROUPS: usize = 4;

/// The share of the examined pixels a group must explain to be told, at least.
const GROUP_SHARE: f64 = 0.01;

/// The share of a group's pixels that must share a geometry for it to be its condition.
const CONDITION_SHARE: f64 = 0.9;

/// A discriminant this small, relative to its terms, is a ray that grazes the surface.
const GRAZING: f64 = 1e-3;

/// The pixels forced two decisions at once, as a multiple of those examined, at most.
const PAIR_BUDGET: usize = 2;

/// The geometry where the reference took a decision on an object, from the shape's notes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Geometry {
    /// The ray's base is inside the surface: its nearer root is behind the base, the
    /// farther one counts.
    BaseInside,
    /// The ray grazes the surface: the two roots nearly meet.
    Grazing,
    /// A tiled plane's hit where one of its coordinates in the plane is negative: relx
    /// or rely below the 10000 spec §5.4 adds, which truncation toward zero needs.
    NegativeTile,
}

impl Geometry {
    /// What the notes of one object's test tell, if anything.
    fn of(notes: &[HitNote]) -> Option<Geometry> {
        let root = |note: &HitNote| match note {
            HitNote::Root { t, verdict, .. } | HitNote::QuadricRoot { t, verdict } => {
                Some((*t, *verdict))
            }
            _ => None,
        };
        let roots = || notes.iter().filter_map(root);
        if roots().any(|(t, v)| v == Verdict::Behind && t <= 0.0)
            && roots().any(|(_, v)| v == Verdict::Counts)
        {
            return Some(Geometry::BaseInside);
        }
        notes.iter().find_map(|note| match note {
            HitNote::Discriminant { relative, .. } if *relative < GRAZING => {
                Some(Geometry::Grazing)
            }
            _ => None,
        })
    }

    /// The words for it.
    fn words(self) -> &'static str {
        match self {
            Geometry::BaseInside => "whose base is inside it (the nearer root is behind the base)",
            Geometry::Grazing => "that graze it (the two roots nearly meet)",
            Geometry::NegativeTile => {
                "where x or y in the plane is negative (relx or rely below 10000)"
            }
        }
    }
}

/// One decision on a pixel's path: what forcing it the other way is, the light of its
/// shadow ray, and the geometry where it was taken.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Decision {
    flip: Override,
    light: Option<usize>,
    geometry: Option<Geometry>,
}

/// The decisions one pixel's path takes, as the tracer tells them.
#[derive(Debug, Default)]
struct Decisions {
    /// The ray under way: 0 the camera's, k the k-th mirror ray's.
    depth: usize,
    /// The light whose term is under way.
    light: Option<usize>,
    /// The geometry of each object hit on the ray under way.
    tested: Vec<(usize, Option<Geometry>)>,
    /// The object the ray under way hit.
    hit: Option<usize>,
    taken: Vec<Decision>,
}

impl Decisions {
    fn geometry(&self, object: usize) -> Option<Geometry> {
        self.tested.iter().rev().find(|t| t.0 == object)?.1
    }

    fn take(&mut self, flip: Override, light: Option<usize>, geometry: Option<Geometry>) {
        self.taken.push(Decision {
            flip,
            light,
            geometry,
        });
    }
}

impl Recorder for Decisions {
    fn record(&mut self, event: impl FnOnce() -> Event) {
        match event() {
            Event::Segment { depth, .. } => {
                // A mirror ray: the object it leaves reflected.
                if let Some(object) = self.hit.take().filter(|_| depth > 0) {
                    self.take(Override::NoBounce { object }, None, None);
                }
                self.depth = depth;
                self.tested.clear();
                self.light = None;
            }
            Event::Closest {
                hit: Some((object, _)),
            } => {
                self.hit = Some(object);
                let rays = match self.depth {
                    0 => Rays::Camera,
                    _ => Rays::Mirror,
                };
                let geometry = self.geometry(object);
                self.take(Override::Miss { object, rays }, None, geometry);
            }
            Event::Surface {
                object,
                pattern: PatternNote::Tile { relx, rely, .. },
                ..
            } => {
                let negative = relx < TILE_ORIGIN || rely < TILE_ORIGIN;
                let geometry = negative.then_some(Geometry::NegativeTile);
                self.take(Override::Tile { object }, None, geometry);
            }
            Event::CutOff { .. } => self.take(Override::NeverCut, None, None),
            Event::Lamp { light } => self.light = Some(light),
            Event::Light(LightStep::ShadowRay { .. }) => self.tested.clear(),
            Event::Light(LightStep::Blocked { blocker }) => {
                let Some(light) = self.light else { return };
                match blocker {
                    Some((object, _)) => {
                        let geometry = self.geometry(object);
                        let miss = Override::Miss {
                            object,
                            rays: Rays::Shadow,
                        };
                        self.take(miss, Some(light), geometry);
                        let open = Override::Shadow {
                            light,
                            blocked: false,
                        };
                        self.take(open, Some(light), geometry);
                    }
                    None => {
                        let shut = Override::Shadow {
                            light,
                            blocked: true,
                        };
                        self.take(shut, Some(light), None);
                    }
                }
            }
            _ => {}
        }
    }

    fn tested(&mut self, object: usize, t: Option<f64>, notes: &[HitNote]) {
        if t.is_some() {
            self.tested.push((object, Geometry::of(notes)));
        }
    }
}

/// An order on overrides, for maps and ties: an object's misses before a light's shadow
/// test, then by index.
fn key(flip: &Override) -> Key {
    match *flip {
        Override::Miss { object, rays } => (rays as u8, object),
        Override::Shadow { light, blocked } => (3 + u8::from(blocked), light),
        Override::Tile { object } => (5, object),
        Override::NoBounce { object } => (6, object),
        Override::NeverCut => (7, 0),
    }
}

/// A set of one or two overrides, ordered.
type Set = Vec<Override>;

/// An override's place in [`key`]'s order.
type Key = (u8, usize);

/// A set of overrides, and the pixels (positions among those examined) it is tried on.
type Job = (Set, Vec<usize>);

/// The groups of the differing pixels (`mask`, over the image `student` is compared to)
/// that one decision, or two, on the reference's path explains, largest first; empty
/// when none explains enough of them. `options` render the reference the mask was taken
/// against (`case.options`): the scene's, with the whole-image causes already found
/// applied (`under`,
/// which move the pixels: the reference's paths are those of its pixels where there are
/// none).
pub fn flips(case: Case, mask: (&[u64], usize), under: &[Variant]) -> Vec<Flip> {
    let Case { scene, options, .. } = case;
    let (mask, count) = mask;
    if count == 0 {
        return Vec::new();
    }
    // The differing pixels examined: every one, or an even sample.
    let stride = count.div_ceil(EXAMINED);
    let mut targets = Vec::with_capacity(count.min(EXAMINED));
    let mut k = 0;
    for_each_set(mask, |i| {
        if k % stride == 0 {
            targets.push(i);
        }
        k += 1;
    });
    let paths: Vec<Decisions> = recorded(scene, options, &targets);
    let examined = Examined {
        case,
        mask,
        under,
        targets,
        paths,
        stride,
        count,
    };
    // Which decisions explain which pixels: each alone, then two together where none
    // does alone.
    let mut explained: Vec<Vec<usize>> = vec![Vec::new(); examined.targets.len()];
    let mut sets = examined.try_singles(&mut explained);
    let first_pair = sets.len();
    let pairs = examined.pairs(&explained);
    sets.extend(examined.try_sets(&pairs, &mut explained, first_pair));
    let groups = examined.groups(&explained, sets.len(), first_pair);
    let told: Vec<Flip> = (merged(groups, &sets).into_iter())
        .map(|(numbers, members)| examined.describe(&numbers, &sets, &members))
        // A group that breaks more than a twentieth of what it explains (the differing
        // pixels counted at the sample's stride), as a cause may not, is a coincidence
        // (of fragile pixels, say).
        .filter(|flip| flip.breaks * BREAKS_PER_FIX <= flip.explains * stride)
        .collect();
    // Told only where the groups together explain at least half of the pixels examined,
    // as a cause must: a decision that gives a few pixels the student's bytes by chance
    // is no cause.
    let explained: usize = told.iter().map(|flip| flip.explains).sum();
    match explained as f64 >= HALF * examined.targets.len() as f64 {
        true => told,
        false => Vec::new(),
    }
}

/// The differing pixels examined, with what [`flips`] was given, and the decisions each
/// one's path takes.
struct Examined<'a> {
    case: Case<'a>,
    /// Which pixels differ (pixel i is bit i % 64 of word i / 64).
    mask: &'a [u64],
    /// The whole-image causes the options hold, which move the pixels.
    under: &'a [Variant],
    /// The pixels examined (output indices).
    targets: Vec<usize>,
    /// Each one's decisions.
    paths: Vec<Decisions>,
    /// One pixel examined for every `stride` differing.
    stride: usize,
    /// How many differ.
    count: usize,
}

impl Examined<'_> {
    /// Each decision any pixel's path takes, with the pixels (positions among those
    /// examined) that take it.
    fn singles(&self) -> Vec<Job> {
        let mut singles: BTreeMap<Key, Job> = BTreeMap::new();
        for (at, path) in self.paths.iter().enumerate() {
            for flip in decisions_of(path) {
                let entry = singles.entry(key(&flip));
                entry.or_insert_with(|| (vec![flip], Vec::new())).1.push(at);
            }
        }
        singles.into_values().collect()
    }

    /// [`Examined::try_sets`] with each decision alone (numbered from 0): every decision
    /// on an even sample of [`PROBE`] pixels first, then on the other pixels only those
    /// that explained one of the sample's. A decision that explains the [`GROUP_SHARE`]
    /// a group needs explains about five of the sample's pixels: it is missed there about
    /// once in 150 times.
    fn try_singles(&self, explained: &mut [Vec<usize>]) -> Vec<Set> {
        let jobs = self.singles();
        let every = self.targets.len().div_ceil(PROBE);
        if every <= 1 {
            return self.try_sets(&jobs, explained, 0);
        }
        let part = |jobs: &[Job], keep: &dyn Fn(usize, usize) -> bool| -> Vec<Job> {
            let job = |(j, (set, ats)): (usize, &Job)| {
                let ats = ats.iter().copied().filter(|&at| keep(j, at)).collect();
                (set.clone(), ats)
            };
            jobs.iter().enumerate().map(job).collect()
        };
        let sets = self.try_sets(&part(&jobs, &|_, at| at % every == 0), explained, 0);
        let mut useful = vec![false; jobs.len()];
        for &j in explained.iter().flatten() {
            useful[j] = true;
        }
        let rest = part(&jobs, &|j, at| useful[j] && at % every != 0);
        self.try_sets(&rest, explained, 0);
        sets
    }

    /// Two decisions of one path, for the pixels no decision explains alone: the pairs
    /// most pixels hold first, within [`PAIR_BUDGET`].
    fn pairs(&self, explained: &[Vec<usize>]) -> Vec<Job> {
        let mut pairs: BTreeMap<[Key; 2], Job> = BTreeMap::new();
        for (at, path) in self.paths.iter().enumerate() {
            if !explained[at].is_empty() {
                continue;
            }
            let mine = decisions_of(path);
            for (a, first) in mine.iter().enumerate() {
                for second in &mine[a + 1..] {
                    let entry = pairs.entry([key(first), key(second)]);
                    let pair = entry.or_insert_with(|| (vec![*first, *second], Vec::new()));
                    pair.1.push(at);
                }
            }
        }
        let mut pairs: Vec<Job> = pairs.into_values().collect();
        pairs.sort_by_key(|(_, ats)| std::cmp::Reverse(ats.len()));
        let mut budget = PAIR_BUDGET * self.targets.len();
        pairs.retain(|(_, ats)| {
            let keep = ats.len() <= budget;
            budget = budget.saturating_sub(ats.len());
            keep
        });
        pairs
    }

    /// Renders each job's pixels with its set forced, and notes in `explained` each
    /// pixel whose bytes then agree (the set's number, from `first`). The sets, in the
    /// jobs' order.
    fn try_sets(&self, jobs: &[Job], explained: &mut [Vec<usize>], first: usize) -> Vec<Set> {
        let indices: Vec<Vec<usize>> = (jobs.iter())
            .map(|(_, ats)| ats.iter().map(|&at| self.targets[at]).collect())
            .collect();
        let forced: Vec<(&[Override], &[usize])> = (jobs.iter().zip(&indices))
            .map(|((set, _), indices)| (&set[..], &indices[..]))
            .collect();
        let bytes = render_forced_each(self.case.scene, self.case.options, &forced);
        for (j, ((_, ats), bytes)) in jobs.iter().zip(bytes).enumerate() {
            for (&at, bytes) in ats.iter().zip(bytes) {
                let student = self.case.student.pixels[self.targets[at]];
                if within(bytes, student, self.case.levels) {
                    explained[at].push(first + j);
                }
            }
        }
        jobs.iter().map(|(set, _)| set.clone()).collect()
    }

    /// The groups, at most [`GROUPS`], each at least [`GROUP_SHARE`] of the pixels: the
    /// set (of `sets`) that explains the most pixels not yet grouped, singles (those
    /// before `first_pair`) before pairs, an object's miss before a light's test.
    fn groups(
        &self,
        explained: &[Vec<usize>],
        sets: usize,
        first_pair: usize,
    ) -> Vec<(usize, Vec<usize>)> {
        let n = self.targets.len();
        let mut grouped = vec![false; n];
        let least = ((GROUP_SHARE * n as f64).ceil() as usize).max(1);
        let mut groups = Vec::new();
        while groups.len() < GROUPS {
            let mut tally = vec![0usize; sets];
            for (at, sets) in explained.iter().enumerate() {
                if !grouped[at] {
                    for &s in sets {
                        tally[s] += 1;
                    }
                }
            }
            let best = (0..sets)
                .filter(|&s| tally[s] >= least)
                .max_by_key(|&s| (usize::from(s < first_pair), tally[s], std::cmp::Reverse(s)));
            let Some(best) = best else { break };
            let members: Vec<usize> = (0..n)
                .filter(|&at| !grouped[at] && explained[at].contains(&best))
                .collect();
            for &at in &members {
                grouped[at] = true;
            }
            groups.push((best, members));
        }
        groups
    }

    /// The group of the pixels `members` that the sets numbered `numbers` (of `sets`)
    /// explain, in words, with its counts.
    fn describe(&self, numbers: &[usize], sets: &[Set], members: &[usize]) -> Flip {
        let flips: Vec<Override> = numbers.iter().flat_map(|&s| sets[s].clone()).collect();
        let taken: Vec<&Decision> = (members.iter())
            .flat_map(|&at| self.paths[at].taken.iter())
            .filter(|d| flips.contains(&d.flip))
            .collect();
        let condition = shared_geometry(members, &self.paths, &flips);
        let (mut breaks, mut breaks_sampled) = (0, false);
        for &set in numbers {
            let (n, sampled) = self.breaks(&sets[set], condition.map(|c| c.0));
            breaks += n;
            breaks_sampled |= sampled;
        }
        let i = self.targets[members[0]];
        Flip {
            decision: words(self.case.scene, self.case.options.max_dist, &flips),
            condition: condition.map(|(g, _)| g.words().to_string()),
            condition_holds: condition.map(|(_, n)| n),
            lights: lights(self.case.scene, &taken),
            explains: members.len(),
            of: self.targets.len(),
            sampled_from: (self.stride > 1).then_some(self.count),
            breaks,
            breaks_sampled,
            advice: advice(self.case.scene, &flips, condition.map(|c| c.0)),
            pixel: pixel_at(i, self.case.student.width, self.case.student.height),
            under: self.under.to_vec(),
            trace: None,
        }
    }

    /// How many agreeing pixels (those not set in the mask) would differ were `flips`
    /// forced where their path takes the same decisions (in the geometry `condition`, if
    /// any), and whether that count was scaled up from an even sample. The reference's
    /// paths choose the pixels to trace where no whole-image cause moves them.
    fn breaks(&self, flips: &[Override], condition: Option<Geometry>) -> (usize, bool) {
        let (rendered, student) = (self.case.rendered, self.case.student);
        let pixels = student.pixels.len();
        let aligned = self.under.is_empty() && rendered.paths.len() == pixels;
        let may = |i: usize| !aligned || flips.iter().all(|f| rendered.paths[i].may_take(f));
        let agrees = |i: usize| !is_set(self.mask, i);
        // Counted first, then sampled: a list of them all would be 8 bytes a pixel.
        let candidates = || (0..pixels).filter(|&i| agrees(i) && may(i));
        let stride = candidates().count().div_ceil(BREAK_SAMPLE).max(1);
        let sample: Vec<usize> = candidates().step_by(stride).collect();
        let paths: Vec<Decisions> = recorded(self.case.scene, self.case.options, &sample);
        let same = |path: &Decisions| {
            let taken = |f: &Override| {
                (path.taken.iter())
                    .any(|d| d.flip == *f && condition.is_none_or(|c| d.geometry == Some(c)))
            };
            flips.iter().all(taken)
        };
        let taking: Vec<usize> = (sample.iter().zip(&paths))
            .filter(|(_, path)| same(path))
            .map(|(&i, _)| i)
            .collect();
        let forced = render_forced_each(self.case.scene, self.case.options, &[(flips, &taking)]);
        let [bytes] = &forced[..] else {
            return (0, false);
        };
        let broken = (taking.iter().zip(bytes))
            .filter(|&(&i, &b)| !within(b, student.pixels[i], self.case.levels))
            .count();
        (broken * stride, stride > 1)
    }
}

/// The decisions a path takes, each once, in [`key`]'s order.
fn decisions_of(path: &Decisions) -> Vec<Override> {
    let mut mine: Vec<Override> = Vec::new();
    for d in &path.taken {
        if !mine.contains(&d.flip) {
            mine.push(d.flip);
        }
    }
    mine.sort_by_key(key);
    mine
}

/// The groups (each a set's number among `sets`, and its pixels) with one object's
/// misses by different kinds of ray made one: the same mistake seen directly, in a
/// mirror, in a shadow (an object left out is missed by all three). Each merged group
/// keeps its sets, in order.
fn merged(groups: Vec<(usize, Vec<usize>)>, sets: &[Set]) -> Vec<(Vec<usize>, Vec<usize>)> {
    let seen = |set: usize| match sets[set][..] {
        [Override::Miss { object, .. }] => Some(object),
        _ => None,
    };
    let mut out: Vec<(Vec<usize>, Vec<usize>)> = Vec::new();
    for (set, members) in groups {
        let same = |group: &&mut (Vec<usize>, Vec<usize>)| {
            seen(set).is_some() && group.0.iter().all(|&s| seen(s) == seen(set))
        };
        match out.iter_mut().find(|g| same(g)) {
            Some(group) => {
                group.0.push(set);
                group.1.extend(members);
            }
            None => out.push((vec![set], members)),
        }
    }
    out
}

/// The geometry the decisions `flips` share on most of the pixels `members` (positions
/// in `paths`), with how many share it: one where at least [`CONDITION_SHARE`] of them
/// take every such decision in it.
fn shared_geometry(
    members: &[usize],
    paths: &[Decisions],
    flips: &[Override],
) -> Option<(Geometry, usize)> {
    let mut counts: BTreeMap<Geometry, usize> = BTreeMap::new();
    for &at in members {
        let mut taken = paths[at].taken.iter().filter(|d| flips.contains(&d.flip));
        let Some(first) = taken.next().and_then(|d| d.geometry) else {
            continue;
        };
        if taken.all(|d| d.geometry == Some(first)) {
            *counts.entry(first).or_default() += 1;
        }
    }
    let (geometry, n) = counts
        .into_iter()
        .max_by_key(|&(g, n)| (n, std::cmp::Reverse(g)))?;
    (n as f64 >= CONDITION_SHARE * members.len() as f64).then_some((geometry, n))
}

/// The decisions as the student's program takes them (MAX_DIST `max_dist`), in words; an
/// object's misses by several kinds of ray are said once.
fn words(scene: &Scene, max_dist: f64, flips: &[Override]) -> String {
    let mut said: Vec<String> = Vec::new();
    let mut objects: Vec<usize> = Vec::new();
    for flip in flips {
        match *flip {
            Override::Miss { object, .. } if objects.contains(&object) => {}
            Override::Miss { object, .. } => {
                objects.push(object);
                let name = object_name(scene, object);
                let rays: Vec<&str> = [
                    (Rays::Camera, "camera"),
                    (Rays::Mirror, "mirror"),
                    (Rays::Shadow, "shadow"),
                ]
                .into_iter()
                .filter(|&(rays, _)| flips.contains(&Override::Miss { object, rays }))
                .map(|(_, word)| word)
                .collect();
                said.push(match rays.split_last() {
                    Some((last, [])) if *last == "shadow" => {
                        format!("{name} does not block shadow rays")
                    }
                    Some((last, [])) => format!("{name} is missed by {last} rays"),
                    Some((last, first)) => {
                        format!("{name} is missed by {} and {last} rays", first.join(", "))
                    }
                    // The object's own miss is among them: not reached.
                    None => format!("{name} is missed"),
                });
            }
            Override::Shadow {
                light,
                blocked: false,
            } => said.push(format!(
                "shadow rays toward {} are never blocked",
                light_name(scene, light)
            )),
            Override::Shadow {
                light,
                blocked: true,
            } => said.push(format!(
                "shadow rays toward {} are blocked where nothing is in the way",
                light_name(scene, light)
            )),
            Override::Tile { object } => said.push(format!(
                "{} takes the other tile's colour",
                object_name(scene, object)
            )),
            Override::NoBounce { object } => {
                said.push(format!("{} reflects nothing", object_name(scene, object)))
            }
            Override::NeverCut => said.push(format!(
                "a path longer than MAX_DIST ({max_dist}) goes on rather than ending black"
            )),
        }
    }
    said.join(", and ")
}

/// The lights the shadow rays of `taken` go toward, in words; `None` for no shadow ray.
fn lights(scene: &Scene, taken: &[&Decision]) -> Option<String> {
    let mut lights: Vec<usize> = taken.iter().filter_map(|d| d.light).collect();
    lights.sort_unstable();
    lights.dedup();
    let all = lights.len() == scene.lights.len();
    match lights[..] {
        [] => None,
        [light] => Some(light_name(scene, light)),
        [_, _] if all => Some("both lights".to_string()),
        _ if all => Some(format!("all {} lights", lights.len())),
        _ => {
            let lines: Vec<String> = (lights.iter())
                .map(|&l| scene.lights[l].line.to_string())
                .collect();
            Some(format!("lights (lines {})", lines.join(", ")))
        }
    }
}

/// Where to look in the student's program for the first of `flips`.
fn advice(scene: &Scene, flips: &[Override], geometry: Option<Geometry>) -> String {
    match flips[0] {
        Override::Miss { object, rays } => {
            let kind = scene.objects[object].kind();
            match geometry {
                Some(Geometry::BaseInside) => {
                    format!(
                        "look at the root your {kind} test returns when the ray starts inside it"
                    )
                }
                Some(Geometry::Grazing) => {
                    format!("look at how your {kind} test treats a discriminant near 0")
                }
                _ if rays == Rays::Shadow => format!(
                    "look at how your shadow test tests a {kind}: whether it is skipped, and \
                     whether a hit at t > 0 closer than the light blocks"
                ),
                _ => format!("look at your {kind} intersection test and its bounds"),
            }
        }
        Override::Shadow {
            light,
            blocked: false,
        } => format!(
            "look at your shadow test toward {}: which objects it tests, and how it compares \
             their t with the light's distance",
            light_name(scene, light)
        ),
        Override::Shadow { light, .. } => format!(
            "look at your shadow test toward {}: what it counts as a blocker (a hit at t > 0 \
             closer than the light)",
            light_name(scene, light)
        ),
        Override::Tile { .. } if geometry == Some(Geometry::NegativeTile) => {
            "look at how your program computes relx and rely: trunc(10000 + q.x/w) and \
             trunc(10000 + q.y/h) (spec §5.4); without the 10000, truncation toward zero \
             gives the tiles either side of 0 one number"
                .to_string()
        }
        Override::Tile { .. } => "look at how your program chooses the tile's material: \
             the foreground where relx + rely is odd (spec §5.4)"
            .to_string(),
        Override::NoBounce { object } => format!(
            "look at when your program traces the mirror ray off {}: wherever its specular \
             is not zero and the path is within MAX_DIST (spec §4.5), at every depth",
            object_name(scene, object)
        ),
        Override::NeverCut => "look at where your program compares the path's length with \
             MAX_DIST: spec §4.2 returns black before each ray whose total_dist, the sum of \
             the path's segments so far, exceeds it"
            .to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// examples/shadows.txt: spheres on lines 11, 18 and 25 and two lights.
    fn shadows() -> Scene {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/shadows.txt");
        crate::load(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    #[test]
    fn an_object_s_misses_are_said_once_with_each_kind_of_ray() {
        let scene = shadows();
        let miss = |object: usize, rays: Rays| Override::Miss { object, rays };
        let said = |flips: &[Override]| words(&scene, 32.0, flips);
        assert_eq!(
            said(&[miss(1, Rays::Shadow)]),
            "sphere (line 11) does not block shadow rays"
        );
        assert_eq!(
            said(&[miss(2, Rays::Shadow), miss(2, Rays::Camera)]),
            "sphere (line 18) is missed by camera and shadow rays"
        );
        assert_eq!(
            said(&[
                miss(3, Rays::Mirror),
                miss(3, Rays::Shadow),
                miss(3, Rays::Camera)
            ]),
            "sphere (line 25) is missed by camera, mirror and shadow rays"
        );
        let open = Override::Shadow {
            light: 0,
            blocked: false,
        };
        assert_eq!(
            said(&[miss(1, Rays::Camera), open]),
            "sphere (line 11) is missed by camera rays, and shadow rays toward light (line \
             32) are never blocked"
        );
    }

    #[test]
    fn a_group_is_merged_only_with_the_same_object_s_misses() {
        let miss = |object: usize, rays: Rays| vec![Override::Miss { object, rays }];
        let sets = vec![
            miss(1, Rays::Camera),
            miss(2, Rays::Shadow),
            miss(1, Rays::Mirror),
            vec![Override::Shadow {
                light: 0,
                blocked: true,
            }],
        ];
        let groups = vec![(0, vec![0, 1]), (1, vec![2]), (2, vec![3]), (3, vec![4])];
        let merged = merged(groups, &sets);
        let expected = [
            (vec![0, 2], vec![0, 1, 3]),
            (vec![1], vec![2]),
            (vec![3], vec![4]),
        ];
        assert_eq!(merged, expected);
    }
}
