//! Reading a student's image: binary and text PPM (P6, P3), as students' programs write
//! them, and PNG. Told apart from a scene file by its first bytes, never by its name.
//!
//! The files come from students, so nothing in them is trusted. The header is read first
//! and an image larger than the caller's pixel budget, grey, or of more than 8 bits per
//! channel is refused before any pixel is decoded. The pixels are decoded straight into
//! the image's own buffer (no second copy), a PNG palette the decoder would choke on is
//! refused before it runs, and the third-party decoder runs behind a panic boundary
//! (`guarded`): whatever else a damaged file does to it is an error, not the end of the
//! process.

use crate::render::Image;
use image::codecs::png::PngDecoder;
use image::codecs::pnm::PnmDecoder;
use image::{ColorType, ImageDecoder, ImageError, Limits};
use std::io::{BufRead, Cursor, Read, Seek, SeekFrom};

/// The most pixels [`read_image`] decodes unless told otherwise: 4096 x 4096, larger than
/// any image of the course and small enough that a grading machine can hold the image,
/// its reference and what `compare --diagnose` keeps of it (docs/compare.md, "Limits").
pub const DEFAULT_MAX_PIXELS: u64 = 4096 * 4096;

/// What a file's first bytes say it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Content {
    /// A PPM (P3, P6) or another Netpbm image (P1, P2, P4, P5, P7).
    Netpbm(u8),
    /// A PNG image (its 8-byte signature).
    Png,
    /// An image in a format this program does not read (named).
    OtherImage(&'static str),
    /// Anything else: a scene file, or not.
    Text,
}

/// Recognises an image by its signature. A Netpbm magic number is followed by
/// whitespace or by a `#` comment (the format allows one anywhere in the header).
pub fn content(bytes: &[u8]) -> Content {
    const PNG: &[u8] = b"\x89PNG\r\n\x1a\n";
    match bytes {
        [b'P', kind @ b'1'..=b'7', next, ..] if next.is_ascii_whitespace() || *next == b'#' => {
            Content::Netpbm(*kind - b'0')
        }
        _ if bytes.starts_with(PNG) => Content::Png,
        [0xff, 0xd8, 0xff, ..] => Content::OtherImage("JPEG"),
        _ if bytes.starts_with(b"GIF8") => Content::OtherImage("GIF"),
        _ if bytes.starts_with(b"BM") => Content::OtherImage("BMP"),
        _ if bytes.starts_with(b"RIFF") && bytes.get(8..12) == Some(b"WEBP") => {
            Content::OtherImage("WebP")
        }
        _ if bytes.starts_with(b"II*\0") || bytes.starts_with(b"MM\0*") => {
            Content::OtherImage("TIFF")
        }
        _ => Content::Text,
    }
}

/// Why an image cannot be compared.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ReadError {
    /// Not an image at all.
    #[error("not a PPM (P3 or P6) or PNG image")]
    NotAnImage,
    /// An image format this program does not read.
    #[error("a {0} image; only PPM (P3 or P6) and PNG are read: convert it first")]
    Unsupported(&'static str),
    /// A Netpbm image that is not a colour PPM.
    #[error("a {0} image (P{1}); the course's images are colour PPM (P3 or P6)")]
    NotPpm(&'static str, u8),
    /// Grey levels only.
    #[error("a grey image; the course's images are RGB")]
    Grey,
    /// More than 8 bits per channel.
    #[error(
        "a 16-bit image (maximum value above 255); the course's images have 8 bits per \
         channel (maximum value 255)"
    )]
    SixteenBit,
    /// Transparent pixels, which have no single colour to compare.
    #[error("a PNG with transparent pixels; the course's images are opaque RGB")]
    Transparent,
    /// A header that announces more pixels than the budget, found before decoding.
    #[error("a {width}x{height} image, more than the {max_pixels} pixels allowed")]
    TooLarge {
        /// The width the header gives.
        width: u32,
        /// The height the header gives.
        height: u32,
        /// The most pixels the caller allows.
        max_pixels: u64,
    },
    /// A file the decoder could not survive, or one known to break it.
    #[error("the image is damaged ({0})")]
    Damaged(String),
    /// The decoder's complaint: a truncated file, a bad header.
    #[error("{0}")]
    Broken(String),
}

