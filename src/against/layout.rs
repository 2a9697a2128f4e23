//! What a student's file says about its own dialect (spec §8), learnt from its first
//! blocks, never assumed: what its pixel labels are (x y, y x, or the image's size on
//! every block), whether its world points identify the pixels and agree with the labels
//! (a row index one off, jittered camera rays), how its ids number the scene's records
//! (from 0, 1, 100 or elsewhere; lights and objects in one counter, or the objects
//! first), and in what units its shadow rays' t is printed.

use super::lex::{Label, Num, Said};
use super::path::founds;
use super::stream::Block;
use crate::render::Tracing;
use crate::scene::Scene;
use glam::DVec3;

/// How many of a file's first blocks its dialect is learnt from.
pub const SAMPLE: usize = 64;

/// What a block's `PIX` numbers are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Labels {
    /// No `PIX` line.
    Absent,
    /// x then y (`PIX x y`; `ROW = x COL = y` as the copy that names them so prints).
    XY,
    /// y then x, as one later copy printed.
    YX,
    /// The same two numbers on every block (the image's size): they name no pixel.
    Constant(i64, i64),
}

/// How a copy's ids name the scene's records (spec §7.1, §8).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Numbering {
    /// The first record's id.
    pub base: i64,
    /// Objects numbered first and the lights after them, whatever the file's order.
    pub objects_first: bool,
}

/// What an id names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Named {
    /// Object k among the scene's objects.
    Object(usize),
    /// Light k among the scene's lights.
    Light(usize),
}

impl Numbering {
    /// In words, for the notes.
    pub fn words(self) -> String {
        let order = match self.objects_first {
            true => "the objects first, then the lights",
            false => "lights and objects in one counter in file order",
        };
        format!("ids from {}, {order}", self.base)
    }
}

/// A numbering of a scene's records: what each id names, and each record's id.
#[derive(Debug, Clone, PartialEq)]
pub struct Ids {
    /// The numbering.
    pub numbering: Numbering,
    /// The records in the numbering's order.
    order: Vec<Named>,
    /// Each object's place in that order.
    objects: Vec<usize>,
    /// Each light's.
    lights: Vec<usize>,
}

impl Ids {
    /// The ids of `scene`'s records under `numbering`.
    pub fn new(scene: &Scene, numbering: Numbering) -> Ids {
        let mut order: Vec<(usize, Named)> = Vec::new();
        for (k, object) in scene.objects.iter().enumerate() {
            order.push((object.line, Named::Object(k)));
        }
        for (k, light) in scene.lights.iter().enumerate() {
            // Objects first: every light after every object, in file order among lights.
            let key = match numbering.objects_first {
                true => usize::MAX / 2 + light.line,
                false => light.line,
            };
            order.push((key, Named::Light(k)));
        }
        order.sort_by_key(|&(key, _)| key);
        let order: Vec<Named> = order.into_iter().map(|(_, named)| named).collect();
        let mut objects = vec![0; scene.objects.len()];
        let mut lights = vec![0; scene.lights.len()];
        for (place, named) in order.iter().enumerate() {
            match *named {
                Named::Object(k) => objects[k] = place,
                Named::Light(k) => lights[k] = place,
            }
        }
        Ids {
            numbering,
            order,
            objects,
            lights,
        }
    }

    /// What `id` names.
    pub fn named(&self, id: i64) -> Option<Named> {
        let k = usize::try_from(id.checked_sub(self.numbering.base)?).ok()?;
        self.order.get(k).copied()
    }

    /// The object `id` names, if it names one.
    pub fn object(&self, id: i64) -> Option<usize> {
        match self.named(id)? {
            Named::Object(k) => Some(k),
            Named::Light(_) => None,
        }
    }

    /// The light `id` names, if it names one.
    pub fn light(&self, id: i64) -> Option<usize> {
        match self.named(id)? {
            Named::Light(k) => Some(k),
            Named::Object(_) => None,
        }
    }

