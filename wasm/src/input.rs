//! Arrays from JS, validated: triangles (positions, indices, colours) and a camera's
//! matrices.

use face_sort::{Camera, ClipSpace, CullMode, Geometry, PolygonMesh, View};
use glam::{DMat4, DVec3};

use crate::error::BindError;

/// Largest image side, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 1 << 14;

/// Largest number of triangles one call takes (a budget: memory grows with them).
pub const MAX_TRIANGLES: usize = 1 << 22;

/// Triangles as JS hands them over: positions (x, y, z per vertex), three vertex indices
/// per triangle, and optionally one sRGB RGBA colour per triangle.
#[derive(Clone, Debug)]
pub struct Triangles {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Three vertex indices per triangle, in the order IDs count them.
    pub triangles: Vec<[u32; 3]>,
}

impl Triangles {
    /// Checks lengths, finiteness and indices.
    pub fn new(positions: &[f64], indices: &[u32]) -> Result<Self, BindError> {
        if !positions.len().is_multiple_of(3) {
            return Err(BindError::argument(
                "positions",
                format!("length {} is not a multiple of 3", positions.len()),
            ));
        }
        if !indices.len().is_multiple_of(3) {
            return Err(BindError::argument(
                "indices",
                format!("length {} is not a multiple of 3", indices.len()),
            ));
        }
        if indices.is_empty() {
            return Err(BindError::argument("indices", "no triangle"));
        }
        if indices.len() / 3 > MAX_TRIANGLES {
            return Err(BindError::argument(
                "indices",
                format!("{} triangles, more than {MAX_TRIANGLES}", indices.len() / 3),
            ));
        }
        let count = positions.len() / 3;
        if let Some(k) = positions.iter().position(|v| !v.is_finite()) {
            return Err(BindError::argument(
                "positions",
                format!("vertex {} has a NaN or infinite coordinate", k / 3),
            ));
        }
        if let Some(k) = indices.iter().position(|&i| i as usize >= count) {
            return Err(BindError::argument(
                "indices",
                format!(
                    "triangle {} refers to vertex {}, but there are {count}",
                    k / 3,
                    indices[k]
                ),
            ));
        }
        Ok(Triangles {
            positions: positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2]))
                .collect(),
            triangles: indices
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect(),
        })
    }

    /// The triangles as a mesh for the sorters (face `i` is triangle `i`).
    pub fn polygon_mesh(&self) -> Result<PolygonMesh, BindError> {
        Ok(PolygonMesh::new(
            self.positions.iter().copied(),
            &self.triangles,
        )?)
    }

    /// The triangles as a model with one colour per face.
    pub fn coloured_model(&self, colours: &[u8]) -> Result<obj_quads::Mesh, BindError> {
        if colours.len() != 4 * self.triangles.len() {
            return Err(BindError::argument(
                "colours",
                format!(
                    "length {} is not 4 per triangle ({} triangles)",
                    colours.len(),
                    self.triangles.len()
                ),
            ));
        }
        let colours: Vec<[u8; 4]> = colours
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect();
        Ok(
            obj_quads::Mesh::from_faces(self.positions.clone(), &self.triangles)?
                .with_face_colours(&colours)?,
        )
    }
}

/// A column-major 4 × 4 matrix (three.js's `Matrix4.elements`).
fn matrix(elements: &[f64], what: &'static str) -> Result<DMat4, BindError> {
    if elements.len() != 16 {
        return Err(BindError::argument(
            what,
            format!("needs 16 numbers (column-major), got {}", elements.len()),
        ));
    }
    Ok(DMat4::from_cols_slice(elements))
}

/// Which faces are drawn: `"back"` culls back faces (three.js's `FrontSide`), `"front"`
/// culls front faces (`BackSide`), `"none"` draws both (`DoubleSide`).
pub fn cull_mode(cull: &str) -> Result<CullMode, BindError> {
    CullMode::from_name(cull).ok_or_else(|| {
        BindError::argument(
            "cull",
            format!("must be \"back\", \"front\" or \"none\", not {cull:?}"),
        )
    })
}

/// The view of `geometry` through a WebGL camera: its view matrix (world → camera,
/// `camera.matrixWorldInverse`) and projection matrix (clip depth in [−1, 1]), in a
/// `width` × `height` image.
pub fn view(
    geometry: &Geometry,
    view_matrix: &[f64],
    projection: &[f64],
    width: u32,
    height: u32,
    cull: CullMode,
) -> Result<View, BindError> {
    for (side, what) in [(width, "width"), (height, "height")] {
        if side == 0 || side > MAX_IMAGE_SIDE {
            return Err(BindError::argument(
                what,
                format!("must be in 1..={MAX_IMAGE_SIDE}, got {side}"),
            ));
        }
    }
    let camera = Camera::from_matrices(
        matrix(view_matrix, "view matrix")?,
        matrix(projection, "projection matrix")?,
        ClipSpace::MinusOneToOne,
    )?;
    let view = camera.view(geometry, width, height)?.with_cull(cull);
    geometry.check_view(&view)?;
    Ok(view)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_arrays_are_named() {
        let e = Triangles::new(&[0.0; 7], &[0, 1, 2]).unwrap_err();
        assert!(e.to_string().starts_with("positions: length 7"), "{e}");
        let e = Triangles::new(&[0.0; 9], &[0, 1, 3]).unwrap_err();
        assert!(
            e.to_string().contains("triangle 0 refers to vertex 3"),
            "{e}"
        );
        let e = Triangles::new(&[0.0, f64::NAN, 0.0], &[0, 0, 0]).unwrap_err();
        assert!(e.to_string().contains("vertex 0 has a NaN"), "{e}");
        let t = Triangles::new(&[0.0; 9], &[0, 1, 2]).unwrap();
        let e = t.coloured_model(&[1, 2, 3]).unwrap_err();
        assert!(e.to_string().starts_with("colours: length 3"), "{e}");
        assert!(cull_mode("sideways").is_err());
    }
}
