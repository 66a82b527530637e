//! WebAssembly bindings of the workspace for the browser (the `facesort-three` npm package
//! in `js/` wraps them for three.js): exact SVG export, plotter edges, and exact
//! transparency by certified orders.
//!
//! The bindings are thin: they check typed arrays, call the library, and turn every error
//! into a thrown JS `Error` that names the argument. Geometry comes in world (or model)
//! space as three positions per vertex and three indices per triangle; triangle `i` is
//! face `i` (its ID colour is `i + 1`, CONVENTIONS.md). Cameras come as three.js holds
//! them: `matrixWorldInverse` and `projectionMatrix`, column-major, WebGL clip space.

mod error;
mod export;
mod input;
mod transparency;

pub use error::BindError;
pub use export::{CameraArgs, plot_svg, svg};
pub use input::{MAX_IMAGE_SIDE, MAX_TRIANGLES, Triangles, cull_mode};
pub use transparency::{Frame, LeafRange, Transparency};

use wasm_bindgen::prelude::*;

fn thrown(e: BindError) -> JsError {
    JsError::new(&e.to_string())
}

/// The triangles and the camera of a file export, checked.
fn inputs<'a>(
    positions: &[f64],
    indices: &[u32],
    view: &'a [f64],
    projection: &'a [f64],
    (width, height): (u32, u32),
    cull: &'a str,
) -> Result<(Triangles, CameraArgs<'a>), JsError> {
    let triangles = Triangles::new(positions, indices).map_err(thrown)?;
    let camera = CameraArgs {
        view,
        projection,
        width,
        height,
        cull,
    };
    Ok((triangles, camera))
}

/// The exact SVG of triangles seen by a camera (see `exportSVG` in the npm package).
#[wasm_bindgen(js_name = exportSvg)]
#[allow(clippy::too_many_arguments)]
pub fn export_svg(
    positions: &[f64],
    indices: &[u32],
    colours: &[u8],
    view: &[f64],
    projection: &[f64],
    width: u32,
    height: u32,
    cull: &str,
    hidden: &str,
    ids: bool,
) -> Result<String, JsError> {
    let (triangles, camera) = inputs(positions, indices, view, projection, (width, height), cull)?;
    svg(&triangles, colours, camera, hidden, ids).map_err(thrown)
}

/// The visible edges of triangles seen by a camera, as SVG strokes (see `plotEdges`).
#[wasm_bindgen(js_name = plotEdges)]
#[allow(clippy::too_many_arguments)]
pub fn plot_edges(
    positions: &[f64],
    indices: &[u32],
    view: &[f64],
    projection: &[f64],
    width: u32,
    height: u32,
    cull: &str,
    crease_deg: f64,
    stroke_px: f64,
) -> Result<String, JsError> {
    let (triangles, camera) = inputs(positions, indices, view, projection, (width, height), cull)?;
    plot_svg(&triangles, camera, crease_deg, stroke_px).map_err(thrown)
}

/// A mesh's certificate as GPU buffers, with the per-frame range lookup (see
/// `ExactTransparency` and `certify` in the npm package).
#[wasm_bindgen]
pub struct Certificate {
    inner: Transparency,
    frame: Frame,
}

impl Certificate {
    fn with(inner: Transparency) -> Self {
        Certificate {
            inner,
            frame: Frame {
                start: 0,
                count: 0,
                rewritten: false,
                fallback: None,
            },
        }
    }
}

#[wasm_bindgen]
impl Certificate {
    /// Certifies triangles in model space for eyes at least `min_eye_distance` bounding
    /// radii from the centre, within `max_build_ms`.
    #[wasm_bindgen(constructor)]
    pub fn new(
        positions: &[f64],
        indices: &[u32],
        min_eye_distance: f64,
        max_build_ms: f64,
    ) -> Result<Certificate, JsError> {
        let triangles = Triangles::new(positions, indices).map_err(thrown)?;
        let inner =
            Transparency::new(&triangles, min_eye_distance, max_build_ms).map_err(thrown)?;
        Ok(Certificate::with(inner))
    }

    /// A certificate that `toBytes` wrote for the same triangles (from a worker, or a
    /// file): validated on load, far quicker than certifying.
    #[wasm_bindgen(js_name = fromBytes)]
    pub fn from_bytes(
        positions: &[f64],
        indices: &[u32],
        bytes: &[u8],
    ) -> Result<Certificate, JsError> {
        let triangles = Triangles::new(positions, indices).map_err(thrown)?;
        let inner = Transparency::from_bytes(&triangles, bytes).map_err(thrown)?;
        Ok(Certificate::with(inner))
    }

