//! Textures as files inside files: an [`Image`]'s original PNG or JPEG bytes when it is
//! unchanged, else a PNG encoding of its pixels, and the `data:` URI SVG and HTML embed.

use std::borrow::Cow;

use base64::Engine as _;

use crate::Image;

/// The image as an encoded file with its MIME type: its original PNG or JPEG bytes when it
/// is unchanged ([`Image::original`]), else a PNG encoding of its pixels.
#[must_use]
pub fn encoded_image(image: &Image) -> (Cow<'_, [u8]>, &'static str) {
    match image.original() {
        Some((bytes, mime)) => (Cow::Borrowed(bytes), mime),
        None => (Cow::Owned(png_of(image)), "image/png"),
    }
}

/// The image as a `data:` URI ([`encoded_image`], base64), as SVG and HTML embed it.
#[must_use]
pub fn image_data_uri(image: &Image) -> String {
    let (bytes, mime) = encoded_image(image);
    format!(
        "data:{mime};base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    )
}

fn png_of(image: &Image) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, image.width(), image.height());
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    // Writing to a Vec of the right size fails only on a mismatched length, which
    // `Image::from_rgba` and the decoders rule out.
    if let Ok(mut writer) = encoder.write_header() {
        let _ = writer.write_image_data(image.rgba());
    }
    out
}
