//! Reading a student's image: binary and text PPM (P6, P3), as students' programs write
//! them, and PNG. Told apart from a scene file by its first bytes, never by its name.

use crate::render::Image;
use image::{DynamicImage, ImageFormat};

/// What a file's first bytes say it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Content {
    /// A PPM (P3, P6) or another Netpbm image (P1, P2, P4, P5, P7).
    Netpbm(u8),
    /// A PNG image.
    Png,
    /// An image in a format this program does not read (named).
    OtherImage(&'static str),
    /// Anything else: a scene file, or not.
    Text,
}

/// Recognises an image by its signature.
pub fn content(bytes: &[u8]) -> Content {
    const PNG: &[u8] = b"\x89PNG\r\n\x1a\n";
    match bytes {
        [b'P', kind @ b'1'..=b'7', next, ..] if next.is_ascii_whitespace() => {
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
    /// The decoder's complaint: a truncated file, a bad header.
    #[error("{0}")]
    Broken(String),
}

/// Decodes a P3, P6 or PNG image into rows top to bottom, 8-bit RGB.
pub fn read_image(bytes: &[u8]) -> Result<Image, ReadError> {
    let format = match content(bytes) {
        Content::Netpbm(3 | 6) => ImageFormat::Pnm,
        Content::Netpbm(kind) => {
            let name = match kind {
                1 | 4 => "black-and-white PBM",
                2 | 5 => "grey PGM",
                _ => "PAM",
            };
            return Err(ReadError::NotPpm(name, kind));
        }
        Content::Png => ImageFormat::Png,
        Content::OtherImage(name) => return Err(ReadError::Unsupported(name)),
        Content::Text => return Err(ReadError::NotAnImage),
    };
    let decoded = image::load_from_memory_with_format(bytes, format).map_err(|error| {
        let message = error.to_string();
        ReadError::Broken(
            match message.contains("end of file") || message.contains("EOF") {
                true => format!("the image is cut short ({message})"),
                false => message,
            },
        )
    })?;
    let rgb = match decoded {
        DynamicImage::ImageRgb8(rgb) => rgb,
        DynamicImage::ImageRgba8(rgba) => {
            if rgba.pixels().any(|p| p.0[3] != 255) {
                return Err(ReadError::Transparent);
            }
            DynamicImage::ImageRgba8(rgba).to_rgb8()
        }
        DynamicImage::ImageLuma8(_) | DynamicImage::ImageLumaA8(_) => return Err(ReadError::Grey),
        DynamicImage::ImageLuma16(_) | DynamicImage::ImageLumaA16(_) => {
            return Err(ReadError::Grey);
        }
        _ => return Err(ReadError::SixteenBit),
    };
    let (width, height) = (rgb.width() as usize, rgb.height() as usize);
    let pixels = rgb.pixels().map(|p| p.0).collect();
    Ok(Image {
        width,
        height,
        pixels,
    })
}

/// The image in a file's `bytes`, or the message `legacy-rt compare` gives: `shown` names
/// the file and `role` what it is ("student's image" or "reference image").
pub fn image_named(bytes: &[u8], shown: &str, role: &str) -> Result<Image, String> {
    if content(bytes) == Content::Text && role == "student's image" {
        let hint = match bytes.first() {
            Some(b'0'..=b'9' | b'-' | b'+' | b'.') => {
                ": it looks like a scene file; the scene comes first, the image second"
            }
            _ => "",
        };
        return Err(format!(
            "error: {shown} (the {role}) is not a PPM or PNG image{hint}"
        ));
    }
    read_image(bytes).map_err(|error| format!("error: {shown} (the {role}): {error}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixels(image: &Image) -> Vec<[u8; 3]> {
        image.pixels.clone()
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
}
