//! Per-sprite texture brushes from texture maps on the faces' planes.

use glam::{DAffine2, DVec2, DVec3};

use crate::{Brush, Compositor, Scene, SpriteId, SpriteSpace, TextureId};

/// Gives every visible sprite of `scene` whose face has a texture map its own
/// [`Brush::Texture`], with the uv map of its own unit square.
///
/// `uv(face, point)` is the face's map: the texture and the texture coordinates (`[0,1]²`,
/// top-left origin) of a point of its plane in *centred model space* (model position minus
/// the geometry's bounds centre; raster-sink's `UvMap::uv` is such a map), `None` for faces
/// without one (they keep their brush). A brush set per face ([`SpritePainter::set_brushes`](crate::SpritePainter::set_brushes))
/// cannot do this: the fan triangles and fragments of one face have different unit squares.
///
/// The sprite's map goes through the centred points of its square's corners `(0,0)`,
/// `(1,0)`, `(0,1)`: exact for affine sprites (parallelograms, triangles and their fragments),
/// whose unit square lies affinely on the face's plane; an approximation for projective ones
/// (planar quads that are not parallelograms). Returns how many sprites got a texture.
pub fn set_plane_textures(
    scene: &mut Scene,
    space: &SpriteSpace,
    uv: impl Fn(u32, DVec3) -> Option<(TextureId, DVec2)>,
) -> usize {
    let centred = |p: DVec3| {
        let d = (p - space.origin) / space.scale;
        DVec3::new(d.x, -d.y, d.z)
    };
    let updates: Vec<(SpriteId, Brush)> = scene
        .visible()
        .filter_map(|(id, sprite)| {
            let at = |s: f64, t: f64| {
                let p = centred(sprite.transform.apply(DVec2::new(s, t)));
                p.is_finite().then(|| uv(sprite.face, p)).flatten()
            };
            let (texture, o) = at(0.0, 0.0)?;
            let ((_, x), (_, y)) = (at(1.0, 0.0)?, at(0.0, 1.0)?);
            let map = DAffine2::from_cols(x - o, y - o, o);
            map.is_finite().then(|| {
                let brush = Brush::Texture {
                    texture,
                    uv: map,
                    fallback: sprite.brush.solid_colour(sprite.face),
                };
                (id, brush)
            })
        })
        .collect();
    for (id, brush) in &updates {
        scene.set_brush(*id, brush);
    }
    updates.len()
}
