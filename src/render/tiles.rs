//! The objects that the camera rays of each tile of pixels can hit: every camera ray
//! starts at the eye, so an object's box seen from the eye covers a rectangle of the
//! screen, and a ray through a pixel outside it cannot reach the box. The renderer tests
//! a camera ray only against its tile's list, in file order (an item buffer), where
//! otherwise it would walk the hierarchy or test every object.
//!
//! Like the hierarchy ([`super::Bvh`]) it changes which objects are tested, never the
//! answer: a camera ray's hit on a bounded object counts only where the ray has entered
//! the object's box by then ([`super::Boxes::admits`]), so a ray whose pixel lies outside
//! the box's shadow on the screen has no hit there that counts. The rectangle is computed
//! with margins a million times larger than the rounding of the rays and of the box test.
//!
//! An unbounded object is left out of a tile only when its hits there are certainly
//! behind the eye: a plane (14, 16, 20) whose t = N·(Q - E) / N·D has opposite signs in
//! numerator and denominator at every pixel of the tile, by a margin that even the
//! single-precision kernel cannot cross. Every other object is in every tile.

use super::bvh::Boxes;
use super::lists::{Builder, Lists, MOST_OBJECTS};
use crate::scene::Scene;
use crate::shapes::Shape;
use glam::{DVec2, DVec3};
use std::ops::Range;

/// Pixels along a tile's side.
const TILE: usize = 8;

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
    /// Tiles per row.
    across: usize,
    /// Per tile, row by row.
    lists: Lists,
}

/// Where an object can be hit by camera rays.
enum Reach {
    /// Through no pixel.
    Nowhere,
    /// Through the pixels of these columns and rows.
    Pixels(Range<usize>, Range<usize>),
    /// A plane (normal, point): through the tiles where its t can be positive.
    Plane(DVec3, DVec3),
    /// Possibly through every pixel.
    Everywhere,
}

impl Tiles {
    /// The lists for camera rays from `eye` through the pixels whose world points are
    /// (`xs[x]`, `ys[y]`, 0); `None` when no tile would keep a list (more unbounded
    /// objects than [`MOST_OBJECTS`]), when there are more objects than pixels (the
    /// lists would cost more than they save: a 2x2 image of a million spheres), or when
    /// the view is too wide or the pixel coordinates are not in order.
    pub(crate) fn new(
        scene: &Scene,
        boxes: &Boxes,
        eye: DVec3,
        xs: &[f64],
        ys: &[f64],
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
        let reaches: Vec<Reach> = scene
            .objects
            .iter()
            .enumerate()
            .map(|(index, object)| match (boxes.get(index), &object.shape) {
                (Some((min, max)), _) => seen_through(eye, min, max, xs, ys),
                (None, Shape::Plane(p)) => Reach::Plane(p.normal, p.point),
                (None, Shape::TiledPlane(t)) => Reach::Plane(t.plane.normal, t.plane.point),
                (None, _) => Reach::Everywhere,
            })
            .collect();
        let unbounded = reaches
            .iter()
            .filter(|r| matches!(r, Reach::Plane(..) | Reach::Everywhere))
            .count();
        if unbounded > MOST_OBJECTS {
            return None;
        }
        let across = xs.len().div_ceil(TILE);
        let down = ys.len().div_ceil(TILE);
        let mut lists = Builder::new(across * down);
        for (index, reach) in reaches.iter().enumerate() {
            match reach {
                Reach::Nowhere => {}
                Reach::Pixels(columns, rows) => {
                    for ty in rows.start / TILE..rows.end.div_ceil(TILE) {
                        for tx in columns.start / TILE..columns.end.div_ceil(TILE) {
                            lists.add(ty * across + tx, index);
                        }
                    }
                }
                Reach::Plane(normal, point) => {
                    for ty in 0..down {
                        for tx in 0..across {
                            let corners = corners(xs, ys, tx, ty);
                            if !behind_the_eye(*normal, *point, eye, corners) {
                                lists.add(ty * across + tx, index);
                            }
                        }
                    }
                }
                Reach::Everywhere => lists.add_everywhere(index),
            }
        }
        Some(Tiles {
            across,
            lists: lists.finish(),
        })
    }

