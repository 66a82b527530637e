//! Materials: base colour factor and base colour texture: a path (confined to the
//! model's folder), or the encoded image held in the file (data URI, GLB buffer view).

use std::path::PathBuf;

use gltf::Document;

use super::buffers::{data_uri, uri_path};
use crate::paths::Folder;
use crate::{AlphaMode, EmbeddedTexture, LoadOptions, Material, WrapMode};

/// Materials in document order: base colour factor and texture.
pub(super) fn materials(
    doc: &Document,
    buffers: &[Vec<u8>],
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
            material.texture_times_diffuse = true;
            material.alpha_mode = match m.alpha_mode() {
                gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
                gltf::material::AlphaMode::Blend => AlphaMode::Blend,
                gltf::material::AlphaMode::Mask => AlphaMode::Mask {
                    cutoff: m.alpha_cutoff().filter(|c| c.is_finite()).unwrap_or(0.5),
                },
            };
            if let Some(info) = pbr.base_color_texture() {
                let sampler = info.texture().sampler();
                let wrap = |mode: gltf::texture::WrappingMode| match mode {
                    gltf::texture::WrappingMode::MirroredRepeat => WrapMode::MirroredRepeat,
                    gltf::texture::WrappingMode::ClampToEdge => WrapMode::ClampToEdge,
                    gltf::texture::WrappingMode::Repeat => WrapMode::Repeat,
                };
                material.wrap = [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())];
                let image = info.texture().source();
                let found = match image.source() {
                    gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                        texture_path(uri, folder, options).map(|path| material.texture = Some(path))
                    }
                    source => embedded(image.index(), &source, buffers, options)
                        .map(|texture| material.embedded_texture = Some(texture)),
                };
                if let Err(e) = found {
                    warnings.push(format!(
                        "material `{}`: texture not used (fallback colour): {e}",
                        material.name
                    ));
                }
            }
            material
        })
        .collect()
}

/// The encoded bytes of an image held in the file: a data URI, or a buffer view (its range
/// checked against its buffer), within the texture file size limit.
fn embedded(
    index: usize,
    source: &gltf::image::Source<'_>,
    buffers: &[Vec<u8>],
    options: &LoadOptions,
) -> Result<EmbeddedTexture, String> {
    let (name, bytes) = match source {
        gltf::image::Source::Uri { uri, .. } => {
            let decoded = data_uri(uri).unwrap_or_else(|| Err("not a data URI".into()))?;
            (format!("image {index} (data URI)"), decoded)
        }
        gltf::image::Source::View { view, .. } => {
            let buffer = buffers.get(view.buffer().index()).ok_or_else(|| {
                format!("image {index}: buffer {} missing", view.buffer().index())
            })?;
            let (start, length) = (view.offset(), view.length());
            let bytes = start
                .checked_add(length)
                .and_then(|end| buffer.get(start..end))
                .ok_or_else(|| {
                    format!(
                        "image {index}: buffer view {} ({length} bytes at {start}) overruns its buffer of {} bytes",
                        view.index(),
                        buffer.len()
                    )
                })?;
            (
                format!("image {index} (buffer view {})", view.index()),
                bytes.to_vec(),
            )
        }
    };
    if bytes.len() as u64 > options.max_texture_file_bytes {
        return Err(format!(
            "{name}: {} bytes, over the texture limit of {}",
            bytes.len(),
            options.max_texture_file_bytes
        ));
    }
    Ok(EmbeddedTexture::new(name, bytes))
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
