//! glTF 2.0 / GLB loading through the `gltf` crate.
//!
//! The document is parsed and validated by `gltf` ([`parse`]); buffers are
//! loaded here ([`buffers`]: external files confined to the model's folder
//! and size-capped, data URIs decoded with `base64`), so no URI can make the
//! loader panic, read outside the folder or read an unbounded stream.
//! Accessors are checked against their buffers ([`accessor`]) before `gltf`'s
//! readers touch them ([`primitive`]); the scene walk ([`scene`]) bounds node
//! depth and visits and refuses cycles.

mod accessor;
mod buffers;
mod materials;
mod primitive;
mod scene;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use crate::build::{RawMesh, finish};
use crate::paths::Folder;
use crate::{LoadError, LoadOptions, LoadReport, Mesh};

/// Loads a `.gltf` (external buffers resolved relative to its directory) or
/// `.glb` file.
///
/// Every primitive in `Triangles` mode of every node of the default scene
/// (or scene 0, or all root nodes when there is no scene) is loaded with its
/// node's world transform applied; other modes are skipped with a warning.
///
/// Buffer and image URIs must resolve inside the file's folder (after `..`,
/// symbolic links and absolute paths) unless
/// [`LoadOptions::allow_outside_paths`] is set: a buffer outside is a
/// [`LoadError::PathOutsideModel`], an image outside is dropped with a warning.
pub fn load_gltf(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let (bytes, file, folder) = read_file(path.as_ref(), options)?;
    load_gltf_bytes(&bytes, file, Some(&folder), options)
}

/// A glTF file's bytes (size-capped), its display name, and its folder (the confinement of
/// the files it names).
fn read_file(path: &Path, options: &LoadOptions) -> Result<(Vec<u8>, String, Folder), LoadError> {
    let file = path.display().to_string();
    let bytes = crate::read_file_capped(path, &file, options.max_file_bytes)?;
    let folder = Folder::new(
        path.parent().unwrap_or(Path::new("")),
        options.allow_outside_paths,
    );
    Ok((bytes, file, folder))
}

/// Loads glTF JSON or GLB bytes from memory. Buffers must be embedded (GLB
/// binary chunk or data URIs). In-memory input has no folder, so texture URIs
/// are dropped with a warning, unless [`LoadOptions::allow_outside_paths`] is
/// set, which records them as given.
pub fn load_gltf_slice(
    bytes: &[u8],
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    load_gltf_bytes(bytes, crate::obj_memory_name(), None, options)
}

/// A [`LoadError::Gltf`].
fn gltf_err(file: &str, detail: impl Into<String>) -> LoadError {
    LoadError::Gltf {
        file: file.to_owned(),
        detail: detail.into(),
    }
}

/// Parses and validates the document, guarding `gltf`'s known panics.
fn parse(bytes: &[u8], file: &str) -> Result<(gltf::Document, Option<Vec<u8>>), LoadError> {
    let parsed = catch_unwind(|| gltf::Gltf::from_slice_without_validation(bytes))
        .map_err(|_| gltf_err(file, "the glTF parser panicked on this input"))?;
    let gltf::Gltf { document, blob } = parsed.map_err(|e| gltf_err(file, e.to_string()))?;
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
                    file,
                    format!("mesh {m} primitive {p}: POSITION accessor does not exist"),
                ));
            }
        }
    }
    let json = document.into_json();
    let document = catch_unwind(AssertUnwindSafe(|| gltf::Document::from_json(json)))
        .map_err(|_| gltf_err(file, "the glTF validator panicked on this input"))?
        .map_err(|e| gltf_err(file, e.to_string()))?;
    Ok((document, blob))
}

/// A camera of a glTF file, placed by the node that carries it.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GltfCamera {
    /// The camera's index in the document (`cameras[i]`).
    pub camera: usize,
    /// The node that carries it.
    pub node: usize,
    /// The camera's name, if it has one.
    pub name: Option<String>,
    /// Camera to model space: the node's matrix times its ancestors' (the model space of
    /// [`load_gltf`]'s positions). The camera looks down its −Z with +Y up.
    pub world: glam::DMat4,
    /// Its projection, as the file gives it.
    pub projection: GltfProjection,
}

