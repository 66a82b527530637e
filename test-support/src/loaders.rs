//! Loader fuzzing (models and textures) and its committed regression cases (`tests/data/loaders/`): the seed
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
pub use test_base::encoded::{glb, grey_jpeg};

/// What kind of file a loader input is, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LoaderFormat {
    /// Wavefront OBJ (`.obj`), loaded from memory (no MTL). Bytes with a NUL are an OBJ, the
    /// NUL, and an MTL library: both are written as files (`case.obj`, `case.mtl`) and the
    /// OBJ is loaded from its file too, so that its `mtllib case.mtl` resolves.
    Obj,
    /// MTL library (`.mtl`), loaded through a fixed OBJ that names it.
    Mtl,
    /// glTF JSON (`.gltf`), loaded from memory and from a file next to the seed's buffer.
    Gltf,
    /// Binary glTF (`.glb`).
    Glb,
    /// PNG texture (`.png`), decoded by `obj_quads::decode_texture`.
    Png,
    /// JPEG texture (`.jpg`), decoded by `obj_quads::decode_texture`.
    Jpeg,
}

impl LoaderFormat {
    /// Every format.
    pub const ALL: [LoaderFormat; 6] = [
        LoaderFormat::Obj,
        LoaderFormat::Mtl,
        LoaderFormat::Gltf,
        LoaderFormat::Glb,
        LoaderFormat::Png,
        LoaderFormat::Jpeg,
    ];

    /// The file extension of saved cases.
    #[must_use]
    pub fn extension(self) -> &'static str {
        match self {
            LoaderFormat::Obj => "obj",
            LoaderFormat::Mtl => "mtl",
            LoaderFormat::Gltf => "gltf",
            LoaderFormat::Glb => "glb",
            LoaderFormat::Png => "png",
            LoaderFormat::Jpeg => "jpg",
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
        LoaderFormat::Png => named(&[
            "gltf/BoxTextured/CesiumLogoFlat.png",
            "gltf/Cube/Cube_MetallicRoughness.png",
            "combobulate-samples/pages.png",
        ]),
        LoaderFormat::Jpeg => vec![("16x8 grey baseline JPEG".to_owned(), grey_jpeg())],
    }
}

/// The fixed OBJ that names the MTL under test: three textured quads using the seeds.
/// material names.
const MTL_HOST_OBJ: &str = "mtllib case.mtl\n\
v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n\
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
usemtl white\nf 1/1 2/2 3/3 4/4\n\
usemtl spot\nf 1/1 2/2 6/3 5/4\n\
usemtl cover\nf 4/1 3/2 6/3 5/4\n";

