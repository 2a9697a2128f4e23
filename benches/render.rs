//! Render benchmark: the course scenes spec1, a04 and d04 and the quadrics gallery at
//! 1024x768, single-threaded. Prints the median of several timed runs and rays per second.
//!
//! Run: `cargo bench --bench render` (add `-- --runs N` for more runs). Course scenes are
//! read from `../shared/course-scenes` and skipped with a message where it is absent.

mod support;

use legacy_rt::render::{Options, count_rays, render};
use std::path::Path;
use std::time::Instant;

fn main() {
    let runs = support::runs(9);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenes = [
        root.join("../shared/course-scenes/spec1.txt"),
        root.join("../shared/course-scenes/a04.txt"),
        root.join("../shared/course-scenes/d04.txt"),
        root.join("examples/quadrics_gallery.txt"),
    ];
    let options = Options::new(1024, 768);
    println!("1024x768, single thread, median of {runs} runs");
    println!(
        "{:<22} {:>8} {:>10} {:>12} {:>14} {:>12}",
        "scene", "objects", "median ms", "rays", "Mrays/s", "camera Mrays/s"
    );
    for path in scenes {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let Ok(text) = std::fs::read_to_string(&path) else {
            println!("{name:<18} skipped: {} is absent", path.display());
            continue;
        };
        let scene = legacy_rt::load(&text).expect("the scene loads");
        let stats = count_rays(&scene, &options);
        let mut times: Vec<f64> = (0..runs)
            .map(|_| {
                let start = Instant::now();
                let image = render(&scene, &options, |_| {});
                std::hint::black_box(image);
                start.elapsed().as_secs_f64()
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let median = times[runs / 2];
        println!(
            "{:<22} {:>8} {:>10.1} {:>12} {:>14.2} {:>12.2}",
            name,
            scene.objects.len(),
            median * 1e3,
            stats.total(),
            stats.total() as f64 / median / 1e6,
            stats.camera as f64 / median / 1e6,
        );
    }
}
