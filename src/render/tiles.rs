//! The objects that the camera rays of each tile of pixels can hit: every camera ray
//! starts at the eye, so an object's box seen from the eye covers a rectangle of the
//! screen, and a ray through a pixel outside it cannot reach the box. The renderer tests
//! a camera ray only against its tile's list (an item buffer), where otherwise it would
//! walk the hierarchy or test every object. The list runs from near to far: the objects
//! without a box first, then by the distance from the eye to the box, so that the test
//! can stop at the first box farther than the best hit so far.
//!
//! Like the hierarchy ([`super::Bvh`]) it changes which objects are tested, never the
//! answer: a camera ray's hit on a bounded object counts only where the ray has entered
//! the object's box by then ([`super::Boxes::admits`]), so a ray whose pixel lies outside
//! the box's shadow on the screen has no hit there that counts. The rectangle is computed
//! with margins a million times larger than the rounding of the rays and of the box test.
//!
//! A plane (14, 16, 20) is left out of a tile where its hits are certainly behind the
//! eye ([`SeenPlane`]: its t has one sign over the tile, decided at the tile's corners).
//! Planes also hide: where every ray of a tile hits a plane beyond the screen (so that
//! the hit counts), a plane that lies beyond it at all four corners, and an object whose
//! box lies wholly on its far side, cannot be the closest hit there and are left out.
//! Each sign is decided by a margin that even the single-precision kernel cannot cross.
//! Other unbounded objects (an open `QUADRIC`) are in every tile.

use super::bvh::Boxes;
use super::lists::{Builder, Lists, MOST_OBJECTS};
use crate::scene::Scene;
use crate::shapes::LANES;
use crate::threads::Threads;
use glam::{DVec2, DVec3};
use std::ops::Range;
use wide::f64x8;

/// Pixels along a tile's side: a span of a row is one set of lanes.
pub(crate) const TILE: usize = LANES;

// A tile's hiding planes are the bits of a `u32`: no tile list is kept beyond
// `MOST_OBJECTS` planes.
const _: () = assert!(MOST_OBJECTS <= 32);

/// How much of a box's own size and distance from the origin is added around it, and
/// around its rectangle on the screen, before deciding that a pixel lies outside:
/// 10⁻⁹ of the sizes involved, where the rounding of a ray's direction, of the
/// projection and of the box test are each below 10⁻¹⁵ of them.
const MARGIN: f64 = 1e-9;

/// The least depth of a box's corners in front of the eye, as a fraction of the eye's
/// distance to the screen, for its rectangle to be computed: nearer the eye's plane, the
/// projection divides by a depth that may have lost digits.
const MIN_DEPTH: f64 = 1e-3;

/// The widest view for which the lists are made: the screen's extent plus the eye's
/// distance from the z axis, over the eye's distance to the screen. Up to this, a ray's
/// rounding moves its point on the screen by less than 10⁻¹² of the sizes involved.
const WIDEST_VIEW: f64 = 1e3;

/// How clearly a plane's numerator and denominator must have their signs to leave it out
/// of a tile: a thousandth of the sum of their terms' sizes. The single-precision kernel
/// computes them to within about 10⁻⁷ of that sum.
const SIGN_MARGIN: f64 = 1e-3;

/// Per tile, the objects its camera rays may hit, or none kept (`None` from [`Tiles::at`]).
#[derive(Debug, Clone)]
pub(crate) struct Tiles {
    /// The number of tiles across the image.
    across: usize,
    /// Per tile, row by row.
    lists: Lists,
    /// Per object, a distance from the eye that no camera ray's hit that counts falls
    /// short of (see [`nearest`]).
    nearest: Vec<f64>,
}

/// A camera ray's tile: the objects it may hit, near to far.
#[derive(Clone, Copy)]
pub(crate) struct Tile<'a> {
    /// The objects, by `nearest` and then in file order.
    pub(crate) objects: &'a [u32],
    /// Per object of the scene, [`nearest`].
    pub(crate) nearest: &'a [f64],
}

