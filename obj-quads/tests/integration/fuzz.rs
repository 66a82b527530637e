//! Property tests: no input makes a loader panic. Cases default to 64 per
//! property; `PROPTEST_CASES` overrides.

use obj_quads::{FacePolicy, LoadOptions, NonPlanarPolicy, load_gltf_slice, load_obj_str};
use proptest::prelude::*;
use std::sync::LazyLock;

/// A model of the repository (`assets/models/`, through the workspace's test scaffolding),
/// read once.
fn asset(relative: &str) -> &'static [u8] {
    let bytes = std::fs::read(test_base::model_path(relative))
        .unwrap_or_else(|e| panic!("{relative}: {e}"));
    Box::leak(bytes.into_boxed_slice())
}

static CORNELL: LazyLock<&str> =
    LazyLock::new(|| std::str::from_utf8(asset("cornell-box/cornell_box.obj")).expect("UTF-8"));
static CONTROL: LazyLock<&str> = LazyLock::new(|| {
    std::str::from_utf8(asset("keenan-crane/spot/spot_control_mesh.obj")).expect("UTF-8")
});
static SIMPLE_GLTF: LazyLock<&[u8]> =
    LazyLock::new(|| asset("gltf/SimpleMeshes/glTF-Embedded/SimpleMeshes.gltf"));
static SCENES_GLTF: LazyLock<&[u8]> =
    LazyLock::new(|| asset("gltf/MultipleScenes/glTF-Embedded/MultipleScenes.gltf"));

fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(64);
    ProptestConfig::with_cases(cases)
}

fn all_options() -> Vec<LoadOptions> {
    let mut v = Vec::new();
    for face_policy in [
        FacePolicy::QuadsOnly,
        FacePolicy::Polygons,
        FacePolicy::MergeTriangles,
    ] {
        for non_planar in [NonPlanarPolicy::Keep, NonPlanarPolicy::SplitFan] {
            v.push(
                LoadOptions::DEFAULT
                    .with_face_policy(face_policy)
                    .with_non_planar(non_planar),
            );
        }
    }
    v
}

fn check_obj(text: &str) {
    for o in all_options() {
        if let Ok((mesh, report)) = load_obj_str(text, &o) {
            assert!(mesh.face_count() > 0);
            assert_eq!(report.faces_kept, mesh.face_count());
        }
    }
}

