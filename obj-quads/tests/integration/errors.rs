//! Typed errors and report counts on small in-memory inputs.

use obj_quads::{
    FacePolicy, LoadError, LoadOptions, NonPlanarPolicy, load, load_gltf_slice, load_obj_str,
};

fn err(text: &str) -> LoadError {
    match load_obj_str(text, &LoadOptions::default()) {
        Ok((mesh, report)) => panic!("expected an error, got {mesh:?} {report:?}"),
        Err(e) => e,
    }
}

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn missing_file_and_unknown_extension() {
    let e = load("/nonexistent/model.obj", &LoadOptions::default()).unwrap_err();
    assert!(matches!(e, LoadError::Io { .. }), "{e}");
    assert!(e.to_string().contains("/nonexistent/model.obj"), "{e}");
    let e = load("model.stl", &LoadOptions::default()).unwrap_err();
    assert!(matches!(e, LoadError::UnsupportedFormat { .. }), "{e}");
}

#[test]
fn index_zero_and_out_of_range_name_line_and_face() {
    let e = err(&format!("{SQUARE}o quad\nf 1 2 3 4\nf 1 2 0\n"));
    assert!(
        matches!(e, LoadError::IndexOutOfRange { index: 0, .. }),
        "{e}"
    );
    let msg = e.to_string();
    assert!(
        msg.contains("face 1") && msg.contains("line 7") && msg.contains("`quad`"),
        "{msg}"
    );
    let e = err(&format!("{SQUARE}f 1 2 9\n"));
    assert!(
        matches!(
            e,
            LoadError::IndexOutOfRange {
                index: 9,
                count: 4,
                ..
            }
        ),
        "{e}"
    );
    let e = err(&format!("{SQUARE}f -1 -2 -5\n"));
    assert!(
        matches!(e, LoadError::IndexOutOfRange { index: -5, .. }),
        "{e}"
    );
}

#[test]
fn negative_indices_work() {
    let (mesh, _) =
        load_obj_str(&format!("{SQUARE}f -4 -3 -2 -1\n"), &LoadOptions::default()).unwrap();
    assert_eq!(mesh.arity_histogram().get(&4), Some(&1));
}

#[test]
fn non_finite_coordinates_are_errors() {
    for bad in ["nan", "inf", "-inf", "NaN"] {
        let e = err(&format!("v 0 0 0\nv 1 0 {bad}\nv 0 1 0\nf 1 2 3\n"));
        assert!(
            matches!(e, LoadError::NonFiniteCoordinate { line: Some(2), .. }),
            "{e}"
        );
    }
}

