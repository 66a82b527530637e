//! The polygon mesh type.

use std::collections::BTreeMap;
use std::path::PathBuf;

use glam::{DVec3, Vec2};

use crate::LoadError;
use crate::limits::MESH_MAX_FACE_CORNERS;

/// A surface material: name, diffuse colour and optional diffuse texture.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Material {
    /// Material name (`newmtl` name, or glTF material name / `material N`).
    pub name: String,
    /// Diffuse colour, linear RGBA (OBJ `Kd` and `d`; glTF base colour factor).
    /// White when the file gives none.
    pub diffuse: [f32; 4],
    /// Diffuse texture file (OBJ `map_Kd`, resolved relative to the MTL file's
    /// directory; glTF base colour texture with a URI, resolved relative to the
    /// glTF file's directory). `None` for embedded images.
    pub texture: Option<PathBuf>,
    /// Diffuse texture held in the file itself (glTF data URI or GLB buffer view), encoded
    /// (PNG or JPEG), for `decode_texture`. `None` when the texture is a file or absent.
    pub embedded_texture: Option<EmbeddedTexture>,
    /// Whether the texture's texels are multiplied by [`diffuse`](Self::diffuse): glTF's base
    /// colour is `baseColorFactor × texture` (true); an OBJ's `Kd` is the colour of faces
    /// without a texture and leaves `map_Kd` as it is (false).
    pub texture_times_diffuse: bool,
    /// How the colour's alpha (the diffuse alpha times the texture's) is used: glTF's
    /// `alphaMode`; an OBJ's `d` blends.
    pub alpha_mode: AlphaMode,
    /// How the texture is sampled outside `[0, 1]` along u and v (glTF's sampler `wrapS`,
    /// `wrapT`; OBJ textures repeat).
    pub wrap: [WrapMode; 2],
}

/// How a texture is sampled at coordinates outside `[0, 1]` (glTF sampler wrap modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum WrapMode {
    /// The texture tiles (glTF `REPEAT`, the default).
    #[default]
    Repeat,
    /// The texture tiles, every other tile mirrored (glTF `MIRRORED_REPEAT`).
    MirroredRepeat,
    /// Coordinates clamp to the edge texels (glTF `CLAMP_TO_EDGE`).
    ClampToEdge,
}

/// How a material's alpha is used (glTF `alphaMode`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub enum AlphaMode {
    /// Alpha is ignored: the surface is opaque.
    Opaque,
    /// Alpha blends the surface over what is behind it (OBJ `d`, glTF `BLEND`).
    #[default]
    Blend,
    /// Alpha at or above `cutoff` is opaque, below it fully transparent (glTF `MASK`).
    Mask {
        /// The threshold, 0 to 1 (glTF's `alphaCutoff`, default 0.5).
        cutoff: f32,
    },
}

/// An encoded image held in a model file.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct EmbeddedTexture {
    /// Where it came from, for messages: e.g. `image 0 (buffer view 3)`.
    pub name: String,
    /// The encoded bytes (PNG or JPEG), shared by every material that uses it.
    pub bytes: std::sync::Arc<[u8]>,
}

impl EmbeddedTexture {
    /// An embedded image with a name for messages.
    pub fn new(name: impl Into<String>, bytes: impl Into<std::sync::Arc<[u8]>>) -> Self {
        EmbeddedTexture {
            name: name.into(),
            bytes: bytes.into(),
        }
    }
}

impl Material {
    /// A material with a name and diffuse colour and no texture.
    pub fn new(name: impl Into<String>, diffuse: [f32; 4]) -> Material {
        Material {
            name: name.into(),
            diffuse,
            texture: None,
            embedded_texture: None,
            texture_times_diffuse: false,
            alpha_mode: AlphaMode::Blend,
            wrap: [WrapMode::Repeat; 2],
        }
    }

    /// The same material with a diffuse texture path.
    pub fn with_texture(mut self, texture: impl Into<PathBuf>) -> Material {
        self.texture = Some(texture.into());
        self
    }
}

/// A polygon mesh: positions, faces of 3 or more corners in file order,
/// per-face material and optional per-corner texture coordinates.
///
/// Invariants (checked by every constructor): at least one face; every face
/// has 3 to 65536 corners; every index is in range; every position is finite;
/// material indices are in range; uvs, when present, have one entry per corner.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    positions: Vec<DVec3>,
    indices: Vec<u32>,
    /// `offsets[i]..offsets[i + 1]` is face `i` in `indices`.
    offsets: Vec<usize>,
    face_materials: Vec<Option<u32>>,
    face_sources: Vec<usize>,
    uvs: Option<Vec<Vec2>>,
    materials: Vec<Material>,
}

