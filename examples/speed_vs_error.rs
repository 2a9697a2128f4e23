//! The speed-against-error report of issue 4:
//!
//! ```text
//! cargo run --release --example speed_vs_error
//! ```
//!
//! For each kernel (the shipped `accurate`, `stable`, `textbook`, `textbook-f32`) and each
//! kind of surface it measures, on the hard-case suite of tests/support/accuracy.rs: the
//! time per ray-surface test (median of 15 timed passes over all the kind's cases, the kernels taking turns), the
//! largest and median error in ulps of the exact root, the hits that should be misses and
//! the misses that should be hits (outside ties), and the ties. Then whole-image rays per
//! second on two example scenes. It prints the tables and writes them to
//! docs/speed-vs-error.md with the chart docs/speed-vs-error.svg.

#[path = "../tests/support/accuracy.rs"]
mod accuracy;

use accuracy::{Case, Family, Reference, SHAPES, Tally, reference, suite, tally};
use legacy_rt::render::{Options, count_rays, render};
use legacy_rt::shapes::kernel::KernelChoice;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

/// One kernel's figures for one kind of surface.
struct Row {
    kernel: &'static str,
    shape: &'static str,
    ns: f64,
    tally: Tally,
}

/// Time per test, in ns, of one pass of `kernel` over `cases` (20 times each).
fn pass(kernel: KernelChoice, cases: &[&Case]) -> f64 {
    let start = Instant::now();
    let mut hits = 0usize;
    for _ in 0..20 {
        for case in cases {
            hits += black_box(case.shape.hit(black_box(&case.ray), kernel)).is_some() as usize;
        }
    }
    black_box(hits);
    start.elapsed().as_secs_f64() * 1e9 / (20 * cases.len()) as f64
}

/// Median time per test of each kernel (in `KernelChoice::ALL` order) over `cases`. The
/// kernels take turns, pass by pass, so that a change of clock speed or a neighbour's
/// load on the shared machine falls on all of them alike.
fn times_per_test(cases: &[&Case]) -> [f64; 4] {
    for kernel in KernelChoice::ALL {
        pass(kernel, cases); // warm-up
    }
    let mut samples: [Vec<f64>; 4] = Default::default();
    for round in 0..15 {
        for k in 0..4 {
            let k = (k + round) % 4;
            samples[k].push(pass(KernelChoice::ALL[k], cases));
        }
    }
    samples.map(|mut times| {
        times.sort_by(f64::total_cmp);
        times[times.len() / 2]
    })
}

/// The rows of every kernel for every kind of surface, and the time per test of each
/// family (accurate, textbook).
fn rows(families: &[(Family, Vec<Reference>)]) -> (Vec<Row>, Vec<(String, f64, f64)>) {
    let mut rows = Vec::new();
    for &shape in SHAPES.iter() {
        let mine: Vec<_> = families.iter().filter(|(f, _)| f.shape == shape).collect();
        let cases: Vec<&Case> = mine.iter().flat_map(|(f, _)| f.cases.iter()).collect();
        let times = times_per_test(&cases);
        let tallies = KernelChoice::ALL.map(|kernel| tally_all(kernel, &mine));
        for ((kernel, ns), tally) in KernelChoice::ALL.iter().zip(times).zip(tallies) {
            rows.push(Row {
                kernel: kernel.name(),
                shape,
                ns,
                tally,
            });
        }
    }
    let per_family = families
        .iter()
        .map(|(family, _)| {
            let cases: Vec<&Case> = family.cases.iter().collect();
            let times = times_per_test(&cases);
            (
                format!("{} {}", family.shape, family.name),
                times[0],
                times[2],
            )
        })
        .collect();
    (rows, per_family)
}

/// One kernel's tally over several families.
fn tally_all(kernel: KernelChoice, families: &[&(Family, Vec<Reference>)]) -> Tally {
    let mut total = Tally::default();
    for (family, references) in families {
        total.merge(&tally(kernel, family, references));
    }
    total
}