impl Tile<'_> {
    /// Whether a walk of the list (near to far) whose best hit so far is at `t` is past
    /// object `index`: it and every object after it lie beyond `t`, so none can win or
    /// tie.
    #[inline(always)]
    pub(crate) fn passed(&self, index: usize, t: f64) -> bool {
        self.nearest[index] > t
    }

    /// [`Tile::passed`] of the walks of a span's rays (lane i's best hit so far at
    /// `t[i]`), as bit i of a mask.
    #[inline(always)]
    pub(crate) fn passed_lanes(&self, index: usize, t: &[f64; LANES]) -> u32 {
        f64x8::splat(self.nearest[index])
            .simd_gt(f64x8::from(*t))
            .to_bitmask()
    }
}

/// Where an object can be hit by camera rays.
enum Reach {
    /// Through no pixel.
    Nowhere,
    /// Through the pixels of these columns and rows, except where one of the planes of
    /// the mask (bit k: the k-th plane) hides it.
    Pixels(Range<usize>, Range<usize>, u32),
    /// The k-th plane: through the tiles where its t can be positive and no nearer
    /// plane hides it.
    Plane(usize),
    /// Possibly through every pixel.
    Everywhere,
}

impl Tiles {
    /// The lists for camera rays from `eye` through the pixels whose world points are
    /// (`xs[x]`, `ys[y]`, 0); `None` when no tile would keep a list (more unbounded
    /// objects than [`MOST_OBJECTS`]), when there are more objects than pixels (the
    /// lists would cost more than they save: a 2x2 image of a million spheres), or when
    /// the view is too wide or the pixel coordinates are not in order. The objects
    /// `hidden` (the variant hidden: camera rays pass through them) hide nothing. With
    /// `cells`, only the tiles it marks ([`cell`]) get lists: the others keep none, at
    /// the cost of the pixels in them alone (`compare --diagnose` traces a few).
    pub(crate) fn new(
        scene: &Scene,
        boxes: &Boxes,
        eye: DVec3,
        (xs, ys): (&[f64], &[f64]),
        hidden: impl Fn(usize) -> bool + Sync,
        cells: Option<&[bool]>,
        threads: &Threads,
    ) -> Option<Tiles> {
        if scene.objects.len() > xs.len() * ys.len() {
            return None;
        }
        let ordered = |v: &[f64]| v.iter().all(|c| c.is_finite()) && v.is_sorted();
        if !(ordered(xs) && ordered(ys) && eye.is_finite()) {
            return None;
        }
        let extent = |v: &[f64]| v[0].abs().max(v[v.len() - 1].abs());
        let view = extent(xs) + extent(ys) + eye.truncate().abs().max_element();
        if view.is_nan() || view >= WIDEST_VIEW * eye.z.abs() {
            return None;
        }
        let unbounded = (0..scene.objects.len())
            .filter(|&index| boxes.get(index).is_none())
            .count();
        if unbounded > MOST_OBJECTS {
            return None;
        }
        // The planes, numbered in file order, then where each object can be hit.
        // (A rectangle's plane has a box, so only planes 14, 16 and 20 are taken.)
        let (plane_objects, seen): (Vec<usize>, Vec<SeenPlane>) = (scene.objects.iter())
            .enumerate()
            .filter(|(index, _)| boxes.get(*index).is_none())
            .filter_map(|(index, object)| Some((index, object.shape.plane()?)))
            .map(|(index, p)| (index, SeenPlane::new(p.normal, p.point, eye, (xs, ys))))
            .unzip();
        let reaches: Vec<Reach> =
            threads.map(scene.objects.len(), |index| match boxes.get(index) {
                Some((min, max)) => seen_through(eye, min, max, xs, ys, &seen),
                None => match plane_objects.iter().position(|&i| i == index) {
                    Some(k) => Reach::Plane(k),
                    None => Reach::Everywhere,
                },
            });
        let (across, down) = tiles_across(xs.len(), ys.len());
        let wanted = |tile: usize| cells.is_none_or(|cells| cells.get(tile) == Some(&true));
        // Tile (tx, ty) of a tile's index.
        let place = |tile: usize| (tile % across, tile / across);
        // Per tile, the planes every ray through it meets ahead (bit k: the k-th plane),
        // and of those the planes whose hits count at every pixel there: whatever lies
        // behind one of them cannot be the closest hit there. A hidden plane is passed
        // through.
        let (ahead, occluders): (Vec<u32>, Vec<u32>) = threads
            .map(across * down, |tile| {
                if !wanted(tile) {
                    return (0, 0);
                }
                let (mut ahead, mut occluders) = (0, 0);
                for (k, plane) in seen.iter().enumerate() {
                    let at = plane.at(place(tile));
                    if plane.ahead(&at) {
                        ahead |= 1 << k;
                        if !hidden(plane_objects[k]) && plane.counts_throughout(&at) {
                            occluders |= 1 << k;
                        }
                    }
                }
                (ahead, occluders)
            })
            .into_iter()
            .unzip();
        let nearest: Vec<f64> = (0..scene.objects.len())
            .map(|index| {
                boxes
                    .get(index)
                    .map_or(0.0, |(min, max)| nearest(eye, min, max))
            })
            .collect();
        let mut order: Vec<usize> = (0..scene.objects.len()).collect();
        order.sort_by(|&i, &j| nearest[i].total_cmp(&nearest[j]).then(i.cmp(&j)));
        // The lists of each band of tile rows, built apart (on the threads) and joined:
        // every object in `order` added to the tiles of the band it reaches, so that a
        // tile's list is the same whatever the bands.
        let rows_per_band = match threads.count() {
            1 => down.max(1),
            n => down.div_ceil(4 * n).max(1),
        };
        let bands = threads.map(down.div_ceil(rows_per_band), |band| {
            let rows = band * rows_per_band..((band + 1) * rows_per_band).min(down);
            let first = rows.start * across;
            let mut lists = Builder::new(rows.len() * across, |cell| wanted(first + cell));
            for &index in &order {
                match &reaches[index] {
                    Reach::Nowhere => {}
                    Reach::Pixels(columns, pixel_rows, hidden_by) => {
                        let from = (pixel_rows.start / TILE).max(rows.start);
                        let to = pixel_rows.end.div_ceil(TILE).min(rows.end);
                        for ty in from..to {
                            for tx in columns.start / TILE..columns.end.div_ceil(TILE) {
                                let tile = ty * across + tx;
                                if occluders[tile] & *hidden_by == 0 {
                                    lists.add(tile - first, index);
                                }
                            }
                        }
                    }
                    Reach::Plane(k) => {
                        let plane = &seen[*k];
                        for tile in first..rows.end * across {
                            if !wanted(tile) {
                                continue;
                            }
                            let at = plane.at(place(tile));
                            // Behind a nearer plane: both met ahead throughout, then the
                            // sign of s - s' at the corners.
                            let both =
                                |j: usize| ahead[tile] & (1 << *k | 1 << j) == 1 << *k | 1 << j;
                            let hidden = (seen.iter().enumerate()).any(|(j, nearer)| {
                                j != *k
                                    && occluders[tile] & 1 << j != 0
                                    && both(j)
                                    && plane.beyond(&at, nearer, &nearer.at(place(tile)))
                            });
                            if !hidden && !plane.behind_the_eye(&at) {
                                lists.add(tile - first, index);
                            }
                        }
                    }
                    Reach::Everywhere => lists.add_everywhere(index),
                }
            }
            lists.finish()
        });
        Some(Tiles {
            across,
            lists: Lists::joined(bands),
            nearest,
        })
    }

