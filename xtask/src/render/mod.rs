//! `cargo xtask render`: one model, one view, one image (and, on request, the same view as
//! SVG, PDF, HTML and a plotter's line drawing). `run` goes through named stages: load, view,
//! sorter, paint, vector files, plot, raster, check, summary.

mod args;
mod report;
mod scene;
mod sorter;

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use face_sort::sorter_api::DrawListWriter;
use face_sort::{DrawList, FaceSorter, Geometry, PolygonMesh, SorterStats, View, oracle};
use raster_sink::GroundGrid;

pub use args::{
    BaseView, CameraFlags, CullChoice, PolicyChoice, RenderArgs, SorterChoice, base_view,
    load_mesh, parse_size,
};
use args::{DEMO_MODEL, DEMO_PITCH, DEMO_TEXTURE, DEMO_YAW};
use report::{PlotSummary, PresortSummary, Summary, VectorSummary, line, ms};

use crate::raster;
use crate::scenes;

/// Runs `render`.
pub fn run(args: &RenderArgs) -> Result<ExitCode> {
    if args.scene {
        return scene::run(args);
    }
    let start = Instant::now();
    let model = Model::load(args)?;
    let load_ms = ms(start);
    let view = model.view(args)?;

    let start = Instant::now();
    // A glTF file of several mesh nodes, with `auto` and no ground grid, goes through the
    // scene path: each mesh once, its BSP built once, placed by its nodes
    // (`face_sort::SceneSorter`).
    let scene = (args.sorter == SorterChoice::Auto && model.grid.is_none())
        .then(|| sorter::gltf_scene(&model.path, args.allow_outside, &model.geometry))
        .flatten();
    let (mut sorter, plan, mut presorted) = match scene {
        Some((sorter, plan)) => (sorter, plan, None),
        None => sorter::plan(
            args.sorter,
            &model.polygons,
            &model.geometry,
            args.presort_cache.as_deref(),
        )?,
    };
    let build_ms = ms(start);
    let sorter_name = sorter.name();
    let mut list = DrawList::new();
    let start = Instant::now();
    sorter.sort(&view, &mut list);
    let sort_ms = ms(start);
    if let Some(report) = &mut presorted {
        record_fallback(report, &sorter.stats());
    }

    let output = output_path(args)?;
    let paint = Paint::new(args, &model, &view)?;
    let (svg, pdf) = if args.svg.is_some() || args.html.is_some() || args.pdf.is_some() {
        write_vector_files(args, &model, &paint, sorter, view)?
    } else {
        (None, None)
    };
    let plot = write_plot(args, &model, &view)?;
    let start = Instant::now();
    write_raster(args, &model, &paint, &view, &list, &output)?;
    let raster_ms = ms(start);
    let (pixel_error, violations) = if args.check {
        let truth = raster_sink::truth(&view, &model.geometry);
        let error = raster::pixel_error(&view, &list, &truth);
        (
            Some(error.wrong as f64 / error.pixels.max(1) as f64),
            Some(oracle::count_violations(&view, &list)),
        )
    } else {
        (None, None)
    };

    let drawn: HashSet<u32> = list.items().iter().map(|i| i.face).collect();
    let summary = Summary {
        model: if model.demo {
            "demo (spot)".to_owned()
        } else {
            model.path.display().to_string()
        },
        output: output.display().to_string(),
        faces: model.mesh.face_count(),
        drawn: drawn.len(),
        fragments: list.len(),
        sorter: sorter_name,
        plan,
        load_ms,
        build_ms,
        sort_ms,
        raster_ms,
        pixel_error,
        violations,
        svg,
        pdf,
        plot,
        presorted,
    };
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    } else {
        println!("{}", line(&summary));
    }
    Ok(ExitCode::SUCCESS)
}

/// The model as `render` draws it: the loaded mesh, its faces with the ground grid (one more
/// face, sorted like any other) when there is one, and their geometry.
struct Model {
    path: PathBuf,
    /// No model given: the demo scene.
    demo: bool,
    mesh: obj_quads::Mesh,
    /// The model's own bounds (the view fits these, not the larger grid).
    bounds: face_sort::Bounds,
    /// The grid's face index (the model's face count) and the grid.
    grid: Option<(u32, GroundGrid)>,
    polygons: PolygonMesh,
    geometry: Geometry,
}

