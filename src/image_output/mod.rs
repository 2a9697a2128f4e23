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
pub fn encode(image: &Image, format: Format) -> io::Result<Vec<u8>> {
    match format {
        Format::Ppm => Ok(ppm(image)),
        Format::Png => png(image),
    }
}

/// `P6 W H 255`, one newline, then the RGB bytes, rows top to bottom (spec §4.7).
pub fn ppm(image: &Image) -> Vec<u8> {
    let header = format!("P6 {} {} 255\n", image.width, image.height);
    let mut bytes = Vec::with_capacity(header.len() + image.pixels.len() * 3);
    bytes.extend_from_slice(header.as_bytes());
    bytes.extend_from_slice(image.pixels.as_flattened());
    bytes
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

/// Writes the encoded image and flushes.
pub fn write(out: &mut impl Write, bytes: &[u8]) -> io::Result<()> {
    out.write_all(bytes)?;
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ppm_is_header_then_rows_top_first() {
        let image = Image {
            width: 2,
            height: 1,
            pixels: vec![[1, 2, 3], [4, 5, 6]],
        };
        assert_eq!(ppm(&image), b"P6 2 1 255\n\x01\x02\x03\x04\x05\x06");
    }
}
