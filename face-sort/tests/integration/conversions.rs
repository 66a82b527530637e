//! The caller's own types reach the camera and the mesh: mint points and matrices (feature
//! `mint`) give the same camera and mesh as glam's and arrays.

use face_sort::{Camera, ClipSpace, Geometry, Lens, PolygonMesh};
use glam::{DMat4, DVec3};

#[test]
fn mint_points_and_matrices_convert_like_glam_ones() {
    let eye = mint::Point3 {
        x: 1.0f32,
        y: 2.0,
        z: 5.0,
    };
    let up = mint::Vector3 {
        x: 0.0f64,
        y: 1.0,
        z: 0.0,
    };
    let lens = Lens::perspective(40.0, 0.1);
    let from_mint = Camera::look_at(eye, [0.0, 0.0, 0.0], up, lens).unwrap();
    let from_arrays = Camera::look_at([1.0f32, 2.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], lens).unwrap();
    assert_eq!(from_mint, from_arrays);

    let view =
        glam::dcamera::rh::view::look_at_mat4(DVec3::new(1.0, 2.0, 5.0), DVec3::ZERO, DVec3::Y);
    let projection = glam::dcamera::rh::proj::directx::perspective(0.7, 1.0, 0.1, 10.0);
    let column = |m: DMat4| mint::ColumnMatrix4::<f64>::from(m.to_cols_array_2d());
    let by_mint =
        Camera::from_matrices(column(view), column(projection), ClipSpace::ZeroToOne).unwrap();
    let by_glam = Camera::from_matrices(view, projection, ClipSpace::ZeroToOne).unwrap();
    assert_eq!(by_mint, by_glam);

    let corners = [
        mint::Point3 {
            x: 0.0f32,
            y: 0.0,
            z: 0.0,
        },
        mint::Point3 {
            x: 1.0,
            y: 0.0,
            z: 0.0,
        },
        mint::Point3 {
            x: 0.0,
            y: 1.0,
            z: 0.0,
        },
    ];
    let mesh = PolygonMesh::new(corners, [[0u32, 1, 2]]).unwrap();
    let geometry = Geometry::new(&mesh).unwrap();
    let camera_view = by_glam.view(&geometry, 64, 64).unwrap();
    assert!(geometry.check_view(&camera_view).is_ok());
    // A view fitted to other bounds does not belong to this geometry.
    let other = face_sort::Bounds {
        min: DVec3::splat(5.0),
        max: DVec3::splat(6.0),
    };
    assert!(matches!(
        geometry.check_view(&face_sort::View::fit(&other, 64, 64)),
        Err(face_sort::CameraError::CentreMismatch { .. })
    ));
}
