//! Wavefront OBJ (+ MTL) loading through `tobj`, with triangulation off.

use std::borrow::Cow;
use std::cell::RefCell;
use std::io::Read;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec2};

use crate::build::{RawMesh, finish};
use crate::error::FaceLocation;
use crate::paths::{Folder, Refusal};
use crate::{LoadError, LoadOptions, LoadReport, Material, Mesh};

/// Display name of in-memory input in error messages.
pub(crate) const MEMORY: &str = "<memory>";

/// Loads an OBJ file (and the MTL libraries it names, relative to the OBJ's
/// directory).
///
/// A missing or broken MTL file is a warning in the report, not an error.
pub fn load_obj(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let path = path.as_ref();
    let file = path.display().to_string();
    let bytes = crate::read_file_capped(path, &file, options.max_file_bytes)?;
    let text = utf8(&bytes, &file)?;
    load_obj_text(text, file, path.parent(), options)
}

/// Loads OBJ text from memory. `mtllib` lines cannot be resolved and are
/// reported as warnings; faces get no material.
///
/// ```
/// let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
/// let (mesh, report) = obj_quads::load_obj_str(obj, &Default::default()).unwrap();
/// assert_eq!(mesh.face(0), Some(&[0u32, 1, 2, 3][..]));
/// assert_eq!(report.faces_kept, 1);
/// ```
pub fn load_obj_str(text: &str, options: &LoadOptions) -> Result<(Mesh, LoadReport), LoadError> {
    load_obj_text(text, MEMORY.to_owned(), None, options)
}

/// Loads OBJ from a reader. MTL libraries are resolved relative to `base_dir`
/// when given, and otherwise reported as warnings. At most
/// [`LoadOptions::max_file_bytes`] bytes are read.
pub fn load_obj_reader(
    reader: impl Read,
    base_dir: Option<&Path>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let file = MEMORY.to_owned();
    let bytes = crate::read_capped(reader, &file, options.max_file_bytes)?;
    let text = utf8(&bytes, &file)?;
    load_obj_text(text, file, base_dir, options)
}

fn utf8<'a>(bytes: &'a [u8], file: &str) -> Result<&'a str, LoadError> {
    std::str::from_utf8(bytes).map_err(|e| {
        let valid = bytes.get(..e.valid_up_to()).unwrap_or(&[]);
        LoadError::InvalidText {
            file: file.to_owned(),
            line: Some(valid.iter().filter(|&&b| b == b'\n').count() + 1),
        }
    })
}

/// One `f` or `l` line, in file order.
struct FaceLine {
    line: usize,
    is_face: bool,
}

/// Cheap pass over the text: face lines with their line numbers, limits,
/// and non-finite vertex coordinates.
fn prescan(text: &str, file: &str, options: &LoadOptions) -> Result<Vec<FaceLine>, LoadError> {
    let mut lines = Vec::new();
    let mut vertices = 0usize;
    let mut texcoords = 0usize;
    let mut normals = 0usize;
    let mut faces = 0usize;
    let mut object = "unnamed_object".to_owned();
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                vertices += 1;
                if vertices > options.max_vertices {
                    return Err(too_large(
                        file,
                        "vertex count",
                        vertices,
                        options.max_vertices,
                    ));
                }
                for w in words.take(3) {
                    if let Ok(x) = w.parse::<f64>()
                        && !x.is_finite()
                    {
                        return Err(LoadError::NonFiniteCoordinate {
                            file: file.to_owned(),
                            line: Some(i + 1),
                            what: format!("vertex {vertices} (object `{object}`)"),
                        });
                    }
                }
            }
            // Texture coordinates and normals are capped like positions.
            Some("vt") => {
                texcoords += 1;
                if texcoords > options.max_vertices {
                    return Err(too_large(
                        file,
                        "texture coordinate count",
                        texcoords,
                        options.max_vertices,
                    ));
                }
            }
            Some("vn") => {
                normals += 1;
                if normals > options.max_vertices {
                    return Err(too_large(
                        file,
                        "normal count",
                        normals,
                        options.max_vertices,
                    ));
                }
            }
            Some(kw @ ("f" | "l")) => {
                let is_face = kw == "f";
                if is_face {
                    let corners = words.count();
                    if corners > options.max_face_corners {
                        return Err(LoadError::TooManyCorners {
                            file: file.to_owned(),
                            at: FaceLocation {
                                object: object.clone(),
                                face: faces,
                                line: Some(i + 1),
                            },
                            corners,
                            max: options.max_face_corners,
                        });
                    }
                    faces += 1;
                    if faces > options.max_faces {
                        return Err(too_large(file, "face count", faces, options.max_faces));
                    }
                }
                lines.push(FaceLine {
                    line: i + 1,
                    is_face,
                });
            }
            Some("o" | "g") => object = object_name(line),
            _ => {}
        }
    }
    Ok(lines)
}

