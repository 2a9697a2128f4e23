//! The course's own scene files (`../shared/course-scenes`) all load. Skipped, with a
//! message, where that folder is absent (and failed under `CI=true`).

use super::common::{course_scenes, image_document, scene_files, snapshots};

#[test]
fn every_course_scene_loads_and_its_dump_and_image_are_reviewed() {
    let Some(dir) = course_scenes() else { return };
    let files = scene_files(&dir);
    assert!(
        files.len() >= 10,
        "expected the course's scenes in {}",
        dir.display()
    );
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        let scene = legacy_rt::load(&text)
            .unwrap_or_else(|error| panic!("{} must load:\n{error}", path.display()));
        // Only the dump is kept: the course's text is theirs, the numbers are facts.
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let document = format!(
            "{}\n---- image ----\n{}",
            legacy_rt::dump(&scene),
            image_document(&scene)
        );
        snapshots().bind(|| insta::assert_snapshot!(format!("course_{name}"), document));
    }
}

#[test]
fn spec1_holds_what_the_issue_describes() {
    let Some(dir) = course_scenes() else { return };
    let scene = legacy_rt::load(&std::fs::read_to_string(dir.join("spec1.txt")).unwrap()).unwrap();
    let kinds: Vec<_> = scene.objects.iter().map(|o| o.kind()).collect();
    assert_eq!(kinds, ["sphere", "sphere", "tiled plane", "tiled plane"]);
    assert_eq!(scene.lights.len(), 4);
}
