//! Colour conventions every sink shares: ID colours (CONVENTIONS.md) and the seed's
//! golden-angle fallback palette.

/// Saturation of the fallback palette.
pub const PALETTE_SATURATION: f64 = 0.55;
/// Value (brightness) of the fallback palette.
pub const PALETTE_VALUE: f64 = 0.92;
/// The palette's hue step per face, in degrees (the golden angle).
pub const GOLDEN_ANGLE_DEG: f64 = 137.508;

/// The ID value of a face (CONVENTIONS.md): its index + 1; 0 is the background.
#[inline]
#[must_use]
pub fn id_value(face: u32) -> u32 {
    face.wrapping_add(1)
}

/// The 24-bit RGB encoding of an ID value (not a face index: see [`id_value`]), R the high
/// byte, as stored in ID images.
#[inline]
#[must_use]
pub fn id_value_to_rgb(value: u32) -> [u8; 3] {
    [(value >> 16) as u8, (value >> 8) as u8, value as u8]
}

/// The ID colour of a face (CONVENTIONS.md): [`id_value`] `= face + 1` as 24-bit RGB
/// ([`id_value_to_rgb`]), opaque. Face indices from `2^24 − 1` on wrap.
#[inline]
#[must_use]
pub fn id_colour(face: u32) -> [u8; 4] {
    let [r, g, b] = id_value_to_rgb(id_value(face));
    [r, g, b, 255]
}

/// The seed's fallback palette: hue `face · 137.508°`, saturation 0.55, value 0.92, opaque.
/// Neighbouring faces get clearly different colours.
#[must_use]
pub fn golden_angle_colour(face: u32) -> [u8; 4] {
    let hue = (f64::from(face) * GOLDEN_ANGLE_DEG).rem_euclid(360.0) / 60.0;
    let (s, v) = (PALETTE_SATURATION, PALETTE_VALUE);
    let c = v * s;
    let x = c * (1.0 - (hue % 2.0 - 1.0).abs());
    let (r, g, b) = match hue as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = v - c;
    let to_byte = |f: f64| ((f + m) * 255.0).round().clamp(0.0, 255.0) as u8;
    [to_byte(r), to_byte(g), to_byte(b), 255]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn id_colour_is_face_plus_one() {
        assert_eq!(id_colour(0), [0, 0, 1, 255]);
        assert_eq!(id_colour(0x01_0202), [1, 2, 3, 255]);
        assert_eq!(id_value_to_rgb(id_value(0x01_0202)), [1, 2, 3]);
        assert_eq!(id_value_to_rgb(0), [0, 0, 0]); // the background
    }

    #[test]
    fn palette_neighbours_differ() {
        let (a, b) = (golden_angle_colour(0), golden_angle_colour(1));
        assert!(
            a.iter()
                .zip(&b)
                .map(|(x, y)| x.abs_diff(*y) as u32)
                .sum::<u32>()
                > 60
        );
    }
}
