//! glTF 2.0 / GLB loading through the `gltf` crate.
//!
//! The document is parsed and validated by `gltf`; buffers are loaded here
//! (external files with a size cap, data URIs decoded here), so no URI can
//! make the loader panic or read an unbounded stream. Accessors are checked
//! against their buffers before `gltf`'s readers touch them.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use glam::{DMat4, DVec3, Vec2};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use gltf::{Accessor, Document, Node, Semantic};

use crate::build::{RawMesh, finish};
use crate::error::FaceLocation;
use crate::{LoadError, LoadOptions, LoadReport, Material, Mesh};

/// Deepest node hierarchy walked (deeper means a cycle or an absurd file).
const MAX_NODE_DEPTH: usize = 64;
/// Most node visits in one scene walk (shared subtrees are walked once per use).
const MAX_NODE_VISITS: usize = 1 << 16;

/// Loads a `.gltf` (external buffers resolved relative to its directory) or
/// `.glb` file.
///
/// Every primitive in `Triangles` mode of every node of the default scene
/// (or scene 0, or all root nodes when there is no scene) is loaded with its
/// node's world transform applied; other modes are skipped with a warning.
pub fn load_gltf(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let path = path.as_ref();
    let file = path.display().to_string();
    let bytes = crate::read_file_capped(path, &file, options.max_file_bytes)?;
    load_gltf_bytes(
        &bytes,
        file,
        Some(path.parent().unwrap_or(Path::new(""))),
        options,
    )
}

/// Loads glTF JSON or GLB bytes from memory. Buffers must be embedded (GLB
/// binary chunk or data URIs); texture URIs are recorded as given.
pub fn load_gltf_slice(
    bytes: &[u8],
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    load_gltf_bytes(bytes, crate::obj_memory_name(), None, options)
}

fn gltf_err(file: &str, detail: impl Into<String>) -> LoadError {
    LoadError::Gltf {
        file: file.to_owned(),
        detail: detail.into(),
    }
}

fn load_gltf_bytes(
    bytes: &[u8],
    file: String,
    base: Option<&Path>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let parsed = catch_unwind(|| gltf::Gltf::from_slice_without_validation(bytes))
        .map_err(|_| gltf_err(&file, "the glTF parser panicked on this input"))?;
    let gltf::Gltf { document, blob } = parsed.map_err(|e| gltf_err(&file, e.to_string()))?;
    // gltf-json's validation indexes the POSITION accessor unchecked: check first.
    let root = document.as_json();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let key = gltf::json::validation::Checked::Valid(gltf::json::mesh::Semantic::Positions);
            if prim
                .attributes
                .get(&key)
                .is_some_and(|a| a.value() >= root.accessors.len())
            {
                return Err(gltf_err(
                    &file,
                    format!("mesh {m} primitive {p}: POSITION accessor does not exist"),
                ));
            }
        }
    }
    let json = document.into_json();
    let document = catch_unwind(AssertUnwindSafe(|| gltf::Document::from_json(json)))
        .map_err(|_| gltf_err(&file, "the glTF validator panicked on this input"))?
        .map_err(|e| gltf_err(&file, e.to_string()))?;
    let buffers = load_buffers(&document, blob, base, &file, options)?;
    let mut raw = RawMesh::new(file);
    raw.materials = materials(&document, base, &mut raw.report.warnings);
    let instances = walk_scene(&document, &raw.file)?;
    let mut uvs_complete = true;
    let mut any_uvs = false;
    let mut uvs: Vec<Vec2> = Vec::new();
    for (node, world) in instances {
        let Some(mesh) = node.mesh() else { continue };
        let flip = world.determinant() < 0.0;
        for prim in mesh.primitives() {
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
                continue;
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
                &buffers,
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
                    &buffers,
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
                    &buffers,
                    "TEXCOORD_0",
                )?;
            }
            let read = catch_unwind(AssertUnwindSafe(|| {
                let reader = prim.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
                let positions: Option<Vec<[f32; 3]>> =
                    reader.read_positions().map(Iterator::collect);
                let indices: Option<Vec<u32>> =
                    reader.read_indices().map(|i| i.into_u32().collect());
                let tex: Option<Vec<[f32; 2]>> =
                    reader.read_tex_coords(0).map(|t| t.into_f32().collect());
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
            any_uvs |= tex.is_some();
            uvs_complete &= tex.is_some();
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
                        uvs.push(Vec2::from_array(uv));
                    }
                }
                raw.offsets.push(raw.indices.len());
                raw.face_materials.push(material);
                raw.face_objects.push(object_id);
                raw.face_lines.push(None);
            }
        }
    }
    if any_uvs && !uvs_complete {
        raw.report
            .warnings
            .push("TEXCOORD_0 missing on some primitives: uvs dropped".into());
    }
    if uvs_complete && any_uvs {
        if uvs.iter().all(|uv| uv.is_finite()) {
            raw.uvs = Some(uvs);
        } else {
            raw.report
                .warnings
                .push("non-finite texture coordinates: uvs dropped".into());
        }
    }
    if raw.face_count() == 0 {
        return Err(LoadError::EmptyModel {
            file: raw.file,
            detail: format!(
                "no triangles in the scene ({} primitives skipped)",
                raw.report.skipped_primitives
            ),
        });
    }
    finish(raw, options)
}

