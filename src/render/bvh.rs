//! A bounding volume hierarchy over the scene's bounded objects, so that the closest-hit
//! and shadow tests of spec §4.3 and §4.6 visit a few boxes instead of every object.
//!
//! It changes which objects are *tested*, never the answer. Every object whose box the
//! ray enters before the best hit so far is tested exactly as the linear scan tests it,
//! and the best hit is chosen with the scan's rule: smallest t, and on an exact tie the
//! earlier object. Both count a hit on a bounded object only where the ray has entered
//! the object's padded box by then ([`Boxes::admits`]), with the same arithmetic as the
//! traversal's box tests: a kernel's t for a shape thinner than the rounding of its
//! coordinates (a paraboloid of height 1e-21) can lie far outside the shape, and the
//! tree must not skip what the scan would take. For ordinary shapes every hit lies well
//! inside its box, so the test changes nothing there. Unbounded objects (planes, tiled
//! planes, open `QUADRIC` records) have no box and are tested for every ray.
//!
//! The tree is built once per render. Each split is chosen along the longest axis of the
//! centroids by the binned surface area heuristic, which can make a lopsided tree (700
//! spheres at x = 1.5^i make a chain); below depth [`SAH_DEPTH`] the split is at the
//! median instead, which halves the objects at each level, so no tree is deeper than
//! `SAH_DEPTH` + 32 and the traversal stack cannot overflow. Each leaf holds one object.
//! The build is deterministic: ties are broken by object index, and the halves of a
//! large split, built at once on two threads, fill parts of the arrays fixed in advance.

use crate::scene::Scene;
use crate::shapes::Ray;
use crate::shapes::Shape;
use crate::shapes::kernel::KernelChoice;
use crate::threads::Threads;
use glam::DVec3;

/// The hierarchy is built when testing every bounded object costs at least this much
/// per ray, in ns of the tests of rays that miss ([`miss_ns`]): walking even a small
/// tree (its stack, the root's box) costs about three sphere tests. Measured with
/// callgrind at 320x240 once camera rays took their tiles' lists: 2 and 3 spheres
/// (spec1, d04: 17.8 and 26.7 ns) scan in 1.14x and 1.09x fewer instructions than they
/// walk, a sphere and a cylinder (examples/mirrors.txt, 31.0 ns) walk in 1.16x fewer.
/// Of the scenes measured, only 2 and 4 rectangles alone (examples/finite_planes.txt,
/// d03) would scan 1.02x and 1.07x faster than they walk.
pub(crate) const HIERARCHY_FROM_NS: f64 = 30.0;

/// What building the tree costs per object and level, in ray-shape tests: callgrind
/// counts about 220 instructions per object per level of the build (100,000 spheres:
/// 364M instructions over 16.6 levels) and about 140 per sphere test.
const BUILD_COST_IN_TESTS: f64 = 1.6;

/// The fewest objects whose two halves are built on two threads at once: below it a
/// subtree is built in less time than handing it to another thread costs.
const PARALLEL_FROM: usize = 4096;

/// The depth below which splits are at the median rather than by the surface area
/// heuristic. Real scenes' trees are far shallower; this only bounds degenerate ones.
const SAH_DEPTH: usize = 31;

/// The deepest a tree can be: `SAH_DEPTH` levels of any split, then median splits, which
/// halve the objects at each level (and there are fewer than 2^32 of them, as indices are
/// `u32`). The traversal's stack then has 64 entries, a size the compiler clears without
/// a call to `memset`.
const MAX_DEPTH: usize = SAH_DEPTH + 32;

/// An axis-aligned box.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Aabb {
    min: DVec3,
    max: DVec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Whether the ray enters the box at some t in [0, limit]. A zero direction
    /// component gives ±inf or NaN slabs; `f64::min` and `max` drop the NaN (in
    /// WebAssembly, [`compared`]), so a ray lying in a face's plane counts as inside,
    /// which is safe (it only tests more).
    #[inline]
    fn entered(&self, base: DVec3, inverse: DVec3, limit: f64) -> bool {
        let near = (self.min - base) * inverse;
        let far = (self.max - base) * inverse;
        #[cfg(not(target_arch = "wasm32"))]
        let (enter, leave) = (
            near.min(far).max_element().max(0.0),
            near.max(far).min_element(),
        );
        #[cfg(target_arch = "wasm32")]
        let (enter, leave) = {
            let [x, y, z] =
                [(near.x, far.x), (near.y, far.y), (near.z, far.z)].map(|(n, f)| compared(n, f));
            let low = DVec3::new(x.0, y.0, z.0).max_element();
            (
                compared(low, 0.0).1,
                DVec3::new(x.1, y.1, z.1).min_element(),
            )
        };
        enter <= leave && enter <= limit
    }
}

