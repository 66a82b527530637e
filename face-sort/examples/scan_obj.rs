//! Writes a scan-like mesh as an OBJ file: a closed blob of about 69,000 triangles (the size of
//! the laser scan that issue 12 measured), a UV sphere displaced radially by a few waves so
//! that it has bumps, dents and folds that hide each other, every quad cut into two triangles
//! as scanners write them. For whole-process measurements (`cargo xtask oneshot`).
//!
//! `cargo run --release -p face-sort --example scan_obj -- target/scan69k.obj`

use face_sort::PolygonMesh;
use face_sort::glam::DVec3;

fn main() {
    let out = std::env::args().nth(1).expect("usage: scan_obj OUT.obj");
    let (segments, rings) = (264usize, 132usize);
    let radius = |d: DVec3| {
        1.0 + 0.18 * (3.0 * d.x).sin() * (4.0 * d.y).sin() * (5.0 * d.z).sin()
            + 0.06 * (13.0 * d.x + 7.0 * d.y).sin()
            + 0.04 * (17.0 * d.z - 11.0 * d.y).sin()
    };
    let mut positions = vec![DVec3::Y * radius(DVec3::Y)];
    for k in 1..rings {
        let theta = std::f64::consts::PI * k as f64 / rings as f64;
        for j in 0..segments {
            let phi = std::f64::consts::TAU * j as f64 / segments as f64;
            let d = DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            positions.push(d * radius(d));
        }
    }
    positions.push(-DVec3::Y * radius(-DVec3::Y));
    let south = (positions.len() - 1) as u32;
    let at = |k: usize, j: usize| (1 + (k - 1) * segments + j % segments) as u32;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for j in 0..segments {
        faces.push(vec![at(1, j), 0, at(1, j + 1)]);
        for k in 1..rings - 1 {
            let (a, b, c, d) = (at(k + 1, j), at(k, j), at(k, j + 1), at(k + 1, j + 1));
            faces.push(vec![a, b, c]);
            faces.push(vec![a, c, d]);
        }
        faces.push(vec![south, at(rings - 1, j), at(rings - 1, j + 1)]);
    }
    let mesh = PolygonMesh::new(positions, faces).expect("a valid mesh");
    let text = test_support::to_obj(
        &mesh,
        &["scan-like blob: face-sort/examples/scan_obj.rs".to_owned()],
    );
    std::fs::write(&out, text).unwrap_or_else(|e| panic!("writing {out}: {e}"));
    println!("{out}: {} triangles", mesh.face_count());
}