/// How an input fared under the default options: loaded (with its face count, or a
/// texture's pixel count) or refused with a typed error. (The other option sets are
/// checked for bugs only.)
#[derive(Debug)]
pub enum Verdict {
    /// Loaded; the face count (models) or pixel count (textures).
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
/// that breaks an invariant (a texture path outside the model's folder among them).
///
/// # Errors
/// The description of the bug found.
pub fn check_loader_input(
    format: LoaderFormat,
    bytes: &[u8],
    scratch: &Path,
) -> Result<Verdict, String> {
    if matches!(format, LoaderFormat::Png | LoaderFormat::Jpeg) {
        return check_texture(bytes);
    }
    let file = prepare(format, bytes, scratch)?;
    // Every texture a loaded mesh names must lie in the model's folder (the options never
    // allow paths outside).
    let folder = scratch
        .canonicalize()
        .map_err(|e| format!("{}: {e}", scratch.display()))?;
    let mut verdict = None;
    for options in option_sets() {
        let mut loaded = None;
        let mut refused = None;
        for (what, result) in load_all(format, bytes, file.as_deref(), &options)? {
            match result {
                Ok((mesh, report)) => {
                    validate(&mesh, &report, &folder).map_err(|e| format!("{what}: {e}"))?;
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

/// Textures: decoded under the default limits and under small ones (64 pixels a side, 1024
/// pixels); a decoded image must have the declared size within the limits and 4 bytes a
/// pixel.
fn check_texture(bytes: &[u8]) -> Result<Verdict, String> {
    let small = LoadOptions::DEFAULT
        .with_max_texture_side(64)
        .with_max_texture_pixels(1024);
    let mut verdict = None;
    for options in [LoadOptions::DEFAULT, small] {
        let result = catch_unwind(AssertUnwindSafe(|| {
            obj_quads::decode_texture(bytes, "case", &options)
        }))
        .map_err(|panic| format!("decode_texture panicked: {}", panic_message(&*panic)))?;
        let outcome = match result {
            Ok(t) => {
                let pixels = u64::from(t.width) * u64::from(t.height);
                if t.width > options.max_texture_side
                    || t.height > options.max_texture_side
                    || pixels > options.max_texture_pixels
                {
                    return Err(format!(
                        "decoded {}×{} beyond the limits",
                        t.width, t.height
                    ));
                }
                if t.rgba.len() as u64 != pixels * 4 {
                    return Err(format!(
                        "{} bytes for {}×{} RGBA",
                        t.rgba.len(),
                        t.width,
                        t.height
                    ));
                }
                Verdict::Loaded(pixels as usize)
            }
            Err(e) => Verdict::Refused(e.to_string()),
        };
        verdict.get_or_insert(outcome);
    }
    verdict.ok_or_else(|| "no decode attempted".to_owned())
}

type LoadResult = Result<(Mesh, LoadReport), obj_quads::LoadError>;

/// Writes the files an input is loaded from (once per input): the MTL and its host OBJ, or
/// the glTF / GLB next to the Box sample's buffer. Returns the file to load, if any.
fn prepare(format: LoaderFormat, bytes: &[u8], scratch: &Path) -> Result<Option<PathBuf>, String> {
    let write = |name: &str, data: &[u8]| {
        let path = scratch.join(name);
        std::fs::write(&path, data)
            .map(|()| path)
            .map_err(|e| format!("writing {}: {e}", scratch.display()))
    };
    match format {
        LoaderFormat::Png | LoaderFormat::Jpeg => Ok(None),
        LoaderFormat::Obj => match split_obj_mtl(bytes) {
            (_, None) => Ok(None),
            (obj, Some(mtl)) => {
                texture_beside(scratch)?;
                write("case.mtl", mtl)?;
                write("case.obj", obj).map(Some)
            }
        },
        LoaderFormat::Mtl => {
            texture_beside(scratch)?;
            write("case.mtl", bytes)?;
            write("case.obj", MTL_HOST_OBJ.as_bytes()).map(Some)
        }
        LoaderFormat::Gltf | LoaderFormat::Glb => {
            let buffer = scratch.join("Box0.bin");
            if !buffer.is_file() {
                let data = std::fs::read(crate::model_path("gltf/Box/Box0.bin"))
                    .map_err(|e| e.to_string())?;
                write("Box0.bin", &data)?;
            }
            write(&format!("case.{}", format.extension()), bytes).map(Some)
        }
    }
}

/// An OBJ input's two parts: the OBJ before the first NUL, and the MTL library after it.
fn split_obj_mtl(bytes: &[u8]) -> (&[u8], Option<&[u8]>) {
    match bytes.iter().position(|&b| b == 0) {
        Some(k) => (&bytes[..k], Some(&bytes[k + 1..])),
        None => (bytes, None),
    }
}

/// The texture spot.mtl names, beside the case, so that accepted texture paths occur too.
fn texture_beside(scratch: &Path) -> Result<(), String> {
    let path = scratch.join("spot_texture.png");
    if path.is_file() {
        return Ok(());
    }
    std::fs::write(&path, b"not decoded here")
        .map_err(|e| format!("writing {}: {e}", path.display()))
}

/// Every way `format` is loaded (from `file`, written by [`prepare`]), each guarded
/// against panics.
fn load_all(
    format: LoaderFormat,
    bytes: &[u8],
    file: Option<&Path>,
    options: &LoadOptions,
) -> Result<Vec<(&'static str, LoadResult)>, String> {
    let guard = |what: &'static str, f: &dyn Fn() -> LoadResult| {
        catch_unwind(AssertUnwindSafe(f))
            .map(|r| (what, r))
            .map_err(|panic| format!("{what} panicked: {}", panic_message(&*panic)))
    };
    let mut out = Vec::new();
    match format {
        LoaderFormat::Obj => out.push(guard("OBJ from memory", &|| {
            obj_quads::load_obj_reader(split_obj_mtl(bytes).0, None, options)
        })?),
        LoaderFormat::Gltf | LoaderFormat::Glb => out.push(guard("glTF from memory", &|| {
            obj_quads::load_gltf_slice(bytes, options)
        })?),
        LoaderFormat::Mtl | LoaderFormat::Png | LoaderFormat::Jpeg => {}
    }
    if let Some(file) = file {
        out.push(guard("from a file", &|| obj_quads::load(file, options))?);
    }
    Ok(out)
}

/// The invariants of a loaded mesh and its report; `folder` is the model's canonical
/// folder, which every texture path must lie in.
fn validate(mesh: &Mesh, report: &LoadReport, folder: &Path) -> Result<(), String> {
    for material in mesh.materials() {
        if let Some(texture) = &material.texture
            && !texture.starts_with(folder)
        {
            return Err(format!(
                "material `{}` names texture {} outside the model's folder {}",
                material.name,
                texture.display(),
                folder.display()
            ));
        }
    }
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
