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
    let data = {
        let ctx = Ctx {
            file: &raw.file,
            object: &object,
        };
        let checked = check(raw, &ctx, prim, buffers, options)?;
        read(&ctx, prim, buffers, &checked)?
    };
    let base_index = raw.positions.len() as u32;
    push_positions(raw, &object, node.index(), world, &data.positions)?;
    if data.indices.len() % 3 != 0 {
        raw.report.warnings.push(format!(
            "{object}: {} indices is not a multiple of 3; the last {} ignored",
            data.indices.len(),
            data.indices.len() % 3
        ));
    }
    if data.tex_unreadable {
        raw.report
            .warnings
            .push(format!("{object}: TEXCOORD_0 cannot be read"));
    }
    uvs.any |= data.tex.is_some();
    uvs.complete &= data.tex.is_some();
    let object_id = raw.objects.len() as u32;
    raw.objects
        .push(format!("{object} (node {})", node.index()));
    let triangles = Triangles {
        object: &object,
        object_id,
        material: prim.material().index().map(|m| m as u32),
        flip: world.determinant() < 0.0,
        base_index,
    };
    triangles.push(raw, uvs, &data)
}

/// What [`check`] found valid: the vertex count, the corner count, and which optional
/// accessors are present.
struct Checked<'a> {
    count: usize,
    corner_count: usize,
    indices: Option<Accessor<'a>>,
    tex: Option<Accessor<'a>>,
}

/// Checks the primitive's accessors against their buffers (types, dimensions, ranges) and
/// the vertex and face counts against the limits, before anything is read.
fn check<'a>(
    raw: &RawMesh,
    ctx: &Ctx<'_>,
    prim: &Primitive<'a>,
    buffers: &[Vec<u8>],
    options: &LoadOptions,
) -> Result<Checked<'a>, LoadError> {
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
    let total = raw.positions.len().saturating_add(count);
    if total > options.max_vertices || total > u32::MAX as usize {
        return Err(LoadError::TooLarge {
            file: raw.file.clone(),
            what: "vertex count",
            actual: total as u64,
            limit: options.max_vertices.min(u32::MAX as usize) as u64,
        });
    }
    let indices = prim.indices();
    if let Some(acc) = &indices {
        ctx.check(
            acc,
            Dimensions::Scalar,
            &[DataType::U8, DataType::U16, DataType::U32],
            buffers,
            "indices",
        )?;
    }
    let corner_count = indices.as_ref().map_or(count, Accessor::count);
    let faces_total = raw.face_count().saturating_add(corner_count / 3);
    if faces_total > options.max_faces {
        return Err(LoadError::TooLarge {
            file: raw.file.clone(),
            what: "face count",
            actual: faces_total as u64,
            limit: options.max_faces as u64,
        });
    }
    let tex = prim.get(&Semantic::TexCoords(0));
    if let Some(acc) = &tex {
        ctx.check(
            acc,
            Dimensions::Vec2,
            &[DataType::F32, DataType::U8, DataType::U16],
            buffers,
            "TEXCOORD_0",
        )?;
    }
    Ok(Checked {
        count,
        corner_count,
        indices,
        tex,
    })
}

/// A primitive's data as read: positions, corner indices (`0..count` when it has no index
/// accessor) and uvs when readable.
struct Read {
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
    tex: Option<Vec<[f32; 2]>>,
    /// The primitive has a TEXCOORD_0 accessor that could not be read.
    tex_unreadable: bool,
}

/// Reads the checked accessors (gltf's reader, under `catch_unwind`: a panic there is a
/// typed error) and checks their lengths.
fn read(
    ctx: &Ctx<'_>,
    prim: &Primitive<'_>,
    buffers: &[Vec<u8>],
    checked: &Checked<'_>,
) -> Result<Read, LoadError> {
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
    let count = checked.count;
    let Some(positions) = positions.filter(|p| p.len() == count) else {
        return Err(ctx.err("POSITION accessor cannot be read (it overruns its buffer?)"));
    };
    let indices = match (checked.indices.is_some(), indices) {
        (true, Some(i)) if i.len() == checked.corner_count => i,
        (true, _) => return Err(ctx.err("indices accessor cannot be read")),
        (false, _) => (0..count as u32).collect(),
    };
    let tex = tex.filter(|t| t.len() == count);
    Ok(Read {
        positions,
        indices,
        tex_unreadable: checked.tex.is_some() && tex.is_none(),
        tex,
    })
}

/// Appends positions under the node's `world` matrix; a non-finite result is an error
/// naming the vertex.
fn push_positions(
    raw: &mut RawMesh,
    object: &str,
    node: usize,
    world: DMat4,
    positions: &[[f32; 3]],
) -> Result<(), LoadError> {
    for (k, p) in positions.iter().enumerate() {
        let p = world.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
        if !p.is_finite() {
            return Err(LoadError::NonFiniteCoordinate {
                file: raw.file.clone(),
                line: None,
                what: format!("{object} vertex {k} (node {node})"),
            });
        }
        raw.positions.push(p);
    }
    Ok(())
}

/// How one primitive's triangles join the mesh.
struct Triangles<'a> {
    object: &'a str,
    object_id: u32,
    material: Option<u32>,
    /// The node mirrors (negative determinant): triangles are clockwise-front, so their
    /// winding is reversed (glTF spec).
    flip: bool,
    /// Index of the primitive's first vertex in the mesh.
    base_index: u32,
}

impl Triangles<'_> {
    /// Appends every whole triangle of `data`, checking each index against the vertex count.
    fn push(&self, raw: &mut RawMesh, uvs: &mut Uvs, data: &Read) -> Result<(), LoadError> {
        let count = data.positions.len();
        for tri in data.indices.chunks_exact(3) {
            let face = raw.face_count();
            if let Some(&i) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(LoadError::IndexOutOfRange {
                    file: raw.file.clone(),
                    at: FaceLocation {
                        object: self.object.to_owned(),
                        face,
                        line: None,
                    },
                    index: i64::from(i),
                    count,
                });
            }
            let order = if self.flip {
                [tri[0], tri[2], tri[1]]
            } else {
                [tri[0], tri[1], tri[2]]
            };
            for i in order {
                raw.indices.push(self.base_index + i);
                if let Some(t) = &data.tex {
                    let uv = t.get(i as usize).copied().unwrap_or([0.0; 2]);
                    uvs.uvs.push(Vec2::from_array(uv));
                }
            }
            raw.offsets.push(raw.indices.len());
            raw.face_materials.push(self.material);
            raw.face_objects.push(self.object_id);
            raw.face_lines.push(None);
        }
        Ok(())
    }
}