/// Median rays per second of a whole render at 640x480.
fn rays_per_second(scene: &legacy_rt::scene::Scene, kernel: KernelChoice) -> f64 {
    let options = Options {
        kernel,
        ..Options::new(640, 480)
    };
    let rays = count_rays(scene, &options).total() as f64;
    let mut rates: Vec<f64> = (0..5)
        .map(|_| {
            let start = Instant::now();
            black_box(render(scene, &options, |_| {}));
            rays / start.elapsed().as_secs_f64()
        })
        .collect();
    rates.sort_by(f64::total_cmp);
    rates[rates.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let families: Vec<(Family, Vec<Reference>)> = suite()
        .into_iter()
        .map(|family| {
            let references = family.cases.iter().map(reference).collect();
            (family, references)
        })
        .collect();
    let cases: usize = families.iter().map(|(f, _)| f.cases.len()).sum();

    let (mut rows, per_family) = rows(&families);
    // Grouped by kernel, shipped one first, as the tables read best.
    rows.sort_by_key(|row| KernelChoice::from_name(row.kernel).map(|k| k as usize));

    let mut md = String::new();
    writeln!(md, "# Speed against error of the intersection kernels\n")?;
    writeln!(
        md,
        "Generated by `cargo run --release --example speed_vs_error` (do not edit by \
         hand). The hard-case suite of `tests/support/accuracy.rs` ({} families, {cases} \
         rays, seed {:#x}); errors in ulps of the exact root of the f64 problem, computed \
         in double-double. ns is the median of 15 passes per test, the kernels taking turns, on one core of the \
         machine that ran the command. `wrong` counts hits that should be misses and \
         misses that should be hits; `ties` counts rays whose exact discriminant, bound \
         coordinate (y = 0 or h, z = 0) or t is within a few ulps of zero and on which \
         the kernel's answer differs from the reference's: there either answer is \
         allowed.\n",
        families.len(),
        accuracy::SEED
    )?;
    writeln!(
        md,
        "| kernel | surface | ns / test | max ulps | median ulps | wrong | ties | cost vs textbook |"
    )?;
    writeln!(md, "|---|---|---:|---:|---:|---:|---:|---:|")?;
    let textbook_ns = |shape: &str| {
        rows.iter()
            .find(|r| r.kernel == KernelChoice::Textbook.name() && r.shape == shape)
            .map(|r| r.ns)
            .unwrap()
    };
    for row in &rows {
        let line = format!(
            "| {} | {} | {:.1} | {} | {:.2} | {} | {} | {:.2}x |",
            row.kernel,
            row.shape,
            row.ns,
            format_ulps(row.tally.max()),
            row.tally.median(),
            row.tally.disagreements,
            row.tally.ties,
            row.ns / textbook_ns(row.shape)
        );
        println!("{line}");
        writeln!(md, "{line}")?;
    }

    // Where the shipped kernel's time goes.
    writeln!(md, "\n## Time per test by family\n")?;
    writeln!(
        md,
        "The same timing, family by family: the families whose rays need the refinement \
         step (grazing, huge, nearly parallel) cost most.\n"
    )?;
    writeln!(
        md,
        "| family | accurate ns | textbook ns | cost vs textbook |"
    )?;
    writeln!(md, "|---|---:|---:|---:|")?;
    for (family, accurate, textbook) in &per_family {
        let line = format!(
            "| {family} | {accurate:.1} | {textbook:.1} | {:.2}x |",
            accurate / textbook
        );
        println!("{line}");
        writeln!(md, "{line}")?;
    }

    // Whole images.
    writeln!(md, "\n## Whole images\n")?;
    writeln!(
        md,
        "Camera, shadow and reflected rays per second, 640x480, one thread, median of 5 \
         renders.\n"
    )?;
    writeln!(
        md,
        "| scene | accurate | stable | textbook | textbook-f32 |"
    )?;
    writeln!(md, "|---|---:|---:|---:|---:|")?;
    for name in ["quadrics_gallery", "spheres"] {
        let text = std::fs::read_to_string(root.join(format!("examples/{name}.txt")))?;
        let scene = legacy_rt::scene::load(&text)?;
        let rates: Vec<String> = KernelChoice::ALL
            .iter()
            .map(|&k| format!("{:.2} M", rays_per_second(&scene, k) / 1e6))
            .collect();
        let line = format!("| {name} | {} |", rates.join(" | "));
        println!("{line}");
        writeln!(md, "{line}")?;
    }

    // Summary of the shipped kernel's cost.
    let worst = SHAPES
        .iter()
        .map(|&shape| {
            let accurate = rows
                .iter()
                .find(|r| r.kernel == KernelChoice::Accurate.name() && r.shape == shape)
                .unwrap();
            (shape, accurate.ns / textbook_ns(shape))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    writeln!(
        md,
        "\nThe shipped kernel's largest cost per test against the textbook formula: \
         {:.2}x ({}). Chart: `speed-vs-error.svg`, error against time per test, one \
         point per kernel and surface.",
        worst.1, worst.0
    )?;
    println!(
        "largest accurate / textbook cost: {:.2}x ({})",
        worst.1, worst.0
    );

    std::fs::write(root.join("docs/speed-vs-error.md"), md)?;
    chart(&rows, &root.join("docs/speed-vs-error.svg"))?;
    println!("wrote docs/speed-vs-error.md and docs/speed-vs-error.svg");
    Ok(())
}

/// Integers above 100 without decimals, the rest with two.
fn format_ulps(ulps: f64) -> String {
    if ulps >= 100.0 {
        format!("{ulps:.3e}")
    } else {
        format!("{ulps:.2}")
    }
}

fn chart(rows: &[Row], path: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (800, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let max_ns = rows.iter().map(|r| r.ns).fold(0.0, f64::max) * 1.3;
    let min_ns = rows.iter().map(|r| r.ns).fold(f64::INFINITY, f64::min) * 0.7;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Largest error against time per ray-surface test",
            ("sans-serif", 20),
        )
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d((min_ns..max_ns).log_scale(), (0.1f64..1e18).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("ns per test (median)")
        .y_desc("max error, ulps (0 drawn at 0.1)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    let colours = [RED, BLUE, GREEN, MAGENTA];
    for (kernel, colour) in KernelChoice::ALL.iter().zip(colours) {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.kernel == kernel.name())
            .map(|r| (r.ns, r.tally.max().max(0.1)))
            .collect();
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 5, colour.filled())))?
            .label(kernel.name())
            .legend(move |(x, y)| Circle::new((x + 8, y), 5, colour.filled()));
    }
    chart
        .draw_series(LineSeries::new(
            [(min_ns, 4.0), (max_ns, 4.0)],
            BLACK.mix(0.4),
        ))?
        .label("4 ulps (the goal)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK.mix(0.4)));
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}