    /// The tile of the camera ray through pixel (x, y), or `None` when it keeps no list.
    #[inline]
    pub(crate) fn at(&self, x: usize, y: usize) -> Option<Tile<'_>> {
        Some(Tile {
            objects: self.lists.get(cell(x, y, self.across))?,
            nearest: &self.nearest,
        })
    }
}

/// The tile of pixel (x, y) of an image `across` tiles wide ([`tiles_across`]).
#[inline]
pub(crate) fn cell(x: usize, y: usize, across: usize) -> usize {
    y / TILE * across + x / TILE
}

/// How many tiles across and down an image of `width` x `height` pixels has.
pub(crate) fn tiles_across(width: usize, height: usize) -> (usize, usize) {
    (width.div_ceil(TILE), height.div_ceil(TILE))
}

/// A distance from `eye` short of any point of the box (min, max), by [`MARGIN`] of
/// itself: a camera ray's hit on the box's object counts only where the ray has entered
/// the box by then ([`super::Boxes::admits`]), at least this far from the eye whatever
/// the rounding of the ray and of the box test. 0 when the eye is inside the box.
fn nearest(eye: DVec3, min: DVec3, max: DVec3) -> f64 {
    let gap = (min - eye).max(eye - max).max(DVec3::ZERO);
    gap.length() * (1.0 - MARGIN)
}