/// The smaller and the larger of `a` and `b`, a NaN dropped, as `f64::min` and `max`
/// give them, by comparisons: for WebAssembly, which has no instruction that drops a NaN
/// and calls a function for those (of two equal zeros either may come out, which no
/// comparison of the box tests tells apart).
#[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
#[inline(always)]
fn compared(a: f64, b: f64) -> (f64, f64) {
    let low = if a < b || b.is_nan() { a } else { b };
    let high = if a > b || b.is_nan() { a } else { b };
    (low, high)
}

/// A node: a box and either two children (`count == 0`: the left child follows this
/// node, the right one is at `first`) or `count` objects at `order[first..]`.
#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: Aabb,
    first: u32,
    count: u32,
    /// The axis the children were split on (0, 1, 2): a ray going up that axis visits
    /// the left (lower) child first, so that the best hit shrinks the search early.
    axis: u32,
}

impl Node {
    /// A node not yet built: every one is overwritten by [`build`].
    const UNSET: Node = Node {
        bounds: Aabb::EMPTY,
        first: 0,
        count: 0,
        axis: 0,
    };
}

/// Every object's padded box in scene order, `None` for an object without one, and
/// what testing every bounded object costs.
#[derive(Debug, Clone)]
pub(crate) struct Boxes {
    boxes: Vec<Option<Aabb>>,
    /// The sum of [`miss_ns`] over the objects with a box.
    scan_ns: f64,
}

impl Boxes {
    /// The boxes of `scene`'s objects, padded for the hits of `kernel`
    /// ([`KernelChoice::box_padding`]).
    #[cfg(test)]
    pub(crate) fn for_kernel(scene: &Scene, kernel: KernelChoice) -> Boxes {
        Boxes::on(scene, kernel, &Threads::one())
    }

    /// [`Boxes::for_kernel`], the boxes found on `threads`.
    pub(crate) fn on(scene: &Scene, kernel: KernelChoice, threads: &Threads) -> Boxes {
        let padding = kernel.box_padding();
        let objects = &scene.objects;
        let boxes: Vec<Option<Aabb>> = threads.map(objects.len(), |i| {
            let (min, max) = objects[i].shape.bounds()?;
            Some(pad(Aabb { min, max }, padding))
        });
        let scan_ns = (scene.objects.iter().zip(&boxes))
            .filter(|(_, b)| b.is_some())
            .map(|(object, _)| miss_ns(&object.shape))
            .sum();
        Boxes { boxes, scan_ns }
    }

    /// Object `index`'s padded box (min, max), if it has one.
    pub(crate) fn get(&self, index: usize) -> Option<(DVec3, DVec3)> {
        self.boxes[index].map(|b| (b.min, b.max))
    }

    /// Whether a hit at distance `t` on object `index` counts: `ray` has entered the
    /// object's box by `t`, or the object has no box.
    #[inline]
    pub(crate) fn admits(&self, index: usize, ray: &Ray, t: f64) -> bool {
        Boxes::admitted(self.of(index), ray, t)
    }

    /// Object `index`'s box, for [`Boxes::admitted`] of many rays.
    #[inline(always)]
    pub(crate) fn of(&self, index: usize) -> Option<&Aabb> {
        self.boxes[index].as_ref()
    }

    /// [`Boxes::admits`] of an object whose box is `of`.
    #[inline(always)]
    pub(crate) fn admitted(of: Option<&Aabb>, ray: &Ray, t: f64) -> bool {
        of.is_none_or(|b| b.entered(ray.base, ray.dir.recip(), t))
    }
}

/// The hierarchy: nodes, the bounded objects' indices in leaf order, and the indices of
/// the objects that have no box.
#[derive(Debug, Clone)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    unbounded: Vec<u32>,
    /// The depth of the deepest node (0: the root alone).
    depth: usize,
}

