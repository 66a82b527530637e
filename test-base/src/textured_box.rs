//! The repository's `BoxTextured` glTF with its texture held every way glTF allows: the PNG
//! beside the file (the asset as is), a data URI, or a GLB buffer view; optionally with a
//! `baseColorFactor`. For the loader's and the raster's embedded-texture tests.

use crate::gltf_scene::data_uri;
use crate::model_path;

/// Where the box's texture is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageSource {
    /// `CesiumLogoFlat.png` beside the `.gltf` (load it by path: [`textured_box_path`]).
    File,
    /// Buffer and image as `data:` URIs in the JSON.
    DataUri,
    /// A `.glb`: the buffer in the binary chunk, the image in a buffer view of it.
    Glb,
}

/// The asset's folder-relative path.
pub const TEXTURED_BOX: &str = "gltf/BoxTextured/BoxTextured.gltf";

/// The asset's path (the [`ImageSource::File`] variant without a factor).
#[must_use]
pub fn textured_box_path() -> std::path::PathBuf {
    model_path(TEXTURED_BOX)
}

/// The box's PNG texture bytes.
#[must_use]
pub fn textured_box_png() -> Vec<u8> {
    read("gltf/BoxTextured/CesiumLogoFlat.png")
}

fn read(relative: &str) -> Vec<u8> {
    let path = model_path(relative);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The box's file bytes (`.gltf` JSON, or `.glb`) with its texture held as `source` says
/// and `factor` as its material's `baseColorFactor`. [`ImageSource::File`] gives the JSON,
/// which names files beside the asset: load it from the asset's folder.
#[must_use]
pub fn textured_box(source: ImageSource, factor: Option<[f32; 4]>) -> Vec<u8> {
    let mut json = String::from_utf8(read(TEXTURED_BOX)).expect("UTF-8 JSON");
    let bin = read("gltf/BoxTextured/BoxTextured0.bin");
    let png = textured_box_png();
    let mut replace = |from: &str, to: &str| {
        assert!(json.contains(from), "BoxTextured.gltf has no `{from}`");
        json = json.replacen(from, to, 1);
    };
    if let Some(f) = factor {
        replace(
            "\"metallicFactor\": 0.0",
            &format!(
                "\"metallicFactor\": 0.0, \"baseColorFactor\": [{:?}, {:?}, {:?}, {:?}]",
                f[0], f[1], f[2], f[3]
            ),
        );
    }
    match source {
        ImageSource::File => json.into_bytes(),
        ImageSource::DataUri => {
            replace(
                "\"uri\": \"CesiumLogoFlat.png\"",
                &format!("\"uri\": \"{}\"", data_uri("image/png", &png)),
            );
            replace(
                "\"uri\": \"BoxTextured0.bin\"",
                &format!(
                    "\"uri\": \"{}\"",
                    data_uri("application/octet-stream", &bin)
                ),
            );
            json.into_bytes()
        }
        ImageSource::Glb => {
            assert_eq!(bin.len() % 4, 0, "the image view starts aligned");
            let total = bin.len() + png.len();
            replace(
                "\"uri\": \"CesiumLogoFlat.png\"",
                "\"bufferView\": 3, \"mimeType\": \"image/png\"",
            );
            replace(
                "\"byteLength\": 840,\n            \"uri\": \"BoxTextured0.bin\"",
                &format!("\"byteLength\": {total}"),
            );
            // The image's view goes last: index 3.
            replace(
                "\"byteStride\": 8,\n            \"target\": 34962\n        }\n    ]",
                &format!(
                    "\"byteStride\": 8,\n            \"target\": 34962\n        }}, {{\"buffer\": 0, \"byteOffset\": 840, \"byteLength\": {}}}\n    ]",
                    png.len()
                ),
            );
            let mut chunk = bin;
            chunk.extend(&png);
            crate::encoded::glb(&json, &chunk)
        }
    }
}