/// The world coordinates of the first and the last pixel of tile `t` along `v` (the
/// camera's xs or ys): a tile's corners are their four pairs.
fn edges(v: &[f64], t: usize) -> [f64; 2] {
    [v[t * TILE], v[(t * TILE + TILE - 1).min(v.len() - 1)]]
}

/// A plane as the camera rays see it: along the ray E + s (P - E) through the screen
/// point P, it lies at s = a / d(P), with a = N·(Q - E) fixed and d(P) = N·(P - E)
/// linear in P, so that over a tile every sign below is decided at its four corners.
/// Each sign is taken only when clear by [`SIGN_MARGIN`] of the sizes of its terms
/// (`None` otherwise): far beyond the rounding of any kernel, the single-precision one
/// included.
struct SeenPlane {
    normal: DVec3,
    point: DVec3,
    eye: DVec3,
    /// a and the size of its terms (the rounding of Q and E counts too).
    a: f64,
    a_size: f64,
    /// The terms of d(P) = Nx (Px - Ex) + Ny (Py - Ey) + Nz (0 - Ez) at the tiles'
    /// corners: per tile column its two x terms, per tile row its two y terms, and the z
    /// term, each computed once.
    columns: Vec<[f64; 2]>,
    rows: Vec<[f64; 2]>,
    z: f64,
}

impl SeenPlane {
    /// The plane of `normal` through `point`, seen from `eye` through the pixels at `xs`
    /// and `ys`.
    fn new(normal: DVec3, point: DVec3, eye: DVec3, (xs, ys): (&[f64], &[f64])) -> SeenPlane {
        let terms = normal * (point - eye);
        let (across, down) = tiles_across(xs.len(), ys.len());
        SeenPlane {
            normal,
            point,
            eye,
            a: terms.element_sum(),
            a_size: terms.abs().element_sum() + normal.abs().dot(point.abs() + eye.abs()),
            columns: (0..across)
                .map(|t| edges(xs, t).map(|x| normal.x * (x - eye.x)))
                .collect(),
            rows: (0..down)
                .map(|t| edges(ys, t).map(|y| normal.y * (y - eye.y)))
                .collect(),
            z: normal.z * (0.0 - eye.z),
        }
    }

    /// d(P) and the size of its terms (x + y + z and |x| + |y| + |z|, summed in that
    /// order) at the four corners of tile (tx, ty): what the tests below read.
    fn at(&self, (tx, ty): (usize, usize)) -> [(f64, f64); 4] {
        let ([x0, x1], [y0, y1]) = (self.columns[tx], self.rows[ty]);
        [(x0, y0), (x1, y0), (x0, y1), (x1, y1)]
            .map(|(x, y)| (x + y + self.z, x.abs() + y.abs() + self.z.abs()))
    }

    /// Whether every ray through the tile (d(P) `at` its corners) meets the plane behind
    /// the eye (s < 0): a and d(P) of opposite signs at all four corners.
    fn behind_the_eye(&self, at: &[(f64, f64); 4]) -> bool {
        let a = sign(self.a, self.a_size);
        a.is_some() && at.iter().all(|&d| sign_of(d) == a.map(|a| !a))
    }

    /// Whether every ray through the tile meets the plane in front of the eye (s > 0):
    /// a and d(P) of one sign at all four corners.
    fn ahead(&self, at: &[(f64, f64); 4]) -> bool {
        let a = sign(self.a, self.a_size);
        a.is_some() && at.iter().all(|&d| sign_of(d) == a)
    }

    /// Whether every ray through the tile, all meeting the plane ahead, hits it beyond
    /// the screen (s > 1, so z < 0 and the hit counts, spec §5.1), the eye being in front
    /// of the screen (E.z > 0): a - d(P) of a's sign at all four corners.
    fn counts_throughout(&self, at: &[(f64, f64); 4]) -> bool {
        self.eye.z > 0.0
            && at.iter().all(|&(d, d_size)| {
                sign(self.a - d, self.a_size + d_size) == sign(self.a, self.a_size)
            })
    }

