//! What users run, on any input: load the text (also as a large text is read, in
//! chunks on several threads, which must give the same scene or error), and if it is a
//! scene, dump it and render it small, with the hierarchy, with the course's linear scan
//! and with `compare`'s margins (which must agree). A panic, a hang or an allocation
//! failure anywhere is a finding.

#![no_main]

use legacy_rt::compare;
use legacy_rt::compare::render_with_margins;
use legacy_rt::render::{Options, render};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let loaded = legacy_rt::load(&text);
    let files = legacy_rt::scene::Disk;
    for chunks in [2, 7] {
        let chunked = legacy_rt::scene::load_in_chunks(&text, &files, 2, chunks);
        match (&loaded, &chunked) {
            // The same scene, field by field as written out: a derived `==` fails on a
            // NaN its precomputed terms may hold (a quadric's value at its anchor, where a
            // coefficient of 1e308 overflows), which both readings hold alike.
            (Ok(a), Ok(b)) => assert_eq!(format!("{a:?}"), format!("{b:?}")),
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
            _ => panic!("read in {chunks} chunks: {chunked:?}, from the start: {loaded:?}"),
        }
    }
    let Ok(scene) = loaded else {
        return;
    };
    let _ = legacy_rt::dump(&scene);
    let options = Options::new(8, 6);
    let image = render(&scene, &options, |_| {});
    let linear = Options {
        accelerate: false,
        ..options
    };
    assert!(image.pixels == render(&scene, &linear, |_| {}).pixels);
    // compare's reference, rendered with its margins, is the same image.
    let (reference, marks) = render_with_margins(&scene, &options, compare::F32);
    assert!(reference.pixels == image.pixels && marks.len() == image.pixels.len());
});
