//! Every scene under `examples/` loads and renders; its `--dump` and its image are locked
//! down by a snapshot.

use super::common::{each_file, image_document, run, scene_files, snapshots};
use std::path::Path;

#[test]
fn every_example_loads_and_its_dump_and_image_are_reviewed() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    snapshots().bind(|| {
        each_file(&dir, |path| {
            let text = std::fs::read_to_string(path).unwrap();
            let scene = legacy_rt::load(&text)
                .unwrap_or_else(|error| panic!("{} must load:\n{error}", path.display()));
            let dump = legacy_rt::dump(&scene);
            let image = image_document(&scene);
            let document = format!("{text}\n---- dump ----\n{dump}\n---- image ----\n{image}");
            insta::assert_snapshot!("example", document);
        });
    });
}

#[test]
fn the_binary_dumps_what_the_library_dumps() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    for path in scene_files(&examples) {
        let text = std::fs::read_to_string(&path).unwrap();
        let output = run(&["--dump"], text.as_bytes());
        assert!(output.status.success(), "{}", path.display());
        assert!(output.stderr.is_empty(), "{}", path.display());
        let expected = legacy_rt::dump(&legacy_rt::load(&text).unwrap());
        assert_eq!(String::from_utf8(output.stdout).unwrap(), expected);
    }
}

#[test]
fn the_examples_cover_every_type_code_and_every_quadric_family() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut kinds = std::collections::BTreeSet::new();
    for path in scene_files(&examples) {
        let scene = legacy_rt::load(&std::fs::read_to_string(&path).unwrap()).unwrap();
        kinds.extend(scene.objects.iter().map(|o| o.kind()));
        for light in &scene.lights {
            kinds.insert(if light.beam.is_some() {
                "spotlight"
            } else {
                "light"
            });
        }
    }
    let all = [
        "light",
        "spotlight",
        "sphere",
        "plane",
        "finite plane",
        "tiled plane",
        "textured plane",
        "procedural sphere",
        "procedural plane",
        "paraboloid",
        "cylinder",
        "cone",
        "hyperboloid",
        "quadric",
    ];
    assert_eq!(kinds, all.into_iter().collect());
    for family in [
        "ellipsoid",
        "cylinder",
        "cone",
        "paraboloid",
        "hyperboloid_one_sheet",
        "hyperboloid_two_sheets",
        "hyperbolic_paraboloid",
    ] {
        assert!(
            examples.join(format!("quadric_{family}.txt")).is_file(),
            "{family}"
        );
    }
}