/// Token soup close to OBJ syntax.
fn obj_line() -> impl Strategy<Value = String> {
    let num = prop_oneof![
        (-3i32..3).prop_map(|i| i.to_string()),
        (-2.0f64..2.0).prop_map(|f| f.to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("1e308".to_string()),
        Just("-9223372036854775808".to_string()),
        Just("x".to_string()),
    ];
    let idx = prop_oneof![
        (-6i64..8).prop_map(|i| i.to_string()),
        ((-6i64..8), (-3i64..4)).prop_map(|(a, b)| format!("{a}/{b}")),
        ((-6i64..8), (-3i64..4), (-3i64..4)).prop_map(|(a, b, c)| format!("{a}/{b}/{c}")),
        (-6i64..8).prop_map(|a| format!("{a}//1")),
        Just("1/2/3/4".to_string()),
    ];
    prop_oneof![
        prop::collection::vec(num.clone(), 0..6).prop_map(|v| format!("v {}", v.join(" "))),
        prop::collection::vec(num, 0..4).prop_map(|v| format!("vt {}", v.join(" "))),
        prop::collection::vec(idx.clone(), 0..7).prop_map(|v| format!("f {}", v.join(" "))),
        prop::collection::vec(idx, 0..4).prop_map(|v| format!("l {}", v.join(" "))),
        "[a-z]{0,6}".prop_map(|n| format!("o {n}")),
        "[a-z]{0,6}".prop_map(|n| format!("usemtl {n}")),
        Just("mtllib missing.mtl".to_string()),
        ".{0,12}",
    ]
}

/// Applies byte-level mutations to a real file.
fn mutate(base: &[u8], edits: &[(usize, u8, u8)]) -> Vec<u8> {
    let mut bytes = base.to_vec();
    for &(pos, kind, byte) in edits {
        if bytes.is_empty() {
            bytes.push(byte);
            continue;
        }
        let i = pos % bytes.len();
        match kind % 4 {
            0 => bytes[i] = byte,
            1 => bytes.insert(i, byte),
            2 => {
                bytes.remove(i);
            }
            _ => bytes.truncate(i),
        }
    }
    bytes
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn random_obj_lines_never_panic(lines in prop::collection::vec(obj_line(), 0..40)) {
        check_obj(&lines.join("\n"));
    }

    #[test]
    fn mutated_obj_lines_never_panic(
        drops in prop::collection::vec(any::<usize>(), 0..8),
        inserts in prop::collection::vec((any::<usize>(), obj_line()), 0..8),
        pick in any::<bool>(),
    ) {
        let base = if pick { *CORNELL } else { *CONTROL };
        let mut lines: Vec<String> = base.lines().map(str::to_owned).collect();
        for d in drops {
            if !lines.is_empty() {
                let i = d % lines.len();
                lines.remove(i);
            }
        }
        for (at, line) in inserts {
            let i = at % (lines.len() + 1);
            lines.insert(i, line);
        }
        check_obj(&lines.join("\n"));
    }

    #[test]
    fn mutated_obj_bytes_never_panic(
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), any::<u8>()), 1..12),
    ) {
        let bytes = mutate(CORNELL.as_bytes(), &edits);
        let _ = obj_quads::load_obj_reader(&bytes[..], None, &LoadOptions::default());
    }

    #[test]
    fn random_bytes_as_gltf_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..256)) {
        let _ = load_gltf_slice(&bytes, &LoadOptions::default());
        // The same bytes behind a valid GLB header.
        let mut glb = b"glTF".to_vec();
        glb.extend_from_slice(&2u32.to_le_bytes());
        glb.extend_from_slice(&((bytes.len() + 12) as u32).to_le_bytes());
        glb.extend_from_slice(&bytes);
        let _ = load_gltf_slice(&glb, &LoadOptions::default());
    }

    #[test]
    fn mutated_gltf_never_panics(
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), any::<u8>()), 1..6),
        pick in any::<bool>(),
    ) {
        let base = if pick { *SIMPLE_GLTF } else { *SCENES_GLTF };
        let bytes = mutate(base, &edits);
        for o in all_options() {
            let _ = load_gltf_slice(&bytes, &o);
        }
    }

    #[test]
    fn mutated_gltf_numbers_never_panic(
        edits in prop::collection::vec((any::<usize>(), prop_oneof![
            Just("0"), Just("1"), Just("2"), Just("3"), Just("-1"), Just("4294967295"),
            Just("1e9"), Just("5121"), Just("5123"), Just("5125"), Just("36"), Just("35"),
        ]), 1..4),
    ) {
        // Replace whole numbers in the JSON: counts, offsets, indices, types.
        let text = String::from_utf8_lossy(*SIMPLE_GLTF).into_owned();
        let mut spans = Vec::new();
        let b = text.as_bytes();
        let mut i = 0;
        while i < b.len() {
            if b[i].is_ascii_digit() && (i == 0 || !b[i - 1].is_ascii_alphanumeric()) {
                let s = i;
                while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                    i += 1;
                }
                spans.push((s, i));
            } else {
                i += 1;
            }
        }
        let mut text = text.clone();
        let mut chosen: Vec<(usize, usize, &str)> = edits
            .iter()
            .map(|(k, v)| { let (s, e) = spans[k % spans.len()]; (s, e, *v) })
            .collect();
        chosen.sort_by_key(|c| std::cmp::Reverse(c.0));
        chosen.dedup_by_key(|c| c.0);
        for (s, e, v) in chosen {
            text.replace_range(s..e, v);
        }
        for o in all_options() {
            let _ = load_gltf_slice(text.as_bytes(), &o);
        }
    }
}
