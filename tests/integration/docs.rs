//! Keeps the docs honest (issue 5): every code reference in `docs/*.md` and `README.md`
//! names a file that exists and an item that the file defines, and every scene snippet
//! of `docs/scene-format.md` loads and renders (or, marked `scene-error`, fails to load).
//!
//! A code reference is a backticked span that starts with `src/`, `tests/`, `examples/`
//! or `bench/` and names a file, optionally followed by `::` and an item path:
//! `src/shapes/quadric.rs::Quadric::coefficients` must name a file that defines a
//! `Quadric` (struct, enum, trait or impl) and a `fn coefficients`.

use legacy_rt::render::{Options, render};
use std::path::PathBuf;

/// The crate root.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The Markdown files the check covers.
fn documents() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "md"))
        .collect();
    files.push(root().join("README.md"));
    files.sort();
    files
}

/// The backticked spans of a Markdown text that look like code references.
fn references(text: &str) -> Vec<String> {
    let prefixes = ["src/", "tests/", "examples/", "bench/", "web/", "docs/"];
    text.split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| prefixes.iter().any(|p| span.starts_with(p)))
        .filter(|span| !span.contains(char::is_whitespace))
        // What web/build.sh writes is not in the repository.
        .filter(|span| !span.starts_with("web/dist"))
        .map(str::to_string)
        .collect()
}

/// Whether `name` follows `keyword ` somewhere in `source` as a whole word.
fn defined_as(source: &str, keyword: &str, name: &str) -> bool {
    let needle = format!("{keyword} {name}");
    source.match_indices(&needle).any(|(at, _)| {
        let after = source[at + needle.len()..].chars().next();
        let before = source[..at].chars().next_back();
        !after.is_some_and(|c| c.is_alphanumeric() || c == '_')
            && !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
    })
}

/// Whether `source` defines an item called `name` (any kind, or an impl of it).
fn defines(source: &str, name: &str) -> bool {
    let keywords = [
        "fn",
        "struct",
        "enum",
        "trait",
        "mod",
        "const",
        "static",
        "type",
        "macro_rules!",
        "impl",
        "for",
    ];
    keywords.iter().any(|k| defined_as(source, k, name))
}

/// What is wrong with one reference, if anything.
fn check(reference: &str) -> Option<String> {
    let (path, items) = match reference.split_once("::") {
        Some((path, items)) => (path, Some(items)),
        None => (reference, None),
    };
    let file = root().join(path);
    if !file.exists() {
        return Some(format!("`{reference}`: no file {path}"));
    }
    let items = items?;
    let source = std::fs::read_to_string(&file).ok()?;
    items
        .split("::")
        .find(|item| !defines(&source, item))
        .map(|item| format!("`{reference}`: {path} defines no `{item}`"))
}

#[test]
fn every_code_reference_in_the_docs_exists() {
    let mut problems = Vec::new();
    let mut count = 0;
    for document in documents() {
        let text = std::fs::read_to_string(&document).unwrap();
        for reference in references(&text) {
            count += 1;
            if let Some(problem) = check(&reference) {
                let name = document.strip_prefix(root()).unwrap().display();
                problems.push(format!("{name}: {problem}"));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The formulas document alone cites over a hundred places; a parser that found
    // none would pass vacuously.
    assert!(count > 100, "only {count} code references found");
}

#[test]
fn the_reference_check_fails_on_a_renamed_item_or_a_moved_file() {
    assert_eq!(check("src/shapes/quadric.rs::Quadric::coefficients"), None);
    assert!(check("src/shapes/quadric.rs::Quadric::coefficients_renamed").is_some());
    assert!(check("src/shapes/moved.rs").is_some());
    assert!(check("src/shapes/quadric.rs::Sphere").is_some());
    // Whole words only: `fn hit_with` does not define `hit`.
    assert!(!defines("fn hit_with() {}", "hit"));
    assert!(defines("impl Kernel for Accurate {", "Accurate"));
}

/// The text of `markdown` from `start` up to the next third-level heading.
fn section_from<'a>(markdown: &'a str, start: &str) -> &'a str {
    let section = &markdown[markdown.find(start).unwrap()..];
    &section[..section.find("\n### ").unwrap()]
}

/// The README's text.
fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).unwrap()
}

/// The fenced blocks of a Markdown text whose info string is `tag`.
fn fenced_blocks(text: &str, tag: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        match current.as_mut() {
            None if line.trim_start().strip_prefix("```") == Some(tag) => {
                current = Some(String::new())
            }
            Some(_) if line.trim_start().starts_with("```") => blocks.push(current.take().unwrap()),
            Some(block) => {
                block.push_str(line);
                block.push('\n');
            }
            None => {}
        }
    }
    blocks
}