/// Decodes a P3, P6 or PNG image held in memory, of at most [`DEFAULT_MAX_PIXELS`].
pub fn read_image(bytes: &[u8]) -> Result<Image, ReadError> {
    read_image_from(Cursor::new(bytes), DEFAULT_MAX_PIXELS)
}

/// Decodes a P3, P6 or PNG image from `reader` into rows top to bottom, 8-bit RGB; an
/// image of more than `max_pixels` pixels is refused from its header.
pub fn read_image_from(
    mut reader: impl BufRead + Seek,
    max_pixels: u64,
) -> Result<Image, ReadError> {
    let mut start = [0u8; 16];
    let seen = read_up_to(&mut reader, &mut start).map_err(broken)?;
    let rewind = |reader: &mut dyn SeekRead| reader.seek(SeekFrom::Start(0)).map_err(broken);
    match content(&start[..seen]) {
        Content::Netpbm(3 | 6) => {
            rewind(&mut reader)?;
            let decoder = guarded(|| PnmDecoder::new(reader))?.map_err(decoding)?;
            decode(decoder, max_pixels)
        }
        Content::Netpbm(kind) => {
            let name = match kind {
                1 | 4 => "black-and-white PBM",
                2 | 5 => "grey PGM",
                _ => "PAM",
            };
            Err(ReadError::NotPpm(name, kind))
        }
        Content::Png => {
            rewind(&mut reader)?;
            check_palette(&mut reader)?;
            rewind(&mut reader)?;
            let limits = decoder_limits(max_pixels);
            // The decoder sees only the chunks the pixels need: it keeps text chunks
            // whatever their number, and 10 million tiny ones took it 1.4 GB.
            let pixels_only = std::io::BufReader::new(PixelChunks::new(reader));
            let decoder =
                guarded(|| PngDecoder::with_limits(pixels_only, limits))?.map_err(decoding)?;
            decode(decoder, max_pixels)
        }
        Content::OtherImage(name) => Err(ReadError::Unsupported(name)),
        Content::Text => Err(ReadError::NotAnImage),
    }
}

/// A reader that can be rewound, as a trait object.
trait SeekRead: Read + Seek {}
impl<T: Read + Seek> SeekRead for T {}

