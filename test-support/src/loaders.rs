//! Loader fuzzing and its committed regression cases (`tests/data/loaders/`): the seed
//! inputs, the one check every loader input must pass, and the list of saved cases.
//!
//! The check: no loader panics, and every input either loads into a valid mesh (faces,
//! finite positions, indices, uvs and materials in range, a report that agrees) or is
//! refused with a typed [`obj_quads::LoadError`]. `cargo xtask fuzz --loaders` mutates the
//! seeds, shrinks every input that fails the check and saves it here; the tests replay
//! every saved file.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use obj_quads::{FacePolicy, LoadOptions, LoadReport, Mesh, NonPlanarPolicy};

/// What kind of file a loader input is, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LoaderFormat {
    /// Wavefront OBJ (`.obj`), loaded from memory (no MTL).
    Obj,
    /// MTL library (`.mtl`), loaded through a fixed OBJ that names it.
    Mtl,
    /// glTF JSON (`.gltf`), loaded from memory and from a file next to the seed's buffer.
    Gltf,
    /// Binary glTF (`.glb`).
    Glb,
}

impl LoaderFormat {
    /// Every format.
    pub const ALL: [LoaderFormat; 4] = [
        LoaderFormat::Obj,
        LoaderFormat::Mtl,
        LoaderFormat::Gltf,
        LoaderFormat::Glb,
    ];

    /// The file extension of saved cases.
    #[must_use]
    pub fn extension(self) -> &'static str {
        match self {
            LoaderFormat::Obj => "obj",
            LoaderFormat::Mtl => "mtl",
            LoaderFormat::Gltf => "gltf",
            LoaderFormat::Glb => "glb",
        }
    }

    /// The format of a saved case, by extension.
    #[must_use]
    pub fn from_path(path: &Path) -> Option<LoaderFormat> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        LoaderFormat::ALL
            .into_iter()
            .find(|f| f.extension() == extension)
    }
}

/// The folder of committed loader regression cases: `tests/data/loaders/`.
#[must_use]
pub fn loader_cases_dir() -> PathBuf {
    crate::test_data_dir().join("loaders")
}

/// Every committed loader case with its format, sorted by path. Files of other extensions
/// (e.g. the folder's README) are left out.
///
/// # Panics
/// When the folder cannot be read.
#[must_use]
pub fn loader_cases() -> Vec<(PathBuf, LoaderFormat)> {
    let dir = loader_cases_dir();
    let entries =
        std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()));
    let mut cases: Vec<(PathBuf, LoaderFormat)> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter_map(|p| LoaderFormat::from_path(&p).map(|f| (p, f)))
        .collect();
    cases.sort_by(|a, b| a.0.cmp(&b.0));
    cases
}