/// docs/scene-format.md.
fn scene_format() -> String {
    std::fs::read_to_string(root().join("docs/scene-format.md")).unwrap()
}

#[test]
fn every_scene_snippet_in_the_format_guide_loads_and_renders() {
    // Texture file names in snippets are relative to the crate root, as the tests run.
    assert_eq!(std::env::current_dir().unwrap(), root());
    let snippets = fenced_blocks(&scene_format(), "scene");
    // One per type code the format accepts (10, 11, 13-17, 19-24) and QUADRIC.
    assert!(snippets.len() >= 14, "{} scene snippets", snippets.len());
    for snippet in &snippets {
        let scene = legacy_rt::load(snippet)
            .unwrap_or_else(|e| panic!("snippet does not load:\n{snippet}\n{e}"));
        let image = render(&scene, &Options::new(40, 30), |_| {});
        assert_eq!((image.width, image.height), (40, 30));
        // Every snippet shows its object: some pixel is not black.
        assert!(
            image.pixels.iter().any(|&pixel| pixel != [0, 0, 0]),
            "snippet renders black:\n{snippet}"
        );
    }
}

#[test]
fn every_error_snippet_in_the_format_guide_fails_to_load() {
    let snippets = fenced_blocks(&scene_format(), "scene-error");
    assert!(snippets.len() >= 2, "{} error snippets", snippets.len());
    for snippet in &snippets {
        assert!(
            legacy_rt::load(snippet).is_err(),
            "snippet loads but should not:\n{snippet}"
        );
    }
}

#[test]
fn fenced_blocks_are_found_by_tag() {
    let text = "a\n```scene\n8 6\n0 0 3\n```\n```scene-error\n12\n```\n";
    assert_eq!(
        fenced_blocks(text, "scene"),
        vec!["8 6\n0 0 3\n".to_string()]
    );
    assert_eq!(fenced_blocks(text, "scene-error"), vec!["12\n".to_string()]);
}

#[test]
fn the_readme_s_trace_example_is_what_the_program_prints() {
    let readme = readme();
    let start = readme
        .find("When no variant explains it, trace a pixel")
        .unwrap();
    let section = &readme[start..];
    let section = &section[..section.find("`legacy-rt` can do that lining up").unwrap()];
    let blocks = fenced_blocks(section, "text");
    assert!(blocks.len() >= 4, "{blocks:?}");
    assert_eq!(blocks[0], "legacy-rt trace 410 175 < examples/studio.txt\n");
    let scene = std::fs::read(root().join("examples/studio.txt")).unwrap();
    let output = super::common::run(&["trace", "410", "175"], &scene);
    let trace = String::from_utf8(output.stdout).unwrap();
    let lines: Vec<&str> = trace.lines().collect();
    for block in &blocks[1..] {
        for line in block.lines() {
            assert!(
                lines.contains(&line),
                "README: `{line}` is not in the trace:\n{trace}"
            );
        }
    }
}

/// Runs the README's command line `args` from the repository's folder, the scene on
/// standard input as the README's `< examples/...` gives it: the exit code and output.
fn readme_command(args: &[&str], scene: &str) -> (Option<i32>, String) {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_legacy-rt"))
        .args(args)
        .current_dir(root())
        .stdin(std::fs::File::open(root().join(scene)).unwrap())
        .output()
        .unwrap();
    (
        output.status.code(),
        String::from_utf8(output.stdout).unwrap(),
    )
}

#[test]
fn the_readme_s_against_examples_are_what_the_program_prints() {
    let readme = readme();
    let section = section_from(&readme, "`legacy-rt` can do that lining up");
    let blocks = fenced_blocks(section, "text");
    assert_eq!(blocks.len(), 4, "{blocks:?}");
    // The whole file: every line shown is the report's, "..." for the rest.
    assert_eq!(
        blocks[0],
        "legacy-rt trace --against examples/studio-8x6.dbg 8 6 < examples/studio.txt\n"
    );
    let args = ["trace", "--against", "examples/studio-8x6.dbg", "8", "6"];
    let (code, report) = readme_command(&args, "examples/studio.txt");
    assert_eq!(code, Some(1));
    let lines: Vec<&str> = report.lines().collect();
    for line in blocks[1].lines().filter(|line| line.trim() != "...") {
        assert!(
            lines.contains(&line),
            "README: `{line}` is not in the report:\n{report}"
        );
    }
    // One pixel.
    let command = "legacy-rt trace 410 175 640 480 --against examples/studio-410-175.dbg \
                   < examples/studio.txt\n";
    assert_eq!(blocks[2], command);
    let args = [
        "trace",
        "410",
        "175",
        "640",
        "480",
        "--against",
        "examples/studio-410-175.dbg",
    ];
    let (code, report) = readme_command(&args, "examples/studio.txt");
    assert_eq!(code, Some(1));
    assert!(
        report.starts_with(&blocks[3]),
        "README:\n{}\nreport:\n{report}",
        blocks[3]
    );
}

