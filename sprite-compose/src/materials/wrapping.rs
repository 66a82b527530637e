//! Wrap modes made concrete: a face whose texture coordinates leave `[0, 1]` gets a map into
//! `[0, 1]`, by an affine remap when it spans one tile, else by an image of its tiles.

use glam::DVec2;
use obj_quads::WrapMode;

use super::Image;
use crate::tolerance::{MAX_TILED_PIXELS, UV_TILE_SLACK};

/// The tiles a face's texture coordinates span: the lowest tile corner and the tile counts
/// per axis (integers, at least 1). Coordinates within [`UV_TILE_SLACK`] of a tile edge
/// count as on it.
pub(super) fn tiles_of(uvs: &[DVec2]) -> (DVec2, DVec2) {
    let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
    for &uv in uvs {
        lo = lo.min(uv);
        hi = hi.max(uv);
    }
    let first = (lo + DVec2::splat(UV_TILE_SLACK)).floor();
    let last = (hi - DVec2::splat(UV_TILE_SLACK)).ceil();
    (first, (last - first).max(DVec2::ONE))
}

/// For a face within one tile, the affine remap `uv ↦ uv · scale + offset` that samples the
/// texture as the wrap modes say; `None` when that needs an image (several tiles, or a
/// clamped tile other than `[0, 1]`).
pub(super) fn single_tile((lo, n): (DVec2, DVec2), wrap: [WrapMode; 2]) -> Option<(DVec2, DVec2)> {
    if n != DVec2::ONE {
        return None;
    }
    let axis = |k: f64, mode: WrapMode| -> Option<(f64, f64)> {
        let odd = k.rem_euclid(2.0) == 1.0;
        match mode {
            _ if k == 0.0 => Some((1.0, 0.0)),
            WrapMode::MirroredRepeat if odd => Some((-1.0, k + 1.0)),
            WrapMode::Repeat | WrapMode::MirroredRepeat => Some((1.0, -k)),
            _ => None,
        }
    };
    let (su, ou) = axis(lo.x, wrap[0])?;
    let (sv, ov) = axis(lo.y, wrap[1])?;
    Some((DVec2::new(su, sv), DVec2::new(ou, ov)))
}

/// Whether the tiled image of `image` over `tiles` stays within [`MAX_TILED_PIXELS`].
pub(super) fn tiles_fit(image: &Image, (_, n): (DVec2, DVec2)) -> bool {
    let (w, h) = (
        f64::from(image.width()) * n.x,
        f64::from(image.height()) * n.y,
    );
    w * h <= MAX_TILED_PIXELS as f64 && w >= 1.0 && h >= 1.0
}

/// `image` tiled over `tiles` (tile `(i, j)` shows texture tile `lo + (i, j)`), each axis
/// wrapped as `wrap` says: repeated, mirrored on odd tiles, or clamped to the edge texels
/// outside tile 0. Texture space has `v` down (the image's first row at `v = 0`).
pub(super) fn tiled(image: &Image, wrap: [WrapMode; 2], (lo, n): (DVec2, DVec2)) -> Image {
    let (w, h) = (image.width() as usize, image.height() as usize);
    let (nu, nv) = (n.x as usize, n.y as usize);
    let source = |tile: i64, at: usize, size: usize, mode: WrapMode| -> usize {
        match mode {
            WrapMode::MirroredRepeat if tile.rem_euclid(2) == 1 => size - 1 - at,
            WrapMode::ClampToEdge if tile < 0 => 0,
            WrapMode::ClampToEdge if tile > 0 => size - 1,
            _ => at,
        }
    };
    let mut rgba = vec![0u8; w * nu * h * nv * 4];
    let row_bytes = w * nu * 4;
    for j in 0..nv {
        let tile_v = lo.y as i64 + j as i64;
        for y in 0..h {
            let sy = source(tile_v, y, h, wrap[1]);
            for i in 0..nu {
                let tile_u = lo.x as i64 + i as i64;
                for x in 0..w {
                    let sx = source(tile_u, x, w, wrap[0]);
                    let from = (sy * w + sx) * 4;
                    let to = (j * h + y) * row_bytes + (i * w + x) * 4;
                    rgba[to..to + 4].copy_from_slice(&image.rgba()[from..from + 4]);
                }
            }
        }
    }
    let name = format!("{} (tiles {lo} + {n})", image.name());
    Image::from_rgba((w * nu) as u32, (h * nv) as u32, rgba, name).unwrap_or_else(|| image.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_tile_remaps_and_mirrors_as_the_wrap_mode_says() {
        let repeat = [WrapMode::Repeat; 2];
        let mirrored = [WrapMode::MirroredRepeat, WrapMode::Repeat];
        let tiles = tiles_of(&[DVec2::new(5.0, 0.0), DVec2::new(6.0, 1.0 - 1e-7)]);
        assert_eq!(tiles, (DVec2::new(5.0, 0.0), DVec2::ONE));
        assert_eq!(
            single_tile(tiles, repeat),
            Some((DVec2::ONE, DVec2::new(-5.0, 0.0)))
        );
        // Tile 5 is odd: mirrored, u = 5.25 samples 0.75.
        let (scale, offset) = single_tile(tiles, mirrored).unwrap();
        assert!((5.25 * scale.x + offset.x - 0.75).abs() < 1e-12);
        let clamp = [WrapMode::ClampToEdge; 2];
        assert_eq!(single_tile(tiles, clamp), None);
        assert_eq!(
            single_tile((DVec2::ZERO, DVec2::ONE), clamp),
            Some((DVec2::ONE, DVec2::ZERO))
        );
    }

    #[test]
    fn tiles_repeat_mirror_and_clamp() {
        // A 2 × 1 image: red, green.
        let image = Image::from_rgba(2, 1, vec![255, 0, 0, 255, 0, 255, 0, 255], "rg").unwrap();
        let row = |wrap: WrapMode| {
            let t = tiled(
                &image,
                [wrap, WrapMode::Repeat],
                (DVec2::new(-1.0, 0.0), DVec2::new(3.0, 1.0)),
            );
            t.rgba()
                .chunks(4)
                .map(|p| if p[0] == 255 { 'r' } else { 'g' })
                .collect::<String>()
        };
        assert_eq!(row(WrapMode::Repeat), "rgrgrg");
        assert_eq!(row(WrapMode::MirroredRepeat), "grrggr");
        assert_eq!(row(WrapMode::ClampToEdge), "rrrggg");
    }
}
