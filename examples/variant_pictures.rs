//! The pictures of docs/variants.md and docs/compare.md:
//!
//! ```text
//! cargo run --release --example variant_pictures
//! ```
//!
//! docs/variants.png has one row per variant of spec §7.3, in the order of
//! docs/variants.md: the reference, the image as if with the variant, and `compare`'s diff
//! image of the two, each 96x72, on a scene where the variant shows. docs/compare-diff.png
//! is the diff image of a student's examples/shadows.txt rendered without shadow rays,
//! docs/compare-fragile.png that of a single-precision studio without one light's shadows.
//! It also writes docs/variants.md's table of the variants, from the program's own table
//! (`legacy_rt::render::variant::markdown_table`). Needs ../shared/course-scenes beside
//! the repository.

use legacy_rt::compare::{self, Reference, diff_image};
use legacy_rt::render::{Image, Options, Variant, render};
use legacy_rt::shapes::kernel::KernelChoice;

const TILE: (usize, usize) = (96, 72);

/// The scene each variant is shown on: one where it changes the image.
fn scene_for(variant: Variant) -> &'static str {
    match variant.row().id {
        "square-falloff" | "no-shadows" => "../shared/course-scenes/d04.txt",
        "segment-distance" | "no-z-rule" | "tile-parity" | "one-bounce" => {
            "../shared/course-scenes/spec1.txt"
        }
        "shadow-epsilon" | "facing-normals" | "cone-scale" | "nearer-root" => {
            "examples/note003_records.txt"
        }
        "max-dist" => "examples/mirrors.txt",
        "behind-root" => "examples/tube.txt",
        "tile-unprojected" => "../shared/course-scenes/d03.txt",
        "z-tolerance" | "far-clip" => "../shared/course-scenes/spec1.txt",
        _ => "../shared/course-scenes/a04.txt",
    }
}

fn load(path: &str) -> legacy_rt::Scene {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    legacy_rt::load(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Writes a PNG at the encoder's best compression: these files are committed.
fn save(image: &Image, path: &str) {
    use image::ImageEncoder;
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    let mut png = Vec::new();
    let bytes: Vec<u8> = image.pixels.iter().flatten().copied().collect();
    PngEncoder::new_with_quality(&mut png, CompressionType::Best, FilterType::Adaptive)
        .write_image(
            &bytes,
            image.width as u32,
            image.height as u32,
            image::ExtendedColorType::Rgb8,
        )
        .expect("encodes");
    std::fs::write(path, png).unwrap_or_else(|e| panic!("{path}: {e}"));
    println!("wrote {path} ({}x{})", image.width, image.height);
}

/// The lines around docs/variants.md's table.
const TABLE_START: &str = "<!-- the table: cargo run --release --example variant_pictures -->\n";
const TABLE_END: &str = "<!-- end of the table -->\n";

/// Rewrites the table of docs/variants.md between its markers.
fn write_table() {
    let path = "docs/variants.md";
    let text = std::fs::read_to_string(path).expect("docs/variants.md");
    let start = text.find(TABLE_START).expect("the table's start marker") + TABLE_START.len();
    let end = text.find(TABLE_END).expect("the table's end marker");
    let table = legacy_rt::render::variant::markdown_table();
    let new = format!("{}{table}{}", &text[..start], &text[end..]);
    std::fs::write(path, new).expect("writes docs/variants.md");
    println!("wrote the table of {path}");
}

fn main() {
    // The course's scenes show most variants: without them, say so instead of failing
    // half-way.
    let course = std::path::Path::new("../shared/course-scenes");
    if !course.is_dir() {
        eprintln!(
            "variant_pictures draws most variants on the course's scenes, which it reads from \
             {} (beside the repository, as the course hands them out): put them there, and \
             run it from the repository's folder",
            course.display()
        );
        std::process::exit(1);
    }
    write_table();
    let (w, h) = TILE;
    let variants: Vec<Variant> = Variant::all().collect();
    let mut sheet = Image {
        width: 3 * w + 2 * 4,
        height: variants.len() * (h + 4) - 4,
        pixels: vec![[255, 255, 255]; (3 * w + 8) * (variants.len() * (h + 4) - 4)],
    };
    for (row, &variant) in variants.iter().enumerate() {
        let scene = load(scene_for(variant));
        let options = Options::new(w, h);
        let reference = render(&scene, &options, |_| {});
        let deviating = options.with_variant(variant).expect("one variant applies");
        let student = render(&scene, &deviating, |_| {});
        let diff = diff_image(&Reference::image(reference.clone()), &student, 0).expect("one size");
        for (column, tile) in [&reference, &student, &diff].into_iter().enumerate() {
            let (x0, y0) = (column * (w + 4), row * (h + 4));
            for (i, &pixel) in tile.pixels.iter().enumerate() {
                sheet.pixels[(y0 + i / w) * sheet.width + x0 + i % w] = pixel;
            }
        }
        println!("{:>18}  {}", variant.id(), scene_for(variant));
    }
    save(&sheet, "docs/variants.png");

    let scene = load("examples/shadows.txt");
    let options = Options::new(320, 240);
    let reference = render(&scene, &options, |_| {});
    let no_shadows = options
        .with_variant(Variant::parse("no-shadows").expect("a variant"))
        .expect("applies");
    let student = render(&scene, &no_shadows, |_| {});
    save(
        &diff_image(&Reference::image(reference), &student, 0).expect("one size"),
        "docs/compare-diff.png",
    );

    // A student in single precision who forgot the shadows of the studio's first light:
    // the missing shadows in red and yellow, the pixels single precision decides otherwise
    // (grazing rays, tile edges, bytes at a step) in purple: fragile, excused.
    let scene = load("examples/studio.txt");
    let light = format!("unshadowed@{}", scene.lights[0].line);
    let student_options = Options {
        kernel: KernelChoice::TextbookF32,
        ..options
            .with_variant(Variant::parse(&light).expect("a variant"))
            .expect("applies")
    };
    let student = render(&scene, &student_options, |_| {});
    let reference = compare::reference(&scene, &options, &student, compare::F32, false);
    save(
        &diff_image(&reference, &student, 0).expect("one size"),
        "docs/compare-fragile.png",
    );
}