    /// The id of object `index`.
    pub fn object_id(&self, index: usize) -> i64 {
        self.numbering.base + self.objects[index] as i64
    }

    /// The id of light `index`.
    pub fn light_id(&self, index: usize) -> i64 {
        self.numbering.base + self.lights[index] as i64
    }
}

/// In what units a shadow ray's printed t is (spec §8): along a unit direction, or along
/// the direction to the light as printed (which some copies do not normalise).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// Along a unit direction.
    Unit,
    /// Along the printed direction.
    Printed,
    /// The file does not tell (no hit's point printed): either is taken.
    Unknown,
}

/// What the file's world points say.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct World {
    /// Half a unit of the printed world points' last digit (the coarsest seen).
    pub half_unit: f64,
    /// Whether that is fine enough to tell neighbouring pixels apart.
    pub identifies: bool,
    /// The offset (in pixels) from a block's labelled pixel to the pixel its world point
    /// is, where most blocks agree on one; (0, 0) when the labels and points agree.
    pub offset: (i64, i64),
    /// Whether most world points are off every pixel's by more than the printing rounds,
    /// each by another amount: the camera rays look jittered.
    pub jittered: bool,
}

/// The file's dialect.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// What the `PIX` numbers are.
    pub labels: Labels,
    /// Whether the pixel label names ROW and COL.
    pub row_col: bool,
    /// What the world points say, if printed.
    pub world: Option<World>,
    /// How the ids number the records.
    pub ids: Ids,
    /// Ids no numbering explains (in the blocks learnt from), with the first one's line.
    pub unexplained: Option<(usize, i64, usize)>,
    /// The units of shadow rays' t.
    pub units: Units,
    /// The image's size.
    pub size: (usize, usize),
    /// How the file was read, in sentences.
    pub notes: Vec<String>,
}

/// A labelled block whose world point is far from its label's pixel's.
#[derive(Debug, Clone, PartialEq)]
pub struct FarOff {
    /// The line of its world point.
    pub line: usize,
    /// Its label, as a pixel.
    pub label: (i64, i64),
    /// Its world point.
    pub world: (f64, f64),
}

/// Where a block's pixel is, and what its camera ray passes through.
#[derive(Debug, Clone, PartialEq)]
pub struct Located {
    /// The pixel of the image the block is for, (0, 0) at the lower left.
    pub pixel: (usize, usize),
    /// The point of the screen the block's camera ray passes through: the pixel's own,
    /// or the printed world point where it is another.
    pub through: DVec3,
    /// How the block was found: `label`, `world point` or `scan order`.
    pub by: &'static str,
    /// Where the block's label and world point disagree (or its ray misses its pixel's
    /// point), in a sentence.
    pub finding: Option<String>,
    /// The line of the finding.
    pub finding_line: usize,
    /// That line's text.
    pub finding_text: String,
    /// The pixel whose point the camera ray passes through, if it is one of the image's:
    /// the block's own, or the one its row or column index is off to.
    pub traced: Option<(usize, usize)>,
}

/// A world point's pixel, as real numbers (spec §4.1 read backwards): column and row.
fn grid(frame: &Tracing<'_>, world: (f64, f64)) -> (f64, f64) {
    let (w, h) = (frame.options().width, frame.options().height);
    let first = frame.world(0, 0);
    let last = frame.world(w - 1, h - 1);
    let fx = (world.0 - first.x) / (last.x - first.x) * (w - 1) as f64;
    let fy = (world.1 - first.y) / (last.y - first.y) * (h - 1) as f64;
    (fx, fy)
}

