//! The certificate target: any bytes given to [`face_sort::Presorted::from_bytes`] for a
//! fixed geometry (a bumpy torus, with a box through its hole so that cycles leave cores)
//! give a typed error, or a sorter that orders a few views without panicking. The check
//! also builds the valid certificate once and asserts it round-trips, so the corpus's seed
//! (`fuzz/corpus/certificate/valid`) stays a certificate that loads.
//!
//! Budgets: the loader allocates at most a small multiple of the input beyond the geometry
//! (each count is checked against the bytes left), and libFuzzer's `-rss_limit_mb` holds it
//! to that.

use std::sync::OnceLock;

use face_sort::glam::{DQuat, DVec3};
use face_sort::{DrawList, FaceSorter, Geometry, PolygonMesh, Presorted, View};

/// The geometry every input is loaded against, and its certificate's bytes.
pub fn fixture() -> &'static (Geometry, Vec<u8>) {
    static FIXTURE: OnceLock<(Geometry, Vec<u8>)> = OnceLock::new();
    FIXTURE.get_or_init(|| {
        let torus = face_sort::generate::torus(32);
        let bar = test_support::models::boxes(&[(
            DVec3::new(-0.2, -1.6, -0.1),
            DVec3::new(0.2, 1.6, 0.1),
        )]);
        let mut positions: Vec<DVec3> = torus.positions().to_vec();
        let mut faces: Vec<Vec<u32>> = torus.faces().map(<[u32]>::to_vec).collect();
        let offset = positions.len() as u32;
        positions.extend_from_slice(bar.positions());
        faces.extend(
            bar.faces()
                .map(|f| f.iter().map(|&v| v + offset).collect::<Vec<u32>>()),
        );
        let mesh = PolygonMesh::new(positions, faces).expect("a valid fixture mesh");
        let geometry = Geometry::with_exact_corners(&mesh).expect("a valid fixture geometry");
        let bytes = Presorted::try_new(&geometry, &face_sort::PresortOptions::default())
            .expect("the fixture's certificate builds")
            .to_bytes();
        (geometry, bytes)
    })
}

/// The check. Panics when loading or sorting panics.
pub fn certificate(data: &[u8]) {
    let (geometry, _) = fixture();
    let Ok(mut sorter) = Presorted::from_bytes(data, geometry) else {
        return;
    };
    let base = View::fit(&geometry.bounds(), 64, 64);
    let radius = 0.5 * geometry.bounds().diagonal();
    let mut list = DrawList::new();
    for k in 0..4 {
        let angle = f64::from(k) * 1.7;
        let view = base.with_quaternion(DQuat::from_axis_angle(
            DVec3::new(0.3, 1.0, 0.2 * f64::from(k)).normalize(),
            angle,
        ));
        sorter.sort(&view, &mut list);
        sorter.sort(
            &view.with_perspective(2.5 * radius * view.scale()),
            &mut list,
        );
    }
}