#[test]
fn the_readme_s_compare_example_is_what_the_program_prints() {
    let readme = readme();
    let start = readme.find("### When your image differs").unwrap();
    let end = readme
        .find("When no variant explains it, trace a pixel")
        .unwrap();
    let blocks = fenced_blocks(&readme[start..end], "text");
    assert_eq!(blocks.len(), 4, "{blocks:?}");
    let command = "legacy-rt compare --diagnose --diff diff.png examples/shadows.txt mine.ppm\n";
    assert_eq!(blocks[0], command);
    // The student's image: the scene without shadow rays, 160x120, as the README's trace
    // commands say, named as the README names it, from the repository's folder.
    let scene = std::fs::read(root().join("examples/shadows.txt")).unwrap();
    let folder = super::common::folder("readme-compare");
    let mine = folder.join("mine.ppm");
    let mine = mine.to_str().unwrap();
    let output = super::common::run(
        &["160", "120", "--variant", "no-shadows", "-o", mine],
        &scene,
    );
    assert!(output.status.success());
    let diff = folder.join("diff.png");
    let args = ["compare", "--diagnose", "--diff", diff.to_str().unwrap()];
    let output = super::common::run(&[&args[..], &["examples/shadows.txt", mine]].concat(), b"");
    assert_eq!(output.status.code(), Some(1));
    let report = String::from_utf8(output.stdout).unwrap();
    let lines: Vec<&str> = report.lines().collect();
    for line in blocks[1].lines().filter(|line| line.trim() != "...") {
        assert!(
            lines.contains(&line),
            "README: `{line}` is not in the report:\n{report}"
        );
    }
    // The student's own mistake: the small white sphere (line 25) casts no shadow.
    let output = super::common::run(
        &["160", "120", "--variant", "no-shadow@25", "-o", mine],
        &scene,
    );
    assert!(output.status.success());
    let args = ["compare", "--diagnose", "examples/shadows.txt", mine];
    let output = super::common::run(&args, b"");
    assert_eq!(output.status.code(), Some(1));
    let report = String::from_utf8(output.stdout).unwrap();
    assert!(
        report.ends_with(&blocks[2]),
        "README:\n{}\nreport:\n{report}",
        blocks[2]
    );
    // Two mistakes, one of them the whole image's: the commands the README gives.
    let tube = std::fs::read(root().join("examples/tube.txt")).unwrap();
    let mistake = "legacy-rt --variant row-offset=1,behind-root < examples/tube.txt > tube.ppm";
    let diagnose = "legacy-rt compare --diagnose examples/tube.txt tube.ppm";
    for command in [mistake, diagnose] {
        assert!(
            readme[start..end].contains(&format!("`{command}`")),
            "{command}"
        );
    }
    let student = folder.join("tube.ppm");
    let student = student.to_str().unwrap();
    let args = ["--variant", "row-offset=1,behind-root", "-o", student];
    assert!(super::common::run(&args, &tube).status.success());
    let args = ["compare", "--diagnose", "examples/tube.txt", student];
    let output = super::common::run(&args, b"");
    assert_eq!(output.status.code(), Some(1));
    let report = String::from_utf8(output.stdout).unwrap();
    assert!(
        report.contains(&blocks[3]),
        "README:\n{}\nreport:\n{report}",
        blocks[3]
    );
}

/// Every command of the README that a reader may copy names the repository's own files:
/// a student who cloned only the repository has no `../shared` (the course's material
/// is named where the README says what the tests read, not in a command).
#[test]
fn the_readme_s_commands_need_nothing_beside_the_repository() {
    let readme = readme();
    let mut commands: Vec<String> = ["text", "sh"]
        .iter()
        .flat_map(|tag| fenced_blocks(&readme, tag))
        .flat_map(|block| block.lines().map(str::to_string).collect::<Vec<_>>())
        .collect();
    // Commands quoted inline: `legacy-rt ...`.
    commands.extend(
        readme
            .split('`')
            .skip(1)
            .step_by(2)
            .filter(|code| code.starts_with("legacy-rt ") || code.starts_with("cargo "))
            .map(str::to_string),
    );
    let mut scenes = 0;
    for command in &commands {
        assert!(
            !command.contains("../shared"),
            "README: `{command}` needs ../shared, which a clone does not have"
        );
        // Every scene file a command reads from the repository exists.
        for word in command.split_whitespace() {
            let word = word.trim_matches(|c| c == '"' || c == '\'');
            if word.starts_with("examples/") && word.ends_with(".txt") {
                assert!(root().join(word).is_file(), "README names {word}");
                scenes += 1;
            }
        }
    }
    assert!(
        scenes >= 5,
        "{scenes} scene files named by the README's commands"
    );
}