impl Model {
    /// Loads the model (or the demo) and adds the ground grid with `--grid` or in the demo.
    fn load(args: &RenderArgs) -> Result<Model> {
        let demo = args.model.is_none();
        let path = (args.model.clone()).unwrap_or_else(|| scenes::asset(DEMO_MODEL));
        let (mesh, model_only) = load_mesh(&path, args.policy, args.allow_outside)?;
        let bounds =
            (model_only.bounds()).ok_or_else(|| anyhow::anyhow!("{}: no faces", path.display()))?;
        let grid = (args.grid || demo).then(|| {
            let extent = (bounds.max - bounds.min).max_element();
            let face = mesh.face_count() as u32;
            (face, GroundGrid::new(&bounds, 2.0 * extent))
        });
        let polygons = match &grid {
            None => model_only,
            Some((face, grid)) => {
                debug_assert_eq!(*face as usize, model_only.face_count());
                let first = model_only.positions().len() as u32;
                let mut positions = model_only.positions().to_vec();
                positions.extend_from_slice(&grid.quad());
                let mut faces: Vec<Vec<u32>> = model_only.faces().map(<[u32]>::to_vec).collect();
                faces.push((first..first + 4).collect());
                PolygonMesh::new(positions, faces)?
            }
        };
        let geometry =
            Geometry::new(&polygons).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        Ok(Model {
            path,
            demo,
            mesh,
            bounds,
            grid,
            polygons,
            geometry,
        })
    }

    /// The grid's face, if any.
    fn grid_face(&self) -> Option<u32> {
        self.grid.as_ref().map(|(face, _)| *face)
    }

    /// The view the flags ask for: a file's or a look-at camera, or yaw, pitch and the rest;
    /// the demo's angle and perspective by default.
    fn view(&self, args: &RenderArgs) -> Result<View> {
        let camera = (args.camera).camera(&self.path, &self.bounds, args.allow_outside)?;
        if camera.is_some()
            && (args.yaw.is_some()
                || args.pitch.is_some()
                || args.roll != 0.0
                || args.scale.is_some()
                || args.persp.is_some())
        {
            bail!("--camera and --look-at replace --yaw, --pitch, --roll, --scale and --persp");
        }
        // A file's camera with an aspect ratio sizes the image from the width.
        let size = camera.map_or(args.size, |c| c.image_size(args.size.0));
        let (width, height) = size;
        let demo = self.demo;
        // Fit the model, not the (larger) grid: the grid leaves the frame and fades out.
        let scale = args.scale.or_else(|| {
            (self.grid.is_some())
                .then(|| 0.9 * f64::from(width.min(height)) / self.bounds.diagonal())
        });
        let persp = match (args.persp, demo && !args.ortho) {
            (Some(d), _) => Some(d),
            (None, true) => Some(f64::from(width)),
            (None, false) => None,
        };
        base_view(
            &self.geometry,
            &BaseView {
                size,
                yaw: args.yaw.unwrap_or(if demo { DEMO_YAW } else { 0.0 }),
                pitch: args.pitch.unwrap_or(if demo { DEMO_PITCH } else { 0.0 }),
                roll: args.roll,
                cull: args.cull,
                cw: args.cw,
                margin: args.margin,
                scale,
                persp,
                camera,
            },
        )
    }
}

/// Records in `report` what `Presorted` did for this view: its fallback frames, and why a
/// view fell back to the BSP (unless the build itself was refused).
fn record_fallback(report: &mut PresortSummary, stats: &SorterStats) {
    report.fallback_frames = stats.fallback_frames;
    if let Some(reason) = stats.fallback.filter(|_| report.refused.is_none()) {
        report.fell_back = Some(reason.to_string());
        report.drawn_by = "bsp";
    }
}

/// `--output`, or `target/render.png`, with its folder made.
fn output_path(args: &RenderArgs) -> Result<PathBuf> {
    let output = (args.output.clone()).unwrap_or_else(|| crate::target_dir().join("render.png"));
    if let Some(parent) = output.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    Ok(output)
}

/// What every writer paints with: the raster style and the materials (palette for ID
/// images), the light, and the visible parts of `--wire` / `--points`.
struct Paint {
    style: raster_sink::Style,
    materials: sprite_compose::Materials,
    shade: Option<raster_sink::Light>,
    overlay: Option<sprite_compose::DrawnOverlay>,
}

impl Paint {
    fn new(args: &RenderArgs, model: &Model, view: &View) -> Result<Paint> {
        let texture = match (&args.texture, model.demo) {
            (Some(path), _) => Some(path.clone()),
            (None, true) => Some(scenes::asset(DEMO_TEXTURE)),
            (None, false) => None,
        };
        let vector = args.svg.is_some() || args.html.is_some() || args.pdf.is_some();
        // ID images need no brushes (and no textures).
        let (style, materials) = if args.ids && !vector {
            (
                raster_sink::Style::palette(),
                sprite_compose::Materials::palette(),
            )
        } else {
            raster::face_style(&model.geometry, &model.mesh, texture, model.grid.as_ref())?
        };
        Ok(Paint {
            style,
            materials,
            shade: (args.shade || model.demo).then_some(raster_sink::Light::DEFAULT),
            overlay: ((args.wire || args.points) && !args.ids).then(|| overlay(args, model, view)),
        })
    }

