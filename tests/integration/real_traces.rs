//! `trace --against` on the traces a student's program really printed (issue 43):
//! ../shared/student-traces/ holds ten real traces of a correct copy of the course's
//! program (64x48, every course scene, MAX_DIST 70). Every pixel of every one must agree;
//! the same traces with one number edited must give that edit as the first difference,
//! with the right light and object; relabelled in another copy's dialect they must read
//! the same.

use crate::common::{course_scenes, folder, run};
use std::io::Read;
use std::path::{Path, PathBuf};

/// The folder of the real traces, or `None` (with a message) where ../shared is absent;
/// under `CI=true` that fails instead.
fn traces() -> Option<PathBuf> {
    let scenes = course_scenes()?;
    Some(scenes.join("../student-traces"))
}

/// The text of a real trace.
fn real(dir: &Path, scene: &str) -> String {
    let file = std::fs::File::open(dir.join(format!("{scene}.dbg.txt.gz"))).unwrap();
    let mut text = String::new();
    flate2::read::GzDecoder::new(file)
        .read_to_string(&mut text)
        .unwrap();
    text
}

/// `trace --against FILE 64 48 --max-dist 70 --json` of `text` against course scene
/// `scene`: the exit code and the JSON.
fn whole(scene: &str, text: &str, name: &str) -> (i32, serde_json::Value, String) {
    let dir = folder(&format!("real-traces-{name}"));
    let file = dir.join("dbg.txt");
    std::fs::write(&file, text).unwrap();
    let scene_text = std::fs::read(course_scenes().unwrap().join(format!("{scene}.txt"))).unwrap();
    let args = [
        "trace",
        "--against",
        file.to_str().unwrap(),
        "64",
        "48",
        "--max-dist",
        "70",
        "--json",
    ];
    let output = run(&args, &scene_text);
    std::fs::remove_dir_all(&dir).unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    let json = serde_json::from_slice(&output.stdout)
        .unwrap_or_else(|e| panic!("{scene}, {name}: {e}\n{stderr}"));
    (output.status.code().unwrap_or(-1), json, stderr)
}

const SCENES: [&str; 10] = [
    "a02", "a03", "a04", "d01", "d02", "d03", "d04", "d05", "d06", "spec1",
];

#[test]
fn every_pixel_of_every_real_trace_agrees() {
    let Some(dir) = traces() else { return };
    for scene in SCENES {
        let (code, json, err) = whole(scene, &real(&dir, scene), "clean");
        assert_eq!(code, 0, "{scene}: {json:#}\n{err}");
        assert_eq!(json["pixels"], 64 * 48, "{scene}: {json:#}");
        assert_eq!(json["agree"], 64 * 48, "{scene}: {json:#}");
        assert_eq!(json["unread"], 0, "{scene}: {json:#}");
    }
}

/// The lines of pixel (x, y)'s block in the course copy's trace: from its `PIX` line to
/// the next one.
fn block(text: &str, (x, y): (usize, usize)) -> std::ops::Range<usize> {
    let lines: Vec<&str> = text.lines().collect();
    let label = format!("PIX {x:4} {y:4} - ");
    let start = lines.iter().position(|l| *l == label).unwrap();
    let end = (start + 1..lines.len())
        .find(|&k| lines[k].starts_with("PIX "))
        .unwrap_or(lines.len());
    start..end
}

/// `text` with the lines of pixel `pixel`'s block passed through `edit`.
fn edited(text: &str, pixel: (usize, usize), edit: impl Fn(&mut Vec<String>)) -> String {
    let range = block(text, pixel);
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut inside: Vec<String> = lines[range.clone()].to_vec();
    let before = inside.clone();
    edit(&mut inside);
    assert_ne!(inside, before, "the edit changes the block");
    lines.splice(range, inside);
    lines.join("\n") + "\n"
}

/// The index of the first line of `lines` from `from` on that starts with `start`.
fn find(lines: &[String], from: usize, start: &str) -> usize {
    (from..lines.len())
        .find(|&k| lines[k].trim_start().starts_with(start))
        .unwrap_or_else(|| panic!("no line starting {start:?} after {from}"))
}

