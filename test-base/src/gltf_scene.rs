//! A glTF scene that exercises the scene path: one cube mesh carried by five nodes, with
//! instancing, nested and non-uniform scales, a matrix node that mirrors, rotations, and
//! two instances whose boxes interlock. Buffers embedded as a data URI. Two cameras: camera 0
//! a perspective one (yfov 0.7, aspect ratio 1.5, znear 0.1) off to the side and looking
//! down, not at the scene's centre; camera 1 an orthographic one (xmag 4.5, ymag 3) under the
//! rotated root node, so its pose composes two nodes.

use base64::Engine as _;

/// A `data:` URI of `bytes` with a MIME type, base64 (as glTF files embed buffers and
/// images).
#[must_use]
pub fn data_uri(mime: &str, bytes: &[u8]) -> String {
    format!(
        "data:{mime};base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// The scene's glTF JSON.
#[must_use]
pub fn cube_scene_gltf() -> String {
    // A unit cube centred at the origin, counter-clockwise outward triangles.
    let corners: [[f32; 3]; 8] = [
        [-0.5, -0.5, -0.5],
        [0.5, -0.5, -0.5],
        [0.5, 0.5, -0.5],
        [-0.5, 0.5, -0.5],
        [-0.5, -0.5, 0.5],
        [0.5, -0.5, 0.5],
        [0.5, 0.5, 0.5],
        [-0.5, 0.5, 0.5],
    ];
    let quads: [[u16; 4]; 6] = [
        [0, 3, 2, 1], // -z
        [4, 5, 6, 7], // +z
        [0, 4, 7, 3], // -x
        [1, 2, 6, 5], // +x
        [0, 1, 5, 4], // -y
        [3, 7, 6, 2], // +y
    ];
    let mut bin = Vec::new();
    for c in corners {
        for v in c {
            bin.extend(v.to_le_bytes());
        }
    }
    for q in quads {
        for i in [q[0], q[1], q[2], q[0], q[2], q[3]] {
            bin.extend(i.to_le_bytes());
        }
    }
    let uri = data_uri("application/octet-stream", &bin);
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 6, 7]}}],
  "nodes": [
    {{"children": [1, 2, 3, 4, 8], "rotation": [0.0, 0.2588190451, 0.0, 0.9659258263]}},
    {{"mesh": 0, "rotation": [0.1, 0.2, 0.05, 0.9741], "scale": [1.5, 0.7, 1.0]}},
    {{"mesh": 0, "translation": [0.8, 0.2, 0.1], "rotation": [0.3, 0.0, 0.1, 0.9487]}},
    {{"mesh": 0, "matrix": [-1.0, 0.0, 0.0, 0.0,  0.0, 1.2, 0.0, 0.0,  0.0, 0.0, 0.8, 0.0,  3.5, 0.0, 0.0, 1.0]}},
    {{"children": [5], "translation": [0.0, 2.5, 0.0], "scale": [0.5, 0.5, 0.5]}},
    {{"mesh": 0, "rotation": [0.0, 0.0, 0.3826834324, 0.9238795325], "scale": [2.0, 1.0, 1.0]}},
    {{"mesh": 0, "translation": [-3.5, 0.0, 0.5], "scale": [1.0, 1.0, -1.0]}},
    {{"camera": 0, "translation": [2.0, 3.0, 9.0], "rotation": [-0.1300295007, 0.0864101133, 0.0113761072, 0.9876721144]}},
    {{"camera": 1, "translation": [0.0, 1.0, 10.0]}}
  ],
  "cameras": [
    {{"type": "perspective", "perspective": {{"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100.0}}}},
    {{"type": "orthographic", "orthographic": {{"xmag": 4.5, "ymag": 3.0, "znear": 0.1, "zfar": 100.0}}}}
  ],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]}},
    {{"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 96}},
    {{"buffer": 0, "byteOffset": 96, "byteLength": 72}}
  ],
  "buffers": [{{"byteLength": {len}, "uri": "{uri}"}}]
}}"#,
        len = bin.len()
    )
}