impl Bvh {
    /// The tree over `boxes` if it pays for `rays` camera rays: not when scanning the
    /// bounded objects costs less than `HIERARCHY_FROM_NS`, nor when building it costs
    /// more than scanning
    /// (a 2x2 image of a million spheres: 4 rays against a build of 20 levels).
    pub(crate) fn for_rays(boxes: &Boxes, rays: usize, threads: &Threads) -> Option<Bvh> {
        let bounded = boxes.boxes.iter().flatten().count() as f64;
        let build = BUILD_COST_IN_TESTS * bounded.log2().max(1.0);
        if (rays as f64) < build {
            return None;
        }
        Bvh::over(boxes, threads)
    }

    /// The tree over `boxes`, built on `threads`, or `None` when scanning them costs less
    /// than `HIERARCHY_FROM_NS`.
    pub(crate) fn over(boxes: &Boxes, threads: &Threads) -> Option<Bvh> {
        if boxes.scan_ns < HIERARCHY_FROM_NS {
            return None;
        }
        let mut items = Vec::new();
        let mut unbounded = Vec::new();
        for (index, b) in boxes.boxes.iter().enumerate() {
            match b {
                Some(b) => items.push(Item {
                    index: index as u32,
                    bin: 0,
                    bounds: *b,
                }),
                None => unbounded.push(index as u32),
            }
        }
        // One object a leaf: a tree over n objects has n leaves and n - 1 inner nodes,
        // so each subtree's place in the arrays is known before it is built.
        let n = items.len();
        // Filled on the threads: a million objects' nodes are 128 MB.
        let mut nodes = threads.map((2 * n).saturating_sub(1), |_| Node::UNSET);
        let mut order = vec![0; n];
        let depth = threads.run(|| {
            let place = Place {
                nodes: &mut nodes,
                order: &mut order,
                at: 0,
                first: 0,
            };
            build(items.as_mut_slice(), place, 0, threads)
        });
        Some(Bvh {
            nodes,
            order,
            unbounded,
            depth,
        })
    }

    /// The closest hit (smallest t, ties to the lower index) among the objects for which
    /// `test` gives a distance that `counts` accepts; `test` skips the caller's skipped
    /// object, and `counts` (t > 0, inside the object's box) is asked only of a hit
    /// that would win. Boxes entered up to `slack` times the best t so far are visited
    /// (1: only those that can still win). Inlined always, as is [`Bvh::any`]: with the
    /// span and the pixel loop both calling them, the compiler kept them out of line, and
    /// the plain render of twin_many took 9 % longer (bench/compare.sh's scene).
    #[inline(always)]
    pub(crate) fn closest(
        &self,
        ray: &Ray,
        mut test: impl FnMut(usize) -> Option<f64>,
        counts: impl Fn(usize, f64) -> bool,
        slack: f64,
    ) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64)> = None;
        self.walk(ray, |objects| {
            for &index in objects {
                let index = index as usize;
                if let Some(t) = test(index)
                    && beats(best, index, t)
                    && counts(index, t)
                {
                    best = Some((index, t));
                }
            }
            Some(best.map_or(f64::INFINITY, |(_, t)| t * slack))
        });
        best
    }

    /// Whether `test` finds any object among those whose boxes the ray enters before
    /// `limit`.
    #[inline(always)]
    pub(crate) fn any(&self, ray: &Ray, limit: f64, mut test: impl FnMut(usize) -> bool) -> bool {
        self.walk(ray, |objects| {
            (!objects.iter().any(|&index| test(index as usize))).then_some(limit)
        })
    }

    /// Hands `visit` the unbounded objects, then the objects of every leaf whose box the
    /// ray enters before the limit `visit` last returned, nearer child first. `visit`
    /// returns the new limit, or `None` to stop; `walk` returns whether it was stopped.
    #[inline]
    fn walk(&self, ray: &Ray, visit: impl FnMut(&[u32]) -> Option<f64>) -> bool {
        // A stack as deep as the tree needs: a new stack is cleared, and clearing the 64
        // entries of the deepest possible tree took a quarter of a shadow ray's walk
        // (twin_many: 26 of 83 instructions).
        match self.depth < SHALLOW {
            true => self.walk_with::<SHALLOW>(ray, visit),
            false => self.walk_with::<{ MAX_DEPTH + 1 }>(ray, visit),
        }
    }

    /// [`Bvh::walk`] with a stack of `N` entries, at least the tree's depth plus one.
    #[inline(always)]
    fn walk_with<const N: usize>(
        &self,
        ray: &Ray,
        mut visit: impl FnMut(&[u32]) -> Option<f64>,
    ) -> bool {
        let Some(mut limit) = visit(&self.unbounded) else {
            return true;
        };
        let inverse = ray.dir.recip();
        let mut stack = Stack::<N>::new();
        while let Some(at) = stack.pop() {
            let node = self.nodes[at];
            if !node.bounds.entered(ray.base, inverse, limit) {
                continue;
            }
            if node.count > 0 {
                let first = node.first as usize;
                match visit(&self.order[first..first + node.count as usize]) {
                    Some(new) => limit = new,
                    None => return true,
                }
            } else if ray.dir[node.axis as usize] < 0.0 {
                stack.push(at + 1);
                stack.push(node.first as usize);
            } else {
                stack.push(node.first as usize);
                stack.push(at + 1);
            }
        }
        false
    }
}