#[test]
fn empty_models_are_errors() {
    for text in ["", "# nothing\n", SQUARE, "v 0 0 0\nl 1 1\n"] {
        let e = err(text);
        assert!(matches!(e, LoadError::EmptyModel { .. }), "{text:?}: {e}");
    }
    // Everything degenerate: also empty.
    let e = err("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    assert!(matches!(e, LoadError::EmptyModel { .. }), "{e}");
}

#[test]
fn faces_with_fewer_than_three_corners() {
    for f in ["f", "f 1", "f 1 2"] {
        let e = err(&format!("{SQUARE}f 1 2 3\n{f}\n"));
        assert!(matches!(e, LoadError::TooFewCorners { .. }), "{f}: {e}");
        assert!(
            e.to_string().contains("line 6") && e.to_string().contains("face 1"),
            "{e}"
        );
    }
}

#[test]
fn lines_and_garbage_are_ignored() {
    let (mesh, report) = load_obj_str(
        &format!("{SQUARE}l 1 2 3\nxyz garbage\nf 1 2 3 4 # a quad\nl 3 4\n"),
        &LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(mesh.face_count(), 1);
    assert_eq!(report.faces_read, 1);
}

#[test]
fn invalid_utf8_names_the_line() {
    let mut bytes = SQUARE.as_bytes().to_vec();
    bytes.extend_from_slice(b"f 1 2 \xff 4\n");
    let e = obj_quads::load_obj_reader(&bytes[..], None, &LoadOptions::default()).unwrap_err();
    assert!(
        matches!(e, LoadError::InvalidText { line: Some(5), .. }),
        "{e}"
    );
}

#[test]
fn too_many_corners() {
    let n = 1100;
    let mut text = String::new();
    for i in 0..n {
        let a = i as f64 / n as f64 * std::f64::consts::TAU;
        text.push_str(&format!("v {} {} 0\n", a.cos(), a.sin()));
    }
    text.push('f');
    for i in 1..=n {
        text.push_str(&format!(" {i}"));
    }
    text.push('\n');
    let e = err(&text);
    assert!(
        matches!(
            e,
            LoadError::TooManyCorners {
                corners: 1100,
                max: 1024,
                ..
            }
        ),
        "{e}"
    );
    let big = LoadOptions::DEFAULT.with_max_face_corners(2000);
    let (mesh, _) = load_obj_str(&text, &big).unwrap();
    assert_eq!(mesh.arity_histogram().get(&1100), Some(&1));
}

#[test]
fn degenerate_faces_are_dropped_and_counted() {
    let text = format!("{SQUARE}v 2 0 0\nf 1 2 3 4\nf 1 2 5\nf 1 1 2 2\n");
    let (mesh, report) = load_obj_str(&text, &LoadOptions::default()).unwrap();
    assert_eq!(mesh.face_count(), 1);
    assert_eq!(report.degenerate_dropped, 2);
    assert_eq!(report.faces_read, 3);
}

#[test]
fn consecutive_duplicate_corners_are_dropped() {
    let (mesh, report) =
        load_obj_str(&format!("{SQUARE}f 1 2 2 3 4 1\n"), &LoadOptions::default()).unwrap();
    assert_eq!(mesh.face(0), Some(&[0u32, 1, 2, 3][..]));
    assert_eq!(report.degenerate_dropped, 0);
}

#[test]
fn non_planar_policies() {
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0.2\nv 0 1 0\nf 1 2 3 4\n";
    let (mesh, report) = load_obj_str(text, &LoadOptions::default()).unwrap();
    assert_eq!((mesh.face_count(), report.non_planar), (1, 1));
    let split = LoadOptions::DEFAULT.with_non_planar(NonPlanarPolicy::SplitFan);
    let (mesh, _) = load_obj_str(text, &split).unwrap();
    assert_eq!(mesh.arity_histogram().get(&3), Some(&2));
    let reject = LoadOptions::DEFAULT.with_non_planar(NonPlanarPolicy::Reject);
    let e = load_obj_str(text, &reject).unwrap_err();
    assert!(matches!(e, LoadError::NonPlanarFace { .. }), "{e}");
}

#[test]
fn merge_pairs_a_split_square_and_keeps_order() {
    let text = format!("{SQUARE}v 5 5 5\nv 6 5 5\nv 5 6 5\nf 5 6 7\nf 1 2 3\nf 1 3 4\n");
    let opts = LoadOptions::DEFAULT.with_face_policy(FacePolicy::MergeTriangles);
    let (mesh, report) = load_obj_str(&text, &opts).unwrap();
    assert_eq!(mesh.face_count(), 2);
    assert_eq!(mesh.face(1).map(<[u32]>::len), Some(4));
    assert_eq!(mesh.face_source(1), Some(1));
    assert_eq!(report.triangles_merged, 2);
    // A folded pair (not coplanar) is not merged.
    let folded = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 1 2 3\nf 1 3 4\n";
    let (mesh, _) = load_obj_str(folded, &opts).unwrap();
    assert_eq!(mesh.face_count(), 2);
}

#[test]
fn from_faces_validates() {
    use glam::DVec3;
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    assert!(obj_quads::Mesh::from_faces(p.clone(), [[0u32, 1, 2]]).is_ok());
    assert!(obj_quads::Mesh::from_faces(p.clone(), [[0u32, 1, 3]]).is_err());
    assert!(obj_quads::Mesh::from_faces(p.clone(), Vec::<Vec<u32>>::new()).is_err());
    let nan = vec![DVec3::ZERO, DVec3::X, DVec3::NAN];
    assert!(obj_quads::Mesh::from_faces(nan, [[0u32, 1, 2]]).is_err());
    let m = obj_quads::Mesh::from_faces(p, [[0u32, 1, 2]]).unwrap();
    assert!(m.clone().with_uvs(vec![glam::Vec2::ZERO; 2]).is_err());
    assert!(m.clone().with_uvs(vec![glam::Vec2::ZERO; 3]).is_ok());
    let mat = obj_quads::Material::new("red", [1.0, 0.0, 0.0, 1.0]);
    assert!(
        m.clone()
            .with_materials(vec![mat.clone()], vec![Some(1)])
            .is_err()
    );
    assert!(m.with_materials(vec![mat], vec![Some(0)]).is_ok());
}

const TRIANGLE_GLTF: &str = r#"{
 "asset": {"version": "2.0"},
 "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}MODE}]}],
 "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
 "bufferViews": [{"buffer": 0, "byteLength": LEN}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0,0,0], "max": [1,1,0]}]
}"#;

fn gltf(mode: &str, len: &str) -> String {
    TRIANGLE_GLTF.replace("MODE", mode).replace("LEN", len)
}

#[test]
fn gltf_in_memory_triangle_and_errors() {
    let (mesh, _) = load_gltf_slice(gltf("", "36").as_bytes(), &LoadOptions::default()).unwrap();
    assert_eq!(mesh.face_count(), 1);
    // Lines mode: skipped with a warning, and then the model is empty.
    let e = load_gltf_slice(
        gltf(r#", "mode": 1"#, "36").as_bytes(),
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e, LoadError::EmptyModel { .. }), "{e}");
    // A buffer view longer than its buffer.
    let e = load_gltf_slice(gltf("", "48").as_bytes(), &LoadOptions::default()).unwrap_err();
    assert!(matches!(e, LoadError::Gltf { .. }), "{e}");
    // Bad percent-encoding in a buffer URI (would panic inside gltf::import).
    let bad = gltf("", "36").replace(
        "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA",
        "%FF.bin",
    );
    let e = load_gltf_slice(bad.as_bytes(), &LoadOptions::default()).unwrap_err();
    assert!(matches!(e, LoadError::Gltf { .. }), "{e}");
    let e = load_gltf_slice(b"not json", &LoadOptions::default()).unwrap_err();
    assert!(matches!(e, LoadError::Gltf { .. }), "{e}");
}

#[test]
fn gltf_node_cycle_is_an_error() {
    let cyclic = gltf("", "36").replace(
        r#""nodes": [{"mesh": 0}]"#,
        r#""nodes": [{"mesh": 0, "children": [1]}, {"children": [0]}]"#,
    );
    match load_gltf_slice(cyclic.as_bytes(), &LoadOptions::default()) {
        Err(LoadError::Gltf { detail, .. }) => assert!(
            detail.contains("node 0 is its own ancestor (cycle"),
            "{detail}"
        ),
        other => panic!("{other:?}"),
    }
}
