//! glTF textures held in the file: data URIs and GLB buffer views become
//! `Material::embedded_texture` (the encoded bytes), and `baseColorFactor` is recorded to
//! multiply the texture (`texture_times_diffuse`).

use obj_quads::{LoadOptions, load, load_gltf_slice};
use test_base::textured_box::{ImageSource, textured_box, textured_box_path, textured_box_png};

#[test]
fn data_uri_and_glb_images_are_embedded_textures() {
    let png = textured_box_png();
    let factor = [0.5, 1.0, 0.25, 1.0];
    for source in [ImageSource::DataUri, ImageSource::Glb] {
        let bytes = textured_box(source, Some(factor));
        let (mesh, report) = load_gltf_slice(&bytes, &LoadOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("{source:?}: {e}"));
        assert_eq!(mesh.face_count(), 12, "{source:?}");
        let [material] = mesh.materials() else {
            panic!("{source:?}: one material, got {:?}", mesh.materials());
        };
        let embedded = material
            .embedded_texture
            .as_ref()
            .unwrap_or_else(|| panic!("{source:?}: no embedded texture; {report:?}"));
        assert_eq!(&embedded.bytes[..], &png[..], "{source:?}");
        assert!(material.texture.is_none());
        assert!(material.texture_times_diffuse);
        assert_eq!(material.diffuse, factor);
        assert!(mesh.face_uvs(0).is_some());
    }
    // The file beside the model stays a path.
    let (mesh, _) = load(textured_box_path(), &LoadOptions::DEFAULT).unwrap();
    let material = &mesh.materials()[0];
    assert!(material.texture.is_some() && material.embedded_texture.is_none());
}

#[test]
fn an_image_view_past_its_buffer_is_a_warning_not_a_texture() {
    let mut bytes = textured_box(ImageSource::Glb, None);
    // Move the image's view past the end of its buffer, keeping the JSON's length.
    let (from, to) = (b"\"byteOffset\": 840", b"\"byteOffset\":9840");
    let at = bytes
        .windows(from.len())
        .position(|w| w == from)
        .expect("the image view");
    bytes[at..at + to.len()].copy_from_slice(to);
    let (mesh, report) = load_gltf_slice(&bytes, &LoadOptions::DEFAULT).unwrap();
    assert!(mesh.materials()[0].embedded_texture.is_none());
    assert!(
        report
            .warnings
            .iter()
            .any(|w| w.contains("overruns its buffer")),
        "{:?}",
        report.warnings
    );
}
