//! Materials: base colour factor and base colour texture path (confined to
//! the model's folder).

use std::path::PathBuf;

use gltf::Document;

use super::buffers::uri_path;
use crate::paths::Folder;
use crate::{LoadOptions, Material};

/// Materials in document order: base colour factor and texture.
pub(super) fn materials(
    doc: &Document,
    folder: Option<&Folder>,
    options: &LoadOptions,
    warnings: &mut Vec<String>,
) -> Vec<Material> {
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
                        match texture_path(uri, folder, options) {
                            Ok(path) => material.texture = Some(path),
                            Err(e) => warnings.push(format!(
                                "material `{}`: texture not used (fallback colour): {e}",
                                material.name
                            )),
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

/// The path of a texture URI, confined to the model's folder unless allowed.
fn texture_path(
    uri: &str,
    folder: Option<&Folder>,
    options: &LoadOptions,
) -> Result<PathBuf, String> {
    let relative = uri_path(uri)?;
    match folder {
        Some(folder) => folder
            .resolve(folder.path(), &relative)
            .map_err(|r| r.describe(folder, uri)),
        None if options.allow_outside_paths => Ok(relative),
        None => Err(format!(
            "`{uri}`: in-memory input has no folder to confine it to \
             (LoadOptions::allow_outside_paths records it as given)"
        )),
    }
}
