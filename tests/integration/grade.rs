//! `legacy-rt grade`: a class made here, graded in one command; every row is what
//! `compare --diagnose --json` says of that pair, run on its own.

use super::common;
use serde_json::Value;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SCENES: [&str; 2] = ["spheres", "studio"];

/// Fails the test, with the program's error, unless it succeeded.
fn succeeded(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Runs the binary in `dir` with `args`, nothing on standard input.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_legacy-rt"))
        .args(args)
        .current_dir(dir)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("the binary runs")
}

/// Renders scene `name` of the class in `dir` to `out` with extra `flags`.
fn render(dir: &Path, name: &str, flags: &[&str], out: &str) {
    let scene = fs::read(dir.join("scenes").join(format!("{name}.txt"))).unwrap();
    let out = dir.join(out);
    fs::create_dir_all(out.parent().unwrap()).unwrap();
    let mut args = flags.to_vec();
    let out = out.to_str().unwrap();
    args.extend(["-o", out]);
    let made = common::run(&args, &scene);
    succeeded(&made);
}

/// The same pixels as a P3 (text) PPM, as some students' programs write.
fn as_p3(p6: &[u8]) -> Vec<u8> {
    let text = String::from_utf8_lossy(&p6[..20]).to_string();
    let mut header = text.split_ascii_whitespace();
    assert_eq!(header.next(), Some("P6"));
    let (w, h): (usize, usize) = (
        header.next().unwrap().parse().unwrap(),
        header.next().unwrap().parse().unwrap(),
    );
    let body = &p6[p6.len() - 3 * w * h..];
    let mut out = format!("P3\n{w} {h}\n255\n");
    for (i, byte) in body.iter().enumerate() {
        out += &byte.to_string();
        out.push(if i % 12 == 11 { '\n' } else { ' ' });
    }
    out.into_bytes()
}

/// A class: two example scenes, and students whose images are the reference, a
/// single-precision textbook tracer's, two variants', a PNG, a P3, a smaller size,
/// missing files, garbage, a truncated image and a folder where an image should be.
fn class(name: &str) -> common::Folder {
    let dir = common::folder(name);
    fs::create_dir_all(dir.join("scenes")).unwrap();
    for scene in SCENES {
        let text = fs::read(format!("examples/{scene}.txt")).unwrap();
        fs::write(dir.join("scenes").join(format!("{scene}.txt")), text).unwrap();
        let size = ["80", "60"];
        render(&dir, scene, &size, &format!("subs/ada/{scene}.ppm"));
        let f32 = [&size[..], &["--kernel", "textbook-f32"]].concat();
        render(&dir, scene, &f32, &format!("subs/bo/{scene}.ppm"));
        let shadows = [&size[..], &["--variant", "no-shadows"]].concat();
        render(&dir, scene, &shadows, &format!("subs/cy/{scene}.png"));
        let falloff = [&size[..], &["--variant", "square-falloff"]].concat();
        render(&dir, scene, &falloff, &format!("subs/di/{scene}.ppm"));
        render(&dir, scene, &["40", "30"], &format!("subs/ed/{scene}.ppm"));
        let p6 = fs::read(dir.join(format!("subs/ada/{scene}.ppm"))).unwrap();
        fs::create_dir_all(dir.join("subs/fay")).unwrap();
        fs::write(dir.join(format!("subs/fay/{scene}.ppm")), as_p3(&p6)).unwrap();
    }
    // gus: one scene missing, the other garbage; hal: truncated, and a folder.
    fs::create_dir_all(dir.join("subs/gus")).unwrap();
    fs::write(dir.join("subs/gus/studio.ppm"), b"not an image at all").unwrap();
    fs::write(dir.join("subs/gus/notes.txt"), b"my report").unwrap();
    let p6 = fs::read(dir.join("subs/ada/studio.ppm")).unwrap();
    fs::create_dir_all(dir.join("subs/hal/spheres.ppm")).unwrap();
    fs::write(dir.join("subs/hal/studio.ppm"), &p6[..p6.len() / 2]).unwrap();
    // ivy: a named pipe (no writer: reading it would wait for ever) and an image whose
    // header claims 10^10 pixels.
    fs::create_dir_all(dir.join("subs/ivy")).unwrap();
    let fifo = std::ffi::CString::new(dir.join("subs/ivy/spheres.ppm").to_str().unwrap()).unwrap();
    // SAFETY: mkfifo reads the NUL-terminated path and creates a FIFO; nothing else.
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);
    fs::write(dir.join("subs/ivy/studio.ppm"), b"P6\n100000 100000\n255\n").unwrap();
    // ada handed in a PNG of studio besides the PPM: the PPM is graded, the PNG listed.
    fs::copy(
        dir.join("subs/cy/studio.png"),
        dir.join("subs/ada/studio.png"),
    )
    .unwrap();
    dir
}

