//! Writing the image: binary PPM as the course's program wrote it (spec §4.7), or PNG,
//! to standard output or to a file ([`mod@file`]).

pub mod file;

use crate::render::Image;
use std::io::{self, Write};

/// The output formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Binary P6 PPM (the legacy output).
    Ppm,
    /// PNG, 8-bit RGB.
    Png,
}

/// The image encoded in `format`, complete, so that nothing is written unless all of it
/// can be.
pub fn encode(image: &Image, format: Format) -> io::Result<Encoded<'_>> {
    match format {
        Format::Ppm => Ok(Encoded {
            head: ppm_header(image).into_bytes(),
            body: image.pixels.as_flattened(),
        }),
        Format::Png => Ok(Encoded {
            head: png(image)?,
            body: &[],
        }),
    }
}

/// An encoded image as two pieces written one after the other: a PPM's header and its
/// pixels, borrowed from the image rather than copied (at 1600x1200 the copy and the
/// fresh pages it filled were 4 % of a render's CPU time), or the whole PNG and nothing.
pub struct Encoded<'a> {
    head: Vec<u8>,
    body: &'a [u8],
}

impl Encoded<'_> {
    /// The pieces, in the order they are written.
    pub fn pieces(&self) -> [&[u8]; 2] {
        [&self.head, self.body]
    }
}

/// `P6 W H 255`, one newline, then the RGB bytes, rows top to bottom (spec §4.7).
pub fn ppm(image: &Image) -> Vec<u8> {
    [ppm_header(image).as_bytes(), image.pixels.as_flattened()].concat()
}

fn ppm_header(image: &Image) -> String {
    format!("P6 {} {} 255\n", image.width, image.height)
}

/// The image as PNG.
pub fn png(image: &Image) -> io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    image::ImageEncoder::write_image(
        encoder,
        image.pixels.as_flattened(),
        image.width as u32,
        image.height as u32,
        image::ExtendedColorType::Rgb8,
    )
    .map_err(io::Error::other)?;
    Ok(bytes)
}

/// Writes `pieces` one after the other and flushes.
pub fn write(out: &mut impl Write, pieces: &[&[u8]]) -> io::Result<()> {
    for piece in pieces {
        out.write_all(piece)?;
    }
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ppm_is_header_then_rows_top_first_and_pieces_write_the_whole_file() {
        let image = Image {
            width: 2,
            height: 1,
            pixels: vec![[1, 2, 3], [4, 5, 6]],
        };
        let expected = b"P6 2 1 255\n\x01\x02\x03\x04\x05\x06";
        assert_eq!(ppm(&image), expected);
        let written = |format| {
            let mut written = Vec::new();
            write(&mut written, &encode(&image, format).unwrap().pieces()).unwrap();
            written
        };
        // Each format's pieces, written in order, are the whole file: the PPM's bytes
        // above, and a PNG that the image crate's decoder reads as the image's pixels.
        assert_eq!(written(Format::Ppm), expected);
        let decoded = ::image::load_from_memory(&written(Format::Png))
            .unwrap()
            .into_rgb8();
        assert_eq!((decoded.width(), decoded.height()), (2, 1));
        assert_eq!(decoded.as_raw(), image.pixels.as_flattened());
    }
}
