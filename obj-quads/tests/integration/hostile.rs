//! Hostile files: paths that leave the model's folder, and every resource limit.
//! Each test builds its files in a fresh temporary folder.

use std::fs;
use std::path::{Path, PathBuf};

use obj_quads::{LoadError, LoadOptions, decode_texture, load, load_gltf_slice, load_texture};

/// A fresh, empty temporary folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("obj-quads-hostile-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).expect("create scratch folder");
    dir
}

fn write(path: &Path, bytes: impl AsRef<[u8]>) {
    if let Some(parent) = path.parent() {
        fs::create_dir_all(parent).expect("create folder");
    }
    fs::write(path, bytes).expect("write file");
}

/// One triangle's positions: 3 × VEC3 f32.
fn triangle_bytes() -> Vec<u8> {
    [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect()
}

/// A glTF triangle whose buffer has `buffer_uri`, with a textured material
/// whose image has `image_uri`, and uvs.
fn gltf_with(buffer_uri: &str, image_uri: &str) -> String {
    r#"{
 "asset": {"version": "2.0"},
 "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
 "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
 "textures": [{"source": 0}],
 "images": [{"uri": "IMAGE"}],
 "buffers": [{"byteLength": 36, "uri": "BUFFER"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0,0,0], "max": [1,1,0]}]
}"#
    .replace("BUFFER", buffer_uri)
    .replace("IMAGE", image_uri)
}

fn trusted() -> LoadOptions {
    LoadOptions::DEFAULT.with_allow_outside_paths(true)
}

fn assert_outside(e: &LoadError, reference: &str) {
    match e {
        LoadError::PathOutsideModel {
            reference: r, file, ..
        } => {
            assert_eq!(r, reference, "{e}");
            assert!(!file.is_empty());
            let message = e.to_string();
            assert!(
                message.contains(reference) && message.contains(file.as_str()),
                "{message}"
            );
        }
        other => panic!("expected PathOutsideModel for `{reference}`, got {other:?}"),
    }
}

// ---------------------------------------------------------------- glTF buffers

#[test]
fn gltf_buffer_with_dot_dot_is_refused_unless_allowed() {
    let dir = scratch("buffer-dotdot");
    write(&dir.join("secret.bin"), triangle_bytes());
    let model = dir.join("model/scene.gltf");
    write(&model, gltf_with("../secret.bin", "t.png"));
    let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
    assert_outside(&e, "../secret.bin");
    // Percent-encoded dots are decoded before the check.
    write(&model, gltf_with("%2E%2E/secret.bin", "t.png"));
    let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
    assert_outside(&e, "%2E%2E/secret.bin");
    // The caller trusts the file: it loads.
    let (mesh, _) = load(&model, &trusted()).expect("allowed outside");
    assert_eq!(mesh.face_count(), 1);
}

#[test]
fn gltf_buffer_with_absolute_path_is_refused() {
    let dir = scratch("buffer-absolute");
    let secret = dir.join("secret.bin");
    write(&secret, triangle_bytes());
    let model = dir.join("model/scene.gltf");
    for uri in [
        secret.display().to_string(),
        format!("file://{}", secret.display()),
    ] {
        write(&model, gltf_with(&uri, "t.png"));
        let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
        assert_outside(&e, &uri);
        assert!(load(&model, &trusted()).is_ok());
    }
    // An absolute path that stays inside the folder is fine.
    let inside = dir.join("model/inside.bin");
    write(&inside, triangle_bytes());
    write(&model, gltf_with(&inside.display().to_string(), "t.png"));
    assert!(load(&model, &LoadOptions::DEFAULT).is_ok());
}