    /// Whether every ray through the tile meets this plane beyond `nearer` (s > s'),
    /// both met ahead throughout (the caller's test) and their d(P) `at` and `nearer_at`
    /// the corners: the sign of a d'(P) - a' d(P) (linear in P) at all four.
    fn beyond(
        &self,
        at: &[(f64, f64); 4],
        nearer: &SeenPlane,
        nearer_at: &[(f64, f64); 4],
    ) -> bool {
        at.iter()
            .zip(nearer_at)
            .all(|(&(d, d_size), &(e, e_size))| {
                let apart = self.a * e - nearer.a * d;
                let size = self.a_size * e_size + nearer.a_size * d_size;
                // s - s' = (a d' - a' d) / (d d'), and d d' has the sign of a a'.
                sign(apart, size) == Some((self.a > 0.0) == (nearer.a > 0.0))
            })
    }

    /// Whether the box (min, max) lies wholly on the far side of the plane from the
    /// eye: every corner's N·(C - Q) has a's sign. A ray from the eye then crosses the
    /// plane before it can enter the box.
    fn hides(&self, min: DVec3, max: DVec3) -> bool {
        let a = sign(self.a, self.a_size);
        a.is_some()
            && (0..8).all(|corner| {
                let c = box_corner(min, max, corner);
                let terms = self.normal * (c - self.point);
                let size =
                    terms.abs().element_sum() + self.normal.abs().dot(c.abs() + self.point.abs());
                sign(terms.element_sum(), size) == a
            })
    }
}

/// Whether `value` is positive (`Some(true)`) or negative, when it is clear by
/// [`SIGN_MARGIN`] of `size`.
fn sign(value: f64, size: f64) -> Option<bool> {
    (value.abs() > SIGN_MARGIN * size).then_some(value > 0.0)
}

/// [`sign`] of a (value, size) pair.
fn sign_of((value, size): (f64, f64)) -> Option<bool> {
    sign(value, size)
}

/// Corner `corner` (0-7, a bit per axis) of the box (min, max).
fn box_corner(min: DVec3, max: DVec3, corner: usize) -> DVec3 {
    let pick = |bit: usize, a: f64, b: f64| if corner & bit == 0 { a } else { b };
    DVec3::new(
        pick(1, min.x, max.x),
        pick(2, min.y, max.y),
        pick(4, min.z, max.z),
    )
}