/// File and object for error messages about one primitive.
struct Ctx<'a> {
    file: &'a str,
    object: &'a str,
}

impl Ctx<'_> {
    fn err(&self, detail: &str) -> LoadError {
        gltf_err(self.file, format!("{}: {detail}", self.object))
    }

    /// Checks an accessor's type and that it lies inside its buffer view and
    /// buffer, so that `gltf`'s readers cannot fail or panic on it.
    fn check(
        &self,
        acc: &Accessor<'_>,
        dims: Dimensions,
        types: &[DataType],
        buffers: &[Vec<u8>],
        what: &str,
    ) -> Result<(), LoadError> {
        let fail =
            |detail: String| Err(self.err(&format!("{what} accessor {}: {detail}", acc.index())));
        if acc.dimensions() != dims || !types.contains(&acc.data_type()) {
            return fail(format!(
                "unsupported type {:?} {:?}",
                acc.dimensions(),
                acc.data_type()
            ));
        }
        if acc.sparse().is_some() {
            return fail("sparse accessors are not supported".into());
        }
        let count = acc.count();
        if count == 0 {
            return fail("count is 0".into());
        }
        let Some(view) = acc.view() else {
            return fail("no buffer view".into());
        };
        let elem = acc.size();
        let stride = view.stride().unwrap_or(elem);
        if stride < elem {
            return fail(format!("stride {stride} smaller than element size {elem}"));
        }
        let end = stride
            .checked_mul(count - 1)
            .and_then(|x| x.checked_add(elem))
            .and_then(|x| x.checked_add(acc.offset()));
        if end.is_none_or(|end| end > view.length()) {
            return fail("overruns its buffer view".into());
        }
        let view_end = view.offset().checked_add(view.length());
        let buffer_len = buffers.get(view.buffer().index()).map_or(0, Vec::len);
        if view_end.is_none_or(|e| e > buffer_len) {
            return fail("buffer view overruns its buffer".into());
        }
        Ok(())
    }
}

/// Loads every buffer: GLB binary chunk, data URI, or external file.
fn load_buffers(
    doc: &Document,
    mut blob: Option<Vec<u8>>,
    base: Option<&Path>,
    file: &str,
    options: &LoadOptions,
) -> Result<Vec<Vec<u8>>, LoadError> {
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let which = format!("buffer {}", buffer.index());
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob
                .take()
                .ok_or_else(|| gltf_err(file, format!("{which}: GLB binary chunk missing")))?,
            gltf::buffer::Source::Uri(uri) => {
                if let Some(rest) = uri.strip_prefix("data:") {
                    let Some((_, payload)) = rest.split_once(";base64,") else {
                        return Err(gltf_err(file, format!("{which}: data URI is not base64")));
                    };
                    base64_decode(payload)
                        .ok_or_else(|| gltf_err(file, format!("{which}: bad base64 in data URI")))?
                } else {
                    let path = resolve_uri(uri, base)
                        .map_err(|e| gltf_err(file, format!("{which}: {e}")))?;
                    if base.is_none() {
                        return Err(gltf_err(
                            file,
                            format!(
                                "{which}: external buffer `{uri}` cannot be loaded from memory"
                            ),
                        ));
                    }
                    let shown = path.display().to_string();
                    crate::read_file_capped(&path, &shown, options.max_file_bytes)?
                }
            }
        };
        if data.len() < buffer.length() {
            return Err(gltf_err(
                file,
                format!(
                    "{which}: {} bytes, declared {}",
                    data.len(),
                    buffer.length()
                ),
            ));
        }
        out.push(data);
    }
    Ok(out)
}

/// Resolves a relative URI (percent-decoded) against `base`.
fn resolve_uri(uri: &str, base: Option<&Path>) -> Result<PathBuf, String> {
    let path = if let Some(rest) = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))
    {
        rest
    } else if uri.contains(':') {
        return Err(format!("unsupported URI scheme in `{uri}`"));
    } else {
        uri
    };
    let decoded = percent_decode(path).ok_or_else(|| format!("bad percent-encoding in `{uri}`"))?;
    Ok(match base {
        Some(base) => base.join(decoded),
        None => PathBuf::from(decoded),
    })
}

