//! What the bindings refuse, named: every message says which argument and why.

/// An argument the library cannot use, or an order it cannot make.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BindError {
    /// An argument has the wrong length, a bad value or an out-of-range index.
    #[error("{what}: {why}")]
    Argument {
        /// The argument.
        what: &'static str,
        /// What is wrong with it.
        why: String,
    },
    /// The triangles do not make a mesh the sorters take.
    #[error("mesh: {0}")]
    Mesh(#[from] face_sort::MeshError),
    /// The camera's matrices do not make a camera, or not for this image.
    #[error("camera: {0}")]
    Camera(#[from] face_sort::CameraError),
    /// The colours do not make materials.
    #[error("colours: {0}")]
    Colours(#[from] obj_quads::LoadError),
    /// The certificate's build stopped on a budget.
    #[error("certificate: {0}")]
    Presort(#[from] face_sort::PresortError),
}

impl BindError {
    pub(crate) fn argument(what: &'static str, why: impl Into<String>) -> Self {
        BindError::Argument {
            what,
            why: why.into(),
        }
    }
}