/// The world point of pixel (i, j), on the screen's grid extended past its edges.
fn point(frame: &Tracing<'_>, (i, j): (i64, i64)) -> DVec3 {
    let (w, h) = (frame.options().width, frame.options().height);
    let first = frame.world(0, 0);
    let last = frame.world(w - 1, h - 1);
    let along = |k: i64, count: usize, a: f64, b: f64| a + (b - a) * k as f64 / (count - 1) as f64;
    DVec3::new(
        along(i, w, first.x, last.x),
        along(j, h, first.y, last.y),
        0.0,
    )
}

/// The world point printed in a block: its two numbers and line.
fn printed_world(block: &Block) -> Option<(Num, Num, usize)> {
    let item = block.world()?;
    match item.said {
        Said::World(x, y) if x.value.is_finite() && y.value.is_finite() => Some((x, y, item.line)),
        _ => None,
    }
}

/// The pixel whose world point a printed one is, within what the printing rounds (and
/// a hair of the size): (column, row) on the grid extended past the edges; `None` when
/// it is off every pixel's point.
fn on_grid(frame: &Tracing<'_>, x: Num, y: Num) -> Option<(i64, i64)> {
    let (fx, fy) = grid(frame, (x.value, y.value));
    if !(fx.abs() < 1e9 && fy.abs() < 1e9) {
        return None;
    }
    let (i, j) = (fx.round() as i64, fy.round() as i64);
    let at = point(frame, (i, j));
    let near = |printed: Num, exact: f64| {
        (printed.value - exact).abs() <= printed.half_unit + 1e-9 * exact.abs().max(1.0)
    };
    (near(x, at.x) && near(y, at.y)).then_some((i, j))
}

impl Layout {
    /// The dialect of a file whose first blocks are `sample`, against `scene` traced
    /// under `frame`.
    pub fn learn(scene: &Scene, frame: &Tracing<'_>, sample: &[Block]) -> Layout {
        let size = (frame.options().width, frame.options().height);
        let mut notes = Vec::new();
        let row_col = sample.iter().any(|b| b.label().is_some_and(|l| l.2));
        let world = world(frame, sample);
        let labels = labels(frame, sample, world.as_ref());
        match labels {
            Labels::Constant(a, b) if sample.len() > 1 => notes.push(format!(
                "every block's pixel label is PIX {a} {b} (the image's size, not the pixel): \
                 the blocks are found by {}",
                match world {
                    Some(w) if w.identifies => "their world points",
                    _ =>
                        "their order (the course's scan: rows from the bottom, each left to right)",
                }
            )),
            Labels::YX => notes.push("PIX prints y first, as one later copy did".into()),
            Labels::Absent if sample.len() > 1 => notes.push(format!(
                "no pixel labels: the blocks are found by {}",
                match world {
                    Some(w) if w.identifies => "their world points",
                    _ =>
                        "their order (the course's scan: rows from the bottom, each left to right)",
                }
            )),
            _ => {}
        }
        if row_col {
            notes.push("the pixel label names x ROW and y COL, as one copy does".into());
        }
        if world.is_some_and(|w| w.jittered) {
            notes.push(
                "the world points are off their pixels' by more than they are printed to, \
                 each by another amount: the camera rays look jittered"
                    .into(),
            );
        }
        let (ids, unexplained) = numbering(scene, sample);
        let default = Numbering {
            base: 0,
            objects_first: false,
        };
        if ids.numbering != default {
            notes.push(format!("{} (read from the file)", ids.numbering.words()));
        }
        let units = units(sample);
        Layout {
            labels,
            row_col,
            world,
            ids,
            unexplained,
            units,
            size,
            notes,
        }
    }