fn too_large(file: &str, what: &'static str, actual: usize, limit: usize) -> LoadError {
    LoadError::TooLarge {
        file: file.to_owned(),
        what,
        actual: actual as u64,
        limit: limit as u64,
    }
}

/// Object name as tobj derives it from an `o`/`g` line.
fn object_name(line: &str) -> String {
    let name = line.trim_start().get(1..).unwrap_or("").trim();
    if name.is_empty() {
        "unnamed_object".to_owned()
    } else {
        name.to_owned()
    }
}

/// Rejects MTL text that would make tobj panic (colour lines with fewer than
/// three values). Returns the offending line.
fn mtl_problem(text: &str) -> Option<usize> {
    text.lines().enumerate().find_map(|(i, line)| {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("Ka" | "Kd" | "Ks" | "Ke") if words.clone().count() < 3 => Some(i + 1),
            _ => None,
        }
    })
}

/// Texture file name from a `map_Kd` value, which may start with options.
fn texture_name(value: &str) -> &str {
    if value.starts_with('-') {
        value.split_whitespace().last().unwrap_or(value)
    } else {
        value
    }
}

/// Removes trailing comments (`#` at the start of a line or after
/// whitespace, to the end of the line), which tobj does not understand.
/// Line structure is kept, so line numbers stay valid.
fn strip_comments(text: &str) -> Cow<'_, str> {
    fn comment_start(line: &str) -> Option<usize> {
        let bytes = line.as_bytes();
        (0..bytes.len())
            .find(|&i| bytes[i] == b'#' && (i == 0 || bytes[i - 1].is_ascii_whitespace()))
    }
    if !text
        .lines()
        .any(|l| comment_start(l).is_some_and(|i| !l[..i].trim().is_empty()))
    {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let (body, end) = match line.strip_suffix('\n') {
            Some(b) => (b.strip_suffix('\r').unwrap_or(b), "\n"),
            None => (line, ""),
        };
        match comment_start(body) {
            Some(i) => out.push_str(&body[..i]),
            None => out.push_str(body),
        }
        out.push_str(end);
    }
    Cow::Owned(out)
}

/// The material libraries an OBJ names, loaded for tobj: inside the model's folder unless
/// the caller allows more, capped in size, checked before tobj parses them; what could not be
/// loaded becomes a warning, a library outside the folder an error.
struct MtlLibraries<'a> {
    folder: Option<&'a Folder>,
    /// The OBJ, for messages.
    file: &'a str,
    max_bytes: u64,
    warnings: RefCell<Vec<String>>,
    /// Directory of each loaded MTL, with the number of materials it holds.
    dirs: RefCell<Vec<(usize, PathBuf)>>,
    /// An `mtllib` that leaves the model's folder: the load fails with it.
    refused: RefCell<Option<LoadError>>,
}