/// A glTF camera's projection, with the file's values (angles in radians, as glTF has them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GltfProjection {
    /// `camera.perspective`.
    Perspective {
        /// Vertical field of view, radians.
        yfov: f64,
        /// Width ÷ height, when the file gives it (else the viewport's).
        aspect_ratio: Option<f64>,
        /// Near plane distance.
        znear: f64,
        /// Far plane distance; `None` for an infinite projection.
        zfar: Option<f64>,
    },
    /// `camera.orthographic`.
    Orthographic {
        /// Half the width the view spans.
        xmag: f64,
        /// Half the height the view spans.
        ymag: f64,
        /// Near plane distance.
        znear: f64,
        /// Far plane distance.
        zfar: f64,
    },
}

/// The cameras of a `.gltf` or `.glb` file: one per node of the scene that carries a camera,
/// in the scene walk's order (the order of [`load_gltf`]'s faces), with the same
/// confinement, limits and errors as [`load_gltf`] (buffers are not read).
pub fn load_gltf_cameras(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<Vec<GltfCamera>, LoadError> {
    let (bytes, file, _) = read_file(path.as_ref(), options)?;
    cameras_of(&bytes, &file, options)
}

/// [`load_gltf_cameras`] from memory.
pub fn load_gltf_cameras_slice(
    bytes: &[u8],
    options: &LoadOptions,
) -> Result<Vec<GltfCamera>, LoadError> {
    cameras_of(bytes, crate::obj_memory_name().as_str(), options)
}

fn cameras_of(
    bytes: &[u8],
    file: &str,
    options: &LoadOptions,
) -> Result<Vec<GltfCamera>, LoadError> {
    let (document, _) = parse(bytes, file)?;
    let walked = scene::walk_scene(&document, file, options)?;
    Ok(walked
        .iter()
        .filter_map(|(node, world)| {
            let camera = node.camera()?;
            let projection = match camera.projection() {
                gltf::camera::Projection::Perspective(p) => GltfProjection::Perspective {
                    yfov: f64::from(p.yfov()),
                    aspect_ratio: p.aspect_ratio().map(f64::from),
                    znear: f64::from(p.znear()),
                    zfar: p.zfar().map(f64::from),
                },
                gltf::camera::Projection::Orthographic(o) => GltfProjection::Orthographic {
                    xmag: f64::from(o.xmag()),
                    ymag: f64::from(o.ymag()),
                    znear: f64::from(o.znear()),
                    zfar: f64::from(o.zfar()),
                },
            };
            Some(GltfCamera {
                camera: camera.index(),
                node: node.index(),
                name: camera.name().map(str::to_owned),
                world: *world,
                projection,
            })
        })
        .collect())
}

/// A glTF scene as instances: each glTF mesh the scene draws, once, in its own coordinates,
/// and every node that carries one with its world matrix. Loaded by [`load_gltf_scene`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GltfScene {
    /// The meshes, each in its own coordinates, in order of first use by the scene walk
    /// (every one carries the document's materials).
    pub meshes: Vec<Mesh>,
    /// Every mesh-carrying node of the scene, in the scene walk's order, which is the order
    /// of [`load_gltf`]'s faces: instance `k`'s faces there are its mesh's faces (a
    /// mirroring instance's with their corners reversed).
    pub instances: Vec<GltfInstance>,
    /// The meshes' load reports, merged.
    pub report: LoadReport,
}

/// One node of a [`GltfScene`] carrying a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct GltfInstance {
    /// Index into [`GltfScene::meshes`].
    pub mesh: usize,
    /// The glTF node index.
    pub node: usize,
    /// Local to world: the node's matrix times its ancestors' (affine; a negative
    /// determinant mirrors, and glTF then makes clockwise faces the front).
    pub world: glam::DAffine3,
}