    /// The first labelled block whose world point is more than three pixels (past what
    /// its printing rounds) from its label's, where most labelled blocks' are: (its
    /// line, its label, its point). A row or column offset, jitter or another sampling
    /// stays within that; another image size or window does not.
    pub fn far_off(&self, frame: &Tracing<'_>, sample: &[Block]) -> Option<FarOff> {
        let spacing = {
            let (w, h) = self.size;
            let first = frame.world(0, 0);
            let last = frame.world(w - 1, h - 1);
            ((last.x - first.x) / (w - 1) as f64)
                .abs()
                .min(((last.y - first.y) / (h - 1) as f64).abs())
        };
        let mut far = Vec::new();
        let mut labelled = 0;
        for block in sample {
            let (Some((a, b, _)), Some((x, y, line))) = (block.label(), printed_world(block))
            else {
                continue;
            };
            let label = match self.labels {
                Labels::XY => (a, b),
                Labels::YX => (b, a),
                _ => return None,
            };
            labelled += 1;
            let (fx, fy) = grid(frame, (x.value, y.value));
            let slack = x.half_unit.max(y.half_unit) / spacing;
            if (fx - label.0 as f64).abs().max((fy - label.1 as f64).abs()) > 3.5 + slack {
                far.push(FarOff {
                    line,
                    label,
                    world: (x.value, y.value),
                });
            }
        }
        (far.len() * 2 > labelled).then(|| far.swap_remove(0))
    }

    /// Where block `block` is for and what its camera ray passes through.
    pub fn locate(&self, frame: &Tracing<'_>, block: &Block) -> Option<Located> {
        let (w, h) = self.size;
        let inside = |(x, y): (i64, i64)| {
            (x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h)
                .then_some((x as usize, y as usize))
        };
        let world = printed_world(block);
        let grid_pixel = world.and_then(|(x, y, _)| on_grid(frame, x, y));
        let identifies = self.world.is_some_and(|w| w.identifies);
        let label = block.label().and_then(|(a, b, _)| match self.labels {
            Labels::XY => Some((a, b)),
            Labels::YX => Some((b, a)),
            Labels::Absent | Labels::Constant(..) => None,
        });
        let (pixel, by) = match (label, grid_pixel) {
            (Some(label), _) => (inside(label)?, "label"),
            (None, Some(at)) if identifies => (inside(at)?, "world point"),
            _ => {
                let index = block.index;
                (
                    inside(((index % w) as i64, (index / w) as i64))?,
                    "scan order",
                )
            }
        };
        let own = frame.world(pixel.0, pixel.1);
        let mut located = Located {
            pixel,
            through: own,
            by,
            finding: None,
            finding_line: block.lines.0,
            finding_text: String::new(),
            traced: Some(pixel),
        };
        let (Some((wx, wy, line)), Some(item)) = (world, block.world()) else {
            return Some(located);
        };
        located.finding_line = line;
        located.finding_text = item.text.clone();
        let near = |printed: Num, exact: f64| {
            (printed.value - exact).abs() <= printed.half_unit + 1e-9 * exact.abs().max(1.0)
        };
        if near(wx, own.x) && near(wy, own.y) {
            return Some(located);
        }
        let (x, y) = (pixel.0 as i64, pixel.1 as i64);
        match grid_pixel {
            Some(at) if identifies => {
                // Another pixel's point: the label is off by rows or columns.
                located.through = point(frame, at);
                located.traced = inside(at);
                let (dx, dy) = (at.0 - x, at.1 - y);
                let what = match (dx, dy) {
                    (0, dy) => format!(
                        "your row index is {} off (each block is labelled {} the row it traces)",
                        count(dy),
                        if dy < 0 { "above" } else { "below" }
                    ),
                    (dx, 0) => format!(
                        "your column index is {} off (each block is labelled {} the column it \
                         traces)",
                        count(dx),
                        if dx < 0 { "right of" } else { "left of" }
                    ),
                    _ => "your row and column indices are off".to_string(),
                };
                located.finding = Some(format!(
                    "your block labelled ({x}, {y}) traces the world point of pixel ({}, {}), \
                     ({}, {}): {what}",
                    at.0,
                    at.1,
                    show(located.through.x),
                    show(located.through.y)
                ));
            }
            _ => {
                // No pixel's point: a ray through another point of the pixel.
                if identifies {
                    located.through = DVec3::new(wx.value, wy.value, 0.0);
                    located.traced = None;
                }
                let why = match self.world.is_some_and(|w| w.jittered) {
                    true => ": the camera rays look jittered",
                    false => "",
                };
                located.finding = Some(format!(
                    "your camera ray of pixel ({x}, {y}) passes through ({}, {}), not the \
                     pixel's point ({}, {}){why}",
                    show(wx.value),
                    show(wy.value),
                    show(own.x),
                    show(own.y)
                ));
            }
        }
        Some(located)
    }
}

