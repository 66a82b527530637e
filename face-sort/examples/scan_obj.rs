//! Writes the scan-like blob (`face_sort::generate::scan_blob(264, 132)`: 69,168 triangles, the
//! size of the laser scan that issue 12 measured) as an OBJ file, for whole-process
//! measurements (`cargo xtask oneshot`) and for trying the CLI on a scan.
//!
//! `cargo run --release -p face-sort --example scan_obj -- target/scan69k.obj`

fn main() {
    let out = std::env::args().nth(1).expect("usage: scan_obj OUT.obj");
    let mesh = face_sort::generate::scan_blob(264, 132);
    let text = face_sort::generate::to_obj(
        &mesh,
        &["scan-like blob: face_sort::generate::scan_blob(264, 132)".to_owned()],
    );
    std::fs::write(&out, text).unwrap_or_else(|e| panic!("writing {out}: {e}"));
    println!("{out}: {} triangles", mesh.face_count());
}
