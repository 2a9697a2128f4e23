//! Every invalid input under `tests/invalid/` is an error that names its line and column,
//! shows the line with a caret, and leaves standard output empty.

use super::common::{run, scene_files, snapshots};
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
    snapshots().bind(|| {
        insta::glob!("../invalid", "*.txt", |path| {
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