/// The one group of differing pixels an edit of one pixel makes: every other pixel agrees.
fn only_group(scene: &str, text: &str, name: &str, pixel: (usize, usize)) -> serde_json::Value {
    let (code, json, err) = whole(scene, text, name);
    assert_eq!(code, 1, "{name}: {json:#}\n{err}");
    assert_eq!(json["differ"], 1, "{name}: {json:#}");
    assert_eq!(json["agree"], 64 * 48 - 1, "{name}: {json:#}");
    let group = json["groups"][0].clone();
    assert_eq!(
        group["pixel"],
        serde_json::json!([pixel.0, pixel.1]),
        "{name}: {group:#}"
    );
    group
}

#[test]
fn a_shadow_ray_s_t_made_negative_is_the_first_difference() {
    let Some(dir) = traces() else { return };
    let text = real(&dir, "spec1");
    // Pixel (40, 10): the floor (line 18), in the blue sphere's (line 4) shadow from
    // light 2 (line 46, id 105): its shadow ray's FND 100 hits at 2.23491021488.
    let planted = edited(&text, (40, 10), |lines| {
        let light = find(lines, 0, "light object id was      105");
        let fnd = find(lines, light, "FND  100:");
        assert!(lines[fnd].contains(" 2.23491021488 "), "{}", lines[fnd]);
        lines[fnd] = lines[fnd].replace(" 2.23491021488 ", " -2.23491021488 ");
    });
    let group = only_group("spec1", &planted, "negative-t", (40, 10));
    assert_eq!(
        group["event"], "shadow ray to light 2 (point light, line 46)",
        "{group:#}"
    );
    assert_eq!(group["object"], "sphere (line 4)", "{group:#}");
    assert_eq!(group["quantity"], "hit or miss", "{group:#}");
    let sentence = group["sentence"].as_str().unwrap();
    assert!(
        sentence.contains("yours misses (t = -2.23491"),
        "{sentence}"
    );
    assert!(sentence.contains("blocks the light"), "{sentence}");
}

#[test]
fn a_normal_s_sign_is_the_first_difference() {
    let Some(dir) = traces() else { return };
    let text = real(&dir, "spec1");
    // Pixel (20, 20): the red sphere (line 11), lit by light 1 (line 42, id 104).
    let planted = edited(&text, (20, 20), |lines| {
        let normal = find(lines, 0, "normal at hitpoint");
        let values = find(lines, normal + 1, "0.003264");
        assert_eq!(lines[values].split_whitespace().count(), 3);
        lines[values] = "   -0.003264   0.304968   -0.952357".into();
    });
    let group = only_group("spec1", &planted, "normal", (20, 20));
    assert_eq!(
        group["event"], "camera ray, light 1 (point light, line 42)",
        "{group:#}"
    );
    assert_eq!(group["object"], "sphere (line 11)", "{group:#}");
    assert_eq!(group["quantity"], "normal", "{group:#}");
    assert!(
        group["sentence"]
            .as_str()
            .unwrap()
            .contains("it is flipped"),
        "{group:#}"
    );
}

#[test]
fn a_light_s_distance_squared_is_the_first_difference() {
    let Some(dir) = traces() else { return };
    let text = real(&dir, "spec1");
    let planted = edited(&text, (20, 20), |lines| {
        let distance = find(lines, 0, "distance to light is");
        assert!(
            lines[distance].ends_with(" 6.441930"),
            "{}",
            lines[distance]
        );
        // 6.441930² = 41.497462...
        lines[distance] = "distance to light is     41.497463".into();
    });
    let group = only_group("spec1", &planted, "distance", (20, 20));
    assert_eq!(
        group["event"], "camera ray, light 1 (point light, line 42)",
        "{group:#}"
    );
    assert_eq!(group["object"], "sphere (line 11)", "{group:#}");
    assert_eq!(group["quantity"], "distance to the light", "{group:#}");
    assert_eq!(group["outcome"], "bytes", "{group:#}");
}

