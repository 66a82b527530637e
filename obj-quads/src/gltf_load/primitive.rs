//! One primitive of one node instance: accessors checked, read, transformed
//! and appended to the mesh under construction.

use std::panic::{AssertUnwindSafe, catch_unwind};

use glam::{DMat4, DVec3, Vec2};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use gltf::{Accessor, Node, Primitive, Semantic};

use super::accessor::Ctx;
use crate::build::RawMesh;
use crate::error::FaceLocation;
use crate::{LoadError, LoadOptions};

/// Texture coordinates gathered across primitives; kept only when every
/// loaded primitive has them.
pub(super) struct Uvs {
    uvs: Vec<Vec2>,
    any: bool,
    complete: bool,
}

impl Default for Uvs {
    fn default() -> Self {
        Uvs {
            uvs: Vec::new(),
            any: false,
            complete: true,
        }
    }
}

impl Uvs {
    /// Hands the uvs to the mesh when every primitive had finite ones.
    pub(super) fn finish(self, raw: &mut RawMesh) {
        if self.any && !self.complete {
            raw.report
                .warnings
                .push("TEXCOORD_0 missing on some primitives: uvs dropped".into());
        }
        if self.complete && self.any {
            if self.uvs.iter().all(|uv| uv.is_finite()) {
                raw.uvs = Some(self.uvs);
            } else {
                raw.report
                    .warnings
                    .push("non-finite texture coordinates: uvs dropped".into());
            }
        }
    }
}

/// Appends the triangles of `prim` (a primitive of `node`'s mesh) under the
/// node's `world` matrix, checking limits and accessors first. Primitives
/// whose mode is not `Triangles` are skipped with a warning.
pub(super) fn append(
    raw: &mut RawMesh,
    uvs: &mut Uvs,
    node: &Node<'_>,
    world: DMat4,
    prim: &Primitive<'_>,
    buffers: &[Vec<u8>],
    options: &LoadOptions,
) -> Result<(), LoadError> {
    let Some(mesh) = node.mesh() else {
        return Ok(());
    };
    let flip = world.determinant() < 0.0;
    let object = match mesh.name() {
        Some(name) => format!("mesh {} `{name}` primitive {}", mesh.index(), prim.index()),
        None => format!("mesh {} primitive {}", mesh.index(), prim.index()),
    };
    if prim.mode() != Mode::Triangles {
        raw.report.skipped_primitives += 1;
        raw.report.warnings.push(format!(
            "{object} (node {}): mode {:?} skipped, only Triangles is loaded",
            node.index(),
            prim.mode()
        ));
        return Ok(());
    }
    let ctx = Ctx {
        file: &raw.file,
        object: &object,
    };
    let Some(pos_acc) = prim.get(&Semantic::Positions) else {
        return Err(ctx.err("primitive has no POSITION attribute"));
    };
    ctx.check(
        &pos_acc,
        Dimensions::Vec3,
        &[DataType::F32],
        buffers,
        "POSITION",
    )?;
    let count = pos_acc.count();
    let base_index = raw.positions.len();
    let total = base_index.saturating_add(count);
    if total > options.max_vertices || total > u32::MAX as usize {
        return Err(LoadError::TooLarge {
            file: raw.file.clone(),
            what: "vertex count",
            actual: total as u64,
            limit: options.max_vertices.min(u32::MAX as usize) as u64,
        });
    }
    let index_acc = prim.indices();
    if let Some(acc) = &index_acc {
        ctx.check(
            acc,
            Dimensions::Scalar,
            &[DataType::U8, DataType::U16, DataType::U32],
            buffers,
            "indices",
        )?;
    }
    let corner_count = index_acc.as_ref().map_or(count, Accessor::count);
    let faces_total = raw.face_count().saturating_add(corner_count / 3);
    if faces_total > options.max_faces {
        return Err(LoadError::TooLarge {
            file: raw.file.clone(),
            what: "face count",
            actual: faces_total as u64,
            limit: options.max_faces as u64,
        });
    }
    let tex_acc = prim.get(&Semantic::TexCoords(0));
    if let Some(acc) = &tex_acc {
        ctx.check(
            acc,
            Dimensions::Vec2,
            &[DataType::F32, DataType::U8, DataType::U16],
            buffers,
            "TEXCOORD_0",
        )?;
    }
    let read = catch_unwind(AssertUnwindSafe(|| {
        let reader = prim.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let positions: Option<Vec<[f32; 3]>> = reader.read_positions().map(Iterator::collect);
        let indices: Option<Vec<u32>> = reader.read_indices().map(|i| i.into_u32().collect());
        let tex: Option<Vec<[f32; 2]>> = reader.read_tex_coords(0).map(|t| t.into_f32().collect());
        (positions, indices, tex)
    }));
    let Ok((positions, indices, tex)) = read else {
        return Err(ctx.err("reading the primitive's accessors panicked"));
    };
    let Some(positions) = positions.filter(|p| p.len() == count) else {
        return Err(ctx.err("POSITION accessor cannot be read (it overruns its buffer?)"));
    };
    for (k, p) in positions.iter().enumerate() {
        let p = world.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
        if !p.is_finite() {
            return Err(LoadError::NonFiniteCoordinate {
                file: raw.file.clone(),
                line: None,
                what: format!("{object} vertex {k} (node {})", node.index()),
            });
        }
        raw.positions.push(p);
    }
    let indices = match (index_acc.is_some(), indices) {
        (true, Some(i)) if i.len() == corner_count => i,
        (true, _) => return Err(ctx.err("indices accessor cannot be read")),
        (false, _) => (0..count as u32).collect(),
    };
    if indices.len() % 3 != 0 {
        raw.report.warnings.push(format!(
            "{object}: {} indices is not a multiple of 3; the last {} ignored",
            indices.len(),
            indices.len() % 3
        ));
    }
    let tex = tex.filter(|t| t.len() == count);
    if tex_acc.is_some() && tex.is_none() {
        raw.report
            .warnings
            .push(format!("{object}: TEXCOORD_0 cannot be read"));
    }
    uvs.any |= tex.is_some();
    uvs.complete &= tex.is_some();
    let object_id = raw.objects.len() as u32;
    raw.objects
        .push(format!("{object} (node {})", node.index()));
    let material = prim.material().index().map(|m| m as u32);
    for tri in indices.chunks_exact(3) {
        let face = raw.face_count();
        for &i in tri {
            if i as usize >= count {
                return Err(LoadError::IndexOutOfRange {
                    file: raw.file.clone(),
                    at: FaceLocation {
                        object: object.clone(),
                        face,
                        line: None,
                    },
                    index: i as i64,
                    count,
                });
            }
        }
        let order = if flip {
            [tri[0], tri[2], tri[1]]
        } else {
            [tri[0], tri[1], tri[2]]
        };
        for i in order {
            raw.indices.push(base_index as u32 + i);
            if let Some(t) = &tex {
                let uv = t.get(i as usize).copied().unwrap_or([0.0; 2]);
                uvs.uvs.push(Vec2::from_array(uv));
            }
        }
        raw.offsets.push(raw.indices.len());
        raw.face_materials.push(material);
        raw.face_objects.push(object_id);
        raw.face_lines.push(None);
    }
    Ok(())
}
