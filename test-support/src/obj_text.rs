//! The OBJ writer (face-sort's `generate::to_obj`) read back by the loader.

#[cfg(test)]
mod tests {
    use crate::to_obj;

    #[test]
    fn reads_back_exactly() {
        let mesh = crate::models::bumpy_torus(200);
        let text = to_obj(&mesh, &["a comment".to_owned()]);
        assert!(text.starts_with("# a comment\n"));
        let (back, _) = obj_quads::load_obj_str(&text, &obj_quads::LoadOptions::default()).unwrap();
        // The loader numbers vertices in order of first use: compare corner positions.
        assert_eq!(back.face_count(), mesh.face_count());
        for f in 0..mesh.face_count() {
            let corners = |positions: &[face_sort::glam::DVec3], indices: &[u32]| {
                indices
                    .iter()
                    .map(|&i| positions[i as usize])
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                corners(back.positions(), back.face(f).unwrap()),
                corners(mesh.positions(), mesh.face(f)),
                "face {f}"
            );
        }
    }
}