/// Fills `buffer` from `reader` as far as the file goes; the count read.
fn read_up_to(reader: &mut impl Read, buffer: &mut [u8]) -> std::io::Result<usize> {
    let mut filled = 0;
    while filled < buffer.len() {
        match reader.read(&mut buffer[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(error) if error.kind() == std::io::ErrorKind::Interrupted => {}
            Err(error) => return Err(error),
        }
    }
    Ok(filled)
}

/// What the PNG decoder may allocate besides the image: its rows, its chunks' buffers.
/// Bounded, so that a small file cannot ask it for gigabytes of metadata.
fn decoder_limits(max_pixels: u64) -> Limits {
    let mut limits = Limits::default();
    limits.max_alloc = Some(max_pixels.saturating_mul(8).saturating_add(64 << 20));
    limits
}

/// The PNG decoder (png 0.18.1, the newest release) panics when a palette's length is not
/// a multiple of 3 (image-rs/image-png issue 694): such a file is refused before it is
/// decoded. The chunks before the first IDAT are walked by their lengths.
fn check_palette(reader: &mut impl Read) -> Result<(), ReadError> {
    let mut signature = [0u8; 8];
    reader.read_exact(&mut signature).map_err(broken)?;
    loop {
        let mut head = [0u8; 8];
        if read_up_to(reader, &mut head).map_err(broken)? < 8 {
            return Ok(()); // cut short: the decoder says so
        }
        let length = u32::from_be_bytes([head[0], head[1], head[2], head[3]]);
        match &head[4..] {
            b"IDAT" | b"IEND" => return Ok(()),
            b"PLTE" if length % 3 != 0 || length == 0 => {
                return Err(ReadError::Damaged(format!(
                    "its palette is {length} bytes long, not 3 bytes per colour"
                )));
            }
            _ => {
                // The chunk's data and its CRC.
                let skip = u64::from(length) + 4;
                if std::io::copy(&mut reader.take(skip), &mut std::io::sink()).map_err(broken)?
                    < skip
                {
                    return Ok(());
                }
            }
        }
    }
}

/// A PNG as a stream of the chunks its pixels need (IHDR, PLTE, tRNS, IDAT, IEND, and any
/// other critical chunk): the ancillary ones (text, time, colour profiles, animation) are
/// skipped as they are read, so that memory stays bounded by the image and time linear
/// in the file, whatever a file holds besides its pixels. Each chunk kept is passed on
/// whole, with its CRC, so the stream is a PNG the decoder checks as before.
struct PixelChunks<R> {
    inner: R,
    /// The header of the chunk being passed on, and how much of it is passed on.
    header: [u8; 8],
    header_sent: usize,
    /// Bytes of the chunk being passed on still to come from `inner` (data, CRC).
    passing: u64,
    /// Whether the signature has been passed on.
    started: bool,
    /// Bytes handed out so far (for `stream_position`).
    position: u64,
}

impl<R: Read> PixelChunks<R> {
    fn new(inner: R) -> PixelChunks<R> {
        PixelChunks {
            inner,
            header: [0; 8],
            header_sent: 8,
            passing: 0,
            started: false,
            position: 0,
        }
    }

    /// Reads up to the next chunk to pass on, skipping ancillary ones, and holds its
    /// header; `false` at the end of the file (or of what is left of it).
    fn next_chunk(&mut self) -> std::io::Result<bool> {
        loop {
            let mut header = [0u8; 8];
            if read_up_to(&mut self.inner, &mut header)? < 8 {
                return Ok(false);
            }
            let length = u64::from(u32::from_be_bytes([
                header[0], header[1], header[2], header[3],
            ]));
            // Bit 5 of a chunk type's first byte: set for ancillary chunks (PNG spec 5.4).
            let ancillary = header[4] & 0x20 != 0;
            if !ancillary || &header[4..8] == b"tRNS" {
                (self.header, self.header_sent, self.passing) = (header, 0, length + 4);
                return Ok(true);
            }
            let skip = length + 4;
            if std::io::copy(&mut (&mut self.inner).take(skip), &mut std::io::sink())? < skip {
                return Ok(false);
            }
        }
    }
}

impl<R: Read> Read for PixelChunks<R> {
    fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        if buffer.is_empty() {
            return Ok(0);
        }
        if !self.started {
            // The 8-byte signature passes as it is, then the chunks.
            self.started = true;
            self.passing = 8;
        }
        if self.passing == 0 && self.header_sent == 8 && !self.next_chunk()? {
            return Ok(0);
        }
        let n = if self.header_sent < 8 {
            let n = (8 - self.header_sent).min(buffer.len());
            buffer[..n].copy_from_slice(&self.header[self.header_sent..self.header_sent + n]);
            self.header_sent += n;
            n
        } else {
            let most = buffer
                .len()
                .min(usize::try_from(self.passing).unwrap_or(usize::MAX));
            let n = self.inner.read(&mut buffer[..most])?;
            self.passing -= n as u64;
            n
        };
        self.position += n as u64;
        Ok(n)
    }
}

impl<R> Seek for PixelChunks<R> {
    /// Only where the stream is: the decoder's bound asks for Seek, and it never moves.
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        match to {
            SeekFrom::Current(0) => Ok(self.position),
            _ => Err(std::io::Error::other(
                "a PNG's pixel chunks are read in order",
            )),
        }
    }
}