/// How many, in a word for small counts.
fn count(k: i64) -> String {
    let words = ["zero", "one", "two", "three", "four", "five"];
    let n = k.unsigned_abs() as usize;
    words.get(n).map_or(n.to_string(), |w| w.to_string())
}

/// A number as the reports print it: six decimals at most.
pub fn show(v: f64) -> String {
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

/// What the sample's world points say, if it prints any.
fn world(frame: &Tracing<'_>, sample: &[Block]) -> Option<World> {
    let points: Vec<(Num, Num, usize)> = sample.iter().filter_map(printed_world).collect();
    if points.is_empty() {
        return None;
    }
    let half_unit = points
        .iter()
        .map(|(x, y, _)| x.half_unit.max(y.half_unit))
        .fold(0.0, f64::max);
    let (w, h) = (frame.options().width, frame.options().height);
    let first = frame.world(0, 0);
    let last = frame.world(w - 1, h - 1);
    let spacing = ((last.x - first.x) / (w - 1) as f64)
        .abs()
        .min(((last.y - first.y) / (h - 1) as f64).abs());
    let identifies = half_unit < 0.45 * spacing;
    // Off the grid: by how much, in pixels.
    let off: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y, _)| on_grid(frame, *x, *y).is_none())
        .map(|(x, y, _)| {
            let (fx, fy) = grid(frame, (x.value, y.value));
            (fx - fx.round(), fy - fy.round())
        })
        .collect();
    let jittered = identifies && off.len() * 2 > points.len() && {
        let spread = |f: fn(&(f64, f64)) -> f64| {
            let (lo, hi) = off
                .iter()
                .map(f)
                .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
            hi - lo
        };
        spread(|o| o.0) > 0.05 || spread(|o| o.1) > 0.05
    };
    // The labels' offset, where they and the points disagree alike on most blocks.
    let mut offsets: Vec<(i64, i64)> = Vec::new();
    if identifies {
        for block in sample {
            let (Some((a, b, _)), Some((x, y, _))) = (block.label(), printed_world(block)) else {
                continue;
            };
            if let Some((i, j)) = on_grid(frame, x, y) {
                offsets.push((i - a, j - b));
            }
        }
    }
    let offset = most_common(&offsets)
        .filter(|&(_, n)| n * 2 > offsets.len())
        .map_or((0, 0), |(o, _)| o);
    Some(World {
        half_unit,
        identifies,
        offset,
        jittered,
    })
}

/// The most common value and how often it comes.
fn most_common<T: Copy + PartialEq>(values: &[T]) -> Option<(T, usize)> {
    let mut best: Option<(T, usize)> = None;
    for &v in values {
        let n = values.iter().filter(|&&u| u == v).count();
        if best.is_none_or(|(_, m)| n > m) {
            best = Some((v, n));
        }
    }
    best
}

