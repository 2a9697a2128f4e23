//! The command line: sizes, output formats, options, errors, and standard output holding
//! the image and nothing else.

use super::common::run;
use legacy_rt::render::{DEFAULT_MAX_DIST, Options, render};

const DEBUG: &str = "8 6\n0 0 3\n14\n5 5 0\n0 0 0\n0 0 0\n0 0 -1\n0 0 -5\n";
const MIRROR: &str = "8 6\n0 0 3\n14\n0.5 0.5 0.5\n0 0 0\n0.25 0.5 1\n0 1 0\n0 -3 0\n\
                      14\n6 3 0\n0 0 0\n0 0 0\n0 0 1\n0 0 -9\n";

fn ppm_of(text: &str, width: usize, height: usize, max_dist: f64) -> Vec<u8> {
    let scene = legacy_rt::load(text).unwrap();
    let options = Options {
        max_dist,
        ..Options::new(width, height)
    };
    legacy_rt::image_output::ppm(&render(&scene, &options, |_| {}))
}

#[test]
fn no_arguments_renders_640_wide_with_the_window_aspect() {
    let output = run(&[], DEBUG.as_bytes());
    assert!(output.status.success());
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(output.stdout.starts_with(b"P6 640 480 255\n"));
    assert_eq!(output.stdout, ppm_of(DEBUG, 640, 480, DEFAULT_MAX_DIST));
}

#[test]
fn width_and_height_as_the_legacy_program_took_them() {
    let output = run(&["5", "3"], DEBUG.as_bytes());
    assert!(output.status.success());
    let expected = [
        81u8, 101, 112, 101, 81, 95, 132, 159, 132, 95, 81, 101, 112, 101, 81,
    ];
    let pixels: Vec<u8> = expected.iter().flat_map(|&v| [v, v, 0]).collect();
    assert_eq!(
        output.stdout,
        [b"P6 5 3 255\n".as_slice(), &pixels].concat()
    );
    // Width alone: the height follows the window (8 x 6 at 100 wide: 75).
    let output = run(&["100"], DEBUG.as_bytes());
    assert!(output.stdout.starts_with(b"P6 100 75 255\n"));
}

#[test]
fn png_output_decodes_to_the_same_pixels_as_the_ppm() {
    let dir = std::env::temp_dir().join(format!("legacy-rt-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (png, ppm) = (dir.join("image.png"), dir.join("image.ppm"));
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/tiled_planes.txt"),
    )
    .unwrap();
    for path in [&png, &ppm] {
        let output = run(&["64", "48", "-o", path.to_str().unwrap()], text.as_bytes());
        assert!(output.status.success());
        assert!(output.stdout.is_empty());
    }
    let ppm_bytes = std::fs::read(&ppm).unwrap();
    assert_eq!(ppm_bytes, ppm_of(&text, 64, 48, DEFAULT_MAX_DIST));
    let decoded = image::open(&png).unwrap().into_rgb8();
    assert_eq!(decoded.dimensions(), (64, 48));
    assert_eq!(
        decoded.as_raw().as_slice(),
        &ppm_bytes["P6 64 48 255\n".len()..]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn max_dist_cuts_off_the_reflection() {
    // The first leg to the mirror floor is 2 √11.25 ≈ 6.7 for the central rays: with
    // MAX_DIST 5 no reflected ray is traced there, with the default it is.
    let short = run(&["--max-dist", "5", "9", "9"], MIRROR.as_bytes());
    assert_eq!(short.stdout, ppm_of(MIRROR, 9, 9, 5.0));
    let long = run(&["9", "9"], MIRROR.as_bytes());
    assert_ne!(short.stdout, long.stdout);
}

#[test]
fn bad_sizes_and_options_are_errors_with_nothing_on_stdout() {
    for args in [
        &["1", "5"][..],
        &["5", "0"][..],
        &["100000", "100000"][..],
        &["--max-dist", "-1"][..],
        &["--max-dist", "nan"][..],
        &["wide"][..],
    ] {
        let output = run(args, DEBUG.as_bytes());
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        assert!(output.stdout.is_empty(), "{args:?}");
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    }
}

#[test]
fn help_teaches_the_usage_with_examples() {
    let output = run(&["--help"], b"");
    let help = String::from_utf8(output.stdout).unwrap();
    for needle in [
        "legacy-rt < scene.txt > image.ppm",
        "--max-dist",
        "--output",
        "--dump",
        "[W]",
    ] {
        assert!(help.contains(needle), "{needle} missing from:\n{help}");
    }
}

#[test]
fn a_closed_pipe_ends_quietly() {
    use std::io::Read;
    use std::process::Stdio;
    let args = ["1200", "900"];
    let mut child = super::common::start(&args, DEBUG.as_bytes(), Stdio::piped(), Stdio::piped());
    let mut first = [0u8; 2];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    // stdout is dropped here: the rest of the image meets a closed pipe.
    assert_eq!(&first, b"P6");
    let output = child.wait_with_output().unwrap();
    assert!(output.status.success());
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn threads_option_gives_the_same_bytes_and_zero_means_every_core() {
    let scene = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/quadrics_gallery.txt"
    ))
    .unwrap();
    let one = run(&["--threads", "1", "160", "120"], &scene);
    assert!(one.status.success());
    assert_eq!(one.stdout.len(), "P6\n160 120\n255\n".len() + 160 * 120 * 3);
    for threads in ["4", "0"] {
        let many = run(&["--threads", threads, "160", "120"], &scene);
        assert!(many.status.success());
        assert!(many.stdout == one.stdout, "--threads {threads}");
    }
}
