//! The loader and the renderer never panic and never hang: random bytes, mutated valid
//! scenes and generated valid scenes go in; a located error, or a scene that renders,
//! comes out. `PROPTEST_CASES=N` runs longer (issue 12's note quotes a run of 10^6).

use super::common::{course_scenes, scene_files};
use legacy_rt::error::{SceneErrorKind, SyntaxError};
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

/// Renders `scene` small, as users run it (with the hierarchy), as the course did (the
/// linear scan) and as `compare` renders its reference (with the margins of its fragile
/// pixels), and checks that all give the same bytes.
fn render_small(scene: &legacy_rt::Scene) {
    use legacy_rt::compare::render_with_margins;
    use legacy_rt::render::{Options, render};
    let accelerated = Options::new(8, 6);
    let linear = Options {
        accelerate: false,
        ..accelerated
    };
    let image = render(scene, &accelerated, |_| {});
    assert_eq!(image.pixels.len(), 8 * 6);
    assert!(image.pixels == render(scene, &linear, |_| {}).pixels);
    let precision = legacy_rt::compare::F32;
    let (reference, marks) = render_with_margins(scene, &accelerated, precision);
    assert!(reference.pixels == image.pixels);
    assert_eq!(marks.len(), 8 * 6);
}

/// Loads `text` and checks what any outcome must satisfy; a scene that loads is dumped
/// and rendered.
fn check(text: &str) {
    match legacy_rt::load(text) {
        Ok(scene) => {
            let _ = legacy_rt::dump(&scene);
            render_small(&scene);
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

/// A number for a generated scene: mostly ordinary, often at the ends of the f64 range,
/// sometimes a hair away from a round value (nearly parallel or degenerate geometry).
fn real() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => (-20i32..20).prop_map(f64::from),
        4 => -20.0..20.0f64,
        1 => (-1.0..1.0f64, -300i32..300).prop_map(|(m, e)| m * 10f64.powi(e)),
        1 => (-3i32..3, -17i32..-6).prop_map(|(v, e)| f64::from(v) + 10f64.powi(e)),
        1 => Just(0.0),
    ]
}

/// A number > 0 over the whole range.
fn positive() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => 0.01..10.0f64,
        1 => (1.0..10.0f64, -300i32..300).prop_map(|(m, e)| m * 10f64.powi(e)),
    ]
}

/// Three numbers on a line, as the format writes a vector.
fn triple() -> impl Strategy<Value = String> {
    [real(), real(), real()].prop_map(|[x, y, z]| format!("{x:e} {y:e} {z:e}"))
}

/// A direction: an axis, an axis tilted by a hair, or anything non-zero.
fn direction() -> impl Strategy<Value = String> {
    prop_oneof![
        (0usize..3, -1e-9..1e-9f64, any::<bool>()).prop_map(|(axis, tilt, negative)| {
            let mut v = [tilt, tilt / 3.0, 0.0];
            v[axis] = if negative { -1.0 } else { 1.0 };
            format!("{:e} {:e} {:e}", v[0], v[1], v[2])
        }),
        triple().prop_filter("a direction is not zero", |t| {
            t.split(' ').any(|n| n.parse::<f64>().unwrap() != 0.0)
        }),
    ]
}

/// A material block; the specular line is often zero and sometimes a full mirror.
fn material() -> impl Strategy<Value = String> {
    let specular = prop_oneof![Just("0 0 0".to_string()), Just("1 1 1".into()), triple()];
    (triple(), triple(), specular).prop_map(|(a, d, s)| format!("{a}\n{d}\n{s}\n"))
}

