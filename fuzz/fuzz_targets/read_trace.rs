//! A student's debug trace is an upload: `trace --against` reads any text against the
//! reference's trace of a pixel of a small scene. The first two bytes choose the pixel
//! of an 8x6 image of examples/studio.txt, the rest is the student's file. A panic, a
//! hang or an allocation failure is a finding; so is a report whose numbers do not add up.

#![no_main]

use legacy_rt::render::{Options, trace};
use libfuzzer_sys::fuzz_target;

const SCENE: &str = include_str!("../../examples/studio.txt");

fuzz_target!(|data: &[u8]| {
    let Some((&[x, y], rest)) = data.split_first_chunk::<2>() else {
        return;
    };
    let scene = legacy_rt::load(SCENE).expect("the example loads");
    let options = Options::new(8, 6);
    let (x, y) = (usize::from(x) % 8, usize::from(y) % 6);
    let reference = trace(&scene, &options, x, y).expect("the pixel is inside");
    let text = String::from_utf8_lossy(rest);
    if let Ok(report) = legacy_rt::against::against(&scene, &reference, &text) {
        let _ = report.text(&scene, &reference, "dbg.txt", &text);
        assert!(report.differences() <= report.compared.len());
        assert!(report.lines.0 >= 1 && report.lines.0 <= report.lines.1);
    }
});