    /// `--wire` / `--points` as markup over the faces, or nothing.
    fn overlay_svg(&self) -> String {
        (self.overlay.as_ref()).map_or_else(String::new, vector_sink::overlay_svg)
    }
}

/// The visible parts of the mesh's edges (`--wire`) and vertices (`--points`), drawn after
/// the faces by every writer (the ground grid's outline left out).
fn overlay(args: &RenderArgs, model: &Model, view: &View) -> sprite_compose::DrawnOverlay {
    let grid_face = model.grid_face();
    let black = [0, 0, 0, 255];
    let mut overlay = sprite_compose::Overlay::default();
    if args.wire {
        overlay = overlay.with(sprite_compose::Overlay::wireframe(
            &model.polygons,
            black,
            1.0,
        ));
    }
    if args.points {
        overlay = overlay.with(sprite_compose::Overlay::vertices(
            &model.polygons,
            black,
            2.0,
        ));
    }
    let model_face = |faces: &[u32]| faces.iter().any(|&f| Some(f) != grid_face);
    overlay.lines.retain(|l| model_face(&l.faces));
    overlay.points.retain(|p| model_face(&p.faces));
    sprite_compose::visible_overlay(&model.geometry, view, &overlay)
}

/// `--svg`, `--pdf` and `--html`: the sprite tree of the same geometry, sorter and view, in
/// the materials' colours (each textured face with its exact texture, each image once per
/// file or linked with `--link-textures`), or ID colours with `--ids`.
fn write_vector_files(
    args: &RenderArgs,
    model: &Model,
    paint: &Paint,
    sorter: Box<dyn FaceSorter>,
    view: View,
) -> Result<(Option<VectorSummary>, Option<VectorSummary>)> {
    let (width, height) = (view.width(), view.height());
    let hidden = if args.keep_hidden {
        vector_sink::HiddenParts::Keep
    } else {
        vector_sink::HiddenParts::Remove
    };
    let scene = painted_scene(args, model, paint, sorter, view);
    let texture_uris = |out: &Path| -> Vec<String> {
        if args.ids {
            return Vec::new();
        }
        (paint.materials.images().iter())
            .map(|image| {
                (image.file())
                    .filter(|_| args.link_textures)
                    .and_then(|file| relative_link(out, file))
                    .unwrap_or_else(|| vector_sink::image_data_uri(image))
            })
            .collect()
    };
    let write = |path: &Path, bytes: &[u8]| {
        std::fs::write(path, bytes).with_context(|| format!("writing {}", path.display()))
    };
    let summary = |start: Instant, bytes: usize, shapes: Option<usize>| VectorSummary {
        shapes,
        bytes,
        write_ms: ms(start),
        keep_hidden: args.keep_hidden,
    };
    let (mut svg_summary, mut pdf_summary) = (None, None);
    if let Some(path) = &args.svg {
        let start = Instant::now();
        let options = (vector_sink::SvgOptions::DEFAULT.with_size(width, height))
            .with_ids(args.ids)
            .with_hidden(hidden)
            .with_textures(texture_uris(path))
            .with_overlay(paint.overlay_svg());
        let svg = vector_sink::write_svg(&scene, &options);
        let shapes = svg.matches("<polygon").count() + svg.matches("<path").count();
        svg_summary = Some(summary(start, svg.len(), Some(shapes)));
        write(path, svg.as_bytes())?;
    }
    if let Some(path) = &args.pdf {
        let start = Instant::now();
        let images = if args.ids {
            Vec::new()
        } else {
            paint.materials.images().to_vec()
        };
        let mut options = (vector_sink::PdfOptions::DEFAULT.with_size(width, height))
            .with_ids(args.ids)
            .with_background(args.ids.then_some([0, 0, 0, 255]))
            .with_hidden(hidden)
            .with_images(images);
        if let Some(overlay) = &paint.overlay {
            options = options.with_overlay(overlay.clone());
        }
        let pdf = vector_sink::write_pdf(&scene, &options);
        pdf_summary = Some(summary(start, pdf.len(), None));
        write(path, &pdf)?;
    }
    if let Some(path) = &args.html {
        let options = (vector_sink::HtmlOptions::DEFAULT.with_size(width, height))
            .with_ids(args.ids)
            .with_textures(texture_uris(path))
            .with_overlay(paint.overlay_svg());
        write(path, vector_sink::write_html(&scene, &options).as_bytes())?;
    }
    Ok((svg_summary, pdf_summary))
}