/// Percent-decodes a URI path; `None` if the result is not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if b == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok());
            if let Some(v) = hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                out.push(v);
                i += 3;
                continue;
            }
        }
        out.push(b);
        i += 1;
    }
    String::from_utf8(out).ok()
}

/// Decodes standard base64 (padding optional); `None` on a bad character.
fn base64_decode(s: &str) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    let mut acc: u32 = 0;
    let mut bits = 0;
    for c in s.bytes() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => break,
            _ => return None,
        };
        acc = (acc << 6) | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

/// Materials in document order: base colour factor and texture.
fn materials(doc: &Document, base: Option<&Path>, warnings: &mut Vec<String>) -> Vec<Material> {
    doc.materials()
        .map(|m| {
            let index = m.index().unwrap_or(0);
            let name = m
                .name()
                .map_or_else(|| format!("material {index}"), str::to_owned);
            let pbr = m.pbr_metallic_roughness();
            let mut diffuse = pbr.base_color_factor();
            if diffuse.iter().any(|c| !c.is_finite()) {
                warnings.push(format!(
                    "material `{name}`: non-finite colour replaced by white"
                ));
                diffuse = [1.0; 4];
            }
            let mut material = Material::new(name, diffuse);
            if let Some(info) = pbr.base_color_texture() {
                match info.texture().source().source() {
                    gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                        match resolve_uri(uri, base) {
                            Ok(path) => material.texture = Some(path),
                            Err(e) => {
                                warnings.push(format!("material `{}`: texture {e}", material.name))
                            }
                        }
                    }
                    _ => warnings.push(format!(
                        "material `{}`: base colour texture is embedded; no path recorded",
                        material.name
                    )),
                }
            }
            material
        })
        .collect()
}

/// Mesh-carrying node instances of the scene, depth first, with world matrices.
fn walk_scene<'a>(doc: &'a Document, file: &str) -> Result<Vec<(Node<'a>, DMat4)>, LoadError> {
    let roots: Vec<Node<'a>> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let mut is_child = vec![false; doc.nodes().len()];
            for node in doc.nodes() {
                for child in node.children() {
                    if let Some(c) = is_child.get_mut(child.index()) {
                        *c = true;
                    }
                }
            }
            doc.nodes()
                .filter(|n| !is_child.get(n.index()).copied().unwrap_or(true))
                .collect()
        }
    };
    let mut out = Vec::new();
    let mut path = Vec::new();
    let mut visits = 0usize;
    for root in roots {
        visit(
            root,
            DMat4::IDENTITY,
            &mut path,
            &mut visits,
            &mut out,
            file,
        )?;
    }
    Ok(out)
}

fn visit<'a>(
    node: Node<'a>,
    parent: DMat4,
    path: &mut Vec<usize>,
    visits: &mut usize,
    out: &mut Vec<(Node<'a>, DMat4)>,
    file: &str,
) -> Result<(), LoadError> {
    if path.contains(&node.index()) {
        return Err(gltf_err(
            file,
            format!("node {} is its own ancestor (cycle)", node.index()),
        ));
    }
    if path.len() >= MAX_NODE_DEPTH {
        return Err(gltf_err(
            file,
            format!(
                "node hierarchy deeper than {MAX_NODE_DEPTH} at node {}",
                node.index()
            ),
        ));
    }
    *visits += 1;
    if *visits > MAX_NODE_VISITS {
        return Err(LoadError::TooLarge {
            file: file.to_owned(),
            what: "node visits in the scene walk",
            actual: *visits as u64,
            limit: MAX_NODE_VISITS as u64,
        });
    }
    let local = node.transform().matrix();
    let local = DMat4::from_cols_array_2d(&local.map(|c| c.map(f64::from)));
    if !local.is_finite() {
        return Err(gltf_err(
            file,
            format!("node {} has a non-finite transform", node.index()),
        ));
    }
    let world = parent * local;
    if node.mesh().is_some() {
        out.push((node.clone(), world));
    }
    path.push(node.index());
    for child in node.children() {
        visit(child, world, path, visits, out, file)?;
    }
    path.pop();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trip() {
        assert_eq!(base64_decode("aGVsbG8=").as_deref(), Some(&b"hello"[..]));
        assert_eq!(base64_decode("aGVsbG8").as_deref(), Some(&b"hello"[..]));
        assert!(base64_decode("a*").is_none());
    }

    #[test]
    fn percent_decoding() {
        assert_eq!(percent_decode("a%20b").as_deref(), Some("a b"));
        assert_eq!(percent_decode("100%").as_deref(), Some("100%"));
        assert!(percent_decode("%FF").is_none());
    }
}