#[cfg(unix)]
#[test]
fn gltf_buffer_through_a_symlink_out_is_refused() {
    let dir = scratch("buffer-symlink");
    write(&dir.join("secret.bin"), triangle_bytes());
    let model = dir.join("model/scene.gltf");
    write(&model, gltf_with("link.bin", "t.png"));
    std::os::unix::fs::symlink(dir.join("secret.bin"), dir.join("model/link.bin")).unwrap();
    let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
    assert_outside(&e, "link.bin");
    // A linked folder that leads out is caught too.
    std::os::unix::fs::symlink(&dir, dir.join("model/up")).unwrap();
    write(&model, gltf_with("up/secret.bin", "t.png"));
    let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
    assert_outside(&e, "up/secret.bin");
    assert!(load(&model, &trusted()).is_ok());
}

#[cfg(unix)]
#[test]
fn special_files_are_not_opened() {
    // A FIFO would block `open` until a writer comes: it must be refused before.
    let dir = scratch("fifo");
    let fifo = dir.join("model/pipe.bin");
    fs::create_dir_all(dir.join("model")).unwrap();
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let model = dir.join("model/scene.gltf");
    write(&model, gltf_with("pipe.bin", "t.png"));
    let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
    assert!(
        matches!(&e, LoadError::Io { file, .. } if file.ends_with("pipe.bin")),
        "{e}"
    );
    assert!(e.to_string().contains("not a regular file"), "{e}");
    let e = load_texture(&fifo, &LoadOptions::DEFAULT).unwrap_err();
    assert!(e.to_string().contains("not a regular file"), "{e}");
}

#[test]
fn gltf_buffers_inside_the_folder_and_data_uris_load() {
    let dir = scratch("buffer-inside");
    write(&dir.join("model/sub/a.bin"), triangle_bytes());
    let model = dir.join("model/scene.gltf");
    write(&model, gltf_with("sub/../sub/a.bin", "t.png"));
    assert!(load(&model, &LoadOptions::DEFAULT).is_ok());
    let data =
        "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    write(&model, gltf_with(data, "t.png"));
    assert!(load(&model, &LoadOptions::DEFAULT).is_ok());
    // A missing buffer is an I/O error naming the path, not a refusal.
    write(&model, gltf_with("missing.bin", "t.png"));
    let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
    assert!(
        matches!(&e, LoadError::Io { file, .. } if file.contains("missing.bin")),
        "{e}"
    );
}

// ---------------------------------------------------------------- glTF images

#[test]
fn gltf_image_outside_is_dropped_with_a_warning() {
    let dir = scratch("image");
    write(&dir.join("model/scene.bin"), triangle_bytes());
    write(&dir.join("secret.png"), b"not really a png");
    write(&dir.join("model/ok.png"), b"not really a png");
    let model = dir.join("model/scene.gltf");
    write(&model, gltf_with("scene.bin", "../secret.png"));
    let (mesh, report) = load(&model, &LoadOptions::DEFAULT).unwrap();
    assert_eq!(mesh.materials()[0].texture, None);
    assert!(
        report
            .warnings
            .iter()
            .any(|w| w.contains("../secret.png") && w.contains("outside")),
        "{:?}",
        report.warnings
    );
    let (mesh, _) = load(&model, &trusted()).unwrap();
    assert!(mesh.materials()[0].texture.is_some());
    // Inside the folder: recorded (canonical path).
    write(&model, gltf_with("scene.bin", "ok.png"));
    let (mesh, _) = load(&model, &LoadOptions::DEFAULT).unwrap();
    let texture = mesh.materials()[0].texture.clone().expect("texture kept");
    assert!(texture.ends_with("model/ok.png"), "{}", texture.display());
    // From memory there is no folder: dropped unless allowed.
    let data =
        "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    let text = gltf_with(data, "/etc/passwd");
    let (mesh, report) = load_gltf_slice(text.as_bytes(), &LoadOptions::DEFAULT).unwrap();
    assert_eq!(mesh.materials()[0].texture, None);
    assert!(report.warnings.iter().any(|w| w.contains("/etc/passwd")));
    let (mesh, _) = load_gltf_slice(text.as_bytes(), &trusted()).unwrap();
    assert_eq!(
        mesh.materials()[0].texture.as_deref(),
        Some(Path::new("/etc/passwd"))
    );
}