/// The painter's scene of `sorter`'s order at `view`, with the materials' brushes (a
/// texture as its mean colour, shaded) and, unless `--ids`, each textured face's exact
/// texture brush.
fn painted_scene(
    args: &RenderArgs,
    model: &Model,
    paint: &Paint,
    sorter: Box<dyn FaceSorter>,
    view: View,
) -> sprite_compose::Scene {
    let light = paint.shade.as_ref().map(|light| (&view, light));
    let brushes = paint.style.sprite_brushes(&model.mesh, light);
    // The painter takes the sorter already built (a BSP build is the costly part).
    let mut painter = sprite_compose::SpritePainter::new(
        &model.geometry,
        sorter,
        view,
        sprite_compose::RecordingCompositor::new(),
    );
    painter.set_brushes(|face| {
        (brushes.get(face as usize).copied()).unwrap_or(sprite_compose::Brush::Palette)
    });
    painter.frame();
    let mut scene = painter.compositor().scene().clone();
    if !args.ids {
        let space = sprite_compose::SpriteSpace::of_view(painter.view());
        paint.materials.set_textures(&mut scene, &space);
    }
    scene
}

/// `--plot` and `--hpgl`: the model's visible edges (the ground grid left out: it is lines
/// over a transparent face, so it hides nothing, and its outline is no edge of the model).
fn write_plot(args: &RenderArgs, model: &Model, view: &View) -> Result<Option<PlotSummary>> {
    if args.plot.is_none() && args.hpgl.is_none() {
        return Ok(None);
    }
    let start = Instant::now();
    let grid_face = model.grid_face();
    let plot = sprite_compose::plot_edges_where(
        &model.polygons,
        &model.geometry,
        view,
        &sprite_compose::PlotOptions::DEFAULT.with_crease_deg(args.crease),
        |face| Some(face) != grid_face,
    );
    let plot_ms = ms(start);
    let mut bytes = 0;
    if let Some(path) = &args.plot {
        let svg = vector_sink::plot_svg(&plot, 1.0);
        bytes = svg.len();
        std::fs::write(path, svg).with_context(|| format!("writing {}", path.display()))?;
    }
    if let Some(path) = &args.hpgl {
        std::fs::write(path, vector_sink::plot_hpgl(&plot, 40.0))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(Some(PlotSummary {
        edges: plot.edges.len(),
        visible_edges: plot.edges.iter().filter(|e| !e.visible.is_empty()).count(),
        polylines: plot.polylines.len(),
        pen_down_px: plot.pen_down_px,
        pen_up_px: plot.pen_up_px,
        bytes,
        plot_ms,
    }))
}

/// The PNG: ID colours with `--ids` (file-order face indices: a face split or merged by the
/// loader keeps its source index), else the colour raster with the overlay on top.
fn write_raster(
    args: &RenderArgs,
    model: &Model,
    paint: &Paint,
    view: &View,
    list: &DrawList,
    output: &Path,
) -> Result<()> {
    if args.ids {
        let mut ids = list.clone();
        for item in ids.items_mut() {
            item.face =
                (model.mesh.face_source(item.face as usize)).unwrap_or(item.face as usize) as u32;
        }
        return raster_sink::render_ids(view, &ids)
            .save_png(output)
            .map_err(|e| anyhow::anyhow!("{}: {e}", output.display()));
    }
    let options = (raster_sink::RasterOptions::DEFAULT.with_anti_alias(!args.no_aa))
        .with_shading(paint.shade);
    let mut image = raster_sink::render_colour(view, list, &paint.style, &options)
        .map_err(|e| anyhow::anyhow!("raster: {e}"))?;
    if let Some(overlay) = &paint.overlay {
        raster_sink::draw_overlay(&mut image, overlay, !args.no_aa);
    }
    raster_sink::save_png(&image, output).map_err(|e| anyhow::anyhow!("{}: {e}", output.display()))
}

/// `file` as a link relative to the folder of `out` (`../textures/a.png`), with `/`
/// separators; `None` when no relative path joins them (different roots) or a path is not
/// valid UTF-8. Never absolute.
fn relative_link(out: &std::path::Path, file: &std::path::Path) -> Option<String> {
    let folder = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(std::path::Path::new("."));
    let folder = std::fs::canonicalize(folder).ok()?;
    let file = std::fs::canonicalize(file).ok()?;
    let from: Vec<_> = folder.components().collect();
    let to: Vec<_> = file.components().collect();
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return None;
    }
    let mut parts: Vec<String> = vec!["..".to_owned(); from.len() - common];
    for c in &to[common..] {
        parts.push(c.as_os_str().to_str()?.to_owned());
    }
    Some(parts.join("/"))
}