/// What the sample's pixel labels are.
fn labels(frame: &Tracing<'_>, sample: &[Block], world: Option<&World>) -> Labels {
    let printed: Vec<(i64, i64)> = sample
        .iter()
        .filter_map(|b| b.label().map(|l| (l.0, l.1)))
        .collect();
    let Some(&first) = printed.first() else {
        return Labels::Absent;
    };
    if printed.len() > 1 && printed.iter().all(|&l| l == first) {
        return Labels::Constant(first.0, first.1);
    }
    let (w, h) = (frame.options().width as i64, frame.options().height as i64);
    // With world points fine enough, the reading under which the labels and the points
    // agree (up to one offset for the whole file) on the most blocks.
    if world.is_some_and(|w| w.identifies) {
        let agree = |swap: bool| {
            let mut offsets = Vec::new();
            for block in sample {
                let (Some((a, b, _)), Some((x, y, _))) = (block.label(), printed_world(block))
                else {
                    continue;
                };
                let label = if swap { (b, a) } else { (a, b) };
                if let Some(at) = on_grid(frame, x, y) {
                    offsets.push((at.0 - label.0, at.1 - label.1));
                }
            }
            most_common(&offsets).map_or(0, |(o, n)| 2 * n + usize::from(o == (0, 0)))
        };
        if agree(true) > agree(false) {
            return Labels::YX;
        }
        return Labels::XY;
    }
    // With coarser ones, the reading under which more labelled pixels' points are the
    // printed ones to their precision.
    if world.is_some() {
        let consistent = |swap: bool| {
            sample
                .iter()
                .filter(|block| {
                    let (Some((a, b, _)), Some((x, y, _))) = (block.label(), printed_world(block))
                    else {
                        return false;
                    };
                    let (i, j) = if swap { (b, a) } else { (a, b) };
                    let at = point(frame, (i, j));
                    (x.value - at.x).abs() <= x.half_unit + 1e-9
                        && (y.value - at.y).abs() <= y.half_unit + 1e-9
                })
                .count()
        };
        let (straight, swapped) = (consistent(false), consistent(true));
        if swapped > straight {
            return Labels::YX;
        }
        if straight > swapped {
            return Labels::XY;
        }
    }
    // Otherwise the reading under which every label is inside the image, x first when
    // both are.
    let fits = |swap: bool| {
        printed.iter().all(|&(a, b)| {
            let (x, y) = if swap { (b, a) } else { (a, b) };
            (0..w).contains(&x) && (0..h).contains(&y)
        })
    };
    if !fits(false) && fits(true) {
        Labels::YX
    } else {
        Labels::XY
    }
}

/// Every id the sample prints, by what it must name: (id, must be a light, the light
/// centre printed with it, line).
fn printed_ids(sample: &[Block]) -> Vec<(i64, bool, Option<DVec3>, usize)> {
    let mut out = Vec::new();
    for block in sample {
        let items = &block.items;
        for (k, item) in items.iter().enumerate() {
            match &item.said {
                Said::Found(id, _) | Said::Hit(id, ..) => out.push((*id, false, None, item.line)),
                Said::Labelled(Label::HitObject | Label::OccludedBy, v) => {
                    out.push((v[0].value as i64, false, None, item.line))
                }
                Said::Labelled(Label::LightObject, v) => {
                    // The centre printed with this light's id, if it follows.
                    let centre = items[k + 1..].iter().take(3).find_map(|i| match &i.said {
                        Said::Labelled(Label::LightCenter, c) => {
                            Some(DVec3::new(c[0].value, c[1].value, c[2].value))
                        }
                        _ => None,
                    });
                    out.push((v[0].value as i64, true, centre, item.line));
                }
                _ => {}
            }
        }
    }
    out
}

