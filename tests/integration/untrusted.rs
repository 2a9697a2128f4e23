//! Files a grader did not write (issue 23): a student's upload can be damaged, huge by
//! its header, not a file at all, or a second name of the file being graded, and its
//! name can hold anything. `compare` must refuse each with exit 2 and a message, never
//! crash, hang, exhaust the machine or overwrite a submission.

use super::common::{folder, run, start};
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A one-sphere scene, as a file.
fn scene_file(dir: &Path) -> String {
    let path = dir.join("scene.txt");
    std::fs::write(&path, "8 6\n0 0 3\n13\n1 1 1\n0 0 0\n0 0 0\n0 0 -3\n1\n").unwrap();
    path.to_str().unwrap().to_string()
}

/// CRC-32 of PNG chunks (ISO 3309), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A PNG chunk: length, type, data, CRC of type and data.
fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut out = (data.len() as u32).to_be_bytes().to_vec();
    out.extend_from_slice(kind);
    out.extend_from_slice(data);
    out.extend_from_slice(&crc32(&[&kind[..], data].concat()).to_be_bytes());
    out
}

/// A PNG of `width` x `height` with colour type `colour` and bit depth `depth`, the
/// chunks `extra` before the image data, and `data` (uncompressed scanlines, each with
/// its filter byte) in zlib's stored blocks.
fn png(width: u32, height: u32, depth: u8, colour: u8, extra: &[u8], data: &[u8]) -> Vec<u8> {
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[depth, colour, 0, 0, 0]);
    let mut zlib = vec![0x78, 0x01];
    let blocks: Vec<&[u8]> = data.chunks(65535).collect();
    for (k, block) in blocks.iter().enumerate() {
        let len = block.len() as u16;
        zlib.push(u8::from(k + 1 == blocks.len()));
        zlib.extend_from_slice(&len.to_le_bytes());
        zlib.extend_from_slice(&(!len).to_le_bytes());
        zlib.extend_from_slice(block);
    }
    let (mut a, mut b) = (1u32, 0u32);
    for &byte in data {
        a = (a + u32::from(byte)) % 65521;
        b = (b + a) % 65521;
    }
    zlib.extend_from_slice(&((b << 16) | a).to_be_bytes());
    let mut file = b"\x89PNG\r\n\x1a\n".to_vec();
    file.extend(chunk(b"IHDR", &ihdr));
    file.extend_from_slice(extra);
    file.extend(chunk(b"IDAT", &zlib));
    file.extend(chunk(b"IEND", b""));
    file
}

/// An all-black 8-bit RGB PNG of `side` x `side`, compressed as zlib would: each row is a
/// filter byte 0 and 3 `side` zero bytes, written as one literal 0 and then copies of
/// 258 bytes from 1 back, in a single block of deflate's fixed Huffman codes (literal 0:
/// 8 bits, length 258: 8 bits, distance 1: 5 bits). 13000² comes to 3.2 MB.
fn black_png(side: u32) -> Vec<u8> {
    struct Bits {
        out: Vec<u8>,
        acc: u64,
        count: u32,
    }
    impl Bits {
        fn put(&mut self, value: u64, count: u32) {
            self.acc |= value << self.count;
            self.count += count;
            while self.count >= 8 {
                self.out.push(self.acc as u8);
                self.acc >>= 8;
                self.count -= 8;
            }
        }
        /// A Huffman code, most significant bit first.
        fn code(&mut self, code: u64, count: u32) {
            let reversed = (0..count).fold(0, |r, i| r | ((code >> i) & 1) << (count - 1 - i));
            self.put(reversed, count);
        }
    }
    let total = u64::from(side) * (3 * u64::from(side) + 1);
    let mut bits = Bits {
        out: vec![0x78, 0x01],
        acc: 0,
        count: 0,
    };
    bits.put(1, 1); // the last block
    bits.put(1, 2); // fixed Huffman codes
    bits.code(0b0011_0000, 8); // literal 0
    let mut left = total - 1;
    while left >= 258 {
        bits.code(0b1100_0101, 8); // length 258 (code 285)
        bits.code(0, 5); // distance 1 (code 0)
        left -= 258;
    }
    for _ in 0..left {
        bits.code(0b0011_0000, 8);
    }
    bits.code(0, 7); // end of block (code 256)
    bits.put(0, 7); // to a byte boundary
    let mut zlib = bits.out;
    // Adler-32 of `total` zero bytes: a = 1, b = total.
    let b = (total % 65521) as u32;
    zlib.extend_from_slice(&((b << 16) | 1).to_be_bytes());
    let mut ihdr = side.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&side.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    let mut file = b"\x89PNG\r\n\x1a\n".to_vec();
    file.extend(chunk(b"IHDR", &ihdr));
    file.extend(chunk(b"IDAT", &zlib));
    file.extend(chunk(b"IEND", b""));
    file
}