/// What testing `shape` costs, in ns, for a ray that misses it, with the shipped kernel
/// (`cargo bench --bench miss_cost`, medians of 5 passes on the machine of issue 16: the
/// sphere 8.9, the rectangle 16.7, the quadrics 21-24 21.4-22.6; an ellipsoid `QUADRIC`,
/// measured later, 26.5 and 26.9 where the sphere took 9.4 and 7.6).
fn miss_ns(shape: &Shape) -> f64 {
    match shape {
        Shape::Sphere(_) => 8.9,
        Shape::FinitePlane(_) => 16.7,
        Shape::Quadric(_) => 27.0,
        _ => 22.0,
    }
}

/// Whether a hit at `t` on object `index` beats `best`, the closest so far in whatever
/// order objects are tested: a smaller t, or on an exact tie the earlier object, which
/// is the linear scan's answer (spec §4.6).
#[inline(always)]
pub(crate) fn beats(best: Option<(usize, f64)>, index: usize, t: f64) -> bool {
    best.is_none_or(|(i, b)| t < b || (t == b && index < i))
}

/// Where a subtree goes: its nodes (its root first, then the left subtree, then the
/// right) and its objects in leaf order, slices of the tree's arrays that begin at `at`
/// and `first`.
struct Place<'t> {
    nodes: &'t mut [Node],
    order: &'t mut [u32],
    at: u32,
    first: u32,
}

/// Builds the subtree of `items` (at least one), whose root is at `depth` (0 for the
/// whole tree), into `place`, and returns the depth of its deepest node. The two halves
/// of a split of at least [`PARALLEL_FROM`] objects are built at once on `threads` (in
/// [`Threads::run`]): each fills its own part of the arrays, so the tree is the same
/// whatever the threads.
fn build(items: &mut [Item], place: Place<'_>, depth: usize, threads: &Threads) -> usize {
    debug_assert!(depth <= MAX_DEPTH, "median splits bound the depth");
    let (root, nodes) = place.nodes.split_first_mut().expect("a node per item");
    // The items' box, and below their centroids' box: over slices of them on `threads`
    // for a large split (unions are exact, so any grouping gives these).
    let union = |a: Aabb, b: Aabb| a.union(b);
    let bounds = match threads.slices(items.len()) {
        false => bounds_of(items),
        true => threads.fold_slices(items, |items| bounds_of(items), union),
    };
    if let [item] = items {
        place.order[0] = item.index;
        *root = Node {
            bounds,
            first: place.first,
            count: 1,
            axis: 0,
        };
        return depth;
    }
    let centre = |b: &Aabb| b.min + b.max;
    let spread = match threads.slices(items.len()) {
        false => centres_of(items),
        true => threads.fold_slices(items, |items| centres_of(items), union),
    };
    let extent = spread.max - spread.min;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let sah = (depth < SAH_DEPTH)
        .then(|| sah_split(items, axis, spread.min[axis], extent[axis], threads))
        .flatten();
    let middle = match sah {
        Some(middle) => middle,
        None => {
            let middle = items.len() / 2;
            items.select_nth_unstable_by(middle, |a, b| {
                let (p, q) = (centre(&a.bounds)[axis], centre(&b.bounds)[axis]);
                p.total_cmp(&q).then(a.index.cmp(&b.index))
            });
            middle
        }
    };
    // The left subtree's 2 * middle - 1 nodes follow the root; the right one's come next.
    let right_at = place.at + 2 * middle as u32;
    *root = Node {
        bounds,
        first: right_at,
        count: 0,
        axis: axis as u32,
    };
    let parallel = items.len() >= PARALLEL_FROM;
    let (left_items, right_items) = items.split_at_mut(middle);
    let (left_nodes, right_nodes) = nodes.split_at_mut(2 * middle - 1);
    let (left_order, right_order) = place.order.split_at_mut(middle);
    let left = Place {
        nodes: left_nodes,
        order: left_order,
        at: place.at + 1,
        first: place.first,
    };
    let right = Place {
        nodes: right_nodes,
        order: right_order,
        at: right_at,
        first: place.first + middle as u32,
    };
    let left = || build(left_items, left, depth + 1, threads);
    let right = || build(right_items, right, depth + 1, threads);
    let (left, right) = match parallel {
        true => threads.join(left, right),
        false => (left(), right()),
    };
    left.max(right)
}

