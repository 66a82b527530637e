//! Conversions from the caller's types: points and matrices as arrays, glam types of either
//! precision, and (feature `mint`) mint's interchange types.

use glam::{DMat4, DVec3, Mat4};

/// A point or vector in 3D, from whatever type the caller holds: `[f32; 3]`, `[f64; 3]`,
/// glam's `Vec3` and `DVec3`, and mint's `Point3` and `Vector3` (feature `mint`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point3(pub DVec3);

impl From<DVec3> for Point3 {
    fn from(p: DVec3) -> Self {
        Point3(p)
    }
}
impl From<&DVec3> for Point3 {
    fn from(p: &DVec3) -> Self {
        Point3(*p)
    }
}
impl From<glam::Vec3> for Point3 {
    fn from(p: glam::Vec3) -> Self {
        Point3(p.as_dvec3())
    }
}
impl From<[f64; 3]> for Point3 {
    fn from(p: [f64; 3]) -> Self {
        Point3(DVec3::from_array(p))
    }
}
impl From<[f32; 3]> for Point3 {
    fn from(p: [f32; 3]) -> Self {
        Point3(glam::Vec3::from_array(p).as_dvec3())
    }
}
impl From<&[f32; 3]> for Point3 {
    fn from(p: &[f32; 3]) -> Self {
        Point3::from(*p)
    }
}
impl From<&[f64; 3]> for Point3 {
    fn from(p: &[f64; 3]) -> Self {
        Point3::from(*p)
    }
}
#[cfg(feature = "mint")]
impl<T: Into<f64>> From<mint::Point3<T>> for Point3 {
    fn from(p: mint::Point3<T>) -> Self {
        Point3(DVec3::new(p.x.into(), p.y.into(), p.z.into()))
    }
}
#[cfg(feature = "mint")]
impl<T: Into<f64>> From<mint::Vector3<T>> for Point3 {
    fn from(p: mint::Vector3<T>) -> Self {
        Point3(DVec3::new(p.x.into(), p.y.into(), p.z.into()))
    }
}

/// A 4 × 4 matrix (column vectors, as glam, OpenGL and most engines keep them), from
/// whatever the caller holds: glam's `Mat4` and `DMat4`, column-major `[[f32; 4]; 4]` and
/// `[[f64; 4]; 4]` (`m[column][row]`), and mint's `ColumnMatrix4` (feature `mint`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Matrix4(pub DMat4);

impl From<DMat4> for Matrix4 {
    fn from(m: DMat4) -> Self {
        Matrix4(m)
    }
}
impl From<Mat4> for Matrix4 {
    fn from(m: Mat4) -> Self {
        Matrix4(m.as_dmat4())
    }
}
impl From<[[f64; 4]; 4]> for Matrix4 {
    fn from(m: [[f64; 4]; 4]) -> Self {
        Matrix4(DMat4::from_cols_array_2d(&m))
    }
}
impl From<[[f32; 4]; 4]> for Matrix4 {
    fn from(m: [[f32; 4]; 4]) -> Self {
        Matrix4(Mat4::from_cols_array_2d(&m).as_dmat4())
    }
}
#[cfg(feature = "mint")]
impl<T: Into<f64>> From<mint::ColumnMatrix4<T>> for Matrix4 {
    fn from(m: mint::ColumnMatrix4<T>) -> Self {
        let column =
            |c: mint::Vector4<T>| glam::DVec4::new(c.x.into(), c.y.into(), c.z.into(), c.w.into());
        Matrix4(DMat4::from_cols(
            column(m.x),
            column(m.y),
            column(m.z),
            column(m.w),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_converts_to_the_same_value() {
        let p = DVec3::new(1.5, -2.0, 0.25);
        for q in [
            Point3::from(p),
            Point3::from([1.5f32, -2.0, 0.25]),
            Point3::from(&[1.5, -2.0, 0.25]),
            Point3::from(glam::Vec3::new(1.5, -2.0, 0.25)),
        ] {
            assert_eq!(q.0, p);
        }
        let m = DMat4::from_cols_array(&std::array::from_fn(|i| i as f64 * 0.5));
        assert_eq!(Matrix4::from(m.as_mat4()).0, m);
        assert_eq!(Matrix4::from(m.to_cols_array_2d()).0, m);
        assert_eq!(Matrix4::from(m.as_mat4().to_cols_array_2d()).0, m);
    }
}