/// The seed inputs of a format: real files from `assets/models/` (a GLB is assembled from
/// the Box sample's JSON and buffer).
///
/// # Panics
/// When an asset is missing.
#[must_use]
pub fn loader_seeds(format: LoaderFormat) -> Vec<(String, Vec<u8>)> {
    let read = |relative: &str| {
        let path = crate::model_path(relative);
        std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    };
    let named = |names: &[&str]| {
        names
            .iter()
            .map(|n| ((*n).to_owned(), read(n)))
            .collect::<Vec<_>>()
    };
    match format {
        LoaderFormat::Obj => named(&[
            "assimp-obj/box.obj",
            "assimp-obj/concave_polygon.obj",
            "cornell-box/cornell_box.obj",
            "keenan-crane/spot/spot_control_mesh_texture.obj",
        ]),
        LoaderFormat::Mtl => named(&[
            "cornell-box/cornell_box.mtl",
            "keenan-crane/spot/spot.mtl",
            "combobulate-samples/book.mtl",
        ]),
        LoaderFormat::Gltf => named(&[
            "gltf/Box/Box.gltf",
            "gltf/SimpleMeshes/glTF-Embedded/SimpleMeshes.gltf",
            "gltf/MultipleScenes/glTF-Embedded/MultipleScenes.gltf",
        ]),
        LoaderFormat::Glb => {
            let json = String::from_utf8(read("gltf/Box/Box.gltf")).expect("Box.gltf is UTF-8");
            // The buffer becomes the GLB binary chunk: drop its URI.
            let json = json.replace(r#""uri": "Box0.bin","#, "");
            vec![(
                "gltf/Box as GLB".to_owned(),
                glb(&json, &read("gltf/Box/Box0.bin")),
            )]
        }
    }
}

/// Assembles a GLB container from a JSON chunk and a binary chunk.
#[must_use]
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + 8 + bin_len;
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json_len as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json.as_bytes());
    out.extend(std::iter::repeat_n(b' ', pad(json.len())));
    out.extend((bin_len as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out.extend(std::iter::repeat_n(0u8, pad(bin.len())));
    out
}

/// The fixed OBJ that names the MTL under test: three textured quads using the seeds.
/// material names.
const MTL_HOST_OBJ: &str = "mtllib case.mtl\n\
v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n\
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
usemtl white\nf 1/1 2/2 3/3 4/4\n\
usemtl spot\nf 1/1 2/2 6/3 5/4\n\
usemtl cover\nf 4/1 3/2 6/3 5/4\n";

/// How an input fared under the default options: loaded (with its face count) or refused
/// with a typed error. (The other option sets are checked for bugs only.)
#[derive(Debug)]
pub enum Verdict {
    /// Loaded; the face count.
    Loaded(usize),
    /// Refused with this typed error's message.
    Refused(String),
}

/// The option sets every input is loaded with.
fn option_sets() -> [LoadOptions; 3] {
    [
        LoadOptions::DEFAULT,
        LoadOptions::DEFAULT.with_face_policy(FacePolicy::QuadsOnly),
        LoadOptions::DEFAULT
            .with_face_policy(FacePolicy::MergeTriangles)
            .with_non_planar(NonPlanarPolicy::SplitFan),
    ]
}

/// Runs one input through its loader under several option sets. `scratch` is a folder the
/// check may write to (the MTL under test and its host OBJ, a glTF file and the Box
/// sample's buffer). Returns the verdict, or a description of the bug: a panic, or a mesh
/// that breaks an invariant.
///
/// # Errors
/// The description of the bug found.
pub fn check_loader_input(
    format: LoaderFormat,
    bytes: &[u8],
    scratch: &Path,
) -> Result<Verdict, String> {
    let mut verdict = None;
    for options in option_sets() {
        let mut loaded = None;
        let mut refused = None;
        for (what, result) in load_all(format, bytes, scratch, &options)? {
            match result {
                Ok((mesh, report)) => {
                    validate(&mesh, &report).map_err(|e| format!("{what}: {e}"))?;
                    loaded.get_or_insert(mesh.face_count());
                }
                Err(e) => {
                    refused.get_or_insert(e.to_string());
                }
            }
        }
        // The verdict is that of the default options (the first set): loaded when any way
        // of loading it did (a glTF with an external buffer loads from a file only).
        if verdict.is_none() {
            verdict = loaded
                .map(Verdict::Loaded)
                .or(refused.map(Verdict::Refused));
        }
    }
    verdict.ok_or_else(|| "no load attempted".to_owned())
}

type LoadResult = Result<(Mesh, LoadReport), obj_quads::LoadError>;

/// Every way `format` is loaded, each guarded against panics.
fn load_all(
    format: LoaderFormat,
    bytes: &[u8],
    scratch: &Path,
    options: &LoadOptions,
) -> Result<Vec<(&'static str, LoadResult)>, String> {
    let guard = |what: &'static str, f: &dyn Fn() -> LoadResult| {
        catch_unwind(AssertUnwindSafe(f))
            .map(|r| (what, r))
            .map_err(|panic| format!("{what} panicked: {}", panic_message(&*panic)))
    };
    let write = |name: &str, data: &[u8]| {
        let path = scratch.join(name);
        std::fs::write(&path, data)
            .map(|()| path)
            .map_err(|e| format!("writing {}: {e}", scratch.display()))
    };
    match format {
        LoaderFormat::Obj => Ok(vec![guard("OBJ from memory", &|| {
            obj_quads::load_obj_reader(bytes, None, options)
        })?]),
        LoaderFormat::Mtl => {
            write("case.mtl", bytes)?;
            let obj = write("case.obj", MTL_HOST_OBJ.as_bytes())?;
            Ok(vec![guard("MTL through its OBJ", &|| {
                obj_quads::load(&obj, options)
            })?])
        }
        LoaderFormat::Gltf | LoaderFormat::Glb => {
            let name = format!("case.{}", format.extension());
            write(
                "Box0.bin",
                &std::fs::read(crate::model_path("gltf/Box/Box0.bin"))
                    .map_err(|e| e.to_string())?,
            )?;
            let path = write(&name, bytes)?;
            Ok(vec![
                guard("glTF from memory", &|| {
                    obj_quads::load_gltf_slice(bytes, options)
                })?,
                guard("glTF from a file", &|| obj_quads::load(&path, options))?,
            ])
        }
    }
}

/// The invariants of a loaded mesh and its report.
fn validate(mesh: &Mesh, report: &LoadReport) -> Result<(), String> {
    let faces = mesh.face_count();
    if faces == 0 {
        return Err("loaded a mesh with no faces".into());
    }
    if report.faces_kept != faces {
        return Err(format!(
            "report says {} faces kept, mesh has {faces}",
            report.faces_kept
        ));
    }
    let positions = mesh.positions();
    if let Some(k) = positions.iter().position(|p| !p.is_finite()) {
        return Err(format!("position {k} is not finite"));
    }
    for i in 0..faces {
        let face = mesh.face(i).ok_or_else(|| format!("face {i} missing"))?;
        if face.len() < 3 {
            return Err(format!("face {i} has {} corners", face.len()));
        }
        if let Some(&bad) = face.iter().find(|&&v| v as usize >= positions.len()) {
            return Err(format!(
                "face {i} names vertex {bad} of {}",
                positions.len()
            ));
        }
        if let Some(m) = mesh.face_material(i)
            && m as usize >= mesh.materials().len()
        {
            return Err(format!(
                "face {i} names material {m} of {}",
                mesh.materials().len()
            ));
        }
    }
    if let Some(uvs) = mesh.uvs() {
        if uvs.len() != mesh.indices().len() {
            return Err(format!(
                "{} uvs for {} corners",
                uvs.len(),
                mesh.indices().len()
            ));
        }
        if uvs.iter().any(|uv| !uv.is_finite()) {
            return Err("non-finite uv kept".into());
        }
    }
    Ok(())
}

/// The message of a caught panic.
fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(no message)".to_owned())
}