    /// The objects that the camera ray through pixel (x, y) may hit, in file order, or
    /// `None` when its tile keeps no list.
    #[inline]
    pub(crate) fn at(&self, x: usize, y: usize) -> Option<&[u32]> {
        self.lists.get(y / TILE * self.across + x / TILE)
    }
}

/// The world points of the corner pixels of tile (tx, ty).
fn corners(xs: &[f64], ys: &[f64], tx: usize, ty: usize) -> [DVec2; 4] {
    let last = |v: &[f64], t: usize| v[(t * TILE + TILE - 1).min(v.len() - 1)];
    let (x0, x1) = (xs[tx * TILE], last(xs, tx));
    let (y0, y1) = (ys[ty * TILE], last(ys, ty));
    [
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x0, y1),
        DVec2::new(x1, y1),
    ]
}

/// Whether the plane through `point` with normal `normal` is hit at t < 0 (behind the
/// eye) by every ray from `eye` through the tile whose corner points are `corners`: the
/// numerator N·(Q - E) has one sign and the denominator N·(P - E) the other at all four
/// corners (it is linear in P, so it has that sign over the whole tile), each clearly.
fn behind_the_eye(normal: DVec3, point: DVec3, eye: DVec3, corners: [DVec2; 4]) -> bool {
    let clearly = |terms: DVec3, size: f64| {
        let sum = terms.element_sum();
        if sum.abs() > SIGN_MARGIN * (terms.abs().element_sum() + size) {
            sum.signum()
        } else {
            0.0
        }
    };
    // The numerator's terms are rounded from Q and E (to single precision by the f32
    // kernel), so their own sizes count; the denominator's from the ray's direction.
    let numerator = clearly(
        normal * (point - eye),
        normal.abs().dot(point.abs() + eye.abs()),
    );
    numerator != 0.0
        && corners.iter().all(|c| {
            let towards = DVec3::new(c.x, c.y, 0.0) - eye;
            clearly(normal * towards, 0.0) == -numerator
        })
}