/// docs/variants.md's table is the program's table of variants, as
/// `cargo run --release --example variant_pictures` writes it.
#[test]
fn the_variants_table_is_the_program_s() {
    let doc = std::fs::read_to_string(root().join("docs/variants.md")).unwrap();
    let table = legacy_rt::render::variant::markdown_table();
    assert!(
        doc.contains(&table),
        "docs/variants.md's table is out of date: run cargo run --release --example \
         variant_pictures"
    );
    // One row per variant.
    assert_eq!(table.lines().count(), legacy_rt::render::VARIANTS.len() + 2);
}

/// `legacy-rt --help` names every variant of the table, with its parameter and scope.
#[test]
fn the_help_lists_every_variant() {
    let output = super::common::run(&["--help"], b"");
    let help = String::from_utf8(output.stdout).unwrap();
    for row in legacy_rt::render::VARIANTS {
        let id = legacy_rt::render::Variant::pattern(row);
        assert!(help.contains(&id), "--help does not list {id}");
    }
}

#[test]
fn the_readme_s_grading_example_is_what_the_program_prints() {
    let readme = readme();
    let section = section_from(&readme, "### Grading a class");
    let blocks = fenced_blocks(section, "sh");
    assert_eq!(blocks.len(), 2, "{blocks:?}");
    // The README's words for what it prints, one line however the paragraph wraps.
    let said = section.split("It prints the counts (`").nth(1).unwrap();
    let said = said[..said.find("`)").unwrap()].replace('\n', " ");
    // Run as a reader runs it: from a folder with the repository's examples/, with the
    // installed legacy-rt on the PATH.
    let folder = super::common::folder("readme-grade");
    std::os::unix::fs::symlink(root().join("examples"), folder.join("examples")).unwrap();
    let binary = std::path::Path::new(env!("CARGO_BIN_EXE_legacy-rt"));
    let path = format!(
        "{}:{}",
        binary.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let output = std::process::Command::new("sh")
        .args(["-e", "-c", &blocks[1]])
        .current_dir(&folder)
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let printed = String::from_utf8(output.stderr).unwrap();
    assert_eq!(printed.trim_end(), said);
    assert!(folder.join("try/report/index.html").is_file());
    std::fs::remove_dir_all(&folder).unwrap();
}

/// The commands the docs give find what they need wherever a newcomer's setup puts it:
/// the bench scripts and the browser test ask cargo where the binary is (a user's
/// CARGO_TARGET_DIR moves it), and the pictures' example says what it needs instead of
/// failing half-way.
#[test]
fn the_documented_commands_find_the_binary_and_say_what_they_need() {
    let elsewhere = std::env::temp_dir().join("legacy-rt-elsewhere");
    let output = std::process::Command::new("python3")
        .args(["bench/built.py", "debug"])
        .env("CARGO_TARGET_DIR", &elsewhere)
        .current_dir(root())
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let printed = String::from_utf8(output.stdout).unwrap();
    assert_eq!(
        printed.trim(),
        elsewhere.join("debug/legacy-rt").to_str().unwrap()
    );
    // No script assumes the default target folder.
    for folder in ["bench", "web"] {
        for entry in std::fs::read_dir(root().join(folder)).unwrap() {
            let path = entry.unwrap().path();
            let script = path.extension().is_some_and(|e| e == "py" || e == "sh");
            if !script {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            for fixed in ["target/release/legacy-rt", "target/debug/legacy-rt"] {
                assert!(!text.contains(fixed), "{} names {fixed}", path.display());
            }
        }
    }
    // The example that draws docs/variants.png, run where there is no ../shared: it says
    // so and stops. cargo test builds it beside this test's binary.
    let examples = std::env::current_exe()
        .unwrap()
        .parent()
        .unwrap()
        .parent()
        .unwrap()
        .join("examples");
    let example = examples.join("variant_pictures");
    let scratch = std::env::temp_dir().join(format!("legacy-rt-no-shared-{}", std::process::id()));
    std::fs::create_dir_all(scratch.join("repo")).unwrap();
    let output = std::process::Command::new(&example)
        .current_dir(scratch.join("repo"))
        .output()
        .unwrap_or_else(|e| panic!("{}: {e}", example.display()));
    assert_eq!(output.status.code(), Some(1));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("../shared/course-scenes") && !message.contains("panicked"),
        "{message}"
    );
    std::fs::remove_dir_all(&scratch).unwrap();
}
