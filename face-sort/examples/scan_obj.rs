//! Writes a scan-like mesh as an OBJ file: a closed blob of about 69,000 triangles (the size of
//! the laser scan that issue 12 measured), a UV sphere displaced radially by a few waves so
//! that it has bumps, dents and folds that hide each other, every quad cut into two triangles
//! as scanners write them. For whole-process measurements (`cargo xtask oneshot`).
//!
//! `cargo run --release -p face-sort --example scan_obj -- target/scan69k.obj`

use face_sort::PolygonMesh;
use face_sort::generate::uv_sphere;
use face_sort::glam::DVec3;

fn main() {
    let out = std::env::args().nth(1).expect("usage: scan_obj OUT.obj");
    let radius = |d: DVec3| {
        1.0 + 0.18 * (3.0 * d.x).sin() * (4.0 * d.y).sin() * (5.0 * d.z).sin()
            + 0.06 * (13.0 * d.x + 7.0 * d.y).sin()
            + 0.04 * (17.0 * d.z - 11.0 * d.y).sin()
    };
    let sphere = uv_sphere(264, 132);
    let positions: Vec<DVec3> = sphere.positions().iter().map(|&d| d * radius(d)).collect();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for face in sphere.faces() {
        match face {
            // Quads as scanners write them: two triangles sharing the first corner.
            &[a, b, c, d] => faces.extend([vec![a, b, c], vec![a, c, d]]),
            triangle => faces.push(triangle.to_vec()),
        }
    }
    let mesh = PolygonMesh::new(positions, faces).expect("a valid mesh");
    let text = face_sort::generate::to_obj(
        &mesh,
        &["scan-like blob: face-sort/examples/scan_obj.rs".to_owned()],
    );
    std::fs::write(&out, text).unwrap_or_else(|e| panic!("writing {out}: {e}"));
    println!("{out}: {} triangles", mesh.face_count());
}