impl MtlLibraries<'_> {
    /// Loads the library `name` (tobj's material loader).
    fn load(&self, name: &Path) -> tobj::MTLLoadResult {
        let Some(folder) = self.folder else {
            self.warnings.borrow_mut().push(format!(
                "material library `{}` not loaded: in-memory input has no directory",
                name.display()
            ));
            return Err(tobj::LoadError::OpenFileFailed);
        };
        let path = match folder.resolve(folder.path(), name) {
            Ok(path) => path,
            Err(Refusal::Outside { resolved }) => {
                self.refused
                    .borrow_mut()
                    .get_or_insert(LoadError::PathOutsideModel {
                        file: self.file.to_owned(),
                        what: "mtllib".into(),
                        reference: name.display().to_string(),
                        resolved,
                        folder: folder.path().to_path_buf(),
                    });
                return Err(tobj::LoadError::OpenFileFailed);
            }
            Err(Refusal::Unresolvable { joined, source }) => {
                self.warnings.borrow_mut().push(format!(
                    "material library not loaded: {}: {source}",
                    joined.display()
                ));
                return Err(tobj::LoadError::OpenFileFailed);
            }
        };
        let shown = path.display().to_string();
        let bytes = match crate::read_file_capped(&path, &shown, self.max_bytes) {
            Ok(b) => b,
            Err(e) => {
                self.warnings
                    .borrow_mut()
                    .push(format!("material library not loaded: {e}"));
                return Err(tobj::LoadError::OpenFileFailed);
            }
        };
        let Ok(mtl) = std::str::from_utf8(&bytes) else {
            self.warnings.borrow_mut().push(format!(
                "material library not loaded: {shown}: not valid UTF-8"
            ));
            return Err(tobj::LoadError::ReadError);
        };
        if let Some(line) = mtl_problem(mtl) {
            self.warnings.borrow_mut().push(format!(
                "material library not loaded: {shown}, line {line}: colour needs three values"
            ));
            return Err(tobj::LoadError::MaterialParseError);
        }
        let mtl = strip_comments(mtl);
        let result = catch_unwind(|| tobj::load_mtl_buf(&mut mtl.as_bytes()))
            .unwrap_or(Err(tobj::LoadError::GenericFailure));
        match &result {
            Ok((mats, _)) => self.dirs.borrow_mut().push((
                mats.len(),
                path.parent().map(Path::to_path_buf).unwrap_or_default(),
            )),
            Err(e) => self
                .warnings
                .borrow_mut()
                .push(format!("material library not loaded: {shown}: {e}")),
        }
        result
    }
}

fn load_obj_text(
    text: &str,
    file: String,
    base: Option<&Path>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let text = strip_comments(text);
    let text = text.as_ref();
    let face_lines = prescan(text, &file, options)?;
    let folder = base.map(|b| Folder::new(b, options.allow_outside_paths));
    let libraries = MtlLibraries {
        folder: folder.as_ref(),
        file: &file,
        max_bytes: options.max_file_bytes,
        warnings: RefCell::new(Vec::new()),
        dirs: RefCell::new(Vec::new()),
        refused: RefCell::new(None),
    };
    let material_loader = |name: &Path| libraries.load(name);
    // tobj's optional `merging`/`reordering` features add fields, hence the update.
    #[allow(clippy::needless_update)]
    let tobj_options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: false,
        ignore_lines: false,
        ..Default::default()
    };
    // Check every face index first: tobj has no line numbers, and overflows
    // on huge indices.
    if let Some(e) = scan_problem(text, &file, None) {
        return Err(e);
    }
    let loaded = catch_unwind(AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut text.as_bytes(), &tobj_options, material_loader)
    }));
    if let Some(e) = libraries.refused.take() {
        return Err(e);
    }
    let (models, materials) = match loaded {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => {
            return Err(
                scan_problem(text, &file, Some(e)).unwrap_or_else(|| LoadError::Parse {
                    file: file.clone(),
                    line: None,
                    detail: format!("OBJ parser: {e}"),
                }),
            );
        }
        Err(_) => {
            return Err(LoadError::Parse {
                file,
                line: None,
                detail: "the OBJ parser panicked on this input".into(),
            });
        }
    };
    let mut raw = RawMesh::new(file.clone());
    raw.report.warnings = libraries.warnings.take();
    // Materials.
    let tobj_materials = match materials {
        Ok(m) => m,
        Err(e) => {
            if raw.report.warnings.is_empty() {
                raw.report
                    .warnings
                    .push(format!("materials not loaded: {e}"));
            }
            Vec::new()
        }
    };
    push_materials(
        &mut raw,
        &tobj_materials,
        &libraries.dirs.take(),
        folder.as_ref(),
    );
    push_faces(&mut raw, &models, &face_lines)?;
    if raw.face_count() == 0 {
        return Err(LoadError::EmptyModel {
            file: raw.file,
            detail: "no `f` lines".into(),
        });
    }
    finish(raw, options)
}

