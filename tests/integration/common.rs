//! Helpers shared by the integration tests.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};

/// Starts the `legacy-rt` binary with `args`, writes `stdin` to it and closes it, with
/// standard output and standard error as given.
pub fn start(args: &[&str], stdin: &[u8], stdout: Stdio, stderr: Stdio) -> Child {
    let mut child = Command::new(env!("CARGO_BIN_EXE_legacy-rt"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(stdout)
        .stderr(stderr)
        .spawn()
        .expect("the binary starts");
    let mut input = child.stdin.take().unwrap();
    // The program may stop reading early (e.g. on --help); a broken pipe is fine then.
    let _ = input.write_all(stdin);
    drop(input);
    child
}

/// Runs the `legacy-rt` binary with `args`, feeding `stdin`.
pub fn run(args: &[&str], stdin: &[u8]) -> Output {
    let child = start(args, stdin, Stdio::piped(), Stdio::piped());
    child.wait_with_output().expect("the binary runs")
}

/// A fresh, empty folder for one test, removed when the test passes (a failing test's is
/// kept, to look at): a run of the tests left some 200 MB of images behind before.
pub fn folder(name: &str) -> Folder {
    let dir = std::env::temp_dir().join(format!("legacy-rt-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Folder(dir)
}

/// A test's folder ([`folder`]): a path, removed on drop unless the test is failing.
pub struct Folder(PathBuf);

impl std::ops::Deref for Folder {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Folder {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// The `.txt` files of a folder, sorted by name.
pub fn scene_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "txt"))
        .collect();
    files.sort();
    files
}

/// Runs `check` on each `.txt` file of `dir` (by name), with insta's settings naming
/// its snapshots after the file, as `insta::glob!` names them (`NAME@file.txt.snap`, the
/// file in the header): folder-driven snapshots without the glob and regex crates that
/// `glob!` compiles in (a sixth of a newcomer's first `cargo test`).
pub fn each_file(dir: &Path, check: impl Fn(&Path)) {
    for path in scene_files(dir) {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let relative = path
            .strip_prefix(env!("CARGO_MANIFEST_DIR"))
            .unwrap_or(&path)
            .to_path_buf();
        let mut settings = insta::Settings::clone_current();
        settings.set_snapshot_suffix(name);
        settings.set_input_file(relative);
        settings.bind(|| check(&path));
    }
}

/// The course's scene folder beside the repository, or `None` (with a message) if absent.
/// Under `CI=true` an absent folder fails the test instead: CI always has it, so a skip
/// there would hide a broken checkout.
pub fn course_scenes() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/course-scenes");
    if dir.is_dir() {
        return Some(dir);
    }
    let ci = std::env::var("CI").is_ok_and(|value| value == "true");
    assert!(!ci, "{} is absent, and CI must have it", dir.display());
    eprintln!("skipped: {} is absent", dir.display());
    None
}

/// The snapshots' settings: short names (no module prefix) and no expression in the
/// header, so that a snapshot file is named after what it shows.
pub fn snapshots() -> insta::Settings {
    let mut settings = insta::Settings::clone_current();
    settings.set_prepend_module_to_snapshot(false);
    settings.set_omit_expression(true);
    settings
}

/// A reviewable picture of a scene for a snapshot: a 32x24 render as text P3, and the
/// FNV-1a hash of the PPM at the default size, which locks the full image down.
pub fn image_document(scene: &legacy_rt::Scene) -> String {
    use legacy_rt::render::{Options, render};
    let options = |(width, height): (u64, u64)| Options::new(width as usize, height as usize);
    let small = render(scene, &options((32, 24)), |_| {});
    let mut text = String::from("P3\n32 24\n255\n");
    for row in small.pixels.chunks(small.width) {
        let row: Vec<String> = row
            .iter()
            .map(|p| format!("{:3} {:3} {:3}", p[0], p[1], p[2]))
            .collect();
        text.push_str(&row.join("  "));
        text.push('\n');
    }
    let size = scene.default_size();
    let full = render(scene, &options(size), |_| {});
    let ppm = legacy_rt::image_output::ppm(&full);
    let hash = ppm.iter().fold(0xcbf29ce484222325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100000001b3)
    });
    text.push_str(&format!("{}x{} PPM fnv1a {hash:016x}\n", size.0, size.1));
    text
}
