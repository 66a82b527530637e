//! Buffers: the GLB binary chunk, data URIs (base64), and external files
//! confined to the model's folder.

use std::path::PathBuf;

use base64::Engine as _;
use base64::engine::{DecodePaddingMode, GeneralPurpose, GeneralPurposeConfig};
use gltf::Document;

use super::gltf_err;
use crate::paths::{Folder, Refusal};
use crate::{LoadError, LoadOptions};

/// Standard base64 with or without padding (glTF writers differ).
const BASE64: GeneralPurpose = GeneralPurpose::new(
    &base64::alphabet::STANDARD,
    GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent),
);

/// Same, URL-safe alphabet (`-`, `_`), which some writers use.
const BASE64_URL: GeneralPurpose = GeneralPurpose::new(
    &base64::alphabet::URL_SAFE,
    GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent),
);

/// Decodes the payload of a `data:…;base64,` URI; `None` if it is not base64.
pub(super) fn data_uri(uri: &str) -> Option<Result<Vec<u8>, String>> {
    let rest = uri.strip_prefix("data:")?;
    let Some((_, payload)) = rest.split_once(";base64,") else {
        return Some(Err("data URI is not base64".into()));
    };
    Some(
        BASE64
            .decode(payload)
            .or_else(|_| BASE64_URL.decode(payload))
            .map_err(|e| format!("bad base64 in data URI: {e}")),
    )
}

/// Loads every buffer: GLB binary chunk, data URI, or external file.
pub(super) fn load_buffers(
    doc: &Document,
    mut blob: Option<Vec<u8>>,
    folder: Option<&Folder>,
    file: &str,
    options: &LoadOptions,
) -> Result<Vec<Vec<u8>>, LoadError> {
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let which = format!("buffer {}", buffer.index());
        if buffer.length() as u64 > options.max_file_bytes {
            return Err(LoadError::TooLarge {
                file: file.to_owned(),
                what: "declared glTF buffer length in bytes",
                actual: buffer.length() as u64,
                limit: options.max_file_bytes,
            });
        }
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob
                .take()
                .ok_or_else(|| gltf_err(file, format!("{which}: GLB binary chunk missing")))?,
            gltf::buffer::Source::Uri(uri) => {
                if let Some(decoded) = data_uri(uri) {
                    decoded.map_err(|e| gltf_err(file, format!("{which}: {e}")))?
                } else {
                    let Some(folder) = folder else {
                        return Err(gltf_err(
                            file,
                            format!(
                                "{which}: external buffer `{uri}` cannot be loaded from memory"
                            ),
                        ));
                    };
                    let relative =
                        uri_path(uri).map_err(|e| gltf_err(file, format!("{which}: {e}")))?;
                    let path = folder
                        .resolve(folder.path(), &relative)
                        .map_err(|refusal| match refusal {
                            Refusal::Outside { resolved } => LoadError::PathOutsideModel {
                                file: file.to_owned(),
                                what: format!("{which} uri"),
                                reference: uri.to_owned(),
                                resolved,
                                folder: folder.path().to_path_buf(),
                            },
                            Refusal::Unresolvable { joined, source } => LoadError::Io {
                                file: joined.display().to_string(),
                                source,
                            },
                        })?;
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

/// The relative (or absolute) file path of a non-data URI, percent-decoded.
/// Only plain paths and the `file:` scheme are accepted.
pub(super) fn uri_path(uri: &str) -> Result<PathBuf, String> {
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
    let decoded = percent_encoding::percent_decode_str(path)
        .decode_utf8()
        .map_err(|_| format!("bad percent-encoding in `{uri}` (not UTF-8)"))?;
    if decoded.contains('\0') {
        return Err(format!("NUL byte in `{uri}`"));
    }
    Ok(PathBuf::from(decoded.as_ref()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_uris_decode_with_or_without_padding_and_either_alphabet() {
        let ok = |uri: &str| data_uri(uri).and_then(Result::ok);
        assert_eq!(ok("data:x;base64,aGVsbG8=").as_deref(), Some(&b"hello"[..]));
        assert_eq!(ok("data:x;base64,aGVsbG8").as_deref(), Some(&b"hello"[..]));
        assert_eq!(ok("data:x;base64,-_8").as_deref(), Some(&[0xfb, 0xff][..]));
        assert!(matches!(data_uri("data:x;base64,a*"), Some(Err(_))));
        assert!(matches!(data_uri("data:,plain"), Some(Err(_))));
        assert!(data_uri("model.bin").is_none());
    }

    #[test]
    fn uri_paths_are_percent_decoded() {
        assert_eq!(uri_path("a%20b.bin"), Ok(PathBuf::from("a b.bin")));
        assert_eq!(uri_path("100%"), Ok(PathBuf::from("100%")));
        assert_eq!(uri_path("file:///x/y.bin"), Ok(PathBuf::from("/x/y.bin")));
        assert!(uri_path("%FF").is_err());
        assert!(uri_path("http://example.com/x.bin").is_err());
        assert!(uri_path("a%00b").is_err());
    }
}