/// The box of `items`' boxes.
#[inline(always)]
fn bounds_of(items: &[Item]) -> Aabb {
    (items.iter()).fold(Aabb::EMPTY, |b, item| b.union(item.bounds))
}

/// The box of `items`' centroids (each `min + max`, twice the centre).
#[inline(always)]
fn centres_of(items: &[Item]) -> Aabb {
    items.iter().fold(Aabb::EMPTY, |b, item| {
        let c = item.bounds.min + item.bounds.max;
        b.union(Aabb { min: c, max: c })
    })
}

/// Each bin's count of items and their box.
type Bins = ([usize; BINS], [Aabb; BINS]);

/// Each item's bin (by `bin`), kept in it, and each bin's count and box added to
/// `counts` and `boxes`.
#[inline(always)]
fn binned(
    items: &mut [Item],
    bin: impl Fn(&Aabb) -> usize,
    (counts, boxes): (&mut [usize; BINS], &mut [Aabb; BINS]),
) {
    for item in items.iter_mut() {
        let k = bin(&item.bounds);
        item.bin = k as u32;
        counts[k] += 1;
        boxes[k] = boxes[k].union(item.bounds);
    }
}

/// Bins of the surface area heuristic.
const BINS: usize = 16;

/// Parts `items` into two groups along `axis` by the binned surface area heuristic (the
/// split that minimises each side's box area times its object count) and returns the
/// size of the first group; `None` if every centroid falls in one bin. Centroids are
/// `min + max` (twice the centre), spread over `[low, low + extent]`.
fn sah_split(
    items: &mut [Item],
    axis: usize,
    low: f64,
    extent: f64,
    threads: &Threads,
) -> Option<usize> {
    if extent <= 0.0 || !extent.is_finite() {
        return None;
    }
    let bin = |b: &Aabb| {
        let c = (b.min + b.max)[axis];
        (((c - low) / extent * BINS as f64) as usize).min(BINS - 1)
    };
    // Each bin's count and box (counted over slices on `threads` for a large split).
    let mut counts = [0usize; BINS];
    let mut boxes = [Aabb::EMPTY; BINS];
    match threads.slices(items.len()) {
        false => binned(items, bin, (&mut counts, &mut boxes)),
        true => {
            let slice = |items: &mut [Item]| {
                let mut bins = ([0usize; BINS], [Aabb::EMPTY; BINS]);
                binned(items, bin, (&mut bins.0, &mut bins.1));
                bins
            };
            let add = |(mut counts, mut boxes): Bins, (more, wider): Bins| {
                for k in 0..BINS {
                    counts[k] += more[k];
                    boxes[k] = boxes[k].union(wider[k]);
                }
                (counts, boxes)
            };
            (counts, boxes) = threads.fold_slices(items, slice, add);
        }
    }
    let area = |b: Aabb| {
        let d = (b.max - b.min).max(DVec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    };
    // Sweep from the right for the right-hand sides, then from the left.
    let mut right = [(0usize, Aabb::EMPTY); BINS];
    let mut acc = (0, Aabb::EMPTY);
    for k in (1..BINS).rev() {
        acc = (acc.0 + counts[k], acc.1.union(boxes[k]));
        right[k] = acc;
    }
    let mut left = (0, Aabb::EMPTY);
    let mut best: Option<(f64, usize)> = None;
    for k in 1..BINS {
        left = (left.0 + counts[k - 1], left.1.union(boxes[k - 1]));
        let (n_right, box_right) = right[k];
        if left.0 == 0 || n_right == 0 {
            continue;
        }
        let cost = area(left.1) * left.0 as f64 + area(box_right) * n_right as f64;
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, k));
        }
    }
    let (_, split) = best?;
    Some(partition(items, |item| (item.bin as usize) < split))
}