/// The columns and rows of the pixels whose camera rays can enter the box (min, max),
/// seen from `eye`: the box's corners projected from the eye onto z = 0, grown by
/// [`MARGIN`]. `Everywhere` when the box is not wholly on the screen's side of the eye's
/// plane z = eye.z (then some of its points project to infinity, or behind).
fn seen_through(eye: DVec3, min: DVec3, max: DVec3, xs: &[f64], ys: &[f64]) -> Reach {
    let grow = MARGIN * ((max - min).max_element() + min.abs().max(max.abs()).max_element());
    let (min, max) = (min - grow, max + grow);
    let mut low = DVec2::splat(f64::INFINITY);
    let mut high = DVec2::splat(f64::NEG_INFINITY);
    for corner in 0..8 {
        let pick = |bit: usize, a: f64, b: f64| if corner & bit == 0 { a } else { b };
        let c = DVec3::new(
            pick(1, min.x, max.x),
            pick(2, min.y, max.y),
            pick(4, min.z, max.z),
        );
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
    Reach::Pixels(columns, rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{Camera, Deviations, Options};
    use crate::shapes::Ray;
    use crate::shapes::kernel::{Accurate, Kernel, TextbookF32};

    /// A small deterministic generator (xorshift64*), so that the scenes are the same on
    /// every run.
    struct Numbers(u64);

    impl Numbers {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        }

        fn within(&mut self, low: f64, high: f64) -> f64 {
            low + (high - low) * self.next()
        }

        fn point(&mut self, reach: f64) -> String {
            let [x, y, z] = [(); 3].map(|_| self.within(-reach, reach));
            format!("{x} {y} {z}")
        }
    }

    const MATERIAL: &str = "1 1 1\n1 1 1\n0 0 0\n";

    /// A scene of `count` random spheres, cylinders, planes and rectangles seen from
    /// `eye`, some of them around the eye, behind it or across its plane z = eye.z. The
    /// rectangles face the screen or lie flat: their boxes are as thin as the padding,
    /// so their hits reach the edges of their boxes' rectangles on the screen.
    fn scene(numbers: &mut Numbers, eye: &str, count: usize) -> Scene {
        let mut text = format!("8 6\n{eye}\n");
        for _ in 0..count {
            let record = match (numbers.next() * 5.0) as usize {
                0 => format!(
                    "13\n{MATERIAL}{}\n{}\n",
                    numbers.point(8.0),
                    numbers.within(0.05, 3.0)
                ),
                1 => format!(
                    "22\n{MATERIAL}{}\n{}\n{} {}\n",
                    numbers.point(8.0),
                    numbers.point(1.0),
                    numbers.within(0.05, 2.0),
                    numbers.within(0.1, 4.0)
                ),
                2 => format!(
                    "14\n{MATERIAL}{}\n{}\n",
                    numbers.point(1.0),
                    numbers.point(8.0)
                ),
                facing => format!(
                    "15\n{MATERIAL}{}\n{}\n1 0 0\n{} {}\n",
                    ["0 0 1", "0 1 0"][facing - 3],
                    numbers.point(8.0),
                    numbers.within(0.1, 6.0),
                    numbers.within(0.1, 12.0)
                ),
            };
            text.push_str(&record);
        }
        crate::load(&text).unwrap()
    }

    /// Whether `K` finds a hit of object `index` along `ray` that counts (t > 0 and
    /// inside its box): the hits a tile must not leave out.
    fn counts<K: Kernel>(scene: &Scene, boxes: &Boxes, index: usize, ray: &Ray) -> bool {
        let shape = &scene.objects[index].shape;
        shape
            .hit_with::<K>(ray)
            .is_some_and(|t| t > 0.0 && boxes.admits(index, ray, t))
    }

    /// Every object left out of a pixel's tile has no hit there that counts, under the
    /// accurate kernel and the single-precision one, for eyes in front of the screen,
    /// behind it, off the axis and close to it, with and without pixel-centre.
    #[test]
    fn no_pixel_loses_an_object_its_ray_can_hit() {
        let mut numbers = Numbers(0x2026_1122);
        let mut left_out = 0;
        let mut kept = 0;
        for eye in [
            "0 0 3",
            "0 0 -3",
            "1.5 -2 0.7",
            "-3 1 12",
            "0 0 0.05",
            "0.3 0.2 2",
            "0 0 5",
        ] {
            for pixel_centre in [false, true] {
                let scene = scene(&mut numbers, eye, 16);
                let options = Options {
                    deviations: Deviations {
                        pixel_centre,
                        ..Deviations::default()
                    },
                    ..Options::new(41, 30)
                };
                let camera = Camera::new(&scene, &options);
                let boxes = Boxes::new(&scene);
                let Some(tiles) =
                    Tiles::new(&scene, &boxes, camera.viewpoint, &camera.xs, &camera.ys)
                else {
                    continue;
                };
                for y in 0..30 {
                    for x in 0..41 {
                        let (Some(list), Some(ray)) = (tiles.at(x, y), camera.ray(x, y)) else {
                            continue;
                        };
                        kept += 1;
                        for index in 0..scene.objects.len() {
                            if list.contains(&(index as u32)) {
                                continue;
                            }
                            left_out += 1;
                            assert!(
                                !counts::<Accurate>(&scene, &boxes, index, &ray)
                                    && !counts::<TextbookF32>(&scene, &boxes, index, &ray),
                                "eye {eye}, pixel ({x}, {y}): object {index} left out"
                            );
                        }
                    }
                }
            }
        }
        // The check means something only where tiles keep lists and leave objects out.
        assert!(
            kept > 10_000 && left_out > 50_000,
            "{kept} pixels, {left_out} left out"
        );
    }
}
