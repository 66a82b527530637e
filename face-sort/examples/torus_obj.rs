//! Writes `face_sort::generate::torus(FACES)` as an OBJ file, for whole-process measurements
//! of large meshes (the README's one-picture figures use 60,000).
//!
//! `cargo run --release -p face-sort --example torus_obj -- 60000 target/torus60k.obj`

fn main() {
    let mut args = std::env::args().skip(1);
    let faces: usize = args
        .next()
        .and_then(|a| a.parse().ok())
        .expect("usage: torus_obj FACES OUT.obj");
    let out = args.next().expect("usage: torus_obj FACES OUT.obj");
    let mesh = face_sort::generate::torus(faces);
    let text = face_sort::generate::to_obj(
        &mesh,
        &[format!(
            "face_sort::generate::torus({faces}) (the tables' bumpy-torus)"
        )],
    );
    std::fs::write(&out, text).unwrap_or_else(|e| panic!("writing {out}: {e}"));
    println!("{out}: {} faces", mesh.face_count());
}