/// Loads a `.gltf` or `.glb` file as a scene of instances ([`GltfScene`]), with the same
/// confinement, limits and errors as [`load_gltf`]; each mesh is loaded once however many
/// nodes carry it. A node matrix that is not affine is a [`LoadError::Gltf`].
pub fn load_gltf_scene(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<GltfScene, LoadError> {
    let (bytes, file, folder) = read_file(path.as_ref(), options)?;
    load_scene_bytes(&bytes, file, Some(&folder), options)
}

/// [`load_gltf_scene`] from memory (see [`load_gltf_slice`]).
pub fn load_gltf_scene_slice(bytes: &[u8], options: &LoadOptions) -> Result<GltfScene, LoadError> {
    load_scene_bytes(bytes, crate::obj_memory_name(), None, options)
}

fn load_scene_bytes(
    bytes: &[u8],
    file: String,
    folder: Option<&Folder>,
    options: &LoadOptions,
) -> Result<GltfScene, LoadError> {
    let (document, blob) = parse(bytes, &file)?;
    let buffers = buffers::load_buffers(&document, blob, folder, &file, options)?;
    let mut report = LoadReport::default();
    let materials =
        materials::materials(&document, &buffers, folder, options, &mut report.warnings);
    let walked = scene::walk_scene(&document, &file, options)?;
    // glTF mesh index → scene mesh index, in order of first use.
    let mut index: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    let mut meshes = Vec::new();
    let mut instances = Vec::new();
    for (node, world) in &walked {
        let Some(gltf_mesh) = node.mesh() else {
            continue;
        };
        let row = world.row(3);
        if row != glam::DVec4::new(0.0, 0.0, 0.0, 1.0) {
            return Err(gltf_err(
                &file,
                format!(
                    "node {}: its world matrix is not affine (last row {row})",
                    node.index()
                ),
            ));
        }
        let mesh = match index.get(&gltf_mesh.index()) {
            Some(&m) => m,
            None => {
                let mut raw = RawMesh::new(file.clone());
                raw.materials = materials.clone();
                let mut uvs = primitive::Uvs::default();
                for prim in gltf_mesh.primitives() {
                    primitive::append(
                        &mut raw,
                        &mut uvs,
                        node,
                        glam::DMat4::IDENTITY,
                        &prim,
                        &buffers,
                        options,
                    )?;
                }
                uvs.finish(&mut raw);
                if raw.face_count() == 0 {
                    report.warnings.append(&mut raw.report.warnings);
                    report.skipped_primitives += raw.report.skipped_primitives;
                    continue;
                }
                let (mesh, part) = finish(raw, options)?;
                merge(&mut report, part);
                meshes.push(mesh);
                index.insert(gltf_mesh.index(), meshes.len() - 1);
                meshes.len() - 1
            }
        };
        instances.push(GltfInstance {
            mesh,
            node: node.index(),
            world: glam::DAffine3::from_mat4(*world),
        });
    }
    if instances.is_empty() {
        return Err(LoadError::EmptyModel {
            file,
            detail: format!(
                "no triangles in the scene ({} primitives skipped)",
                report.skipped_primitives
            ),
        });
    }
    Ok(GltfScene {
        meshes,
        instances,
        report,
    })
}

/// Adds one mesh's load report to the scene's.
fn merge(total: &mut LoadReport, part: LoadReport) {
    total.faces_read += part.faces_read;
    total.faces_kept += part.faces_kept;
    total.degenerate_dropped += part.degenerate_dropped;
    total.non_planar += part.non_planar;
    total.non_convex_split += part.non_convex_split;
    total.triangles_merged += part.triangles_merged;
    total.skipped_primitives += part.skipped_primitives;
    total.warnings.extend(part.warnings);
}

fn load_gltf_bytes(
    bytes: &[u8],
    file: String,
    folder: Option<&Folder>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let (document, blob) = parse(bytes, &file)?;
    let buffers = buffers::load_buffers(&document, blob, folder, &file, options)?;
    let mut raw = RawMesh::new(file);
    raw.materials = materials::materials(
        &document,
        &buffers,
        folder,
        options,
        &mut raw.report.warnings,
    );
    let instances = scene::walk_scene(&document, &raw.file, options)?;
    let mut uvs = primitive::Uvs::default();
    for (node, world) in instances {
        let Some(mesh) = node.mesh() else { continue };
        for prim in mesh.primitives() {
            primitive::append(&mut raw, &mut uvs, &node, world, &prim, &buffers, options)?;
        }
    }
    uvs.finish(&mut raw);
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
