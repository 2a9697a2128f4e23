//! The failures a hostile audit found (issue 12), each as the user met it: the binary,
//! run the way that broke it, must now render or fail cleanly with the right status, and
//! must never destroy what `-o` names.

use super::common::{folder, run, start};
use std::io::{Read, Write};
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

const SCENE: &str = "8 6\n0 0 3\n10\n9 9 9\n0 4 2\n13\n1 1 1\n2 2 2\n0 0 0\n0 0 -4\n1.5\n";

fn render_to(path: &Path) -> Output {
    run(
        &["16", "12", "-o", path.to_str().unwrap()],
        SCENE.as_bytes(),
    )
}

/// The PPM the scene gives at 16x12 on standard output.
fn expected_ppm() -> Vec<u8> {
    let output = run(&["16", "12"], SCENE.as_bytes());
    assert!(output.status.success());
    output.stdout
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Waits for `child` at most `limit`, killing it if it is still running then.
fn wait_at_most(mut child: Child, limit: Duration) -> Option<Output> {
    let start = Instant::now();
    while start.elapsed() < limit {
        if child.try_wait().unwrap().is_some() {
            return Some(child.wait_with_output().unwrap());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(status.success());
}

#[cfg(unix)]
fn mode(path: &Path) -> u32 {
    use std::os::unix::fs::PermissionsExt;
    std::fs::metadata(path).unwrap().permissions().mode() & 0o7777
}

#[test]
fn output_to_a_device_writes_into_it_and_leaves_it_a_device() {
    use std::os::unix::fs::FileTypeExt;
    let output = render_to(Path::new("/dev/null"));
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );
    // A full device is an error, not a replaced file.
    let output = render_to(Path::new("/dev/full"));
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("/dev/full"), "{}", stderr(&output));
    assert!(
        std::fs::metadata("/dev/full")
            .unwrap()
            .file_type()
            .is_char_device()
    );
}

#[test]
fn output_to_a_fifo_writes_into_the_pipe() {
    use std::os::unix::fs::FileTypeExt;
    let dir = folder("fifo-out");
    let fifo = dir.join("image.ppm");
    mkfifo(&fifo);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let output = render_to(&fifo);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(reader.join().unwrap(), expected_ppm());
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo()
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn output_through_a_symbolic_link_replaces_the_target_and_keeps_the_link() {
    let dir = folder("symlink-out");
    let target = dir.join("target.ppm");
    let link = dir.join("latest.ppm");
    std::fs::write(&target, "old").unwrap();
    std::os::unix::fs::symlink("target.ppm", &link).unwrap();
    let output = render_to(&link);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    assert_eq!(std::fs::read(&target).unwrap(), expected_ppm());
    // Nothing else was left in the folder.
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn output_to_a_hard_linked_file_keeps_the_link() {
    let dir = folder("hardlink-out");
    let (first, second) = (dir.join("a.ppm"), dir.join("b.ppm"));
    std::fs::write(&first, "old").unwrap();
    std::fs::hard_link(&first, &second).unwrap();
    let output = render_to(&first);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(std::fs::read(&second).unwrap(), expected_ppm());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn output_never_replaces_a_read_only_file_and_keeps_a_file_s_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = folder("modes-out");
    let read_only = dir.join("graded.ppm");
    std::fs::write(&read_only, "keep me").unwrap();
    std::fs::set_permissions(&read_only, std::fs::Permissions::from_mode(0o444)).unwrap();
    let output = render_to(&read_only);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("read-only"), "{}", stderr(&output));
    assert_eq!(std::fs::read(&read_only).unwrap(), b"keep me");
    assert_eq!(mode(&read_only), 0o444);

    let private = dir.join("private.ppm");
    std::fs::write(&private, "old").unwrap();
    std::fs::set_permissions(&private, std::fs::Permissions::from_mode(0o600)).unwrap();
    let output = render_to(&private);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(std::fs::read(&private).unwrap(), expected_ppm());
    assert_eq!(mode(&private), 0o600);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_unknown_extension_or_a_folder_is_refused_before_anything_is_written() {
    let dir = folder("names-out");
    let jpg = dir.join("image.jpg");
    let output = render_to(&jpg);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains(".png"), "{}", stderr(&output));
    assert!(!jpg.exists());
    let output = render_to(&dir);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("folder"), "{}", stderr(&output));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    // The names that do choose a format.
    for name in ["a.ppm", "b.PNM", "c", "d.PNG"] {
        let output = render_to(&dir.join(name));
        assert!(output.status.success(), "{name}: {}", stderr(&output));
    }
    assert!(
        std::fs::read(dir.join("d.PNG"))
            .unwrap()
            .starts_with(b"\x89PNG")
    );
    assert_eq!(std::fs::read(dir.join("c")).unwrap(), expected_ppm());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_interrupt_while_writing_leaves_no_temporary_file() {
    // The image is large enough that writing and syncing it takes a while; the test
    // watches the folder for the temporary file and interrupts the program while it
    // exists. It retries where the write was too quick to catch, and fails if it never
    // caught one: a pass must mean that an interrupt was really tested.
    let dir = folder("interrupt-out");
    let target = dir.join("big.ppm");
    let mut caught = 0;
    for _ in 0..20 {
        let args = [
            "6000",
            "4000",
            "--max-dist",
            "1",
            "-o",
            target.to_str().unwrap(),
        ];
        let mut child = start(&args, SCENE.as_bytes(), Stdio::null(), Stdio::null());
        let partial = loop {
            if let Some(status) = child.try_wait().unwrap() {
                assert!(status.success());
                break None;
            }
            let found = std::fs::read_dir(&dir)
                .unwrap()
                .map(|entry| entry.unwrap().path())
                .find(|path| path.to_string_lossy().ends_with(".partial"));
            if found.is_some() {
                break found;
            }
        };
        let Some(partial) = partial else {
            let _ = std::fs::remove_file(&target);
            continue;
        };
        // SAFETY: kill(2) on our own child's pid, with a valid signal number.
        let sent = unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGTERM) };
        assert_eq!(sent, 0);
        let status = child.wait().unwrap();
        caught += 1;
        assert!(!partial.exists(), "{} was left behind", partial.display());
        // Either the rename happened before the signal (a whole image) or no image.
        if status.success() {
            assert_eq!(
                std::fs::metadata(&target).unwrap().len(),
                13 + 6000 * 4000 * 3
            );
        } else {
            assert_eq!(status.code(), Some(128 + 15));
            assert!(!target.exists());
        }
        let _ = std::fs::remove_file(&target);
        if caught == 2 {
            break;
        }
    }
    assert!(caught > 0, "never saw the temporary file to interrupt");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn threads_are_bounded_with_a_message_that_names_the_limit() {
    let output = run(&["--threads", "100000", "16", "12"], SCENE.as_bytes());
    assert_eq!(output.status.code(), Some(2));
    assert!(output.stdout.is_empty());
    assert!(
        stderr(&output).contains("at most 256 threads"),
        "{}",
        stderr(&output)
    );
    let output = run(&["--threads", "256", "16", "12"], SCENE.as_bytes());
    assert!(output.status.success());
}

#[test]
fn a_closed_standard_error_is_no_panic() {
    // `printf '8 -6\n0 0 3\n' | legacy-rt 2>&1 >/dev/null | true`: the error message
    // meets a pipe whose reader has gone.
    let mut child = Command::new(env!("CARGO_BIN_EXE_legacy-rt"))
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"8 -6\n0 0 3\n")
        .unwrap();
    assert_eq!(child.wait().unwrap().code(), Some(1));
}