/// Moves the items `left` takes before the others and returns how many it takes, in one
/// pass (`<[T]>::partition_in_place` is not stable yet). The order within each side is
/// left as it falls: a split decides only the sides' sets, for each later step is blind
/// to the order (the boxes' unions, the bins' counts, the median's selection by centroid
/// then index, a leaf's one object), so the tree is the one a sort by side and index
/// made, at O(n) a level instead of O(n log n) (a million spheres: 17.8G instructions to
/// build -> 4.7G, callgrind; 4.0G with [`Item::bin`] kept).
fn partition<T>(items: &mut [T], left: impl Fn(&T) -> bool) -> usize {
    let mut taken = 0;
    for i in 0..items.len() {
        if left(&items[i]) {
            items.swap(taken, i);
            taken += 1;
        }
    }
    taken
}

/// A bounded object while the tree is built: its index, its box, and the bin of the
/// split being chosen (kept from the count to the partition, which would otherwise
/// compute it again; the three take the 56 bytes that the index and the box took).
#[derive(Clone, Copy)]
struct Item {
    index: u32,
    bin: u32,
    bounds: Aabb,
}

/// The nodes still to visit, starting with the root. Visiting a node pops it and pushes
/// at most its two children, so the stack holds at most one node per level plus one: a
/// tree whose deepest node is at depth D needs D + 1 entries, and `MAX_DEPTH + 1` always
/// suffice.
struct Stack<const N: usize> {
    nodes: [u32; N],
    len: usize,
}

/// The entries of the stack of a tree shallower than this: every course scene's (a04's
/// 30 boxes make a tree 6 deep), 112 spheres' (7) and 1,000 objects' (13); a million
/// spheres make one 24 deep.
const SHALLOW: usize = 16;

impl<const N: usize> Stack<N> {
    #[inline]
    fn new() -> Stack<N> {
        Stack {
            nodes: [0; N],
            len: 1,
        }
    }

    #[inline]
    fn push(&mut self, node: usize) {
        self.nodes[self.len] = node as u32;
        self.len += 1;
    }

    #[inline]
    fn pop(&mut self) -> Option<usize> {
        self.len = self.len.checked_sub(1)?;
        Some(self.nodes[self.len] as usize)
    }
}