impl Mesh {
    /// Builds a mesh from positions and faces (lists of position indices),
    /// validating it. No material, no uvs; face `i` has source index `i`.
    ///
    /// Faces are taken as given: no planarity, convexity or degeneracy
    /// processing happens here.
    ///
    /// ```
    /// use glam::DVec3;
    /// use obj_quads::Mesh;
    /// let positions = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    /// let mesh = Mesh::from_faces(positions, [[0u32, 1, 2, 3]]).unwrap();
    /// assert_eq!(mesh.face(0), Some(&[0u32, 1, 2, 3][..]));
    /// assert!(Mesh::from_faces(vec![DVec3::ZERO], [[0u32, 0]]).is_err());
    /// ```
    pub fn from_faces<I, F>(positions: Vec<DVec3>, faces: I) -> Result<Mesh, LoadError>
    where
        I: IntoIterator<Item = F>,
        F: AsRef<[u32]>,
    {
        let mut indices = Vec::new();
        let mut offsets = vec![0];
        for face in faces {
            indices.extend_from_slice(face.as_ref());
            offsets.push(indices.len());
        }
        let count = offsets.len() - 1;
        let mesh = Mesh {
            positions,
            indices,
            offsets,
            face_materials: vec![None; count],
            face_sources: (0..count).collect(),
            uvs: None,
            materials: Vec::new(),
        };
        mesh.validate()?;
        Ok(mesh)
    }

    /// Sets the material list and one material index (or `None`) per face.
    pub fn with_materials(
        mut self,
        materials: Vec<Material>,
        face_materials: Vec<Option<u32>>,
    ) -> Result<Mesh, LoadError> {
        self.materials = materials;
        self.face_materials = face_materials;
        self.validate()?;
        Ok(self)
    }

    /// Paints face `i` in `colours[i]` (sRGB with straight alpha): one material per distinct
    /// colour, named `colour0`, `colour1`, … in order of first use. Errors as
    /// [`with_materials`](Self::with_materials) does, when `colours` is not one per face.
    ///
    /// ```
    /// use glam::DVec3;
    /// use obj_quads::Mesh;
    /// let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    /// let mesh = Mesh::from_faces(positions, [[0u32, 1, 2], [0, 1, 3], [0, 2, 3]]).unwrap();
    /// let red = [255, 0, 0, 255];
    /// let mesh = mesh.with_face_colours(&[red, [0, 0, 255, 128], red]).unwrap();
    /// assert_eq!(mesh.materials().len(), 2);
    /// ```
    pub fn with_face_colours(self, colours: &[[u8; 4]]) -> Result<Mesh, LoadError> {
        let mut materials: Vec<Material> = Vec::new();
        let mut slots = std::collections::HashMap::new();
        let face_materials = colours
            .iter()
            .map(|c| {
                let slot = *slots.entry(*c).or_insert_with(|| {
                    let diffuse = c.map(|v| f32::from(v) / 255.0);
                    materials.push(Material::new(format!("colour{}", materials.len()), diffuse));
                    materials.len() as u32 - 1
                });
                Some(slot)
            })
            .collect();
        self.with_materials(materials, face_materials)
    }

    /// Sets per-corner texture coordinates, parallel to the faces' corners
    /// (face 0's corners first, then face 1's, ...).
    pub fn with_uvs(mut self, uvs: Vec<Vec2>) -> Result<Mesh, LoadError> {
        self.uvs = Some(uvs);
        self.validate()?;
        Ok(self)
    }

    /// Assembles a mesh from raw parts (crate-internal), validating it.
    pub(crate) fn from_parts(
        positions: Vec<DVec3>,
        indices: Vec<u32>,
        offsets: Vec<usize>,
        face_materials: Vec<Option<u32>>,
        face_sources: Vec<usize>,
        uvs: Option<Vec<Vec2>>,
        materials: Vec<Material>,
    ) -> Result<Mesh, LoadError> {
        let mesh = Mesh {
            positions,
            indices,
            offsets,
            face_materials,
            face_sources,
            uvs,
            materials,
        };
        mesh.validate()?;
        Ok(mesh)
    }

