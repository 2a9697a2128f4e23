//! What `compare`'s reference costs: the plain render against the reference rendered
//! with its margins (`render_with_margins`, the fragile pixels of docs/compare.md), on the
//! course scenes spec1, a04, d04 and d05 and three examples at 640x480, single-threaded.
//! The two are timed alternately, run by run, so that a machine's drift falls on both;
//! prints the medians and their ratio (issue 25 asks at most 2).
//!
//! Run: `cargo bench --bench compare` (add `-- --runs N` for more runs).

mod support;

use legacy_rt::compare;
use legacy_rt::render::{Options, render, render_with_margins};
use std::path::Path;
use std::time::Instant;

fn main() {
    let runs = support::runs(7);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenes = [
        root.join("../shared/course-scenes/spec1.txt"),
        root.join("../shared/course-scenes/a04.txt"),
        root.join("../shared/course-scenes/d04.txt"),
        root.join("../shared/course-scenes/d05.txt"),
        root.join("examples/quadrics_gallery.txt"),
        root.join("examples/studio.txt"),
        root.join("examples/mirrors.txt"),
    ];
    let options = Options::new(640, 480);
    println!("640x480, single thread, median of {runs} alternated runs");
    println!(
        "{:<22} {:>10} {:>14} {:>7}",
        "scene", "plain ms", "margins ms", "ratio"
    );
    let time = |f: &dyn Fn()| {
        let start = Instant::now();
        f();
        start.elapsed().as_secs_f64()
    };
    for path in scenes {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let Ok(text) = std::fs::read_to_string(&path) else {
            println!("{name:<22} skipped: {} is absent", path.display());
            continue;
        };
        let scene = legacy_rt::load(&text).expect("the scene loads");
        let plain = || {
            std::hint::black_box(render(&scene, &options, |_| {}));
        };
        let margins = || {
            std::hint::black_box(render_with_margins(&scene, &options, compare::F32));
        };
        let (mut a, mut b): (Vec<f64>, Vec<f64>) =
            (0..runs).map(|_| (time(&plain), time(&margins))).unzip();
        a.sort_by(f64::total_cmp);
        b.sort_by(f64::total_cmp);
        let (a, b) = (a[runs / 2], b[runs / 2]);
        println!(
            "{name:<22} {:>10.1} {:>14.1} {:>7.2}",
            a * 1e3,
            b * 1e3,
            b / a
        );
    }
}
