//! Every invalid input under `tests/invalid/` is an error that names its line and column,
//! shows the line with a caret, and leaves standard output empty.

use super::common::{each_file, run, scene_files, snapshots};
use legacy_rt::error::{MeaningError, SceneErrorKind, SyntaxError};
use std::collections::BTreeSet;
use std::path::Path;

fn invalid_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/invalid")
}

/// A name per error variant; the match is exhaustive so a new variant must be added here
/// (and then get an invalid input of its own).
fn variant(kind: &SceneErrorKind) -> &'static str {
    match kind {
        SceneErrorKind::Syntax(error) => match error {
            SyntaxError::Expected { .. } => "Expected",
            SyntaxError::NonFinite { .. } => "NonFinite",
            SyntaxError::UnknownTypeCode { .. } => "UnknownTypeCode",
            SyntaxError::Unsupported { .. } => "Unsupported",
            SyntaxError::QuadricLineShort { .. } => "QuadricLineShort",
            SyntaxError::ByteOrderMark => "ByteOrderMark",
            SyntaxError::TooManyRecords { .. } => "TooManyRecords",
        },
        SceneErrorKind::Meaning(error) => match error {
            MeaningError::ZeroVector { .. } => "ZeroVector",
            MeaningError::AimAtLocation => "AimAtLocation",
            MeaningError::XdirParallel { .. } => "XdirParallel",
            MeaningError::NotPositive { .. } => "NotPositive",
            MeaningError::NegativeWaist { .. } => "NegativeWaist",
            MeaningError::SpotAngle { .. } => "SpotAngle",
            MeaningError::UnknownShader { .. } => "UnknownShader",
            MeaningError::TextureMode { .. } => "TextureMode",
            MeaningError::Texture { .. } => "Texture",
            MeaningError::ZeroQuadric => "ZeroQuadric",
            MeaningError::Internal { .. } => "Internal",
        },
    }
}

#[test]
fn every_invalid_input_is_an_error_with_line_column_and_caret() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/invalid");
    snapshots().bind(|| {
        each_file(&dir, |path| {
            let text = std::fs::read_to_string(path).unwrap();
            let error =
                legacy_rt::load(&text).expect_err(&format!("{} must not load", path.display()));
            let shown = error.to_string();
            let (line, column) = (error.at.line, error.at.column);
            assert!(shown.contains(&format!("--> line {line}, column {column}")));
            // The line shown is the file's own line `line` (escaped where it holds control or
            // invisible characters: `error::tests` checks that form), and a caret follows it.
            let source_line = text.lines().nth(line - 1).unwrap_or("");
            assert_eq!(error.at.line_text, source_line.trim_end_matches('\r'));
            let plain = !source_line.contains(|c: char| c.is_control() || c == '\u{feff}');
            assert!(
                !plain || shown.contains(&format!("{line} | {source_line}\n")),
                "{shown}"
            );
            assert!(
                shown.lines().any(|l| l.trim_end().ends_with('^')),
                "{shown}"
            );
            insta::assert_snapshot!("invalid", format!("{text}\n---- error ----\n{shown}"));
        });
    });
}

#[test]
fn every_error_variant_has_an_invalid_input() {
    let mut seen = BTreeSet::new();
    let files = scene_files(&invalid_dir());
    assert!(files.len() >= 20);
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        seen.insert(variant(&legacy_rt::load(&text).unwrap_err().kind));
    }
    // TooManyRecords needs a million records; `robustness` tests it on generated text.
    // Internal reports a mistake of this program, which no input can cause.
    seen.extend(["TooManyRecords", "Internal"]);
    assert_eq!(seen.len(), 18, "{seen:?}");
}

#[test]
fn the_binary_prints_the_error_on_stderr_and_nothing_on_stdout() {
    for path in scene_files(&invalid_dir()) {
        let text = std::fs::read_to_string(&path).unwrap();
        let expected = legacy_rt::load(&text).unwrap_err().to_string();
        for args in [&[][..], &["--dump"][..]] {
            let output = run(args, text.as_bytes());
            assert_eq!(output.status.code(), Some(1), "{}", path.display());
            assert!(output.stdout.is_empty(), "{}", path.display());
            assert_eq!(
                String::from_utf8(output.stderr).unwrap(),
                format!("{expected}\n")
            );
        }
    }
}

/// Every file under `folder` (relative to the crate's top folder, as the scenes name
/// them), by that name.
fn files_under(folder: &str) -> legacy_rt::scene::InMemory {
    let top = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = legacy_rt::scene::InMemory::new();
    for entry in std::fs::read_dir(top.join(folder)).unwrap() {
        let path = entry.unwrap().path();
        if !path.is_file() {
            continue;
        }
        let name = format!("{folder}/{}", path.file_name().unwrap().to_string_lossy());
        files.insert(name, std::fs::read(&path).unwrap());
    }
    files
}

/// The web page gives the textures a user added instead of the disk: a scene loads to the
/// same scene, and fails with the same message, wherever its files come from.
#[test]
#[cfg(target_os = "linux")]
fn textures_from_memory_load_and_fail_as_from_the_disk() {
    // texture_not_p6.txt names a scene file as its texture.
    let mut files = files_under("examples");
    files.extend(files_under("examples/textures"));
    files.extend(files_under("tests/invalid/textures"));
    let top = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes = scene_files(&invalid_dir());
    scenes.extend(scene_files(&top.join("examples")));
    let mut textured = 0;
    for path in scenes {
        let text = std::fs::read_to_string(&path).unwrap();
        // The scenes' file names are relative to the crate's top folder, where cargo
        // runs the tests.
        let from_disk = legacy_rt::load(&text);
        let from_memory = legacy_rt::load_with(&text, &files);
        textured += text.contains("textures/") as usize;
        match (from_disk, from_memory) {
            (Ok(disk), Ok(memory)) => {
                let options = legacy_rt::Options::new(64, 48);
                let render = |scene| legacy_rt::render(scene, &options, |_| {});
                assert_eq!(render(&disk), render(&memory), "{}", path.display());
            }
            (Err(disk), Err(memory)) => {
                assert_eq!(disk.to_string(), memory.to_string(), "{}", path.display())
            }
            (disk, memory) => panic!("{}: {disk:?} but {memory:?}", path.display()),
        }
    }
    // Under textures/: the missing, too large and mode-3 textures, and the textured example.
    assert!(textured >= 4, "{textured}");
}