    fn validate(&self) -> Result<(), LoadError> {
        let bad = |detail: String| Err(LoadError::InvalidMesh { detail });
        let faces = self.face_count();
        if faces == 0 {
            return bad("no faces".into());
        }
        if self.offsets.first() != Some(&0) || self.offsets.last() != Some(&self.indices.len()) {
            return bad("face offsets do not cover the index buffer".into());
        }
        for (i, w) in self.offsets.windows(2).enumerate() {
            let n = w[1].saturating_sub(w[0]);
            if w[1] < w[0] || !(3..=MESH_MAX_FACE_CORNERS).contains(&n) {
                return bad(format!(
                    "face {i} has {n} corners (need 3..={MESH_MAX_FACE_CORNERS})"
                ));
            }
        }
        if let Some((i, p)) = self
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite())
        {
            return bad(format!("position {i} is not finite: {p}"));
        }
        let n = self.positions.len();
        if let Some(k) = self.indices.iter().position(|&v| v as usize >= n) {
            let face = self.offsets.partition_point(|&o| o <= k).saturating_sub(1);
            return bad(format!(
                "face {face}: vertex index {} out of range ({n} positions)",
                self.indices[k]
            ));
        }
        if self.face_materials.len() != faces {
            return bad(format!(
                "{} face materials for {faces} faces",
                self.face_materials.len()
            ));
        }
        if self.face_sources.len() != faces {
            return bad("face source list has the wrong length".into());
        }
        let m = self.materials.len();
        if let Some(i) = self
            .face_materials
            .iter()
            .position(|fm| fm.is_some_and(|x| x as usize >= m))
        {
            return bad(format!(
                "face {i}: material index out of range ({m} materials)"
            ));
        }
        if let Some(uvs) = &self.uvs {
            if uvs.len() != self.indices.len() {
                return bad(format!(
                    "{} uvs for {} face corners",
                    uvs.len(),
                    self.indices.len()
                ));
            }
            if let Some(i) = uvs.iter().position(|uv| !uv.is_finite()) {
                return bad(format!("uv {i} is not finite"));
            }
        }
        Ok(())
    }

    /// Vertex positions in model space.
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Total number of face corners (length of the flat index buffer).
    pub fn corner_count(&self) -> usize {
        self.indices.len()
    }

    /// Corner range of face `i` in the flat index buffer.
    fn range(&self, i: usize) -> Option<std::ops::Range<usize>> {
        let start = *self.offsets.get(i)?;
        let end = *self.offsets.get(i.checked_add(1)?)?;
        Some(start..end)
    }

    /// The position indices of face `i`, in file order, or `None` if `i` is out of range.
    pub fn face(&self, i: usize) -> Option<&[u32]> {
        self.indices.get(self.range(i)?)
    }

    /// The corner positions of face `i`.
    pub fn face_positions(&self, i: usize) -> Option<impl Iterator<Item = DVec3> + '_> {
        let face = self.face(i)?;
        Some(
            face.iter()
                .filter_map(|&v| self.positions.get(v as usize).copied()),
        )
    }

    /// Iterates over the faces' position indices, in face order.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.offsets
            .windows(2)
            .map(|w| self.indices.get(w[0]..w[1]).unwrap_or(&[]))
    }

    /// The flat index buffer (all faces' corners, face after face).
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// Face start offsets into [`indices`](Self::indices); one more entry than faces.
    pub fn offsets(&self) -> &[usize] {
        &self.offsets
    }

    /// The material index of face `i` (into [`materials`](Self::materials)).
    /// `None` when the face has no material or `i` is out of range.
    pub fn face_material(&self, i: usize) -> Option<u32> {
        self.face_materials.get(i).copied().flatten()
    }

    /// The index, in file order, of the input face that face `i` came from.
    /// Faces split from one input face share it; a merged triangle pair has
    /// the lower of its two indices.
    pub fn face_source(&self, i: usize) -> Option<usize> {
        self.face_sources.get(i).copied()
    }

    /// Per-corner texture coordinates of face `i`, if the mesh has uvs.
    pub fn face_uvs(&self, i: usize) -> Option<&[Vec2]> {
        self.uvs.as_ref()?.get(self.range(i)?)
    }

    /// All per-corner texture coordinates, parallel to [`indices`](Self::indices).
    pub fn uvs(&self) -> Option<&[Vec2]> {
        self.uvs.as_deref()
    }

    /// The materials faces refer to.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// How many faces have each corner count, e.g. `{3: 32, 4: 468}`.
    pub fn arity_histogram(&self) -> BTreeMap<usize, usize> {
        let mut hist = BTreeMap::new();
        for w in self.offsets.windows(2) {
            *hist.entry(w[1].saturating_sub(w[0])).or_insert(0) += 1;
        }
        hist
    }

    /// Normal of face `i` by Newell's method (not normalised; length is twice
    /// the area for a planar face).
    pub fn face_normal(&self, i: usize) -> Option<DVec3> {
        let pts: Vec<DVec3> = self.face_positions(i)?.collect();
        Some(crate::geometry::newell(&pts))
    }

    /// Axis-aligned bounding box of the positions used by faces, as `(min, max)`.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let mut min = DVec3::splat(f64::INFINITY);
        let mut max = DVec3::splat(f64::NEG_INFINITY);
        for &v in &self.indices {
            if let Some(&p) = self.positions.get(v as usize) {
                min = min.min(p);
                max = max.max(p);
            }
        }
        (min, max)
    }
}
