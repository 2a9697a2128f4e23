//! What one test of a ray that misses costs, shape by shape, with the shipped kernel: the
//! figures behind the hierarchy's cost model (`src/render/bvh.rs`, `miss_ns`). Each
//! shape sits 11 units in front of the eye; 2,000,000 rays from the eye pass beside it.
//! Prints the median of several passes, the shapes taking turns.
//!
//! Run: `cargo bench --bench miss_cost` (add `-- --runs N` for more passes).

mod support;

use glam::DVec3;
use legacy_rt::shapes::Ray;
use legacy_rt::shapes::kernel::KernelChoice::Accurate;
use std::hint::black_box;
use std::time::Instant;

const RAYS: usize = 2_000_000;

fn main() {
    let runs = support::runs(5);
    let material = "1 1 1\n1 1 1\n0 0 0\n";
    let records = [
        ("sphere (13)", format!("13\n{material}0 0 -8\n1\n")),
        (
            "finite plane (15)",
            format!("15\n{material}0 0 1\n-1 -1 -8\n1 0 0\n2 2\n"),
        ),
        (
            "paraboloid (21)",
            format!("21\n{material}0 -1 -8\n0 1 0\n1 2\n"),
        ),
        (
            "cylinder (22)",
            format!("22\n{material}0 -1 -8\n0 1 0\n1 2\n"),
        ),
        ("cone (23)", format!("23\n{material}0 -1 -8\n0 1 0\n1 2\n")),
        (
            "hyperboloid (24)",
            format!("24\n{material}0 -1 -8\n0 1 0\n1 1\n0.5\n"),
        ),
        (
            "QUADRIC ellipsoid",
            format!("QUADRIC 1 0 0 0 4 0 0 1 8 63\n{material}"),
        ),
    ];
    let scenes: Vec<_> = records
        .iter()
        .map(|(name, record)| {
            let scene = legacy_rt::load(&format!("8 6\n0 0 3\n{record}")).expect("it loads");
            (*name, scene)
        })
        .collect();
    let mut times = vec![Vec::new(); scenes.len()];
    for _ in 0..runs {
        for (k, (_, scene)) in scenes.iter().enumerate() {
            let shape = &scene.objects[0].shape;
            let start = Instant::now();
            let mut hits = 0;
            for i in 0..RAYS {
                // Directions to the right of and above the shape, none of them hitting it.
                let a = (i % 1000) as f64 * 0.001;
                let dir = DVec3::new(0.5 + a, 0.3 - 0.2 * a, -1.0).normalize();
                let ray = Ray::new(DVec3::new(0.0, 0.0, 3.0), dir);
                hits += usize::from(black_box(shape).hit(black_box(&ray), Accurate).is_some());
            }
            assert_eq!(hits, 0, "every ray misses");
            times[k].push(start.elapsed().as_secs_f64() * 1e9 / RAYS as f64);
        }
    }
    println!("ns per test of a missing ray, median of {runs} passes");
    for ((name, _), mut ns) in scenes.iter().zip(times) {
        ns.sort_by(f64::total_cmp);
        println!("{name:<20} {:>6.1}", ns[runs / 2]);
    }
}
