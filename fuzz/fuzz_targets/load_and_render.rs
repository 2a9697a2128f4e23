//! What users run, on any input: load the text, and if it is a scene, dump it and
//! render it small, with the hierarchy, with the course's linear scan and with
//! `compare`'s margins (which must agree). A panic, a hang or an allocation failure anywhere is a finding.

#![no_main]

use legacy_rt::compare;
use legacy_rt::render::{Options, render, render_with_margins};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let Ok(scene) = legacy_rt::load(&text) else {
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