fn stderr(output: &std::process::Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn the_png_generator_makes_images_the_reader_decodes() {
    // The helpers above are checked against the library's reader on small sizes.
    let black = legacy_rt::compare::read_image(&black_png(37)).unwrap();
    assert_eq!((black.width, black.height), (37, 37));
    assert!(black.pixels.iter().all(|&p| p == [0, 0, 0]));
    let rows = [0u8, 1, 2, 3, 0, 4, 5, 6];
    let small = legacy_rt::compare::read_image(&png(1, 2, 8, 2, b"", &rows)).unwrap();
    assert_eq!(small.pixels, vec![[1, 2, 3], [4, 5, 6]]);
}

#[test]
fn a_palette_of_4_bytes_is_a_damaged_image_not_a_crash() {
    // 86 bytes (83 with zlib's own compression): a 1x1 palette image whose PLTE chunk
    // holds 4 bytes (not 3 per colour), which made the png crate panic while expanding
    // the palette.
    let dir = folder("palette");
    let bad = png(1, 1, 8, 3, &chunk(b"PLTE", &[10, 20, 30, 40]), &[0, 1]);
    let path = dir.join("palette.png");
    std::fs::write(&path, &bad).unwrap();
    let output = run(&["compare", &scene_file(&dir), path.to_str().unwrap()], b"");
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    let message = stderr(&output);
    assert!(message.contains("the image is damaged"), "{message}");
    assert!(!message.contains("panicked"), "{message}");
    // A palette of 3 bytes per colour decodes.
    let good = png(1, 1, 8, 3, &chunk(b"PLTE", &[10, 20, 30]), &[0, 0]);
    let image = legacy_rt::compare::read_image(&good).unwrap();
    assert_eq!(image.pixels, vec![[10, 20, 30]]);
}

/// Runs `compare` with `args` and waits at most `limit`: `None` if it had not ended.
fn compare_within(args: &[&str], limit: Duration) -> Option<std::process::Output> {
    let mut all = vec!["compare"];
    all.extend_from_slice(args);
    let mut child = start(&all, b"", Stdio::piped(), Stdio::piped());
    let began = Instant::now();
    while began.elapsed() < limit {
        if child.try_wait().unwrap().is_some() {
            return Some(child.wait_with_output().unwrap());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

#[test]
fn a_fifo_as_the_student_or_the_reference_is_refused_at_once() {
    let dir = folder("fifo");
    let fifo = dir.join("image.ppm");
    let status = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(status.success());
    let (fifo, scene) = (fifo.to_str().unwrap(), scene_file(&dir));
    for args in [[scene.as_str(), fifo], [fifo, scene.as_str()]] {
        let output = compare_within(&args, Duration::from_secs(10))
            .unwrap_or_else(|| panic!("compare {args:?} hangs on a FIFO"));
        assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
        assert!(
            stderr(&output).contains("not a regular file"),
            "{}",
            stderr(&output)
        );
    }
}

#[test]
fn a_huge_image_by_its_header_is_refused_before_it_is_decoded() {
    // A valid all-black 13000x13000 PNG of 3.2 MB: decoded, it is 507 MB, and the
    // reference rendered at its size 3.8 GB. Under a 1 GB address-space limit it must
    // be refused from its header.
    let dir = folder("huge");
    let huge = dir.join("huge.png");
    std::fs::write(&huge, black_png(13000)).unwrap();
    let scene = scene_file(&dir);
    let binary = env!("CARGO_BIN_EXE_legacy-rt");
    let script = format!(
        "ulimit -v 1000000; exec '{binary}' compare --threads 1 '{scene}' '{}'",
        huge.display()
    );
    let output = Command::new("sh").args(["-c", &script]).output().unwrap();
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    let message = stderr(&output);
    assert!(
        message.contains("a 13000x13000 image, more than the 16777216 pixels allowed")
            && message.contains("--max-pixels"),
        "{message}"
    );
    // A 16-bit image is refused from its header too, before its pixels are decoded:
    // here it has none at all.
    let wide = dir.join("wide.png");
    std::fs::write(&wide, png(4096, 4096, 16, 2, b"", &[])).unwrap();
    let output = run(&["compare", &scene, wide.to_str().unwrap()], b"");
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output).contains("a 16-bit image"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_diff_named_as_a_hard_link_to_the_student_s_image_is_refused() {
    let dir = folder("hard-link");
    let scene = scene_file(&dir);
    let student = dir.join("student.ppm");
    let output = run(
        &["4", "3", "-o", student.to_str().unwrap()],
        &std::fs::read(&scene).unwrap(),
    );
    assert!(output.status.success());
    let before = std::fs::read(&student).unwrap();
    let hard = dir.join("hard.ppm");
    std::fs::hard_link(&student, &hard).unwrap();
    for diff in [&hard, &student] {
        let output = run(
            &[
                "compare",
                "--diff",
                diff.to_str().unwrap(),
                &scene,
                student.to_str().unwrap(),
            ],
            b"",
        );
        assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
        assert!(stderr(&output).contains("names a file being compared"));
        assert_eq!(
            std::fs::read(&student).unwrap(),
            before,
            "the submission changed"
        );
    }
}

#[test]
fn a_file_name_cannot_write_lines_of_its_own_into_the_report() {
    let dir = folder("names");
    let plain = scene_file(&dir);
    let scene = dir.join("scene\nverdict: match.txt");
    std::fs::rename(&plain, &scene).unwrap();
    let scene = scene.to_str().unwrap().to_string();
    let name = dir.join("x\nverdict: match\u{1b}[31m.ppm");
    let output = run(
        &["4", "3", "-o", name.to_str().unwrap()],
        &std::fs::read(&scene).unwrap(),
    );
    assert!(output.status.success());
    // A student image that differs: the verdict is "differ", and no line may say "match".
    let mut bytes = std::fs::read(&name).unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 0x40;
    std::fs::write(&name, &bytes).unwrap();
    let output = run(&["compare", &scene, name.to_str().unwrap()], b"");
    assert_eq!(output.status.code(), Some(1));
    let report = String::from_utf8(output.stdout).unwrap();
    assert!(!report.contains('\u{1b}'), "{report}");
    assert!(
        report.contains("x\\u{a}verdict: match\\u{1b}[31m.ppm"),
        "{report}"
    );
    let verdicts: Vec<&str> = report
        .lines()
        .filter(|l| l.starts_with("verdict"))
        .collect();
    assert_eq!(verdicts, ["verdict: differ"], "{report}");
    // The trace commands quote the scene's name so that a shell reads it back.
    assert!(report.contains("< $'"), "{report}");
    assert!(
        report.contains("\\U0000000averdict: match.txt'"),
        "{report}"
    );
}

#[test]
fn a_discarded_standard_output_keeps_the_exit_status() {
    let dir = folder("discarded-stdout");
    let scene = scene_file(&dir);
    let text = std::fs::read(&scene).unwrap();
    let student = dir.join("student.ppm");
    assert!(
        run(&["4", "3", "-o", student.to_str().unwrap()], &text)
            .status
            .success()
    );
    // Another image: the student's with its last byte changed.
    let other = dir.join("other.ppm");
    let mut bytes = std::fs::read(&student).unwrap();
    *bytes.last_mut().unwrap() ^= 0x80;
    std::fs::write(&other, bytes).unwrap();
    let binary = env!("CARGO_BIN_EXE_legacy-rt");
    // /dev/null opened for writing (`>`), for reading and writing (`1<>`, Python's
    // subprocess.DEVNULL), or standard output closed (`>&-`, which Rust's runtime opens
    // on /dev/null): the output is discarded, and the exit status is the command's.
    for discard in ["> /dev/null", "1<> /dev/null", ">&-"] {
        for (args, code) in [
            (format!("4 3 < '{scene}'"), 0),
            (format!("trace 1 1 4 3 < '{scene}'"), 0),
            (format!("compare '{scene}' '{}'", student.display()), 0),
            (format!("compare '{scene}' '{}'", other.display()), 1),
        ] {
            let script = format!("exec '{binary}' {args} {discard}");
            let output = Command::new("sh").args(["-c", &script]).output().unwrap();
            assert_eq!(
                output.status.code(),
                Some(code),
                "{args} {discard}: {}",
                stderr(&output)
            );
            assert_eq!(stderr(&output), "", "{args} {discard}");
        }
    }
    // As a Python grader runs it: subprocess.run(..., stdout=subprocess.DEVNULL).
    let python = format!(
        "import subprocess, sys\n\
         codes = [subprocess.run(['{binary}', 'compare', '{scene}', name], \
         stdout=subprocess.DEVNULL).returncode for name in sys.argv[1:]]\n\
         print(codes)\n"
    );
    let output = Command::new("python3")
        .args([
            "-c",
            &python,
            student.to_str().unwrap(),
            other.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(
        String::from_utf8_lossy(&output.stdout).trim(),
        "[0, 1]",
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_ppm_with_a_comment_after_its_magic_number_compares() {
    let dir = folder("comment");
    let scene = scene_file(&dir);
    let reference = run(&["2", "2"], &std::fs::read(&scene).unwrap()).stdout;
    let pixels = &reference[reference.len() - 12..];
    let mut text = String::from("P3#written by hand\n2 2\n255\n");
    for value in pixels {
        text += &format!("{value} ");
    }
    let path = dir.join("student.ppm");
    let mut file = std::fs::File::create(&path).unwrap();
    file.write_all(text.as_bytes()).unwrap();
    let output = run(&["compare", &scene, path.to_str().unwrap()], b"");
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

#[test]
fn a_fixed_size_makes_an_image_of_another_size_a_wrong_size_verdict() {
    let dir = folder("size");
    let scene = scene_file(&dir);
    let student = dir.join("student.ppm");
    let text = std::fs::read(&scene).unwrap();
    assert!(
        run(&["8", "6", "-o", student.to_str().unwrap()], &text)
            .status
            .success()
    );
    let student = student.to_str().unwrap();
    // Without --size the reference is rendered at the student's size: a match.
    let output = run(&["compare", &scene, student], b"");
    assert_eq!(output.status.code(), Some(0));
    let output = run(&["compare", "--size", "8", "6", &scene, student], b"");
    assert_eq!(output.status.code(), Some(0));
    let output = run(
        &["compare", "--json", "--size", "16", "12", &scene, student],
        b"",
    );
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["verdict"], "wrong-size");
    assert_eq!(json["expected_size"], serde_json::json!([16, 12]));
    assert_eq!(
        (json["width"].as_u64(), json["height"].as_u64()),
        (Some(8), Some(6))
    );
    let output = run(&["compare", "--size", "16", "12", &scene, student], b"");
    let report = String::from_utf8(output.stdout).unwrap();
    assert!(report.contains("verdict: wrong-size"), "{report}");
    assert!(report.contains("must be 16x12"), "{report}");
}

// ---------------------------------------------------------------------------------------
// Issue 48: bounded memory and time for every file a student hands in, nothing followed
// out of the class folder.

/// What a run of the binary did: its exit code, its CPU seconds (user and system, from
/// the kernel's account of that child alone, `wait4`), its standard error.
struct Measured {
    code: Option<i32>,
    cpu: f64,
    stderr: String,
}

/// Runs the binary with `args` in `dir`, standard input from `stdin` (a file) or none,
/// standard output discarded, within an address space of `limit_mb` MB (`RLIMIT_AS`: an
/// allocation past it fails, and the program with it), and measures it. The child's
/// peak memory cannot be read back (a forked child's account starts from its parent's
/// pages), so the limit is what bounds it. The child is reaped by `wait4` itself.
#[allow(clippy::zombie_processes)]
fn measured(dir: &Path, args: &[&str], stdin: Option<&Path>, limit_mb: u64) -> Measured {
    use std::os::unix::process::CommandExt;
    let error_file = dir.join("stderr.txt");
    let mut command = Command::new(env!("CARGO_BIN_EXE_legacy-rt"));
    command
        .args(args)
        .current_dir(dir)
        .stdin(match stdin {
            Some(path) => Stdio::from(std::fs::File::open(path).unwrap()),
            None => Stdio::null(),
        })
        .stdout(Stdio::null())
        .stderr(Stdio::from(std::fs::File::create(&error_file).unwrap()));
    let bytes = limit_mb << 20;
    // SAFETY: setrlimit is async-signal-safe, and the closure touches nothing else.
    unsafe {
        command.pre_exec(move || {
            let limit = libc::rlimit {
                rlim_cur: bytes,
                rlim_max: bytes,
            };
            match libc::setrlimit(libc::RLIMIT_AS, &limit) {
                0 => Ok(()),
                _ => Err(std::io::Error::last_os_error()),
            }
        });
    }
    let child = command.spawn().unwrap();
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value for wait4 to fill in.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: wait4 on our own child's pid, with valid pointers to locals; it reaps the
    // child, which `child` is not waited on after.
    let pid = unsafe { libc::wait4(child.id() as libc::pid_t, &mut status, 0, &mut usage) };
    assert_eq!(pid, child.id() as libc::pid_t);
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 / 1e6;
    Measured {
        code: libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status)),
        cpu: seconds(usage.ru_utime) + seconds(usage.ru_stime),
        stderr: std::fs::read_to_string(&error_file).unwrap(),
    }
}

/// A 4x4 black PNG with `count` tiny text chunks of `kind` (iTXt or tEXt: the keyword
/// `k` and the text `x`, which the decoder keeps) before its image data.
fn flooded_png(kind: &[u8; 4], count: usize) -> Vec<u8> {
    let data: &[u8] = match kind {
        b"iTXt" => b"k\0\0\0\0\0x",
        _ => b"k\0x",
    };
    let tiny = chunk(kind, data);
    let mut extra = Vec::with_capacity(tiny.len() * count);
    for _ in 0..count {
        extra.extend_from_slice(&tiny);
    }
    png(4, 4, 8, 2, &extra, &[0u8; 4 * 13])
}

#[test]
fn a_png_flooded_with_text_chunks_is_read_in_bounded_memory() {
    // 2 million iTXt chunks (38 MB) before the image data: read in under 200 MB of address
    // space (the decoder kept them all: 348 MB resident for these, 1.4 GB for 10
    // million), the pixels compared.
    let dir = folder("png-flood");
    let scene = scene_file(&dir);
    // At 4x4 no ray meets the sphere: the reference is black, as the PNG is.
    let reference = run(&["4", "4"], &std::fs::read(&scene).unwrap()).stdout;
    assert!(reference.ends_with(&[0; 48]));
    for kind in [b"iTXt", b"tEXt"] {
        let student = dir.join("flooded.png");
        std::fs::write(&student, flooded_png(kind, 2_000_000)).unwrap();
        let args = ["compare", &scene, student.to_str().unwrap()];
        // Read within 200 MB, its pixels compared: they match.
        let run = measured(&dir, &args, None, 200);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `trace --against FILE 8 6` of the one-sphere scene, measured within 300 MB.
fn read_trace(dir: &Path, file: &Path) -> Measured {
    let scene = scene_file(dir);
    let args = ["trace", "--against", file.to_str().unwrap(), "8", "6"];
    measured(dir, &args, Some(Path::new(&scene)), 300)
}

#[test]
fn a_hostile_trace_is_read_in_linear_time_and_bounded_memory() {
    let dir = folder("trace-hostile");
    // Lines of `nan(` without their `)`, which the number reader once rescanned to the end
    // of the line after each: four times as many lines cost about four times the CPU
    // (quadratic, a line alone took seconds).
    let line = format!("PIX 3 2 {}\n", "nan(".repeat(15_000));
    let cpu = |lines: usize| {
        let file = dir.join("nan.txt");
        std::fs::write(&file, line.repeat(lines)).unwrap();
        let run = read_trace(&dir, &file);
        assert_eq!(run.code, Some(2), "{}", run.stderr);
        run.cpu
    };
    let (few, many) = (cpu(64), cpu(256));
    assert!(
        many < 8.0 * few.max(0.05),
        "64 lines: {few} s, 256 lines: {many} s"
    );
    // 32 MB of newlines: read as a stream within 300 MB, not held (it took 16 times its
    // size).
    let file = dir.join("newlines.txt");
    std::fs::write(&file, vec![b'\n'; 32 << 20]).unwrap();
    let run = read_trace(&dir, &file);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(
        run.stderr.contains("no line the course's DBG_ flags print"),
        "{}",
        run.stderr
    );
    // One line of 32 MB holding FND lines' words: read to its first 64 KiB (a block of
    // some 5,000 tests, read against the reference: it differs), within 300 MB.
    let file = dir.join("long.txt");
    std::fs::write(&file, "FND 1: 2.0 - ".repeat(32 << 20 >> 4)).unwrap();
    let run = read_trace(&dir, &file);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_diff_into_a_link_or_a_fifo_is_refused() {
    let dir = folder("diff-link");
    let scene = scene_file(&dir);
    let student = dir.join("student.ppm");
    assert!(
        run(
            &["4", "3", "-o", student.to_str().unwrap()],
            &std::fs::read(&scene).unwrap()
        )
        .status
        .success()
    );
    // A student's diff.png linking to a file of the grader's: refused, the file intact.
    let precious = dir.join("precious.txt");
    std::fs::write(&precious, "the grader's notes").unwrap();
    let link = dir.join("diff.png");
    std::os::unix::fs::symlink(&precious, &link).unwrap();
    let args = [
        "--diff",
        link.to_str().unwrap(),
        &scene,
        student.to_str().unwrap(),
    ];
    let output = compare_within(&args, Duration::from_secs(30)).unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output).contains("is a symbolic link"),
        "{}",
        stderr(&output)
    );
    assert_eq!(
        std::fs::read_to_string(&precious).unwrap(),
        "the grader's notes"
    );
    // A dangling link: refused, its target not created.
    std::fs::remove_file(&link).unwrap();
    let nowhere = dir.join("created-by-the-link.png");
    std::os::unix::fs::symlink(&nowhere, &link).unwrap();
    let output = compare_within(&args, Duration::from_secs(30)).unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(!nowhere.exists());
    // A FIFO: refused at once, not written into (which would wait for a reader).
    std::fs::remove_file(&link).unwrap();
    assert!(
        Command::new("mkfifo")
            .arg(&link)
            .status()
            .unwrap()
            .success()
    );
    let output =
        compare_within(&args, Duration::from_secs(10)).expect("compare hangs on a FIFO --diff");
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output).contains("not a regular file"),
        "{}",
        stderr(&output)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
