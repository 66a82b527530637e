//! A polygon mesh written back as OBJ text (shrunk fuzz cases, generated models for
//! whole-process measurements).

use face_sort::PolygonMesh;

/// Writes a polygon mesh as OBJ text, with `comment` lines first.
#[must_use]
pub fn to_obj(mesh: &PolygonMesh, comment: &[String]) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    for line in comment {
        let _ = writeln!(out, "# {line}");
    }
    for p in mesh.positions() {
        // `{:?}` prints f64 so that it reads back exactly.
        let _ = writeln!(out, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    for face in mesh.faces() {
        out.push('f');
        for &i in face {
            let _ = write!(out, " {}", i + 1);
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::to_obj;

    #[test]
    fn reads_back_exactly() {
        let mesh = crate::models::bumpy_torus(200);
        let text = to_obj(&mesh, &["a comment".to_owned()]);
        assert!(text.starts_with("# a comment\n"));
        let (back, _) = obj_quads::load_obj_str(&text, &obj_quads::LoadOptions::default()).unwrap();
        // The loader numbers vertices in order of first use: compare corner positions.
        assert_eq!(back.face_count(), mesh.face_count());
        for f in 0..mesh.face_count() {
            let corners = |positions: &[face_sort::glam::DVec3], indices: &[u32]| {
                indices
                    .iter()
                    .map(|&i| positions[i as usize])
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                corners(back.positions(), back.face(f).unwrap()),
                corners(mesh.positions(), mesh.face(f)),
                "face {f}"
            );
        }
    }
}