/// The MTL materials in file order, each with the folder of the library it came from (for
/// its `map_Kd`, resolved inside the model's folder), appended to `raw`.
fn push_materials(
    raw: &mut RawMesh,
    tobj_materials: &[tobj::Material],
    dirs: &[(usize, PathBuf)],
    folder: Option<&Folder>,
) {
    let mut dir_of = dirs
        .iter()
        .flat_map(|(n, d)| std::iter::repeat_n(d.clone(), *n));
    for m in tobj_materials {
        let dir = dir_of.next().unwrap_or_default();
        let kd = m.diffuse.unwrap_or([1.0; 3]);
        let alpha = m.dissolve.unwrap_or(1.0);
        let mut diffuse = [kd[0] as f32, kd[1] as f32, kd[2] as f32, alpha as f32];
        if diffuse.iter().any(|c| !c.is_finite()) {
            raw.report.warnings.push(format!(
                "material `{}`: non-finite colour replaced by white",
                m.name
            ));
            diffuse = [1.0; 4];
        }
        let mut material = Material::new(m.name.clone(), diffuse);
        if let (Some(tex), Some(folder)) = (&m.diffuse_texture, folder) {
            let name = texture_name(tex);
            match folder.resolve(&dir, Path::new(name)) {
                Ok(path) => material.texture = Some(path),
                Err(refusal) => raw.report.warnings.push(format!(
                    "material `{}`: map_Kd not used (fallback colour): {}",
                    m.name,
                    refusal.describe(folder, name)
                )),
            }
        }
        raw.materials.push(material);
    }
}

/// The faces of tobj's models, in file order (models come in file order, faces in order
/// within), with their positions, materials, objects, source lines and uvs (dropped with a
/// warning unless every face has finite ones), appended to `raw`.
fn push_faces(
    raw: &mut RawMesh,
    models: &[tobj::Model],
    face_lines: &[FaceLine],
) -> Result<(), LoadError> {
    let mut all_uvs = Some(Vec::<Vec2>::new());
    let mut scan = face_lines.iter();
    let scan_ok = face_lines.len() == models.iter().map(|m| arities(&m.mesh).len()).sum::<usize>();
    let mut bad_uvs = false;
    for model in models {
        let mesh = &model.mesh;
        let base_index = raw.positions.len();
        let n_pos = mesh.positions.len() / 3;
        if base_index + n_pos > u32::MAX as usize {
            return Err(too_large(
                &raw.file,
                "vertex count",
                base_index + n_pos,
                u32::MAX as usize,
            ));
        }
        for (k, p) in mesh.positions.chunks_exact(3).enumerate() {
            let p = DVec3::new(p[0], p[1], p[2]);
            if !p.is_finite() {
                return Err(LoadError::NonFiniteCoordinate {
                    file: raw.file.clone(),
                    line: None,
                    what: format!("vertex {k} of object `{}` (after w division)", model.name),
                });
            }
            raw.positions.push(p);
        }
        let object = if raw.objects.last() == Some(&model.name) {
            raw.objects.len() - 1
        } else {
            raw.objects.push(model.name.clone());
            raw.objects.len() - 1
        };
        let has_uv = mesh.texcoord_indices.len() == mesh.indices.len() && !mesh.indices.is_empty();
        let material = mesh
            .material_id
            .filter(|&m| m < raw.materials.len())
            .map(|m| m as u32);
        let mut at = 0usize;
        for arity in arities(mesh) {
            let arity = arity as usize;
            let range = at..at.saturating_add(arity);
            at = range.end;
            let entry = if scan_ok { scan.next() } else { None };
            if entry.is_some_and(|e| !e.is_face) {
                continue;
            }
            let Some(idx) = mesh.indices.get(range.clone()) else {
                return Err(LoadError::Parse {
                    file: raw.file.clone(),
                    line: entry.map(|e| e.line),
                    detail: "face indices missing from the OBJ parser's output".into(),
                });
            };
            raw.indices
                .extend(idx.iter().map(|&i| i + base_index as u32));
            raw.offsets.push(raw.indices.len());
            raw.face_materials.push(material);
            raw.face_objects.push(object as u32);
            raw.face_lines.push(entry.map(|e| e.line));
            match (&mut all_uvs, has_uv) {
                (Some(uvs), true) => {
                    for &t in mesh.texcoord_indices.get(range).unwrap_or(&[]) {
                        let t = t as usize;
                        let uv = match (mesh.texcoords.get(2 * t), mesh.texcoords.get(2 * t + 1)) {
                            (Some(&u), Some(&v)) => Vec2::new(u as f32, v as f32),
                            _ => Vec2::ZERO,
                        };
                        bad_uvs |= !uv.is_finite();
                        uvs.push(uv);
                    }
                }
                _ => all_uvs = None,
            }
        }
    }
    if bad_uvs {
        raw.report
            .warnings
            .push("non-finite texture coordinates: uvs dropped".into());
        all_uvs = None;
    }
    if all_uvs.is_none() && models.iter().any(|m| !m.mesh.texcoord_indices.is_empty()) {
        raw.report
            .warnings
            .push("texture coordinates missing on some faces: uvs dropped".into());
    }
    raw.uvs = all_uvs.filter(|u| u.len() == raw.indices.len());
    Ok(())
}

