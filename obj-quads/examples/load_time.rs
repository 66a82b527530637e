//! Prints how long loading spot and blub takes (best of 5 runs each).
//!
//! `cargo run -p obj-quads --example load_time`

use std::time::{Duration, Instant};

use obj_quads::{FacePolicy, LoadOptions, load};

fn main() -> Result<(), obj_quads::LoadError> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/models/");
    let cases = [
        (
            "keenan-crane/spot/spot_quadrangulated.obj",
            FacePolicy::QuadsOnly,
        ),
        (
            "keenan-crane/blub/blub_quadrangulated.obj",
            FacePolicy::QuadsOnly,
        ),
        (
            "keenan-crane/spot/spot_triangulated.obj",
            FacePolicy::MergeTriangles,
        ),
    ];
    for (file, policy) in cases {
        let options = LoadOptions::DEFAULT.with_face_policy(policy);
        let mut best = Duration::MAX;
        let mut faces = 0;
        let mut report = obj_quads::LoadReport::default();
        for _ in 0..5 {
            let start = Instant::now();
            let (mesh, r) = load(format!("{dir}{file}"), &options)?;
            best = best.min(start.elapsed());
            faces = mesh.face_count();
            report = r;
        }
        println!(
            "{file} ({policy:?}): {faces} faces ({} non-planar, {} triangles merged), best of 5: {best:.1?}",
            report.non_planar, report.triangles_merged
        );
    }
    Ok(())
}
