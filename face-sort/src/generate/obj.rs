//! A polygon mesh written as OBJ text (generated models for whole-process measurements,
//! shrunk fuzz cases).

use crate::PolygonMesh;

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