// ---------------------------------------------------------------- OBJ and MTL

const OBJ_BODY: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n";

#[test]
fn mtllib_outside_is_refused_unless_allowed() {
    let dir = scratch("mtllib");
    write(&dir.join("secret.mtl"), "newmtl m\nKd 1 0 0\n");
    let model = dir.join("model/m.obj");
    let absolute = dir.join("secret.mtl").display().to_string();
    for name in ["../secret.mtl", absolute.as_str()] {
        write(&model, format!("mtllib {name}\n{OBJ_BODY}"));
        let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
        assert_outside(&e, name);
        let (mesh, _) = load(&model, &trusted()).unwrap();
        assert_eq!(mesh.materials()[0].diffuse, [1.0, 0.0, 0.0, 1.0]);
    }
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(dir.join("secret.mtl"), dir.join("model/link.mtl")).unwrap();
        write(&model, format!("mtllib link.mtl\n{OBJ_BODY}"));
        let e = load(&model, &LoadOptions::DEFAULT).unwrap_err();
        assert_outside(&e, "link.mtl");
    }
    // Inside: loads. Missing: a warning, as before.
    write(&dir.join("model/mats/in.mtl"), "newmtl m\nKd 0 1 0\n");
    write(&model, format!("mtllib mats/in.mtl\n{OBJ_BODY}"));
    let (mesh, _) = load(&model, &LoadOptions::DEFAULT).unwrap();
    assert_eq!(mesh.materials()[0].diffuse, [0.0, 1.0, 0.0, 1.0]);
    write(&model, format!("mtllib missing.mtl\n{OBJ_BODY}"));
    let (_, report) = load(&model, &LoadOptions::DEFAULT).unwrap();
    assert!(report.warnings.iter().any(|w| w.contains("missing.mtl")));
}

#[test]
fn map_kd_outside_is_dropped_with_a_warning() {
    let dir = scratch("map-kd");
    write(&dir.join("secret.png"), b"x");
    write(&dir.join("model/tex/in.png"), b"x");
    let model = dir.join("model/m.obj");
    write(&model, format!("mtllib mats/m.mtl\n{OBJ_BODY}"));
    let absolute = dir.join("secret.png").display().to_string();
    // The MTL sits in a subfolder: `../tex/in.png` stays inside the model's
    // folder, `../../secret.png` leaves it.
    for (map, inside) in [
        ("../tex/in.png", true),
        ("../../secret.png", false),
        ("-s 1 1 1 ../../secret.png", false),
        (absolute.as_str(), false),
    ] {
        write(
            &dir.join("model/mats/m.mtl"),
            format!("newmtl m\nKd 1 0 0\nmap_Kd {map}\n"),
        );
        let (mesh, report) = load(&model, &LoadOptions::DEFAULT).unwrap();
        let texture = &mesh.materials()[0].texture;
        if inside {
            assert!(texture.as_ref().is_some_and(|t| t.ends_with("tex/in.png")));
        } else {
            assert_eq!(texture, &None, "{map}");
            assert!(
                report
                    .warnings
                    .iter()
                    .any(|w| w.contains("map_Kd") && w.contains("outside")),
                "{map}: {:?}",
                report.warnings
            );
            // The diffuse colour stays as the fallback.
            assert_eq!(mesh.materials()[0].diffuse, [1.0, 0.0, 0.0, 1.0]);
            let (mesh, _) = load(&model, &trusted()).unwrap();
            assert!(mesh.materials()[0].texture.is_some(), "{map}");
        }
    }
}

// ---------------------------------------------------------------- limits