    /// The certificate as bytes (versioned, compact).
    #[wasm_bindgen(js_name = toBytes)]
    pub fn to_bytes(&self) -> Vec<u8> {
        self.inner.to_bytes()
    }

    /// Vertex positions (x, y, z per vertex): every piece's corners.
    #[wasm_bindgen(getter)]
    pub fn positions(&self) -> Vec<f32> {
        self.inner.positions().to_vec()
    }

    /// Per vertex, the input triangle its piece comes from.
    #[wasm_bindgen(getter, js_name = vertexTriangles)]
    pub fn vertex_triangles(&self) -> Vec<u32> {
        self.inner.vertex_triangles().to_vec()
    }

    /// The index buffer: every certified order without cycles, then the scratch tail.
    #[wasm_bindgen(getter)]
    pub fn indices(&self) -> Vec<u32> {
        self.inner.indices().to_vec()
    }

    /// The region table: per certified order, `[start, count, cycles]` (cycles: 1 when the
    /// order is made per frame, its range then unused).
    #[wasm_bindgen(getter)]
    pub fn orders(&self) -> Vec<u32> {
        (self.inner.leaves().iter())
            .flat_map(|l| [l.start, l.count, u32::from(l.cycles)])
            .collect()
    }

    /// Where the scratch tail of the index buffer begins.
    #[wasm_bindgen(getter, js_name = scratchStart)]
    pub fn scratch_start(&self) -> u32 {
        self.inner.scratch_start()
    }

    /// The frame for a viewer at `(x, y, z, w)` in model space (`w = 1`: an eye, `w = 0`:
    /// a direction toward the viewer). Read the range from `start` and `count`; when
    /// `rewritten`, upload the scratch tail's `count` indices.
    pub fn frame(&mut self, x: f64, y: f64, z: f64, w: f64) -> Result<(), JsError> {
        self.frame = self.inner.frame([x, y, z, w]).map_err(thrown)?;
        Ok(())
    }

    /// The last frame's first index.
    #[wasm_bindgen(getter)]
    pub fn start(&self) -> u32 {
        self.frame.start
    }

    /// The last frame's index count.
    #[wasm_bindgen(getter)]
    pub fn count(&self) -> u32 {
        self.frame.count
    }

    /// Whether the last frame rewrote the scratch tail.
    #[wasm_bindgen(getter)]
    pub fn rewritten(&self) -> bool {
        self.frame.rewritten
    }

    /// Whether the last frame was outside the certificate (drawn by centroid).
    #[wasm_bindgen(getter, js_name = fellBack)]
    pub fn fell_back(&self) -> bool {
        self.frame.fallback.is_some()
    }

    /// Why the last frame was outside the certificate, or `undefined`.
    #[wasm_bindgen(getter, js_name = fallbackReason)]
    pub fn fallback_reason(&self) -> Option<String> {
        self.frame.fallback.map(|r| r.to_string())
    }

    /// Where the scratch tail's indices of the last frame sit in the module's memory (a
    /// byte offset): a page uploads them from a view of `memory.buffer` without a copy.
    /// Valid until the next call into the module.
    #[wasm_bindgen(getter, js_name = scratchPointer)]
    pub fn scratch_pointer(&self) -> usize {
        self.inner.indices()[self.inner.scratch_start() as usize..].as_ptr() as usize
    }

    /// The scratch tail's indices of the last frame (to upload when `rewritten`), copied.
    #[wasm_bindgen(js_name = scratch)]
    pub fn scratch(&self) -> Vec<u32> {
        let start = self.inner.scratch_start() as usize;
        self.inner.indices()[start..start + self.frame.count as usize].to_vec()
    }

    /// Frames so far.
    #[wasm_bindgen(getter)]
    pub fn frames(&self) -> f64 {
        self.inner.frames().0 as f64
    }

    /// Frames outside the certificate so far.
    #[wasm_bindgen(getter, js_name = fallbackFrames)]
    pub fn fallback_frames(&self) -> f64 {
        self.inner.frames().1 as f64
    }

    /// Certified orders (leaf regions).
    #[wasm_bindgen(getter, js_name = orderCount)]
    pub fn order_count(&self) -> u32 {
        self.inner.leaves().len() as u32
    }
}
