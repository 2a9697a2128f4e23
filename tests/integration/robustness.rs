//! The loader never panics and never hangs: random bytes and mutated valid scenes go in,
//! an `Ok` or a located error comes out. `PROPTEST_CASES=N` runs longer.

use super::common::{course_scenes, scene_files};
use legacy_rt::error::{MeaningError, SceneErrorKind};
use proptest::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

fn config(default_cases: u32) -> ProptestConfig {
    let mut config = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = default_cases;
    }
    config.failure_persistence = None;
    config
}

/// Valid scenes to mutate: the examples and, where present, the course's scenes.
fn corpus() -> &'static [String] {
    static CORPUS: OnceLock<Vec<String>> = OnceLock::new();
    CORPUS.get_or_init(|| {
        let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
        let mut dirs = vec![examples];
        dirs.extend(course_scenes());
        dirs.iter()
            .flat_map(|dir| scene_files(dir))
            .map(|path| std::fs::read_to_string(path).unwrap())
            .collect()
    })
}

/// Loads `text` and checks what any outcome must satisfy.
fn check(text: &str) {
    match legacy_rt::load(text) {
        Ok(scene) => {
            let _ = legacy_rt::dump(&scene);
        }
        Err(error) => {
            let lines = text.split('\n').count();
            assert!(error.at.line >= 1 && error.at.line <= lines, "{error:?}");
            assert!(error.at.column >= 1);
            assert!(error.to_string().contains('^'));
        }
    }
}

/// One edit of a scene text.
#[derive(Debug, Clone)]
enum Edit {
    Insert(usize, char),
    Delete(usize),
    Replace(usize, char),
    DuplicateLine(usize),
    DeleteLine(usize),
    Truncate(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let chars = prop::sample::select(
        " \t\n\r0123456789-+.eExXpnaifQUADRICz#\u{e9}\u{0}"
            .chars()
            .collect::<Vec<_>>(),
    );
    prop_oneof![
        (any::<usize>(), chars.clone()).prop_map(|(i, c)| Edit::Insert(i, c)),
        any::<usize>().prop_map(Edit::Delete),
        (any::<usize>(), chars).prop_map(|(i, c)| Edit::Replace(i, c)),
        any::<usize>().prop_map(Edit::DuplicateLine),
        any::<usize>().prop_map(Edit::DeleteLine),
        any::<usize>().prop_map(Edit::Truncate),
    ]
}

fn apply(text: &str, edit: &Edit) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    let mut lines: Vec<&str> = text.split_inclusive('\n').collect();
    let at = |i: usize, len: usize| if len == 0 { 0 } else { i % len };
    match *edit {
        Edit::Insert(i, c) => chars.insert(at(i, chars.len() + 1), c),
        Edit::Delete(_) | Edit::Replace(_, _) if chars.is_empty() => {}
        Edit::Delete(i) => {
            chars.remove(at(i, chars.len()));
        }
        Edit::Replace(i, c) => {
            let i = at(i, chars.len());
            chars[i] = c;
        }
        Edit::DuplicateLine(_) | Edit::DeleteLine(_) if lines.is_empty() => {}
        Edit::DuplicateLine(i) => {
            let i = at(i, lines.len());
            lines.insert(i, lines[i]);
            return lines.concat();
        }
        Edit::DeleteLine(i) => {
            lines.remove(at(i, lines.len()));
            return lines.concat();
        }
        Edit::Truncate(i) => chars.truncate(at(i, chars.len() + 1)),
    }
    chars.into_iter().collect()
}

proptest! {
    #![proptest_config(config(2_000))]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        check(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_scene_like_text_never_panics(
        text in "([0-9 .eE+\\-]{0,12}[ \t]*[a-zA-Z]{0,4}\n){0,40}"
    ) {
        check(&format!("8 6\n0 0 3\n{text}"));
    }

    #[test]
    fn mutated_valid_scenes_never_panic(
        pick in any::<usize>(),
        edits in prop::collection::vec(edit(), 1..6),
    ) {
        let corpus = corpus();
        let mut text = corpus[pick % corpus.len()].clone();
        for e in &edits {
            text = apply(&text, e);
        }
        check(&text);
    }
}

#[test]
fn a_million_and_one_records_is_a_clear_error_not_an_allocation_failure() {
    let limit = legacy_rt::scene_file::MAX_RECORDS;
    let mut text = String::from("8 6\n0 0 3\n");
    for _ in 0..=limit {
        text.push_str("10\n1 1 1\n0 0 0\n");
    }
    let error = legacy_rt::load(&text).unwrap_err();
    let expected: SceneErrorKind = MeaningError::TooManyRecords { limit }.into();
    assert_eq!(error.kind, expected);
    assert_eq!(error.at.line, 3 + 3 * limit);
}
