//! One path from a geometry, a view and materials to an SVG, a PDF or an HTML page.

use face_sort::{Geometry, SorterKind, View};

use sprite_compose::{Materials, RecordingCompositor, Scene, SpritePainter, SpriteSpace};

use crate::{HiddenParts, HtmlOptions, PdfOptions, SvgOptions, write_html, write_pdf, write_svg};

/// A picture ready to be written as a vector file: the model's sprites in an exact paint
/// order, in its own materials, at the view's size.
///
/// ```
/// use vector_sink::face_sort::{Geometry, PolygonMesh, View};
/// use vector_sink::Export;
///
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, 0.5]];
/// let mesh = PolygonMesh::new(positions, [[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]).unwrap();
/// let geometry = Geometry::new(&mesh).unwrap();
/// let view = View::fit(&geometry.bounds(), 200, 100).with_yaw_pitch_roll(30.0, 20.0, 0.0);
/// let export = Export::new(&geometry, view);
/// assert!(export.svg().starts_with("<svg"));
/// assert!(export.pdf().starts_with(b"%PDF"));
/// assert!(export.html().contains("200px"));
/// ```
pub struct Export {
    painter: SpritePainter<RecordingCompositor>,
    textured: Option<Scene>,
    texture_uris: Vec<String>,
    images: Vec<std::sync::Arc<crate::Image>>,
    hidden: HiddenParts,
}

impl Export {
    /// The picture of `geometry` through `view`, every face in its palette colour until
    /// [`with_materials`](Self::with_materials), ordered by whichever exact sorter of
    /// [`Export::SORTERS`] draws the fewest sprites (a file's size follows its sprites):
    /// Newell splits only faces in cycles, the BSP splits along its planes, and the merged
    /// BSP draws split pieces whole where it can. The first wins a tie.
    #[must_use]
    pub fn new(geometry: &Geometry, view: View) -> Self {
        let mut best: Option<(usize, Self)> = None;
        for sorter in Self::SORTERS {
            let export = Self::with_sorter(geometry, view, sorter);
            let sprites = export.painter.compositor().scene().visible().count();
            if best.as_ref().is_none_or(|(fewest, _)| sprites < *fewest) {
                best = Some((sprites, export));
            }
        }
        best.map_or_else(
            || Self::with_sorter(geometry, view, SorterKind::Bsp),
            |(_, e)| e,
        )
    }

    /// The exact sorters [`new`](Self::new) chooses from, in order of preference.
    pub const SORTERS: [SorterKind; 3] =
        [SorterKind::Newell, SorterKind::BspMerged, SorterKind::Bsp];

    /// [`new`](Self::new) with another sorter.
    #[must_use]
    pub fn with_sorter(geometry: &Geometry, view: View, sorter: SorterKind) -> Self {
        let mut painter = SpritePainter::new(
            geometry,
            sorter.build(geometry),
            view,
            RecordingCompositor::new(),
        );
        painter.frame();
        Export {
            painter,
            textured: None,
            texture_uris: Vec::new(),
            images: Vec::new(),
            hidden: HiddenParts::Remove,
        }
    }

    /// Paints each face as `materials` say: colours and textures, each image embedded once
    /// per file (`data:` URIs in SVG and HTML, an image XObject in PDF).
    #[must_use]
    pub fn with_materials(mut self, materials: &Materials) -> Self {
        self.painter.set_brushes(|face| materials.brush(face));
        self.painter.frame();
        let mut textured = self.painter.compositor().scene().clone();
        let space = SpriteSpace::of_view(self.painter.view());
        if materials.set_textures(&mut textured, &space) > 0 {
            self.texture_uris = materials
                .images()
                .iter()
                .map(|i| crate::image_data_uri(i))
                .collect();
            self.images = materials.images().to_vec();
            self.textured = Some(textured);
        }
        self
    }

    /// Keeps hidden polygons (and parts) in SVG and PDF instead of removing them.
    #[must_use]
    pub fn with_hidden(mut self, hidden: HiddenParts) -> Self {
        self.hidden = hidden;
        self
    }

    fn size(&self) -> (u32, u32) {
        (self.painter.view().width(), self.painter.view().height())
    }

    /// The scene the files are written from: the sprites in paint order, with texture
    /// brushes where the materials have textures. For writer options that `Export` does not
    /// set (textures linked by path, backgrounds, ID colours), pass it to
    /// [`write_svg`], [`write_pdf`] or [`write_html`] directly.
    #[must_use]
    pub fn scene(&self) -> &Scene {
        self.textured
            .as_ref()
            .unwrap_or_else(|| self.painter.compositor().scene())
    }

    /// The SVG file.
    #[must_use]
    pub fn svg(&self) -> String {
        let (width, height) = self.size();
        write_svg(
            self.scene(),
            &SvgOptions::DEFAULT
                .with_size(width, height)
                .with_hidden(self.hidden)
                .with_textures(self.texture_uris.clone()),
        )
    }

    /// The one-page PDF file (one pixel to one point).
    #[must_use]
    pub fn pdf(&self) -> Vec<u8> {
        let (width, height) = self.size();
        write_pdf(
            self.scene(),
            &PdfOptions::DEFAULT
                .with_size(width, height)
                .with_hidden(self.hidden)
                .with_images(self.images.clone()),
        )
    }

    /// The HTML/CSS 3D page.
    #[must_use]
    pub fn html(&self) -> String {
        let (width, height) = self.size();
        write_html(
            self.scene(),
            &HtmlOptions::DEFAULT
                .with_size(width, height)
                .with_textures(self.texture_uris.clone()),
        )
    }
}