/// The numbering that explains the most of the sample's ids, and what it leaves
/// unexplained: how many ids, the first, and its line.
fn numbering(scene: &Scene, sample: &[Block]) -> (Ids, Option<(usize, i64, usize)>) {
    let printed = printed_ids(sample);
    let mut candidates: Vec<Numbering> = Vec::new();
    for base in [0, 100, 1] {
        for objects_first in [false, true] {
            candidates.push(Numbering {
                base,
                objects_first,
            });
        }
    }
    // A base the file itself suggests: its first camera ray's first FND is the first
    // object.
    let first_found = sample.iter().find_map(|b| {
        b.items.iter().find_map(|i| match i.said {
            Said::Found(id, _) => Some(id),
            _ => None,
        })
    });
    if let (Some(id), false) = (first_found, scene.objects.is_empty()) {
        for objects_first in [false, true] {
            let from_0 = Ids::new(
                scene,
                Numbering {
                    base: 0,
                    objects_first,
                },
            );
            candidates.push(Numbering {
                base: id.saturating_sub(from_0.object_id(0)),
                objects_first,
            });
        }
    }
    let misfits = |ids: &Ids| -> Vec<(i64, usize)> {
        printed
            .iter()
            .filter(|(id, light, centre, _)| match ids.named(*id) {
                Some(Named::Object(_)) => *light,
                Some(Named::Light(k)) => {
                    let location = scene.lights[k].location;
                    !*light
                        || centre
                            .is_some_and(|c| (c - location).length() > 1e-3 * (1.0 + c.length()))
                }
                None => true,
            })
            .map(|&(id, _, _, line)| (id, line))
            .collect()
    };
    let mut best: Option<(Ids, Vec<(i64, usize)>)> = None;
    for candidate in candidates {
        let ids = Ids::new(scene, candidate);
        let wrong = misfits(&ids);
        if best.as_ref().is_none_or(|(_, w)| wrong.len() < w.len()) {
            best = Some((ids, wrong));
        }
    }
    let (ids, wrong) = best.expect("there are candidates");
    let unexplained = wrong.first().map(|&(id, line)| (wrong.len(), id, line));
    (ids, unexplained)
}