fn read_grades(report: &Path) -> Value {
    serde_json::from_slice(&fs::read(report.join("grades.json")).unwrap()).unwrap()
}

/// Every row against `compare --diagnose --json` (with `flags`) on its pair.
fn rows_are_compares(dir: &Path, grades: &Value, flags: &[&str]) {
    for row in grades["rows"].as_array().unwrap() {
        let scene = format!("scenes/{}.txt", row["scene"].as_str().unwrap());
        let what = format!("{} {}", row["student"], row["scene"]);
        let Some(file) = row["file"].as_str() else {
            assert_eq!(row["verdict"], "missing", "{what}");
            continue;
        };
        let args = [
            &["compare", "--diagnose", "--json"][..],
            flags,
            &[&scene, file],
        ]
        .concat();
        let compared = run_in(dir, &args);
        match row["verdict"].as_str().unwrap() {
            "unreadable" => {
                assert_eq!(compared.status.code(), Some(2), "{what}");
                let stderr = String::from_utf8_lossy(&compared.stderr);
                let message = row["message"].as_str().unwrap();
                assert_eq!(stderr.trim_end(), format!("error: {message}"), "{what}");
            }
            verdict => {
                let report: Value = serde_json::from_slice(&compared.stdout).unwrap();
                assert_eq!(row["compare"], report, "{what}");
                assert_eq!(report["verdict"], verdict, "{what}");
                let matched = verdict == "match";
                assert_eq!(compared.status.code(), Some(if matched { 0 } else { 1 }));
                let points = if matched {
                    row["max_points"].as_f64()
                } else {
                    Some(0.0)
                };
                assert_eq!(row["points"].as_f64(), points, "{what}");
                let causes = report["causes"].as_array();
                let ids: Vec<&str> = causes
                    .into_iter()
                    .flatten()
                    .map(|c| c["id"].as_str().unwrap())
                    .collect();
                assert_eq!(row["diagnosis"], ids.join(","), "{what}");
            }
        }
    }
}