#[test]
fn vertex_face_and_file_size_limits() {
    let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 3 4\n";
    let too_large = |e: LoadError, expected: &str| match e {
        LoadError::TooLarge {
            what,
            actual,
            limit,
            ..
        } => {
            assert!(what.contains(expected), "{what}");
            assert!(actual > limit);
        }
        other => panic!("expected TooLarge {expected}, got {other:?}"),
    };
    let e = obj_quads::load_obj_str(quad, &LoadOptions::DEFAULT.with_max_vertices(3)).unwrap_err();
    too_large(e, "vertex count");
    let with_uvs = format!("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n{quad}");
    let e =
        obj_quads::load_obj_str(&with_uvs, &LoadOptions::DEFAULT.with_max_vertices(3)).unwrap_err();
    too_large(e, "texture coordinate count");
    let with_normals = format!("vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n{quad}");
    let e = obj_quads::load_obj_str(&with_normals, &LoadOptions::DEFAULT.with_max_vertices(3))
        .unwrap_err();
    too_large(e, "normal count");
    let e = obj_quads::load_obj_str(quad, &LoadOptions::DEFAULT.with_max_faces(1)).unwrap_err();
    too_large(e, "face count");
    let e = obj_quads::load_obj_reader(
        quad.as_bytes(),
        None,
        &LoadOptions::DEFAULT.with_max_file_bytes(10),
    )
    .unwrap_err();
    too_large(e, "size in bytes");
    let dir = scratch("limits");
    let model = dir.join("m.obj");
    write(&model, quad);
    let e = load(&model, &LoadOptions::DEFAULT.with_max_file_bytes(10)).unwrap_err();
    too_large(e, "file size");
    // glTF: vertices, faces, declared buffer length, external buffer size.
    // The buffer file holds 2000 bytes beyond the 36 it declares.
    let mut padded = triangle_bytes();
    padded.resize(2036, 0);
    write(&dir.join("t.bin"), padded);
    let gltf = dir.join("t.gltf");
    write(&gltf, gltf_with("t.bin", "x.png"));
    too_large(
        load(&gltf, &LoadOptions::DEFAULT.with_max_vertices(2)).unwrap_err(),
        "vertex count",
    );
    too_large(
        load(&gltf, &LoadOptions::DEFAULT.with_max_faces(0)).unwrap_err(),
        "face count",
    );
    assert!(load(&gltf, &LoadOptions::DEFAULT).is_ok());
    match load(&gltf, &LoadOptions::DEFAULT.with_max_file_bytes(1500)) {
        Err(LoadError::TooLarge { file, what, .. }) => {
            assert!(file.ends_with("t.bin"), "{file}");
            assert!(what.contains("file size"), "{what}");
        }
        other => panic!("{other:?}"),
    }
    let huge = gltf_with("t.bin", "x.png").replace(
        r#""byteLength": 36, "uri""#,
        r#""byteLength": 99999999999, "uri""#,
    );
    write(&gltf, huge);
    too_large(
        load(&gltf, &LoadOptions::DEFAULT).unwrap_err(),
        "declared glTF buffer length",
    );
}

const DATA_TRIANGLE: &str =
    "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";