/// Face arities of a tobj mesh; tobj leaves the list empty when every face
/// is a triangle.
fn arities(mesh: &tobj::Mesh) -> Vec<u32> {
    if mesh.face_arities.is_empty() {
        vec![3; mesh.indices.len() / 3]
    } else {
        mesh.face_arities.clone()
    }
}

/// Finds the first out-of-range face index (always) and, given a tobj
/// error, the line that caused it.
fn scan_problem(text: &str, file: &str, error: Option<tobj::LoadError>) -> Option<LoadError> {
    use tobj::LoadError as T;
    let (mut v, mut vt, mut vn) = (0usize, 0usize, 0usize);
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => v += 1,
            Some("vt") => vt += 1,
            Some("vn") => vn += 1,
            _ => {}
        }
    }
    let totals = [v, vt, vn];
    let mut counts = [0usize; 3];
    let mut face = 0usize;
    let mut object = "unnamed_object".to_owned();
    for (i, line) in text.lines().enumerate() {
        let lineno = i + 1;
        let parse_err = |detail: &str| LoadError::Parse {
            file: file.to_owned(),
            line: Some(lineno),
            detail: format!("{detail}: `{}`", line.trim()),
        };
        let mut words = line.split_whitespace();
        let floats_ok = |words: std::str::SplitWhitespace, n: usize| {
            let vals: Vec<_> = words.take(n).map(str::parse::<f64>).collect();
            vals.len() == n && vals.iter().all(Result::is_ok)
        };
        match words.next() {
            Some("v") => {
                counts[0] += 1;
                if matches!(error, Some(T::PositionParseError)) && !floats_ok(words, 3) {
                    return Some(parse_err("bad vertex position"));
                }
            }
            Some("vt") => {
                counts[1] += 1;
                if matches!(error, Some(T::TexcoordParseError)) && !floats_ok(words, 2) {
                    return Some(parse_err("bad texture coordinate"));
                }
            }
            Some("vn") => {
                counts[2] += 1;
                if matches!(error, Some(T::NormalParseError)) && !floats_ok(words, 3) {
                    return Some(parse_err("bad normal"));
                }
            }
            Some("o" | "g") => object = object_name(line),
            Some(kw @ ("f" | "l")) => {
                let at = FaceLocation {
                    object: object.clone(),
                    face,
                    line: Some(lineno),
                };
                if kw == "f" {
                    face += 1;
                }
                for token in words {
                    for (slot, part) in token.split('/').enumerate() {
                        if part.is_empty() {
                            continue;
                        }
                        let Ok(x) = part.parse::<i64>() else {
                            if error.is_none() {
                                break;
                            }
                            return Some(parse_err("bad face index"));
                        };
                        let Some(&count) = counts.get(slot) else {
                            if error.is_none() {
                                break;
                            }
                            return Some(parse_err("bad face corner (more than v/vt/vn)"));
                        };
                        let total = totals.get(slot).copied().unwrap_or(0);
                        // tobj ignores vt/vn references when the file has none.
                        if slot > 0 && total == 0 {
                            continue;
                        }
                        let bad = if x < 0 {
                            x.unsigned_abs() > count as u64
                        } else {
                            x == 0 || x as u64 > total as u64
                        };
                        if bad {
                            let what = ["vertex", "texture coordinate", "normal"][slot];
                            return Some(if slot == 0 {
                                LoadError::IndexOutOfRange {
                                    file: file.to_owned(),
                                    at,
                                    index: x,
                                    count: if x < 0 { count } else { total },
                                }
                            } else {
                                LoadError::Parse {
                                    file: file.to_owned(),
                                    line: Some(lineno),
                                    detail: format!(
                                        "{at}: {what} index {x} out of range ({total} available)"
                                    ),
                                }
                            });
                        }
                    }
                }
            }
            _ => {}
        }
    }
    None
}