/// Decodes the pixels of `decoder` once its header has passed: at most `max_pixels`
/// pixels, 8-bit RGB or opaque RGBA.
fn decode(decoder: impl ImageDecoder, max_pixels: u64) -> Result<Image, ReadError> {
    let (width, height) = decoder.dimensions();
    if u64::from(width) * u64::from(height) > max_pixels {
        return Err(ReadError::TooLarge {
            width,
            height,
            max_pixels,
        });
    }
    let (w, h) = (width as usize, height as usize);
    let pixels = match decoder.color_type() {
        ColorType::Rgb8 => {
            let mut pixels = vec![[0u8; 3]; w * h];
            guarded(|| decoder.read_image(pixels.as_flattened_mut()))?.map_err(decoding)?;
            pixels
        }
        ColorType::Rgba8 => {
            let mut rgba = vec![0u8; 4 * w * h];
            guarded(|| decoder.read_image(&mut rgba))?.map_err(decoding)?;
            if rgba.chunks_exact(4).any(|p| p[3] != 255) {
                return Err(ReadError::Transparent);
            }
            rgba.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect()
        }
        ColorType::L8 | ColorType::La8 | ColorType::L16 | ColorType::La16 => {
            return Err(ReadError::Grey);
        }
        _ => return Err(ReadError::SixteenBit),
    };
    Ok(Image {
        width: w,
        height: h,
        pixels,
    })
}

/// A reading error as the decoder's complaint.
fn broken(error: std::io::Error) -> ReadError {
    decoding(ImageError::IoError(error))
}

/// The decoder's error in words, saying "cut short" for a truncated file.
fn decoding(error: ImageError) -> ReadError {
    let message = error.to_string();
    ReadError::Broken(
        match message.contains("end of file") || message.contains("EOF") {
            true => format!("the image is cut short ({message})"),
            false => message,
        },
    )
}

/// Runs the third-party decoder: a panic in it becomes [`ReadError::Damaged`], and its
/// message is not printed (the panic hook stays quiet for this thread while it runs).
/// Where panics abort (the WebAssembly build) this cannot help, and the checks before
/// decoding are what keep the known crashes out.
pub(crate) fn guarded<T>(decode: impl FnOnce() -> T) -> Result<T, ReadError> {
    use std::cell::Cell;
    use std::panic::{AssertUnwindSafe, catch_unwind};
    thread_local! {
        static QUIET: Cell<bool> = const { Cell::new(false) };
    }
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    let was = QUIET.with(|quiet| quiet.replace(true));
    let result = catch_unwind(AssertUnwindSafe(decode));
    QUIET.with(|quiet| quiet.set(was));
    result.map_err(|panic| {
        let what = (panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        ReadError::Damaged(match what.is_empty() {
            true => "the decoder failed on it".to_string(),
            false => format!("the decoder failed on it: {what}"),
        })
    })
}

/// Why an image a user named is not read: [`ReadError`] with the file's name and what it
/// is for, as `legacy-rt compare` and the page say it.
#[derive(Debug, thiserror::Error)]
pub enum ImageFileError {
    /// Text where the student's image was expected (a scene file given second, say).
    #[error("{shown} (the {role}) is not a PPM or PNG image{hint}")]
    Text {
        /// The file's name, escaped.
        shown: String,
        /// What the image is for: "student's image" or "reference image".
        role: String,
        /// What it looks like, if it looks like something.
        hint: &'static str,
    },
    /// The image cannot be read.
    #[error("{shown} (the {role}): {error}{hint}", hint = limit_hint(.error))]
    Read {
        /// The file's name, escaped.
        shown: String,
        /// What the image is for.
        role: String,
        /// Why it cannot be read.
        error: ReadError,
    },
}

/// What raises the limit an image went past, if it went past one.
fn limit_hint(error: &ReadError) -> &'static str {
    match error {
        ReadError::TooLarge { .. } => " (--max-pixels raises the limit)",
        _ => "",
    }
}