#[test]
fn a_deleted_fnd_line_is_the_first_difference() {
    let Some(dir) = traces() else { return };
    let text = real(&dir, "spec1");
    // The camera ray's FND of the red sphere (id 101), which it hits first, with its
    // base, dir and hits lines.
    let planted = edited(&text, (20, 20), |lines| {
        let fnd = find(lines, 0, "FND  101:");
        assert!(lines[fnd + 1].starts_with("dir X:") && lines[fnd + 2].starts_with("hits:"));
        lines.drain(fnd..fnd + 3);
    });
    let group = only_group("spec1", &planted, "deleted", (20, 20));
    assert_eq!(group["event"], "camera ray", "{group:#}");
    assert_eq!(group["object"], "sphere (line 11)", "{group:#}");
    assert_eq!(group["outcome"], "closest object", "{group:#}");
    assert!(
        group["sentence"]
            .as_str()
            .unwrap()
            .contains("does not test sphere (line 11)"),
        "{group:#}"
    );
}

/// The real trace with every `PIX x y` label rewritten by `label`.
fn relabelled(text: &str, label: impl Fn(usize, usize) -> String) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        match line.strip_prefix("PIX ") {
            Some(rest) => {
                let mut numbers = rest.split_whitespace().map(|n| n.parse::<usize>().unwrap());
                let (x, y) = (numbers.next().unwrap(), numbers.next().unwrap());
                out.push_str(&label(x, y));
            }
            None => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

/// The real trace with every id moved by `by` (FND, HIT and the diffuse block's ids).
fn renumbered(text: &str, by: i64) -> String {
    let mut out = String::with_capacity(text.len());
    let shift = |id: &str| (id.parse::<i64>().unwrap() + by).to_string();
    for line in text.lines() {
        let tag = ["FND ", "HIT "].into_iter().find(|t| line.starts_with(t));
        let label = [
            "hit object id was",
            "light object id was",
            "hit object occluded by",
        ]
        .into_iter()
        .find(|l| line.starts_with(l));
        if let Some(tag) = tag {
            let (id, rest) = line[4..].trim_start().split_once(':').unwrap();
            out.push_str(&format!("{tag}{:>4}:{rest}", shift(id)));
        } else if let Some(label) = label {
            let id = line[label.len()..].trim();
            out.push_str(&format!("{label} {}", shift(id)));
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}

#[test]
fn other_copies_labels_and_ids_read_the_same() {
    let Some(dir) = traces() else { return };
    let text = real(&dir, "d05");
    let dialects = [
        (
            "the image's size on every block",
            relabelled(&text, |_, _| "PIX   64   48 - ".into()),
        ),
        (
            "Pix: ROW = x COL = y",
            relabelled(&text, |x, y| format!("Pix: ROW = {x} COL = {y} - ")),
        ),
        ("ids from 1", renumbered(&text, -99)),
        ("ids from 0", renumbered(&text, -100)),
    ];
    for (name, text) in dialects {
        let (code, json, err) = whole("d05", &text, "dialect");
        assert_eq!(code, 0, "{name}: {json:#}\n{err}");
        assert_eq!(json["agree"], 64 * 48, "{name}: {json:#}");
        let notes = json["notes"].to_string();
        match name {
            "the image's size on every block" => {
                assert!(notes.contains("their world points"), "{notes}")
            }
            "Pix: ROW = x COL = y" => assert!(notes.contains("ROW"), "{notes}"),
            "ids from 1" => assert!(notes.contains("ids from 1,"), "{notes}"),
            _ => assert!(!notes.contains("ids from"), "{notes}"),
        }
    }
}

#[test]
fn labels_one_row_off_are_found_as_the_row() {
    let Some(dir) = traces() else { return };
    let text = real(&dir, "d02");
    // Each block labelled with the row above the one its world point is on, as a
    // program that writes `rows - y` for `rows - 1 - y` does.
    let shifted = relabelled(&text, |x, y| format!("PIX {x:4} {:4} - ", y + 1));
    let (code, json, err) = whole("d02", &shifted, "shifted");
    assert_eq!(code, 1, "{json:#}\n{err}");
    // The top row's blocks are labelled 48, outside the image.
    assert_eq!(json["unread"], 64, "{json:#}");
    assert_eq!(json["differ"], 64 * 47, "{json:#}");
    let groups = json["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 1, "{json:#}");
    assert_eq!(groups[0]["quantity"], "world point", "{json:#}");
    let sentence = groups[0]["sentence"].as_str().unwrap();
    assert!(sentence.contains("row index is one"), "{sentence}");
}