/// A triangle glTF whose node list is `nodes` (node 0 is the scene root; the
/// node named in `mesh_node` carries the mesh).
fn gltf_nodes(nodes: &str) -> String {
    gltf_with(DATA_TRIANGLE, "x.png").replace(r#""nodes": [{"mesh": 0}]"#, nodes)
}

#[test]
fn gltf_node_depth_limit_and_cycles() {
    // A chain of 100 nodes, the mesh at the bottom.
    let chain: Vec<String> = (0..100)
        .map(|i| {
            if i == 99 {
                r#"{"mesh": 0}"#.to_owned()
            } else {
                format!(r#"{{"children": [{}]}}"#, i + 1)
            }
        })
        .collect();
    let text = gltf_nodes(&format!(r#""nodes": [{}]"#, chain.join(",")));
    match load_gltf_slice(text.as_bytes(), &LoadOptions::DEFAULT) {
        Err(LoadError::Gltf { detail, .. }) => {
            assert!(detail.contains("deeper than the limit 64"), "{detail}");
            assert!(detail.contains("node 64"), "{detail}");
        }
        other => panic!("{other:?}"),
    }
    let deep = LoadOptions::DEFAULT.with_max_node_depth(100);
    assert_eq!(
        load_gltf_slice(text.as_bytes(), &deep)
            .unwrap()
            .0
            .face_count(),
        1
    );
    // A cycle 0 -> 1 -> 2 -> 1 is found and named, whatever the depth limit.
    let cycle = gltf_nodes(
        r#""nodes": [{"mesh": 0, "children": [1]}, {"children": [2]}, {"children": [1]}]"#,
    );
    for options in [LoadOptions::DEFAULT, deep.with_max_node_depth(usize::MAX)] {
        match load_gltf_slice(cycle.as_bytes(), &options) {
            Err(LoadError::Gltf { detail, .. }) => {
                assert!(detail.contains("node 1 is its own ancestor"), "{detail}")
            }
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn gltf_shared_subtrees_cannot_explode_the_walk() {
    // Node i has node i+1 as both its children: 2^30 paths to the last node.
    let nodes: Vec<String> = (0..31)
        .map(|i| {
            if i == 30 {
                r#"{"mesh": 0}"#.to_owned()
            } else {
                format!(r#"{{"children": [{0}, {0}]}}"#, i + 1)
            }
        })
        .collect();
    let text = gltf_nodes(&format!(r#""nodes": [{}]"#, nodes.join(",")));
    match load_gltf_slice(text.as_bytes(), &LoadOptions::DEFAULT) {
        Err(LoadError::TooLarge {
            what,
            actual,
            limit,
            ..
        }) => {
            assert!(what.contains("node visits"), "{what}");
            assert_eq!((actual, limit), (65_537, 65_536));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn gltf_accessor_counts_are_checked_against_buffer_sizes() {
    let base = gltf_with(DATA_TRIANGLE, "x.png");
    for (count, view_length) in [("4", "36"), ("3000000000", "36"), ("3", "1000")] {
        let text = base
            .replace(r#""count": 3"#, &format!(r#""count": {count}"#))
            .replace(
                r#""byteLength": 36}"#,
                &format!(r#""byteLength": {view_length}}}"#),
            );
        match load_gltf_slice(text.as_bytes(), &LoadOptions::DEFAULT) {
            Err(LoadError::Gltf { detail, .. }) => {
                assert!(detail.contains("POSITION accessor 0"), "{detail}");
                assert!(detail.contains("overruns"), "{detail}");
            }
            other => panic!("count {count}, view {view_length}: {other:?}"),
        }
    }
}

// ---------------------------------------------------------------- textures

/// A zlib stream of `len` zero bytes in stored (uncompressed) blocks.
fn zlib_zeros(len: usize) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let mut left = len;
    while left > 0 {
        let n = left.min(65_535);
        left -= n;
        out.push(u8::from(left == 0));
        out.extend((n as u16).to_le_bytes());
        out.extend((!(n as u16)).to_le_bytes());
        out.extend(std::iter::repeat_n(0u8, n));
    }
    out.extend(1u32.to_be_bytes()); // Adler-32 of zeros
    out
}

/// PNG chunk with its CRC.
fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in kind.iter().chain(data) {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    let mut out = (data.len() as u32).to_be_bytes().to_vec();
    out.extend(kind);
    out.extend(data);
    out.extend((!crc).to_be_bytes());
    out
}

/// An RGBA8 PNG declaring `width × height` with `idat` as its image data.
fn png(width: u32, height: u32, idat: &[u8]) -> Vec<u8> {
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend(height.to_be_bytes());
    ihdr.extend([8, 6, 0, 0, 0]);
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    out.extend(chunk(b"IHDR", &ihdr));
    out.extend(chunk(b"IDAT", idat));
    out.extend(chunk(b"IEND", &[]));
    out
}

#[test]
fn png_bomb_is_refused_from_its_header() {
    // The issue's bomb: a 2.6 MB PNG declaring 30000 × 30000 RGBA pixels
    // (3.6 GB decoded). Refused from the IHDR, before any decoding.
    let bomb = png(30_000, 30_000, &zlib_zeros(2_600_000));
    assert!(bomb.len() > 2_600_000);
    let dir = scratch("bomb");
    let path = dir.join("bomb.png");
    write(&path, &bomb);
    match load_texture(&path, &LoadOptions::DEFAULT) {
        Err(LoadError::TooLarge {
            file,
            what,
            actual,
            limit,
        }) => {
            assert!(file.ends_with("bomb.png"), "{file}");
            assert_eq!(what, "texture width in pixels");
            assert_eq!((actual, limit), (30_000, 16_384));
        }
        other => panic!("{other:?}"),
    }
    // Within the side limit, the pixel count still refuses it.
    let options = LoadOptions::DEFAULT.with_max_texture_side(30_000);
    match load_texture(&path, &options) {
        Err(LoadError::TooLarge { what, actual, .. }) => {
            assert!(what.contains("pixel count"), "{what}");
            assert_eq!(actual, 900_000_000);
        }
        other => panic!("{other:?}"),
    }
    // And the file size limit refuses it before reading.
    let options = LoadOptions::DEFAULT.with_max_texture_file_bytes(1 << 20);
    match load_texture(&path, &options) {
        Err(LoadError::TooLarge { what, .. }) => assert!(what.contains("bytes"), "{what}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn png_within_limits_decodes_and_short_data_is_an_error() {
    // 2 × 2 RGBA: each row is a filter byte (0) and 8 zero bytes.
    let ok = png(2, 2, &zlib_zeros(18));
    let texture = decode_texture(&ok, "ok.png", &LoadOptions::DEFAULT).unwrap();
    assert_eq!((texture.width, texture.height), (2, 2));
    assert_eq!(texture.rgba, vec![0; 16]);
    // Declares 2048 × 2048 but holds 1 kB of data: a typed error, not a panic.
    let short = png(2048, 2048, &zlib_zeros(1024));
    let e = decode_texture(&short, "short.png", &LoadOptions::DEFAULT).unwrap_err();
    assert!(
        matches!(&e, LoadError::Texture { file, .. } if file == "short.png"),
        "{e}"
    );
    // A real texture.
    let spot = test_base::model_path("keenan-crane/spot/spot_texture.png");
    let texture = load_texture(&spot, &LoadOptions::DEFAULT).unwrap();
    assert_eq!(
        texture.rgba.len(),
        texture.width as usize * texture.height as usize * 4
    );
    assert!(texture.width > 0);
    // Neither PNG nor JPEG.
    let e = decode_texture(b"GIF89a", "x.gif", &LoadOptions::DEFAULT).unwrap_err();
    assert!(matches!(e, LoadError::Texture { .. }), "{e}");
}

#[test]
fn jpeg_limits_are_read_from_the_frame_header() {
    // SOI, an APP0 segment, then SOF0 declaring 60000 × 50000.
    let mut jpeg = vec![0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x04, 0x00, 0x00];
    jpeg.extend([0xFF, 0xC0, 0x00, 0x11, 0x08]);
    jpeg.extend(50_000u16.to_be_bytes()); // height
    jpeg.extend(60_000u16.to_be_bytes()); // width
    jpeg.extend([3, 1, 0x22, 0, 2, 0x11, 1, 3, 0x11, 1]);
    let header = obj_quads::texture_header(&jpeg, "big.jpg").unwrap();
    assert_eq!((header.width, header.height), (60_000, 50_000));
    match decode_texture(&jpeg, "big.jpg", &LoadOptions::DEFAULT) {
        Err(LoadError::TooLarge { what, actual, .. }) => {
            assert_eq!((what, actual), ("texture width in pixels", 60_000))
        }
        other => panic!("{other:?}"),
    }
    // Small enough, but no scan data: a typed decoding error.
    let small: Vec<u8> = jpeg
        .iter()
        .copied()
        .enumerate()
        .map(|(i, b)| match i {
            13 | 15 => 0,
            14 | 16 => 8,
            _ => b,
        })
        .collect();
    let e = decode_texture(&small, "small.jpg", &LoadOptions::DEFAULT).unwrap_err();
    assert!(matches!(e, LoadError::Texture { .. }), "{e}");
    // Truncated headers.
    for cut in [2, 5, 9, 14] {
        assert!(obj_quads::texture_header(&jpeg[..cut], "cut.jpg").is_err());
    }
}

#[test]
fn jpeg_within_limits_decodes() {
    let jpeg = test_base::encoded::grey_jpeg();
    let header = obj_quads::texture_header(&jpeg, "grey.jpg").unwrap();
    assert_eq!((header.width, header.height), (16, 8));
    let texture = decode_texture(&jpeg, "grey.jpg", &LoadOptions::DEFAULT).unwrap();
    assert_eq!((texture.width, texture.height), (16, 8));
    assert_eq!(texture.rgba.len(), 16 * 8 * 4);
    for pixel in texture.rgba.chunks_exact(4) {
        assert!(
            pixel[..3].iter().all(|&c| c.abs_diff(144) <= 1),
            "{pixel:?}"
        );
        assert_eq!(pixel[3], 255);
    }
    // The side limit applies to JPEG as to PNG.
    let small = LoadOptions::DEFAULT.with_max_texture_side(8);
    match decode_texture(&jpeg, "grey.jpg", &small) {
        Err(LoadError::TooLarge { what, actual, .. }) => {
            assert_eq!((what, actual), ("texture width in pixels", 16))
        }
        other => panic!("{other:?}"),
    }
}

/// An 8-bit palette PNG of 2 × 1 pixels (indices 0, 1) with the given PLTE and
/// optional tRNS payloads.
fn palette_png(plte: &[u8], trns: Option<&[u8]>) -> Vec<u8> {
    let mut ihdr = 2u32.to_be_bytes().to_vec();
    ihdr.extend(1u32.to_be_bytes());
    ihdr.extend([8, 3, 0, 0, 0]);
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    out.extend(chunk(b"IHDR", &ihdr));
    out.extend(chunk(b"PLTE", plte));
    if let Some(trns) = trns {
        out.extend(chunk(b"tRNS", trns));
    }
    // One row: filter 0, indices 0 and 1, in a stored zlib block.
    let row = [0u8, 0, 1];
    let mut idat = vec![0x78, 0x01, 0x01, 3, 0, !3u8, 0xFF];
    idat.extend(row);
    let (mut a, mut b) = (1u32, 0u32);
    for &x in &row {
        a = (a + u32::from(x)) % 65_521;
        b = (b + a) % 65_521;
    }
    idat.extend(((b << 16) | a).to_be_bytes());
    out.extend(chunk(b"IDAT", &idat));
    out.extend(chunk(b"IEND", &[]));
    out
}

#[test]
fn malformed_png_palettes_are_refused_not_panicked_on() {
    // Found by `cargo xtask fuzz --loaders` (tests/data/loaders/fuzz-ccf2ef2c3e0747d3.png):
    // png 0.18 panics expanding a PLTE whose length is not a multiple of 3.
    let two_entries = [255, 0, 0, 0, 0, 255];
    let ok = decode_texture(
        &palette_png(&two_entries, Some(&[128])),
        "ok.png",
        &LoadOptions::DEFAULT,
    )
    .unwrap();
    assert_eq!(ok.rgba, vec![255, 0, 0, 128, 0, 0, 255, 255]);
    for (plte, trns, expected) in [
        (&two_entries[..5], None, "PLTE chunk of 5 bytes"),
        (&[7u8; 3 * 257][..], None, "PLTE chunk of 771 bytes"),
        (
            &two_entries[..],
            Some(&[1u8, 2, 3][..]),
            "tRNS chunk of 3 entries",
        ),
    ] {
        match decode_texture(&palette_png(plte, trns), "bad.png", &LoadOptions::DEFAULT) {
            Err(LoadError::Texture { file, detail }) => {
                assert_eq!(file, "bad.png");
                assert!(detail.contains(expected), "{detail}");
            }
            other => panic!("{expected}: {other:?}"),
        }
    }
}
