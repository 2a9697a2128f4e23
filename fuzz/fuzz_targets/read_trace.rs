//! A student's debug trace is an upload: `trace --against` reads any text against the
//! reference's traces of a small scene. The first byte chooses the mode (one pixel of an
//! 8x6 image of examples/studio.txt, chosen by the next two bytes, or the whole file),
//! the rest is the student's file. A panic, a hang or an allocation failure is a
//! finding; so is a report whose numbers do not add up.

#![no_main]

use legacy_rt::render::{Options, tracing};
use libfuzzer_sys::fuzz_target;

const SCENE: &str = include_str!("../../examples/studio.txt");

fuzz_target!(|data: &[u8]| {
    let Some((&[mode, x, y], rest)) = data.split_first_chunk::<3>() else {
        return;
    };
    let scene = legacy_rt::load(SCENE).expect("the example loads");
    let options = Options::new(8, 6);
    tracing(&scene, &options, |frame| {
        if mode % 2 == 0 {
            let pixel = (usize::from(x) % 8, usize::from(y) % 6);
            if let Ok((report, trace)) = legacy_rt::against::against(&scene, frame, pixel, rest) {
                let _ = report.text(&scene, &trace, "dbg.txt");
                assert!(report.differences() <= report.compared.len());
                assert!(report.lines.0 >= 1 && report.lines.0 <= report.lines.1);
                let _ = serde_json::to_string(&report.summary((8, 6), "dbg.txt")).unwrap();
            }
        } else if let Ok(whole) = legacy_rt::against::whole(&scene, frame, rest) {
            assert_eq!(whole.agree + whole.differ, whole.pixels);
            let grouped: usize = whole.groups.iter().map(|g| g.count).sum();
            assert_eq!(grouped, whole.differ);
            let _ = whole.text("dbg.txt", |x, y| format!("{x} {y}"));
            let _ = serde_json::to_string(&whole).unwrap();
        }
    });
});