#[test]
fn every_row_is_what_compare_says_of_its_pair() {
    let dir = class("grade-class");
    let graded = run_in(
        &dir,
        &["grade", "--threads", "2", "scenes", "subs", "-o", "report"],
    );
    succeeded(&graded);
    let grades = read_grades(&dir.join("report"));
    let rows = grades["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 9 * SCENES.len());
    rows_are_compares(&dir, &grades, &[]);
    let verdict = |student: &str, scene: &str| {
        let row = rows
            .iter()
            .find(|r| r["student"] == student && r["scene"] == scene);
        row.unwrap()["verdict"].as_str().unwrap().to_string()
    };
    // What each student was made to be.
    assert_eq!(verdict("ada", "studio"), "match");
    assert_eq!(verdict("fay", "studio"), "match", "a P3 of the reference");
    assert_eq!(
        verdict("ed", "studio"),
        "match",
        "rendered at the student's size"
    );
    assert_eq!(verdict("cy", "studio"), "differ");
    assert_eq!(verdict("gus", "spheres"), "missing");
    assert_eq!(verdict("gus", "studio"), "unreadable");
    assert_eq!(verdict("hal", "spheres"), "unreadable", "a folder");
    assert_eq!(verdict("hal", "studio"), "unreadable", "truncated");
    assert_eq!(verdict("ivy", "spheres"), "unreadable", "a named pipe");
    assert_eq!(
        verdict("ivy", "studio"),
        "unreadable",
        "too large by its header"
    );
    let cy = rows
        .iter()
        .find(|r| r["student"] == "cy" && r["scene"] == "studio")
        .unwrap();
    assert!(
        cy["diagnosis"].as_str().unwrap().contains("no-shadows"),
        "{}",
        cy["diagnosis"]
    );
    let unexpected = serde_json::json!(["ada/studio.png", "gus/notes.txt"]);
    assert_eq!(grades["unexpected"], unexpected);
    let ada = rows
        .iter()
        .find(|r| r["student"] == "ada" && r["scene"] == "studio")
        .unwrap();
    assert_eq!(ada["file"], "subs/ada/studio.ppm");
    // And a warning on that row, which the CSV and the page carry too: the PNG beside it
    // is not graded.
    let warning = ada["warning"].as_str().unwrap();
    assert!(
        warning.contains("ada/studio.png") && warning.contains("studio.ppm is"),
        "{warning}"
    );
    assert!(rows.iter().filter(|r| r["warning"].is_string()).count() == 1);

    // The CSV says what the JSON says.
    let mut csv = csv::Reader::from_path(dir.join("report/grades.csv")).unwrap();
    let headers = csv.headers().unwrap().clone();
    let wanted = [
        "student",
        "scene",
        "verdict",
        "differing_pixels",
        "diagnosis",
        "points",
        "max_points",
    ];
    assert_eq!(headers.iter().take(7).collect::<Vec<_>>(), wanted);
    assert_eq!(headers.iter().next_back(), Some("warning"));
    let records: Vec<csv::StringRecord> = csv.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), rows.len());
    for (record, row) in records.iter().zip(rows) {
        assert_eq!(
            &record[record.len() - 1],
            row["warning"].as_str().unwrap_or("")
        );
    }
    for (record, row) in records.iter().zip(rows) {
        for (i, key) in wanted.iter().enumerate() {
            let json = match &row[key] {
                Value::Null => String::new(),
                Value::String(s) => s.clone(),
                other => other.to_string().trim_end_matches(".0").to_string(),
            };
            assert_eq!(&record[i], json, "{key} of {record:?}");
        }
    }

    // Every image the page names is a file of the report, and each pair with an image
    // has the student's image, and with a reference the reference and the diff.
    let page = fs::read_to_string(dir.join("report/index.html")).unwrap();
    let sources: Vec<&str> = page
        .split("src=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap())
        .collect();
    assert!(sources.len() >= 3 * 10, "{} images", sources.len());
    for source in &sources {
        let file = dir.join("report").join(source);
        let bytes = fs::read(&file).unwrap_or_else(|_| panic!("{source} is named and missing"));
        assert_eq!(&bytes[1..4], b"PNG", "{source}");
    }
    assert!(!page.contains("http"), "no network");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_required_size_makes_other_sizes_wrong_size() {
    let dir = class("grade-size");
    let args = [
        "grade", "--size", "80", "60", "scenes", "subs", "-o", "report",
    ];
    let graded = run_in(&dir, &args);
    succeeded(&graded);
    let grades = read_grades(&dir.join("report"));
    rows_are_compares(&dir, &grades, &["--size", "80", "60"]);
    for row in grades["rows"].as_array().unwrap() {
        let expected = if row["student"] == "ed" {
            "wrong-size"
        } else {
            ""
        };
        if !expected.is_empty() {
            assert_eq!(row["verdict"], expected);
            assert_eq!(row["points"].as_f64(), Some(0.0));
        }
    }
    // A scheme: studio worth 3 points at 40x30, spheres 2 by default.
    fs::write(
        dir.join("points.toml"),
        "points = 2\n[scenes.studio]\npoints = 3\nsize = [40, 30]\n",
    )
    .unwrap();
    let args = [
        "grade",
        "--scheme",
        "points.toml",
        "scenes",
        "subs",
        "-o",
        "schemed",
    ];
    let graded = run_in(&dir, &args);
    succeeded(&graded);
    let schemed = read_grades(&dir.join("schemed"));
    for row in schemed["rows"].as_array().unwrap() {
        let studio = row["scene"] == "studio";
        assert_eq!(
            row["max_points"].as_f64(),
            Some(if studio { 3.0 } else { 2.0 })
        );
        if studio && row["width"] == 80 {
            assert_eq!(row["verdict"], "wrong-size", "{}", row["student"]);
        }
        if row["student"] == "ed" && studio {
            assert_eq!(row["verdict"], "match");
            assert_eq!(row["points"].as_f64(), Some(3.0));
        }
    }
    // A scheme naming a scene SCENES lacks is refused, naming it, the file and its line.
    fs::write(
        dir.join("typo.toml"),
        "points = 1\n\n[scenes.studoi]\npoints = 3\n",
    )
    .unwrap();
    let refused = run_in(
        &dir,
        &[
            "grade",
            "--scheme",
            "typo.toml",
            "scenes",
            "subs",
            "-o",
            "typo",
        ],
    );
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr).into_owned();
    assert!(message.contains("studoi"), "{message}");
    assert!(message.contains("--scheme typo.toml (line 3)"), "{message}");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shards_merged_equal_the_whole_class() {
    let dir = class("grade-shards");
    let whole = run_in(&dir, &["grade", "scenes", "subs", "-o", "whole"]);
    succeeded(&whole);
    let mut sizes = Vec::new();
    for k in 1..=3 {
        let shard = format!("{k}/3");
        let part = format!("part{k}");
        let graded = run_in(
            &dir,
            &["grade", "--shard", &shard, "scenes", "subs", "-o", &part],
        );
        succeeded(&graded);
        sizes.push(
            read_grades(&dir.join(&part))["rows"]
                .as_array()
                .unwrap()
                .len(),
        );
    }
    assert_eq!(sizes.iter().sum::<usize>(), 9 * SCENES.len(), "{sizes:?}");
    assert!(sizes.iter().all(|&n| n > 0), "{sizes:?}");
    let merged = run_in(
        &dir,
        &[
            "grade", "--merge", "part3", "part1", "part2", "-o", "merged",
        ],
    );
    succeeded(&merged);
    assert_eq!(
        read_grades(&dir.join("merged")),
        read_grades(&dir.join("whole"))
    );
    assert_eq!(
        fs::read(dir.join("merged/grades.csv")).unwrap(),
        fs::read(dir.join("whole/grades.csv")).unwrap()
    );
    // Every image of the merged page was copied.
    let page = fs::read_to_string(dir.join("merged/index.html")).unwrap();
    for source in page
        .split("src=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap())
    {
        assert!(dir.join("merged").join(source).is_file(), "{source}");
    }
    // A part given twice is refused.
    let twice = run_in(&dir, &["grade", "--merge", "part1", "part1", "-o", "twice"]);
    assert_eq!(twice.status.code(), Some(2));
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gradescope_s_score_is_the_sum_of_its_tests() {
    let dir = class("grade-gradescope");
    // As an autograder gives it: one student's images directly in the folder.
    let one = dir.join("submission");
    fs::create_dir_all(&one).unwrap();
    fs::copy(dir.join("subs/ada/spheres.ppm"), one.join("spheres.ppm")).unwrap();
    fs::copy(dir.join("subs/cy/studio.png"), one.join("studio.png")).unwrap();
    let args = [
        "grade",
        "--gradescope",
        "results.json",
        "scenes",
        "submission",
        "-o",
        "report",
    ];
    let graded = run_in(&dir, &args);
    succeeded(&graded);
    let results: Value =
        serde_json::from_slice(&fs::read(dir.join("results.json")).unwrap()).unwrap();
    let tests = results["tests"].as_array().unwrap();
    assert_eq!(tests.len(), SCENES.len());
    let sum: f64 = tests.iter().map(|t| t["score"].as_f64().unwrap()).sum();
    assert_eq!(results["score"].as_f64(), Some(sum));
    assert_eq!(sum, 1.0);
    let studio = tests.iter().find(|t| t["name"] == "studio").unwrap();
    assert_eq!(studio["status"], "failed");
    assert_eq!(studio["max_score"].as_f64(), Some(1.0));
    let output = studio["output"].as_str().unwrap();
    assert!(output.contains("--variant no-shadows"), "{output}");
    assert!(output.contains("--against dbg.txt"), "{output}");
    // Several students' folders are not one student's results.
    let refused = run_in(
        &dir,
        &[
            "grade",
            "--gradescope",
            "r.json",
            "scenes",
            "subs",
            "-o",
            "r",
        ],
    );
    assert_eq!(refused.status.code(), Some(2));
    assert!(!dir.join("r.json").exists());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn grade_refuses_what_it_cannot_read_or_would_overwrite() {
    let dir = class("grade-refusals");
    // The report inside the submissions would be graded as a student.
    let inside = run_in(&dir, &["grade", "scenes", "subs", "-o", "subs/report"]);
    assert_eq!(inside.status.code(), Some(2));
    assert!(!dir.join("subs/report").exists());
    // A folder of other files is not replaced.
    fs::create_dir_all(dir.join("mine")).unwrap();
    fs::write(dir.join("mine/thesis.tex"), b"years of work").unwrap();
    let occupied = run_in(&dir, &["grade", "scenes", "subs", "-o", "mine"]);
    assert_eq!(occupied.status.code(), Some(2));
    assert_eq!(fs::read_dir(dir.join("mine")).unwrap().count(), 1);
    // An earlier report whose page was made a hard link to a student's image, and whose
    // CSV a symbolic link to it: grading again replaces the links, not the image.
    let first = run_in(&dir, &["grade", "scenes", "subs", "-o", "again"]);
    succeeded(&first);
    let image = dir.join("subs/ada/spheres.ppm");
    let before = fs::read(&image).unwrap();
    fs::remove_file(dir.join("again/index.html")).unwrap();
    fs::hard_link(&image, dir.join("again/index.html")).unwrap();
    fs::remove_file(dir.join("again/grades.csv")).unwrap();
    std::os::unix::fs::symlink(&image, dir.join("again/grades.csv")).unwrap();
    let second = run_in(&dir, &["grade", "scenes", "subs", "-o", "again"]);
    succeeded(&second);
    assert_eq!(
        fs::read(&image).unwrap(),
        before,
        "the student's image is untouched"
    );
    assert!(
        fs::read_to_string(dir.join("again/index.html"))
            .unwrap()
            .starts_with("<!doctype html>")
    );
    assert!(
        !fs::symlink_metadata(dir.join("again/grades.csv"))
            .unwrap()
            .is_symlink()
    );
    // A scene that does not load is named.
    fs::write(dir.join("scenes/broken.txt"), b"this is not a scene\n").unwrap();
    let broken = run_in(&dir, &["grade", "scenes", "subs", "-o", "report"]);
    assert_eq!(broken.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&broken.stderr).contains("broken.txt"));
    // Folders that are not there.
    let absent = run_in(&dir, &["grade", "nowhere", "subs", "-o", "report"]);
    assert_eq!(absent.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&absent.stderr).contains("nowhere"));
    fs::remove_dir_all(&dir).unwrap();
}

/// Each refusal says `error: ` once, at its start, whichever layer found it: the
/// command line, a file, a scene, a reference's options or the report folder.
#[test]
fn each_refusal_says_error_once() {
    let dir = common::folder("grade-error-once");
    small_class(&dir);
    fs::create_dir_all(dir.join("mine")).unwrap();
    fs::write(dir.join("mine/thesis.tex"), b"years of work").unwrap();
    let cases: [&[&str]; 5] = [
        // A record line the scene does not have (studio's objects start later).
        &[
            "grade",
            "--variant",
            "hidden@2",
            "scenes",
            "subs",
            "-o",
            "r1",
        ],
        &["grade", "scenes", "subs", "extra", "-o", "r2"],
        &["grade", "nowhere", "subs", "-o", "r3"],
        &["grade", "scenes", "subs", "-o", "mine"],
        &["grade", "--scheme", "scenes", "scenes", "subs", "-o", "r4"],
    ];
    let mut said = Vec::new();
    for args in cases {
        let output = run_in(&dir, args);
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
        assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
        assert_eq!(stderr.matches("error: ").count(), 1, "{args:?}: {stderr}");
        said.push(stderr);
    }
    assert!(
        said[0].contains("studio.txt: --variant hidden@2: line 2 starts no record"),
        "{}",
        said[0]
    );
    // Refused before the report folder was made.
    assert!(!dir.join("r1").exists());
    fs::remove_dir_all(&dir).unwrap();
}

/// The `.partial` files under `dir` (the report folder and its images/).
fn partial_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for folder in [dir.to_path_buf(), dir.join("images")] {
        let Ok(entries) = fs::read_dir(&folder) else {
            continue;
        };
        for entry in entries.flatten() {
            if entry.file_name().to_string_lossy().ends_with(".partial") {
                found.push(entry.path());
            }
        }
    }
    found
}

#[test]
fn an_interrupted_grade_leaves_no_temporary_file() {
    // Eight students' large images of one scene: the report's images take a while to
    // write. The test interrupts `grade` while one of its temporary files exists, and
    // retries where it was too quick to catch; it fails if it never caught one.
    let dir = common::folder("grade-interrupt");
    fs::create_dir_all(dir.join("scenes")).unwrap();
    fs::copy("examples/studio.txt", dir.join("scenes/studio.txt")).unwrap();
    render(&dir, "studio", &["1200", "900"], "subs/s0/studio.ppm");
    for k in 1..8 {
        fs::create_dir_all(dir.join(format!("subs/s{k}"))).unwrap();
        fs::copy(
            dir.join("subs/s0/studio.ppm"),
            dir.join(format!("subs/s{k}/studio.ppm")),
        )
        .unwrap();
    }
    let mut caught = 0;
    for attempt in 0..20 {
        let report = dir.join(format!("report{attempt}"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_legacy-rt"))
            .args(["grade", "scenes", "subs", "-o", report.to_str().unwrap()])
            .current_dir(&dir)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let seen = loop {
            if child.try_wait().unwrap().is_some() {
                break false;
            }
            if !partial_files(&report).is_empty() {
                break true;
            }
        };
        if !seen {
            continue;
        }
        // SAFETY: kill(2) on our own child's pid, with a valid signal number.
        assert_eq!(
            unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGTERM) },
            0
        );
        let status = child.wait().unwrap();
        caught += 1;
        assert_eq!(partial_files(&report), Vec::<PathBuf>::new(), "{status:?}");
        if caught == 2 {
            break;
        }
    }
    assert!(caught > 0, "never saw a temporary file to interrupt");
    fs::remove_dir_all(&dir).unwrap();
}

/// A class of one scene (studio) with one correct student, `ada`, in `dir`.
fn small_class(dir: &Path) {
    fs::create_dir_all(dir.join("scenes")).unwrap();
    fs::copy("examples/studio.txt", dir.join("scenes/studio.txt")).unwrap();
    render(dir, "studio", &["40", "30"], "subs/ada/studio.ppm");
}

#[test]
fn links_in_the_submissions_are_listed_never_followed() {
    let dir = common::folder("grade-links");
    small_class(&dir);
    // bo's folder is a link to /etc; cy's image a link to a file outside SUBMISSIONS.
    let outside = dir.join("outside.ppm");
    fs::copy(dir.join("subs/ada/studio.ppm"), &outside).unwrap();
    std::os::unix::fs::symlink("/etc", dir.join("subs/bo")).unwrap();
    fs::create_dir_all(dir.join("subs/cy")).unwrap();
    std::os::unix::fs::symlink(&outside, dir.join("subs/cy/studio.ppm")).unwrap();
    succeeded(&run_in(&dir, &["grade", "scenes", "subs", "-o", "report"]));
    let grades = read_grades(&dir.join("report"));
    let rows = grades["rows"].as_array().unwrap();
    let row = |student: &str| rows.iter().find(|r| r["student"] == student).unwrap();
    assert_eq!(row("ada")["verdict"], "match");
    for student in ["bo", "cy"] {
        assert_eq!(row(student)["verdict"], "unreadable", "{student}");
        let message = row(student)["message"].as_str().unwrap();
        assert!(
            message.contains("is a symbolic link") && message.contains("not followed"),
            "{message}"
        );
        assert!(row(student)["images"].is_null(), "{student}");
    }
    // Nothing of /etc in the report: no name of it listed, no image of cy's copied.
    let json = fs::read_to_string(dir.join("report/grades.json")).unwrap();
    let page = fs::read_to_string(dir.join("report/index.html")).unwrap();
    for text in [&json, &page] {
        assert!(!text.contains("passwd") && !text.contains("hostname"));
    }
    assert!(!dir.join("report/images/cy").exists());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_merged_part_is_read_only_from_its_own_files() {
    let dir = common::folder("grade-merge-links");
    small_class(&dir);
    succeeded(&run_in(&dir, &["grade", "scenes", "subs", "-o", "part"]));
    // The part's images/ replaced by a link to a folder of the grader's.
    let secret = dir.join("secret");
    fs::rename(dir.join("part/images"), &secret).unwrap();
    std::os::unix::fs::symlink(&secret, dir.join("part/images")).unwrap();
    let refused = run_in(&dir, &["grade", "--merge", "part", "-o", "merged"]);
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr).into_owned();
    assert!(message.contains("is a symbolic link"), "{message}");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_crafted_part_is_bounded_and_its_words_escaped() {
    let dir = common::folder("grade-merge-crafted");
    small_class(&dir);
    succeeded(&run_in(&dir, &["grade", "scenes", "subs", "-o", "part"]));
    let mut grades = read_grades(&dir.join("part"));
    // A verdict with a terminal's escape codes: the summary shows them escaped.
    grades["rows"][0]["verdict"] = "\u{1b}[31mmatch\u{1b}[0m".into();
    fs::write(dir.join("part/grades.json"), grades.to_string()).unwrap();
    let merged = run_in(&dir, &["grade", "--merge", "part", "-o", "merged"]);
    succeeded(&merged);
    let summary = String::from_utf8_lossy(&merged.stderr).into_owned();
    assert!(
        !summary.contains('\u{1b}') && summary.contains("\\u{1b}[31m"),
        "{summary}"
    );
    // A list of 20,000 lines of explanation (the cap is 10,000, scaled down from a
    // 60-million-element array that aborted the merge): refused, not held.
    grades["rows"][0]["explanation"] = vec![""; 20_000].into();
    fs::write(dir.join("part/grades.json"), grades.to_string()).unwrap();
    let refused = run_in(&dir, &["grade", "--merge", "part", "-o", "merged2"]);
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr).into_owned();
    assert!(message.contains("more than 10000 items"), "{message}");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn csv_cells_are_no_formulas_and_no_escapes() {
    let dir = common::folder("grade-csv");
    small_class(&dir);
    for name in ["=HYPERLINK(\"x\")", "+1", "-1", "@sum", "bo\u{1b}[2J"] {
        fs::create_dir_all(dir.join("subs").join(name)).unwrap();
        fs::copy(
            dir.join("subs/ada/studio.ppm"),
            dir.join("subs").join(name).join("studio.ppm"),
        )
        .unwrap();
    }
    succeeded(&run_in(&dir, &["grade", "scenes", "subs", "-o", "report"]));
    let mut csv = csv::Reader::from_path(dir.join("report/grades.csv")).unwrap();
    let students: Vec<String> = csv.records().map(|r| r.unwrap()[0].to_string()).collect();
    for expected in [
        "'=HYPERLINK(\"x\")",
        "'+1",
        "'-1",
        "'@sum",
        "bo\\u{1b}[2J",
        "ada",
    ] {
        assert!(
            students.iter().any(|s| s == expected),
            "{expected} in {students:?}"
        );
    }
    let bytes = fs::read(dir.join("report/grades.csv")).unwrap();
    assert!(!bytes.contains(&0x1b));
    fs::remove_dir_all(&dir).unwrap();
}