#[test]
fn a_fifo_named_as_a_texture_is_an_error_not_a_hang() {
    let dir = folder("fifo-texture");
    let fifo = dir.join("texture.ppm");
    mkfifo(&fifo);
    let scene = format!(
        "8 6\n0 0 3\n17\n1 1 1\n1 1 1\n0 0 0\n0 0 1\n-1 -1 -5\n1 0 0\n2 2\n{}\n1\n",
        fifo.display()
    );
    let child = start(
        &["16", "12"],
        scene.as_bytes(),
        Stdio::piped(),
        Stdio::piped(),
    );
    let output = wait_at_most(child, Duration::from_secs(30)).expect("the load finishes");
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("not a regular file"),
        "{}",
        stderr(&output)
    );
    assert!(output.stdout.is_empty());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_ten_million_digit_number_gives_a_short_error() {
    let mut scene = String::from("8 6\n0 0 3\n13\n1 1 1\n1 1 1\n0 0 0\n0 0 -4\n");
    scene.push_str(&"9".repeat(10_000_000));
    scene.push('\n');
    let output = run(&["16", "12"], scene.as_bytes());
    assert_eq!(output.status.code(), Some(1));
    assert!(output.stderr.len() < 2_000, "{} bytes", output.stderr.len());
    assert!(
        stderr(&output).contains("not a finite number"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_default_size_the_window_cannot_give_is_the_scene_s_error() {
    // 640 wide at a window of 8 x 0.001 is 0 pixels high: the scene is the cause.
    let scene = "8 0.001\n0 0 3\n";
    let output = run(&[], scene.as_bytes());
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("world window"),
        "{}",
        stderr(&output)
    );
    assert!(stderr(&output).contains("W and H"), "{}", stderr(&output));
    // Typed by the user, the same size is the command line's error.
    let output = run(&["640", "0"], scene.as_bytes());
    assert_eq!(output.status.code(), Some(2));
    // And with a size given, the scene renders.
    assert!(run(&["640", "4"], scene.as_bytes()).status.success());
}

#[test]
fn a_scene_over_the_input_limit_is_a_scene_error_naming_the_limit() {
    let mut scene = b"8 6\n0 0 3\n".to_vec();
    scene.resize((256 << 20) + 1, b' ');
    let output = run(&["16", "12"], &scene);
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("256 MiB"), "{}", stderr(&output));
}

#[test]
fn a_scene_file_on_standard_input_reads_as_the_piped_scene() {
    // `legacy-rt < file` reads a regular file, whose size sizes the read; piped, the
    // same bytes. The image is the same from the file, from a hard link to it and from
    // the pipe; a sparse file past the limit is refused as the piped one is.
    let dir = folder("stdin-file");
    let scene =
        std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/spheres.txt")).unwrap();
    let file = dir.join("scene.txt");
    std::fs::write(&file, &scene).unwrap();
    let link = dir.join("link.txt");
    std::fs::hard_link(&file, &link).unwrap();
    let from_file = |path: &Path| {
        Command::new(env!("CARGO_BIN_EXE_legacy-rt"))
            .args(["40", "30"])
            .stdin(std::fs::File::open(path).unwrap())
            .output()
            .unwrap()
    };
    let piped = run(&["40", "30"], &scene);
    assert!(piped.status.success());
    for path in [&file, &link] {
        let output = from_file(path);
        assert!(output.status.success(), "{}", stderr(&output));
        assert_eq!(output.stdout, piped.stdout);
    }
    let huge = dir.join("huge.txt");
    let handle = std::fs::File::create(&huge).unwrap();
    handle.set_len((256 << 20) + 1).unwrap();
    let output = from_file(&huge);
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("256 MiB"), "{}", stderr(&output));
    assert!(output.stdout.is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_scene_named_as_an_argument_says_how_to_run_it() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/spheres.txt");
    for name in [scene, "scene.txt"] {
        let output = run(&[name], b"");
        assert_eq!(output.status.code(), Some(2));
        let expected = format!("legacy-rt < {name} > image.ppm");
        assert!(stderr(&output).contains(&expected), "{}", stderr(&output));
    }
}

#[test]
fn a_terminal_on_standard_input_gets_a_hint_instead_of_silence() {
    // `script` gives the program a terminal; Ctrl-D after the hint ends the input.
    let dir = folder("terminal-in");
    let command = format!(
        "{} -o {}",
        env!("CARGO_BIN_EXE_legacy-rt"),
        dir.join("x.png").display()
    );
    let mut child = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("script (util-linux) runs");
    let mut out = child.stdout.take().unwrap();
    let mut seen = Vec::new();
    let mut buffer = [0u8; 256];
    while !String::from_utf8_lossy(&seen).contains("Ctrl-D") {
        let n = out.read(&mut buffer).unwrap();
        assert!(
            n > 0,
            "no hint before the end: {}",
            String::from_utf8_lossy(&seen)
        );
        seen.extend_from_slice(&buffer[..n]);
    }
    child.stdin.take().unwrap().write_all(b"\x04").unwrap();
    out.read_to_end(&mut seen).unwrap();
    let output = wait_at_most(child, Duration::from_secs(30)).expect("the input ends");
    assert_eq!(
        output.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&seen)
    );
    std::fs::remove_dir_all(dir).unwrap();
}
