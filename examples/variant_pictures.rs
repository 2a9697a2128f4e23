//! The pictures of docs/variants.md and docs/compare.md:
//!
//! ```text
//! cargo run --release --example variant_pictures
//! ```
//!
//! docs/variants.png has one row per variant of spec §7.3, in the order of
//! docs/variants.md: the reference, the image as if with the variant, and `compare`'s diff
//! image of the two, each 96x72, on a scene where the variant shows. docs/compare-diff.png
//! is the diff image of a student's d04 rendered without shadow rays.
//! Needs ../shared/course-scenes beside the repository.

use legacy_rt::compare::diff_image;
use legacy_rt::render::{Image, Options, Variant, render};

const TILE: (usize, usize) = (96, 72);

/// The scene each variant is shown on: one where it changes the image.
fn scene_for(variant: Variant) -> &'static str {
    match variant.about().id {
        "square-falloff" | "no-shadows" => "../shared/course-scenes/d04.txt",
        "segment-distance" | "no-z-rule" | "tile-parity" | "one-bounce" => {
            "../shared/course-scenes/spec1.txt"
        }
        "shadow-epsilon" | "facing-normals" | "cone-scale" | "nearer-root" => {
            "examples/note003_records.txt"
        }
        "max-dist=D" => "examples/mirrors.txt",
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

fn main() {
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
        let reference = render(&scene, &options, |_| {}).0;
        let deviating = options.with_variant(variant).expect("one variant applies");
        let student = render(&scene, &deviating, |_| {}).0;
        let diff = diff_image(&reference, &student, 0).expect("one size");
        for (column, tile) in [&reference, &student, &diff].into_iter().enumerate() {
            let (x0, y0) = (column * (w + 4), row * (h + 4));
            for (i, &pixel) in tile.pixels.iter().enumerate() {
                sheet.pixels[(y0 + i / w) * sheet.width + x0 + i % w] = pixel;
            }
        }
        println!("{:>18}  {}", variant.id(), scene_for(variant));
    }
    save(&sheet, "docs/variants.png");

    let scene = load("../shared/course-scenes/d04.txt");
    let options = Options::new(320, 240);
    let reference = render(&scene, &options, |_| {}).0;
    let no_shadows = options.with_variant(Variant::NoShadows).expect("applies");
    let student = render(&scene, &no_shadows, |_| {}).0;
    save(
        &diff_image(&reference, &student, 0).expect("one size"),
        "docs/compare-diff.png",
    );
}
