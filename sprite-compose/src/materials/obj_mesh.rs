//! [`FaceMaterials`] for obj-quads' loaded meshes.

use std::path::Path;

use glam::{DVec3, Vec2};

use super::FaceMaterials;

impl FaceMaterials for obj_quads::Mesh {
    fn face_count(&self) -> usize {
        obj_quads::Mesh::face_count(self)
    }
    fn positions(&self) -> &[DVec3] {
        obj_quads::Mesh::positions(self)
    }
    fn face_corners(&self, face: usize) -> Option<&[u32]> {
        self.face(face)
    }
    fn face_uvs(&self, face: usize) -> Option<&[Vec2]> {
        obj_quads::Mesh::face_uvs(self, face)
    }
    fn face_diffuse(&self, face: usize) -> Option<[f32; 4]> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .map(|m| m.diffuse)
    }
    fn face_texture(&self, face: usize) -> Option<&Path> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .and_then(|m| m.texture.as_deref())
    }
    fn face_embedded_texture(&self, face: usize) -> Option<(&str, &[u8])> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .and_then(|m| m.embedded_texture.as_ref())
            .map(|t| (t.name.as_str(), &t.bytes[..]))
    }
    fn face_texture_factor(&self, face: usize) -> Option<[f32; 4]> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .filter(|m| m.texture_times_diffuse)
            .map(|m| m.diffuse)
    }
    fn face_texture_wrap(&self, face: usize) -> [obj_quads::WrapMode; 2] {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .map_or([obj_quads::WrapMode::Repeat; 2], |m| m.wrap)
    }
    fn face_alpha_mode(&self, face: usize) -> obj_quads::AlphaMode {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .map_or(obj_quads::AlphaMode::Blend, |m| m.alpha_mode)
    }
    fn face_normal(&self, face: usize) -> Option<DVec3> {
        obj_quads::Mesh::face_normal(self, face)
    }
}