/// The image in `reader`, or why not: `shown` names the file and `role` what it is
/// ("student's image" or "reference image").
pub fn image_named(
    mut reader: impl BufRead + Seek,
    max_pixels: u64,
    shown: &str,
    role: &str,
) -> Result<Image, ImageFileError> {
    let mut start = [0u8; 16];
    let seen = read_up_to(&mut reader, &mut start).unwrap_or(0);
    let _ = reader.seek(SeekFrom::Start(0));
    let first = &start[..seen];
    if content(first) == Content::Text && role == "student's image" {
        let hint = match first.first() {
            Some(b'0'..=b'9' | b'-' | b'+' | b'.') => {
                ": it looks like a scene file; the scene comes first, the image second"
            }
            _ => "",
        };
        return Err(ImageFileError::Text {
            shown: shown.to_string(),
            role: role.to_string(),
            hint,
        });
    }
    read_image_from(reader, max_pixels).map_err(|error| ImageFileError::Read {
        shown: shown.to_string(),
        role: role.to_string(),
        error,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixels(image: &Image) -> Vec<[u8; 3]> {
        image.pixels.clone()
    }

    /// `png` with `count` copies of the ancillary chunk `kind` (CRC left 0: the decoder
    /// never sees it) inserted before its first IDAT.
    fn flooded(png: &[u8], kind: &[u8; 4], count: usize) -> Vec<u8> {
        let at = png.windows(4).position(|w| w == b"IDAT").unwrap() - 4;
        let mut out = png[..at].to_vec();
        for _ in 0..count {
            out.extend_from_slice(&5u32.to_be_bytes());
            out.extend_from_slice(kind);
            out.extend_from_slice(b"k\0\0\0\0");
            out.extend_from_slice(&[0; 4]);
        }
        out.extend_from_slice(&png[at..]);
        out
    }

    #[test]
    fn a_png_s_ancillary_chunks_are_skipped_and_its_pixels_read() {
        let image = Image {
            width: 3,
            height: 2,
            pixels: vec![
                [1, 2, 3],
                [4, 5, 6],
                [7, 8, 9],
                [10, 11, 12],
                [13, 14, 15],
                [16, 17, 18],
            ],
        };
        let png = crate::image_output::png(&image).unwrap();
        for kind in [b"tEXt", b"iTXt", b"zTXt", b"tIME"] {
            let read = read_image(&flooded(&png, kind, 1000)).unwrap();
            assert_eq!(read, image);
        }
        // Read through a reader that hands out a byte at a time: every header and chunk
        // is passed on whole however the reads fall.
        let mut stream = PixelChunks::new(Cursor::new(flooded(&png, b"tEXt", 3)));
        let mut out = Vec::new();
        let mut byte = [0u8; 1];
        while stream.read(&mut byte).unwrap() == 1 {
            out.push(byte[0]);
        }
        assert_eq!(out, png);
        assert_eq!(stream.stream_position().unwrap(), png.len() as u64);
        assert!(stream.seek(SeekFrom::Start(0)).is_err());
    }

    #[test]
    fn text_and_binary_ppm_give_the_same_pixels() {
        let text = b"P3\n# made by a student\n2 1\n255\n255 0 0   0 128 255\n";
        let binary = b"P6 2 1 255\n\xff\x00\x00\x00\x80\xff";
        let (a, b) = (read_image(text).unwrap(), read_image(binary).unwrap());
        assert_eq!((a.width, a.height), (2, 1));
        assert_eq!(pixels(&a), vec![[255, 0, 0], [0, 128, 255]]);
        assert_eq!(pixels(&a), pixels(&b));
    }

    #[test]
    fn a_comment_may_follow_the_magic_number() {
        // Netpbm allows a comment anywhere before the raster, right after "P3" too.
        let text = b"P3#made by hand\n1 1\n255\n1 2 3\n";
        assert_eq!(content(text), Content::Netpbm(3));
        assert_eq!(pixels(&read_image(text).unwrap()), vec![[1, 2, 3]]);
    }

    #[test]
    fn grey_sixteen_bit_and_truncated_images_are_refused() {
        assert_eq!(
            read_image(b"P5 1 1 255\n\x80"),
            Err(ReadError::NotPpm("grey PGM", 5))
        );
        let wide = b"P6 1 1 65535\n\x01\x00\x02\x00\x03\x00";
        assert_eq!(read_image(wide), Err(ReadError::SixteenBit));
        let cut = read_image(b"P6 2 2 255\n\x01\x02\x03");
        assert!(matches!(cut, Err(ReadError::Broken(_))), "{cut:?}");
        assert_eq!(
            read_image(b"8 6 world\n0 0 3\n"),
            Err(ReadError::NotAnImage)
        );
        assert_eq!(
            read_image(b"\xff\xd8\xff\xe0"),
            Err(ReadError::Unsupported("JPEG"))
        );
    }

    #[test]
    fn a_header_over_the_budget_is_refused_before_decoding() {
        // A 13000x13000 P6 with no pixels at all: refused by its header, not cut short.
        let huge = b"P6 13000 13000 255\n";
        assert_eq!(
            read_image(huge),
            Err(ReadError::TooLarge {
                width: 13000,
                height: 13000,
                max_pixels: DEFAULT_MAX_PIXELS
            })
        );
        // Within a larger budget the same header is read, and the missing pixels found.
        let cut = read_image_from(Cursor::new(&huge[..]), 13000 * 13000);
        assert!(matches!(cut, Err(ReadError::Broken(_))), "{cut:?}");
    }

    #[test]
    fn a_png_reads_back_as_written() {
        let image = Image {
            width: 2,
            height: 2,
            pixels: vec![[1, 2, 3], [4, 5, 6], [7, 8, 9], [250, 251, 252]],
        };
        let png = crate::image_output::png(&image).unwrap();
        assert_eq!(content(&png), Content::Png);
        assert_eq!(read_image(&png), Ok(image));
    }

    /// The PNG that made png 0.18.1 panic: 1x1, a palette of 4 bytes (not 3 per colour).
    fn four_byte_palette() -> Vec<u8> {
        let chunk = |kind: &[u8], data: &[u8]| {
            let mut crc = !0u32;
            for &byte in kind.iter().chain(data) {
                crc ^= u32::from(byte);
                for _ in 0..8 {
                    crc = (crc >> 1) ^ (0xedb8_8320 * (crc & 1));
                }
            }
            let length = (data.len() as u32).to_be_bytes();
            [&length[..], kind, data, &(!crc).to_be_bytes()].concat()
        };
        // One scanline, filter 0 and index 1, in a zlib stored block.
        let idat = [
            0x78, 0x01, 0x01, 0x02, 0x00, 0xfd, 0xff, 0x00, 0x01, 0x00, 0x03, 0x00, 0x02,
        ];
        let ihdr = [0, 0, 0, 1, 0, 0, 0, 1, 8, 3, 0, 0, 0];
        let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
        png.extend(chunk(b"IHDR", &ihdr));
        png.extend(chunk(b"PLTE", &[10, 20, 30, 40]));
        png.extend(chunk(b"IDAT", &idat));
        png.extend(chunk(b"IEND", b""));
        png
    }

    #[test]
    fn the_palette_that_breaks_the_decoder_is_refused_and_its_panic_caught() {
        let png = four_byte_palette();
        let refused = read_image(&png);
        assert!(matches!(&refused, Err(ReadError::Damaged(why)) if why.contains("palette")));
        // Without the check the decoder panics, and the boundary turns that into an error.
        let decode = || {
            let decoder = PngDecoder::new(Cursor::new(&png)).unwrap();
            let mut pixels = vec![0u8; 3];
            decoder.read_image(&mut pixels)
        };
        assert!(matches!(guarded(decode), Err(ReadError::Damaged(_))));
    }

    #[test]
    fn a_panic_in_the_decoder_is_an_error() {
        let damaged = guarded(|| -> u8 { panic!("index out of range") });
        assert_eq!(
            damaged,
            Err(ReadError::Damaged(
                "the decoder failed on it: index out of range".into()
            ))
        );
        assert_eq!(guarded(|| 7), Ok(7));
    }
}
