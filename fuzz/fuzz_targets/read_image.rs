//! What `compare` does with a student's upload, on any bytes: read it as an image within a
//! small pixel budget, and if it is one, compare it with a reference of its size (the
//! report, its text and JSON, and the diff image), against a rendered scene when it is
//! small. A panic, a hang or an allocation failure anywhere is a finding; a panic inside
//! the third-party decoder must come back as `ReadError::Damaged` instead.

#![no_main]

use legacy_rt::compare::read::read_image_from;
use legacy_rt::compare::{self, Settings, Tolerance};
use legacy_rt::render::{Image, Options, render};
use libfuzzer_sys::fuzz_target;
use std::io::Cursor;

/// The budget: large enough for every branch of the readers, small enough to run fast.
const MAX_PIXELS: u64 = 1 << 16;

const SCENE: &str = "8 6\n0 0 3\n14\n1 1 1\n2 2 2\n0.5 0.5 0.5\n0 1 0\n0 -3 0\n\
                     13\n5 1 1\n3 3 3\n0 0 0\n0 0 -4\n1.5\n10\n4 4 4\n2 3 0\n";

fuzz_target!(|data: &[u8]| {
    let Ok(student) = read_image_from(Cursor::new(data), MAX_PIXELS) else {
        return;
    };
    assert_eq!(student.pixels.len(), student.width * student.height);
    let settings = Settings {
        tolerance: Tolerance::default(),
        worst: 5,
        diagnose: false,
    };
    // A reference of the same size that is not the student's.
    let reference = compare::Reference::image(Image {
        width: student.width,
        height: student.height,
        pixels: (0..student.pixels.len())
            .map(|i| [i as u8, (i >> 8) as u8, 255 - i as u8])
            .collect(),
    });
    let report = compare::report(&reference, &student, None, &settings).unwrap();
    let _ = compare::text::text(&report, "reference", "student", None);
    let _ = serde_json::to_string(&report).unwrap();
    let diff = compare::diff_image(&reference, &student, 0).unwrap();
    assert_eq!(diff.pixels.len(), student.pixels.len());
    // Against a scene rendered at the image's size, as `compare scene.txt image` does.
    if (2..=48).contains(&student.width) && (2..=48).contains(&student.height) {
        let scene = legacy_rt::load(SCENE).unwrap();
        let options = Options::new(student.width, student.height);
        let rendered = compare::reference(&scene, &options, &student, compare::F32, false);
        assert!(rendered.image == render(&scene, &options, |_| {}));
        let report = compare::report(&rendered, &student, Some((&scene, &options)), &settings);
        let _ = compare::text::text(&report.unwrap(), "scene.txt", "student", None);
        let _ = compare::diff_image(&rendered, &student, 0).unwrap();
    }
});