/// One record of any type, with numbers that may well describe no valid object (the
/// loader must then say so, with a location).
fn record() -> impl Strategy<Value = String> {
    let m = material;
    let framed = || {
        (
            m(),
            direction(),
            triple(),
            direction(),
            positive(),
            positive(),
        )
    };
    let frame = |(m, n, p, x, w, h): (String, String, String, String, f64, f64)| {
        format!("{m}{n}\n{p}\n{x}\n{w:e} {h:e}\n")
    };
    prop_oneof![
        (triple(), triple()).prop_map(|(e, l)| format!("10\n{e}\n{l}\n")),
        (triple(), triple(), triple(), 0.5..179.5f64)
            .prop_map(|(e, l, a, angle)| format!("11\n{e}\n{l}\n{a}\n{angle}\n")),
        (m(), triple(), positive()).prop_map(|(m, c, r)| format!("13\n{m}{c}\n{r:e}\n")),
        (m(), direction(), triple()).prop_map(|(m, n, p)| format!("14\n{m}{n}\n{p}\n")),
        framed().prop_map(move |f| format!("15\n{}", frame(f))),
        (framed(), m()).prop_map(move |(f, b)| format!("16\n{}{b}", frame(f))),
        (framed(), 1u8..3).prop_map(move |(f, mode)| {
            let texture = "examples/textures/colours4x3.ppm";
            format!("17\n{}{texture}\n{mode}\n", frame(f))
        }),
        (m(), triple(), positive(), 0u8..2)
            .prop_map(|(m, c, r, s)| format!("19\n{m}{c}\n{r:e}\n{s}\n")),
        (m(), direction(), triple(), 0u8..2)
            .prop_map(|(m, n, p, s)| format!("20\n{m}{n}\n{p}\n{s}\n")),
        (21u8..24, m(), triple(), direction(), positive(), positive())
            .prop_map(|(code, m, p, line, r, h)| format!("{code}\n{m}{p}\n{line}\n{r:e} {h:e}\n")),
        (
            m(),
            triple(),
            direction(),
            positive(),
            positive(),
            0.0..2.0f64
        )
            .prop_map(|(m, p, line, r, h, rc)| format!(
                "24\n{m}{p}\n{line}\n{r:e} {h:e}\n{rc:e}\n"
            )),
        (prop::array::uniform10(real()), m()).prop_map(|(q, m)| {
            let q: Vec<String> = q.iter().map(|c| format!("{c:e}")).collect();
            format!("QUADRIC {}\n{m}", q.join(" "))
        }),
    ]
}

/// Runs of records that stress the renderer rather than the loader: a chain of spheres
/// at x = 1.5^i (a lopsided, deep hierarchy), and two facing mirrors a hair apart.
fn stress() -> impl Strategy<Value = String> {
    prop_oneof![
        (8usize..300, 1.01..2.0f64).prop_map(|(count, ratio)| {
            (0..count)
                .map(|i| {
                    let x = ratio.powi(i as i32);
                    format!("13\n1 1 1\n1 1 1\n0.5 0.5 0.5\n{x:e} 0 -6\n0.5\n")
                })
                .collect::<String>()
        }),
        (1e-9..1e-3f64).prop_map(|gap| {
            format!(
                "14\n1 1 1\n0 0 0\n1 1 1\n0 1 0\n0 -1 0\n\
                 14\n1 1 1\n0 0 0\n1 1 1\n0 -1 0\n0 {:e} 0\n",
                gap - 1.0
            )
        }),
    ]
}

/// A whole scene: a header over the whole range, then records and stress runs.
fn scene() -> impl Strategy<Value = String> {
    let window = prop_oneof![
        4 => Just("8 6".to_string()),
        1 => (positive(), positive()).prop_map(|(w, h)| format!("{w:e} {h:e}")),
    ];
    let eye = prop_oneof![4 => Just("0 0 3".to_string()), 1 => triple()];
    let part = prop_oneof![6 => record(), 1 => stress()];
    (window, eye, prop::collection::vec(part, 0..12))
        .prop_map(|(w, e, parts)| format!("{w}\n{e}\n{}", parts.concat()))
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn generated_scenes_load_or_fail_with_a_located_error_and_render(text in scene()) {
        check(&text);
    }
}

#[test]
fn most_generated_scenes_are_valid() {
    // The generator is meant to produce valid scenes; if most were rejected, the
    // property above would test the loader's errors and not the renderer.
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let strategy = scene();
    let total = 200;
    let loaded = (0..total)
        .filter(|_| {
            let text = strategy.new_tree(&mut runner).unwrap().current();
            legacy_rt::load(&text).is_ok()
        })
        .count();
    assert!(
        loaded * 2 > total,
        "{loaded} of {total} generated scenes load"
    );
}

#[test]
fn a_million_and_one_records_is_a_clear_error_not_an_allocation_failure() {
    let limit = legacy_rt::scene::MAX_RECORDS;
    let mut text = String::from("8 6\n0 0 3\n");
    for _ in 0..=limit {
        text.push_str("10\n1 1 1\n0 0 0\n");
    }
    let error = legacy_rt::load(&text).unwrap_err();
    let expected: SceneErrorKind = SyntaxError::TooManyRecords { limit }.into();
    assert_eq!(error.kind, expected);
    assert_eq!(error.at.line, 3 + 3 * limit);
}