/// Grows a box by `padding` times its size plus its distance from the origin: a kernel's
/// hit lies off the exact surface by its rounding (and the accurate kernel accepts
/// points a few ulps outside a shape's bounds), and such a point must still lie inside
/// the box.
fn pad(b: Aabb, padding: f64) -> Aabb {
    let size = (b.max - b.min).max_element() + b.min.abs().max(b.max.abs()).max_element();
    let margin = DVec3::splat(padding * size + f64::MIN_POSITIVE);
    Aabb {
        min: b.min - margin,
        max: b.max + margin,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_compared_minimum_and_maximum_are_f64_s() {
        // The WebAssembly form of the slabs' ends against f64::min and max, on the values
        // a slab takes: signed zeros and infinities, NaN, and ordinary numbers.
        let values = [
            0.0,
            -0.0,
            1.5,
            -2.25,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e-310,
        ];
        let same = |x: f64, y: f64| x == y || (x.is_nan() && y.is_nan());
        for a in values {
            for b in values {
                let (low, high) = compared(a, b);
                assert!(same(low, a.min(b)) && same(high, a.max(b)), "{a} {b}");
            }
        }
    }
    use crate::render::Options;
    use crate::shapes::kernel::{Accurate, Kernel, Stable, Textbook, TextbookF32};
    use crate::shapes::testing::Numbers;

    /// A scene of course-like objects: rectangles lying in the coordinate planes (boxes of
    /// zero thickness, as in the course's scenes d05 and d06), turned rectangles,
    /// spheres and cylinders, within 10 of the origin.
    fn scene(numbers: &mut Numbers) -> Scene {
        let mut text = String::from("8 6\n0 3 7\n");
        let mut at = |reach: f64| {
            let [x, y, z] = [(); 3].map(|_| numbers.within(-reach, reach));
            format!("{x} {y} {z}")
        };
        for k in 0..40 {
            let material = "1 1 1\n1 1 1\n0 0 0\n";
            let record = match k % 5 {
                0 => format!("15\n{material}0 1 0\n{}\n1 0 0\n5 5\n", at(8.0)),
                1 => format!("15\n{material}0 0 1\n{}\n3 0 0\n2 7\n", at(8.0)),
                2 => format!("15\n{material}3 0 4\n{}\n4 0 -3\n5 5\n", at(8.0)),
                3 => format!("13\n{material}{}\n0.5\n", at(8.0)),
                _ => format!("22\n{material}{}\n{}\n1 3\n", at(8.0), at(1.0)),
            };
            text.push_str(&record);
        }
        crate::load(&text).unwrap()
    }

    /// The hits of kernel `K` on every object, for camera rays from the eye and for rays
    /// from points on the objects (shadow and mirror rays), that `boxes` does not admit.
    fn refused<K: Kernel>(scene: &Scene, boxes: &Boxes, numbers: &mut Numbers) -> (usize, usize) {
        let (mut hits, mut refused) = (0, 0);
        for _ in 0..4000 {
            let screen = DVec3::new(numbers.within(-4.0, 4.0), numbers.within(-3.0, 3.0), 0.0);
            let eye = DVec3::new(0.0, 3.0, 7.0);
            let camera = Ray::new(eye, (screen - eye).normalize());
            // A ray from the camera ray's first counted hit, in a random direction.
            let from_hit = (0..scene.objects.len())
                .filter_map(|i| {
                    Some((
                        i,
                        scene.objects[i]
                            .shape
                            .hit(&camera, KernelChoice::Accurate)?,
                    ))
                })
                .filter(|&(_, t)| t > 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(_, t)| {
                    let dir = DVec3::new(
                        numbers.within(-1.0, 1.0),
                        numbers.within(-1.0, 1.0),
                        numbers.within(-1.0, 1.0),
                    );
                    Ray::new(camera.base + t * camera.dir, dir.normalize())
                });
            for ray in [Some(camera), from_hit].into_iter().flatten() {
                for (index, object) in scene.objects.iter().enumerate() {
                    if let Some(t) = object.shape.hit_by::<K>(&ray, &mut ())
                        && t > 0.0
                    {
                        hits += 1;
                        refused += usize::from(!boxes.admits(index, &ray, t));
                    }
                }
            }
        }
        (hits, refused)
    }

    /// Every hit of every kernel lies in its object's box as padded for that kernel, so
    /// that the boxes never drop a hit the kernel found (`Boxes::admits`). The f32
    /// kernel's hits on rectangles in boxes of zero thickness need its own padding: with
    /// the f64 kernels' they are refused, which is what the test would catch.
    #[test]
    fn every_kernel_s_hits_lie_in_their_boxes() {
        let mut numbers = Numbers(0x2026_1123);
        for _ in 0..3 {
            let scene = scene(&mut numbers);
            let boxes = |kernel| Boxes::for_kernel(&scene, kernel);
            let all = [
                refused::<Accurate>(&scene, &boxes(KernelChoice::Accurate), &mut numbers),
                refused::<Stable>(&scene, &boxes(KernelChoice::Stable), &mut numbers),
                refused::<Textbook>(&scene, &boxes(KernelChoice::Textbook), &mut numbers),
                refused::<TextbookF32>(&scene, &boxes(KernelChoice::TextbookF32), &mut numbers),
            ];
            for (kernel, (hits, refused)) in KernelChoice::ALL.iter().zip(all) {
                assert!(hits > 2000, "{kernel:?}: {hits} hits");
                assert_eq!(refused, 0, "{kernel:?}: {refused} of {hits} hits refused");
            }
            let narrow = boxes(KernelChoice::Accurate);
            let (hits, refused) = refused::<TextbookF32>(&scene, &narrow, &mut numbers);
            assert!(
                refused * 50 > hits,
                "f32 in f64 boxes: {refused} of {hits} refused"
            );
        }
    }

    /// The boxes of `scene` for the shipped kernel.
    fn boxes(scene: &Scene) -> Boxes {
        Boxes::for_kernel(scene, KernelChoice::Accurate)
    }

    #[test]
    fn a_partition_puts_what_it_takes_first_and_keeps_every_item() {
        // Every choice of which of 10 items to take: the first `taken` are exactly the
        // taken ones, the rest the others, and no item is lost or repeated.
        for mask in 0u32..1024 {
            let takes = |i: &u32| mask & (1 << i) != 0;
            let mut items: Vec<u32> = (0..10).collect();
            let taken = partition(&mut items, takes);
            assert_eq!(taken, mask.count_ones() as usize);
            assert!(items[..taken].iter().all(takes));
            assert!(!items[taken..].iter().any(takes));
            let mut sorted = items.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..10).collect::<Vec<_>>());
        }
    }

    #[test]
    fn the_hierarchy_is_built_where_it_pays_for_its_rays() {
        let spheres = |n: usize| -> String {
            let one = |i: usize| format!("13\n1 1 1\n1 1 1\n0 0 0\n{} 0 -8\n0.4\n", i as f64 - 2.0);
            format!("8 6\n0 0 3\n{}", (0..n).map(one).collect::<String>())
        };
        // Three spheres cost less to test than a walk of their tree (27 ns against 30, in
        // `HIERARCHY_FROM_NS`): scanned; four, or three and a cylinder: a tree, for any real
        // image.
        let one = Threads::one();
        let three = boxes(&crate::load(&spheres(3)).unwrap());
        assert!(Bvh::for_rays(&three, 640 * 480, &one).is_none());
        let four = boxes(&crate::load(&spheres(4)).unwrap());
        assert!(Bvh::for_rays(&four, 640 * 480, &one).is_some());
        let cylinder = "22\n1 1 1\n1 1 1\n0 0 0\n3 0 -8\n0 1 0\n0.4 1\n";
        let mixed = crate::load(&format!("{}{cylinder}", spheres(3))).unwrap();
        assert!(Bvh::for_rays(&boxes(&mixed), 640 * 480, &one).is_some());
        // 1,000 objects: the build costs about 1.6 × log2(1000) = 16 tests per object, more than
        // 4 rays scanning every object, less than a 16x12 image does.
        let many = boxes(&crate::load(&spheres(1000)).unwrap());
        assert!(Bvh::for_rays(&many, 4, &one).is_none());
        assert!(Bvh::for_rays(&many, 16 * 12, &one).is_some());
    }

    /// Built on three threads, the tree over 70,000 spheres (so that several splits are
    /// built at once, and the largest ones' boxes and bins counted over slices at once)
    /// is the one built on one thread: the same nodes, objects and depth. And it is a
    /// tree over them: every object in one leaf, every inner node's box
    /// holding its children's, its right child where the left subtree ends.
    #[test]
    fn the_tree_built_on_threads_is_the_tree_built_on_one() {
        let mut numbers = Numbers(0x2026_1127);
        let mut text = String::from("8 6\n0 0 3\n");
        for _ in 0..70_000 {
            let [x, y, z] = [(); 3].map(|_| numbers.within(-50.0, 50.0));
            let r = numbers.within(0.01, 2.0);
            text.push_str(&format!("13\n1 1 1\n1 1 1\n0 0 0\n{x} {y} {z}\n{r}\n"));
        }
        let scene = crate::load(&text).unwrap();
        let boxes = boxes(&scene);
        let one = Bvh::over(&boxes, &Threads::one()).unwrap();
        let options = Options {
            threads: 3,
            ..Options::new(8, 6)
        };
        let three = Bvh::over(&boxes, &Threads::of(&options)).unwrap();
        assert_eq!(format!("{three:?}"), format!("{one:?}"));
        // The subtree at `at`: its objects' count, after checking its boxes and links.
        fn check(bvh: &Bvh, at: usize, seen: &mut [bool]) -> usize {
            let node = bvh.nodes[at];
            if node.count > 0 {
                let index = bvh.order[node.first as usize] as usize;
                assert!(
                    !std::mem::replace(&mut seen[index], true),
                    "object {index} twice"
                );
                return node.count as usize;
            }
            let (left, right) = (at + 1, node.first as usize);
            for child in [left, right] {
                let b = bvh.nodes[child].bounds;
                assert!(node.bounds.min.cmple(b.min).all() && b.max.cmple(node.bounds.max).all());
            }
            let n = check(bvh, left, seen);
            assert_eq!(
                right,
                left + 2 * n - 1,
                "the right child follows the left subtree"
            );
            n + check(bvh, right, seen)
        }
        let mut seen = vec![false; scene.objects.len()];
        assert_eq!(check(&three, 0, &mut seen), 70_000);
        assert!(seen.iter().all(|&s| s));
    }
}