/// The units of the sample's shadow rays' t, from the `FND` lines that print the hit's
/// point: which of base + t·dir and base + t·unit(dir) it is.
fn units(sample: &[Block]) -> Units {
    let (mut unit, mut printed) = (0, 0);
    for block in sample {
        for found in founds(&block.items) {
            match found.units() {
                Some(Units::Unit) => unit += 1,
                Some(Units::Printed) => printed += 1,
                _ => {}
            }
        }
    }
    match (unit, printed) {
        (0, 0) => Units::Unknown,
        (u, p) if u >= p => Units::Unit,
        _ => Units::Printed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::against::stream::blocks;
    use crate::render::{Options, tracing};

    /// A light, a plane and a sphere, the light first.
    const SCENE: &str = "8 6\n0 0 3\n10\n1 1 1\n0 4 0\n14\n1 1 1\n1 1 1\n0 0 0\n0 1 0\n0 -3 0\n\
                         13\n1 1 1\n1 1 1\n0 0 0\n0 0 -3\n1\n";

    /// A block per pixel of an 8x6 image, its world point moved by `offset(x, y)` pixels.
    fn trace(
        label: impl Fn(usize, usize) -> String,
        offset: impl Fn(usize, usize) -> (f64, f64),
    ) -> String {
        let mut text = String::new();
        for y in 0..6 {
            for x in 0..8 {
                let (dx, dy) = offset(x, y);
                let wx = (x as f64 + dx) / 7.0 * 8.0 - 4.0;
                let wy = (y as f64 + dy) / 5.0 * 6.0 - 3.0;
                text += &format!(
                    "{}\nFND 1: 2.0 -\nWRL ({wx:.11}, {wy:.11}) -\n",
                    label(x, y)
                );
            }
        }
        text
    }

    fn learn(text: &str, check: impl Fn(&Layout, &[Block], &Tracing<'_>)) {
        let scene = crate::load(SCENE).unwrap();
        tracing(&scene, &Options::new(8, 6), |frame| {
            let sample = blocks(text);
            let layout = Layout::learn(&scene, frame, &sample);
            check(&layout, &sample, frame);
        });
    }

    #[test]
    fn labels_world_points_and_scan_order() {
        // Labels that agree with the world points.
        learn(
            &trace(|x, y| format!("PIX {x} {y} -"), |_, _| (0.0, 0.0)),
            |layout, sample, frame| {
                assert_eq!(layout.labels, Labels::XY);
                let world = layout.world.unwrap();
                assert!(world.identifies && !world.jittered && world.offset == (0, 0));
                let located = layout.locate(frame, &sample[13]).unwrap();
                assert_eq!(
                    (located.pixel, located.by, located.finding),
                    ((5, 1), "label", None)
                );
            },
        );
        // y first.
        learn(
            &trace(|x, y| format!("PIX {y} {x} -"), |_, _| (0.0, 0.0)),
            |layout, _, _| {
                assert_eq!(layout.labels, Labels::YX);
            },
        );
        // The image's size on every block: found by the world point.
        learn(
            &trace(|_, _| "PIX 8 6 -".into(), |_, _| (0.0, 0.0)),
            |layout, sample, frame| {
                assert_eq!(layout.labels, Labels::Constant(8, 6));
                let located = layout.locate(frame, &sample[13]).unwrap();
                assert_eq!((located.pixel, located.by), ((5, 1), "world point"));
            },
        );
    }

    #[test]
    fn a_row_off_and_jittered_rays_are_findings() {
        // Labelled a row below the point traced.
        learn(
            &trace(|x, y| format!("PIX {x} {y} -"), |_, _| (0.0, 1.0)),
            |layout, sample, frame| {
                assert_eq!(layout.world.unwrap().offset, (0, 1));
                let located = layout.locate(frame, &sample[13]).unwrap();
                assert_eq!(located.pixel, (5, 1));
                assert_eq!(located.traced, Some((5, 2)));
                let finding = located.finding.unwrap();
                assert!(finding.contains("row index is one off"), "{finding}");
            },
        );
        // Each ray through another point of its pixel, within half a pixel.
        let jitter = |x: usize, y: usize| {
            let h = (x * 7 + y * 13) % 10;
            (h as f64 / 10.0 - 0.45, (9 - h) as f64 / 10.0 - 0.45)
        };
        learn(
            &trace(|x, y| format!("PIX {x} {y} -"), jitter),
            |layout, sample, frame| {
                assert!(layout.world.unwrap().jittered);
                assert!(layout.notes.iter().any(|n| n.contains("jittered")));
                let located = layout.locate(frame, &sample[13]).unwrap();
                assert_eq!((located.pixel, located.traced), ((5, 1), None));
                assert!(located.finding.unwrap().contains("look jittered"));
            },
        );
    }

    #[test]
    fn ids_are_numbered_as_the_file_numbers_them() {
        let scene = crate::load(SCENE).unwrap();
        // File order from 0: the light 0, the plane 1, the sphere 2.
        let file = Ids::new(
            &scene,
            Numbering {
                base: 0,
                objects_first: false,
            },
        );
        assert_eq!(
            (file.light_id(0), file.object_id(0), file.object_id(1)),
            (0, 1, 2)
        );
        assert_eq!(
            (file.named(0), file.named(2), file.named(3)),
            (Some(Named::Light(0)), Some(Named::Object(1)), None)
        );
        // Objects first from 100: the plane 100, the sphere 101, the light 102.
        let first = Ids::new(
            &scene,
            Numbering {
                base: 100,
                objects_first: true,
            },
        );
        assert_eq!(
            (first.object_id(0), first.object_id(1), first.light_id(0)),
            (100, 101, 102)
        );
        assert_eq!(first.named(99), None);
        // Learnt from a file whose camera ray tests 100 and 101 and whose light is 102.
        let text = "PIX 0 0 -\nFND 100: 5.0 -\nFND 101: -1 -\nHIT 100: 5.0 (0, 0, 0) -\n\
                    hit object id was 100\nlight object id was 102\nlight center was 0 4 0\n";
        learn(text, |layout, _, _| {
            assert_eq!(
                layout.ids.numbering,
                Numbering {
                    base: 100,
                    objects_first: true
                }
            );
            assert_eq!(layout.unexplained, None);
        });
    }
}