/// The columns and rows of the pixels whose camera rays can enter the box (min, max),
/// seen from `eye`: the box's corners projected from the eye onto z = 0, grown by
/// [`MARGIN`]. `Everywhere` when the box is not wholly on the screen's side of the eye's
/// plane z = eye.z (then some of its points project to infinity, or behind).
fn seen_through(
    eye: DVec3,
    min: DVec3,
    max: DVec3,
    xs: &[f64],
    ys: &[f64],
    planes: &[SeenPlane],
) -> Reach {
    let grow = MARGIN * ((max - min).max_element() + min.abs().max(max.abs()).max_element());
    let (min, max) = (min - grow, max + grow);
    let mut low = DVec2::splat(f64::INFINITY);
    let mut high = DVec2::splat(f64::NEG_INFINITY);
    for corner in 0..8 {
        let c = box_corner(min, max, corner);
        // The ray E + s (P - E) reaches the corner's depth at s = (E.z - c.z) / E.z,
        // and there its screen point P = E + (c - E) / s.
        let s = (eye.z - c.z) / eye.z;
        if s.is_nan() || s <= MIN_DEPTH {
            return Reach::Everywhere;
        }
        let on_screen = eye.truncate() + (c - eye).truncate() / s;
        low = low.min(on_screen);
        high = high.max(on_screen);
    }
    let size = (high - low).max_element() + low.abs().max(high.abs()).max_element();
    let grow = MARGIN * (size + eye.abs().max_element());
    let (low, high) = (low - grow, high + grow);
    if !(low.is_finite() && high.is_finite()) {
        return Reach::Everywhere;
    }
    let within = |v: &[f64], low: f64, high: f64| {
        v.partition_point(|&c| c < low)..v.partition_point(|&c| c <= high)
    };
    let columns = within(xs, low.x, high.x);
    let rows = within(ys, low.y, high.y);
    if columns.is_empty() || rows.is_empty() {
        return Reach::Nowhere;
    }
    let hidden_by = (planes.iter().enumerate())
        .filter(|(_, plane)| plane.hides(min, max))
        .fold(0, |mask, (k, _)| mask | 1 << k);
    Reach::Pixels(columns, rows, hidden_by)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::variant::{Kind, Rules, Variant};
    use crate::render::{Camera, Options};
    use crate::shapes::Ray;
    use crate::shapes::kernel::{Accurate, Kernel, KernelChoice, TextbookF32};
    use crate::shapes::testing::Numbers;

    /// A random point within `reach` of the origin on each axis, as a scene file writes it.
    fn point(numbers: &mut Numbers, reach: f64) -> String {
        let [x, y, z] = [(); 3].map(|_| numbers.within(-reach, reach));
        format!("{x} {y} {z}")
    }

    const MATERIAL: &str = "1 1 1\n1 1 1\n0 0 0\n";

    /// A scene of `count` random spheres, cylinders, rectangles and (with `planes`)
    /// planes seen from `eye`, some of them around the eye, behind it or across its plane
    /// z = eye.z. The rectangles face the screen or lie flat: their boxes are as thin as
    /// the padding, so their hits reach the edges of their boxes' rectangles on the screen.
    fn scene(numbers: &mut Numbers, eye: &str, count: usize, planes: bool) -> Scene {
        let mut text = format!("8 6\n{eye}\n");
        for _ in 0..count {
            let record = match (numbers.next() * 5.0) as usize {
                0 | 2 if !planes => format!(
                    "13\n{MATERIAL}{}\n{}\n",
                    point(numbers, 8.0),
                    numbers.within(0.05, 3.0)
                ),
                0 => format!(
                    "13\n{MATERIAL}{}\n{}\n",
                    point(numbers, 8.0),
                    numbers.within(0.05, 3.0)
                ),
                1 => format!(
                    "22\n{MATERIAL}{}\n{}\n{} {}\n",
                    point(numbers, 8.0),
                    point(numbers, 1.0),
                    numbers.within(0.05, 2.0),
                    numbers.within(0.1, 4.0)
                ),
                2 => format!(
                    "14\n{MATERIAL}{}\n{}\n",
                    point(numbers, 1.0),
                    point(numbers, 8.0)
                ),
                facing => format!(
                    "15\n{MATERIAL}{}\n{}\n1 0 0\n{} {}\n",
                    ["0 0 1", "0 1 0"][facing - 3],
                    point(numbers, 8.0),
                    numbers.within(0.1, 6.0),
                    numbers.within(0.1, 12.0)
                ),
            };
            text.push_str(&record);
        }
        crate::load(&text).unwrap()
    }

    /// The closest hit along `ray` that counts (t > 0, inside the object's box; ties to
    /// the earlier object) among `objects`, with kernel `K`: the linear scan's answer,
    /// written out here independently of the renderer's.
    fn closest<K: Kernel>(
        scene: &Scene,
        boxes: &Boxes,
        objects: impl Iterator<Item = usize>,
        ray: &Ray,
    ) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64)> = None;
        for index in objects {
            let t = scene.objects[index].shape.hit_by::<K>(ray, &mut ());
            if let Some(t) = t
                && t > 0.0
                && boxes.admits(index, ray, t)
                && best.is_none_or(|(i, b)| t < b || (t == b && index < i))
            {
                best = Some((index, t));
            }
        }
        best
    }

    /// At every pixel whose tile keeps a list, the closest hit among the list's objects
    /// is the closest among all objects, under the accurate kernel and the
    /// single-precision one, for eyes in front of the screen, behind it, off the axis and
    /// close to it, with and without pixel-centre. Objects are left out both because the
    /// ray cannot reach them and because a nearer plane hides them; in the scenes without
    /// planes nothing can hide, and no object left out has a hit there that counts.
    #[test]
    fn every_pixel_s_tile_holds_its_closest_hit() {
        let mut numbers = Numbers(0x2026_1122);
        let (mut kept, mut unreachable, mut hidden) = (0, 0, 0);
        for eye in [
            "0 0 3",
            "0 0 -3",
            "1.5 -2 0.7",
            "-3 1 12",
            "0 0 0.05",
            "0.3 0.2 2",
            "0 0 5",
        ] {
            for (pixel_centre, planes) in
                [(false, true), (true, true), (false, false), (true, false)]
            {
                let scene = scene(&mut numbers, eye, 16, planes);
                let mut options = Options::new(41, 30);
                if pixel_centre {
                    options = options
                        .with_variant(Variant::of(Kind::PixelCentre))
                        .unwrap();
                }
                let camera = Camera::new(&scene, &options, &Rules::new(&options, &scene));
                // Each kernel with the boxes the renderer gives it.
                let boxes = Boxes::for_kernel(&scene, KernelChoice::Accurate);
                let f32_boxes = Boxes::for_kernel(&scene, KernelChoice::TextbookF32);
                let pixels = (&camera.xs[..], &camera.ys[..]);
                let tiles_on = |boxes, threads: &Threads| {
                    Tiles::new(
                        &scene,
                        boxes,
                        camera.viewpoint,
                        pixels,
                        |_| false,
                        None,
                        threads,
                    )
                };
                let tiles_of = |boxes| tiles_on(boxes, &Threads::one());
                let (Some(tiles), Some(f32_tiles)) = (tiles_of(&boxes), tiles_of(&f32_boxes))
                else {
                    continue;
                };
                // Built in bands on three threads, the same lists.
                let pool = Threads::of(&Options {
                    threads: 3,
                    ..options
                });
                let banded = tiles_on(&boxes, &pool).unwrap();
                for (y, x) in (0..30).flat_map(|y| (0..41).map(move |x| (y, x))) {
                    let list = |t: &Tiles| t.at(x, y).map(|tile| tile.objects.to_vec());
                    assert_eq!(list(&banded), list(&tiles), "eye {eye}, pixel ({x}, {y})");
                }
                for y in 0..30 {
                    for x in 0..41 {
                        let Some(ray) = camera.ray(x, y) else {
                            continue;
                        };
                        let every = || 0..scene.objects.len();
                        if let Some(tile) = f32_tiles.at(x, y) {
                            let list = tile.objects;
                            let listed = list.iter().map(|&i| i as usize);
                            assert_eq!(
                                closest::<TextbookF32>(&scene, &f32_boxes, listed, &ray),
                                closest::<TextbookF32>(&scene, &f32_boxes, every(), &ray),
                                "eye {eye}, pixel ({x}, {y}), f32"
                            );
                            let left_out = every().filter(|&i| !list.contains(&(i as u32)));
                            for index in left_out.filter(|_| !planes) {
                                let alone = [index].into_iter();
                                assert_eq!(
                                    closest::<TextbookF32>(&scene, &f32_boxes, alone, &ray),
                                    None,
                                    "eye {eye}, pixel ({x}, {y}): object {index} left out, f32"
                                );
                            }
                        }
                        let Some(tile) = tiles.at(x, y) else {
                            continue;
                        };
                        let list = tile.objects;
                        kept += 1;
                        let listed = || list.iter().map(|&i| i as usize);
                        assert_eq!(
                            closest::<Accurate>(&scene, &boxes, listed(), &ray),
                            closest::<Accurate>(&scene, &boxes, every(), &ray),
                            "eye {eye}, pixel ({x}, {y})"
                        );
                        for index in every().filter(|&i| !list.contains(&(i as u32))) {
                            let alone = || [index].into_iter();
                            let hit = closest::<Accurate>(&scene, &boxes, alone(), &ray);
                            match hit {
                                Some(_) if !planes => {
                                    panic!("eye {eye}, pixel ({x}, {y}): object {index} left out")
                                }
                                Some(_) => hidden += 1,
                                None => unreachable += 1,
                            }
                        }
                    }
                }
            }
        }
        // The check means something only where tiles keep lists and leave objects out,
        // for both reasons.
        assert!(
            kept > 20_000 && unreachable > 100_000 && hidden > 1_000,
            "{kept} pixels, {unreachable} left out unreachable, {hidden} hidden"
        );
    }
}
