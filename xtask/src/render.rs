//! `cargo xtask render`: one model, one view, one image.

use face_sort::sorter_api::DrawListWriter;
use std::collections::HashSet;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use face_sort::{
    CullMode, DrawList, FaceSorter, FrontFace, Geometry, Plan, PlanHint, PolygonMesh, SorterKind,
    View, oracle,
};
use raster_sink::GroundGrid;
use serde::Serialize;

use crate::raster;
use crate::scenes;

/// The demo scene: spot the cow (Keenan Crane, CC0), textured, on a ground grid.
const DEMO_MODEL: &str = "assets/models/keenan-crane/spot/spot_quadrangulated.obj";
/// The demo model's texture (its OBJ has uvs but no MTL).
const DEMO_TEXTURE: &str = "assets/models/keenan-crane/spot/spot_texture.png";
/// The demo's view when no angle is given.
const DEMO_YAW: f64 = 145.0;
const DEMO_PITCH: f64 = -25.0;

/// Options of `render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Model to draw (.obj, .gltf, .glb). Default: the demo scene (spot on a ground grid).
    pub(crate) model: Option<PathBuf>,
    /// Output PNG. Default: target/render.png.
    #[arg(short, long, value_name = "OUT.png")]
    pub(crate) output: Option<PathBuf>,
    /// Yaw in degrees (about the screen's vertical axis). Default 0 (the demo: 145).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub(crate) yaw: Option<f64>,
    /// Pitch in degrees. Default 0 (the demo: -25; yaw turns the pitched model, so near yaw 180 a negative pitch shows the top).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub(crate) pitch: Option<f64>,
    /// Roll in degrees. Default 0.
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    pub(crate) roll: f64,
    /// Image size. With a camera of the file that has an aspect ratio, the height follows
    /// the width.
    #[arg(long, value_name = "WxH", default_value = "512x512", value_parser = parse_size)]
    pub(crate) size: (u32, u32),
    /// A camera instead of yaw, pitch, roll, scale and --persp.
    #[command(flatten)]
    pub(crate) camera: CameraFlags,
    /// Scale in pixels per model unit. Default: fit (0.9 · min(W, H) / L).
    #[arg(long, value_name = "S")]
    pub(crate) scale: Option<f64>,
    /// Perspective with the eye D pixels from the centre (CONVENTIONS default D = W).
    /// Absent: orthographic (the demo is perspective with D = W unless --ortho).
    #[arg(long, value_name = "D")]
    pub(crate) persp: Option<f64>,
    /// Orthographic even for the demo scene.
    #[arg(long, conflicts_with = "persp")]
    pub(crate) ortho: bool,
    /// Sorter. `auto` picks the best exact one and says why (see `plan` in --json).
    #[arg(long, value_enum, default_value_t = SorterChoice::Auto)]
    pub(crate) sorter: SorterChoice,
    /// Which faces culling removes.
    #[arg(long, value_enum, default_value_t = CullChoice::Back)]
    pub(crate) cull: CullChoice,
    /// Clockwise faces are the front (default: counter-clockwise).
    #[arg(long)]
    pub(crate) cw: bool,
    /// Cull margin in degrees: also keep faces this close to edge-on.
    #[arg(long, value_name = "DEG", default_value_t = 0.0)]
    pub(crate) margin: f64,
    /// Which faces the loader accepts.
    #[arg(long, value_enum, default_value_t = PolicyChoice::Polygons)]
    pub(crate) policy: PolicyChoice,
    /// Write an ID image (CONVENTIONS.md: face index + 1 as 24-bit RGB, no anti-aliasing)
    /// instead of colour.
    #[arg(long)]
    pub(crate) ids: bool,
    /// Colour without anti-aliasing.
    #[arg(long)]
    pub(crate) no_aa: bool,
    /// Flat shading (Lambert, light over the viewer's shoulder).
    #[arg(long)]
    pub(crate) shade: bool,
    /// Draw a ground grid under the model (always on for the demo).
    #[arg(long)]
    pub(crate) grid: bool,
    /// Texture (PNG) for a model with uvs but no material texture (the demo uses spot's).
    #[arg(long, value_name = "PNG")]
    pub(crate) texture: Option<PathBuf>,
    /// Also write an SVG of the same view (sprite-compose writer, palette colours).
    #[arg(long, value_name = "OUT.svg")]
    pub(crate) svg: Option<PathBuf>,
    /// Also write an HTML/CSS 3D page of the same view (sprite-compose writer).
    #[arg(long, value_name = "OUT.html")]
    pub(crate) html: Option<PathBuf>,
    /// Also write a one-page PDF of the same view (sprite-compose writer; one pixel to one
    /// point).
    #[arg(long, value_name = "OUT.pdf")]
    pub(crate) pdf: Option<PathBuf>,
    /// Draw every mesh edge over the model (hidden parts hidden), black, 1 px, in the PNG,
    /// --svg, --pdf and --html (ignored with --ids).
    #[arg(long)]
    pub(crate) wire: bool,
    /// Draw every vertex (hidden ones hidden) as a 2 px dot, like --wire.
    #[arg(long)]
    pub(crate) points: bool,
    /// Also write a plot of the same view: an SVG of strokes only, the visible parts of the
    /// boundary, silhouette, crease and non-manifold edges (hidden-line removal), joined
    /// into polylines for a pen plotter.
    #[arg(long, value_name = "OUT.svg")]
    pub(crate) plot: Option<PathBuf>,
    /// With --plot: edges between drawn faces whose normals differ by at least this many
    /// degrees are creases and drawn.
    #[arg(long, value_name = "DEG", default_value_t = 30.0)]
    pub(crate) crease: f64,
    /// Also write the plot as HP-GL (40 plotter units per pixel: one pixel to one mm).
    #[arg(long, value_name = "OUT.hpgl")]
    pub(crate) hpgl: Option<PathBuf>,
    /// Write every polygon into --svg and --pdf, hidden parts included (the default leaves out
    /// every polygon, or part of one, that opaque polygons in front cover).
    #[arg(long)]
    pub(crate) keep_hidden: bool,
    /// In --svg and --html, link each texture file relative to the output file instead of
    /// embedding it (the default: every file is self-contained). Tinted or embedded
    /// textures are always embedded.
    #[arg(long)]
    pub(crate) link_textures: bool,
    /// Read files the model names (glTF buffers and images, OBJ mtllib, MTL map_Kd) even
    /// when they resolve outside the model's folder. Only for files you trust.
    #[arg(long)]
    pub(crate) allow_outside: bool,
    /// Render the generated demo scene instead of a model: 30 instances of a box, a sphere
    /// and suzanne (rotated, non-uniformly scaled, mirrored, some interlocking), a third of
    /// them translucent, a cloud of 24 translucent billboards, on a backdrop slab in the
    /// background layer, with a marker in the overlay layer, ordered by
    /// `face_sort::SceneSorter`.
    #[arg(long, conflicts_with = "model")]
    pub(crate) scene: bool,
    /// Print one JSON object instead of the summary line.
    #[arg(long)]
    pub(crate) json: bool,
    /// With `--sorter presorted`: load the certificate from FILE when it holds one for this
    /// model, else build it and save it there.
    #[arg(long, value_name = "FILE")]
    pub(crate) presort_cache: Option<PathBuf>,
    /// Also measure the order: pixel error against the z-buffer truth, oracle violations.
    #[arg(long)]
    pub(crate) check: bool,
}

/// `--sorter`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SorterChoice {
    /// The planner's exact choice for one picture: cull only for a mesh in convex position,
    /// else the cheaper of Newell and BSP (see `plan` in --json).
    Auto,
    /// Centroid depth (baseline, not exact).
    Centroid,
    /// Pairwise graph, topological order (not exact).
    Topological,
    /// Newell's cascade with splits (exact, no precomputation).
    Newell,
    /// BSP tree built once (exact).
    Bsp,
    /// BSP, split pieces drawn whole where nothing between their fragments overlaps them
    /// (exact, fewer items).
    BspMerged,
    /// Orders certified over regions of views, looked up per frame (exact; the build is the
    /// cost).
    Presorted,
}

/// `--cull`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CullChoice {
    /// Remove back faces.
    Back,
    /// Remove front faces.
    Front,
    /// Keep every face.
    None,
}

/// `--policy`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PolicyChoice {
    /// Every face must be a quad.
    Quads,
    /// Any convex polygon.
    Polygons,
    /// Merge coplanar triangle pairs into quads.
    Merge,
}

pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WxH, e.g. 512x512, got {s:?}"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|e| format!("bad size {v:?}: {e}"))
    };
    let (w, h) = (parse(w)?, parse(h)?);
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!("size {w}x{h} out of range (1 to 16384 per side)"));
    }
    Ok((w, h))
}

/// What `render --json` prints.
#[derive(Debug, Serialize)]
struct Summary {
    model: String,
    output: String,
    faces: usize,
    drawn: usize,
    fragments: usize,
    sorter: &'static str,
    plan: String,
    load_ms: f64,
    build_ms: f64,
    sort_ms: f64,
    raster_ms: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pixel_error: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    violations: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    svg: Option<VectorSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pdf: Option<VectorSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    plot: Option<PlotSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    presorted: Option<PresortSummary>,
}

/// What `--plot` (and `--hpgl`) wrote.
#[derive(Debug, Serialize)]
struct PlotSummary {
    /// Edges drawn (boundary, silhouette, crease, non-manifold), visible or not.
    edges: usize,
    /// Of those, the ones with a visible part.
    visible_edges: usize,
    polylines: usize,
    /// Length drawn with the pen down, pixels.
    pen_down_px: f64,
    /// Travel with the pen up between polylines, pixels.
    pen_up_px: f64,
    bytes: usize,
    /// Edge classification, hidden-line removal, joining and ordering.
    plot_ms: f64,
}

/// What `--svg` or `--pdf` wrote.
#[derive(Debug, Serialize)]
struct VectorSummary {
    /// SVG: `<polygon>` and `<path>` elements.
    #[serde(skip_serializing_if = "Option::is_none")]
    shapes: Option<usize>,
    bytes: usize,
    /// Hidden-part removal and writing.
    write_ms: f64,
    keep_hidden: bool,
}

/// The scene path for a glTF file: its meshes and nodes as a `SceneSorter`, when the file
/// is glTF with at least two mesh nodes and the scene's faces and frame of reference are
/// those of the flattened load (`geometry`); else `None` (the flattened path).
fn gltf_scene(
    path: &std::path::Path,
    allow_outside: bool,
    geometry: &Geometry,
) -> Option<(Box<dyn FaceSorter>, String)> {
    let gltf = matches!(
        path.extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref(),
        Some("gltf" | "glb")
    );
    if !gltf {
        return None;
    }
    let options = obj_quads::LoadOptions::DEFAULT.with_allow_outside_paths(allow_outside);
    let loaded = obj_quads::load_gltf_scene(path, &options).ok()?;
    let meshes: Vec<face_sort::PolygonMesh> = loaded
        .meshes
        .iter()
        .map(scenes::to_polygon_mesh)
        .collect::<Result<_>>()
        .ok()?;
    let instances: Vec<face_sort::Instance> = loaded
        .instances
        .iter()
        .map(|i| face_sort::Instance::new(i.mesh, i.world))
        .collect();
    let (count, kinds) = (instances.len(), meshes.len());
    if count < 2 {
        return None; // one object: the planner's one-picture choice is cheaper
    }
    let scene = face_sort::SceneSorter::new(meshes, instances).ok()?;
    let faces = scene.flattened().face_count();
    (faces == geometry.face_count() && scene.bounds() == geometry.bounds()).then(|| {
        let plan = format!(
            "glTF scene: {count} instances of {kinds} meshes, one BSP per mesh, objects ordered by separating planes"
        );
        (Box::new(scene) as Box<dyn FaceSorter>, plan)
    })
}

/// What `--sorter presorted` built and did: the certificate's size, and whether this view
/// fell back to the BSP, and why (a refused build names its budget).
#[derive(Debug, Default, Serialize)]
struct PresortSummary {
    regions: usize,
    orders: usize,
    /// Cycles left to per-frame BSP trees, and the pieces in them.
    cores: usize,
    core_pieces: usize,
    /// Threads the build used.
    threads: usize,
    fallback_frames: usize,
    /// Why the build stopped, when it did (every view is then drawn by the BSP).
    #[serde(skip_serializing_if = "Option::is_none")]
    refused: Option<String>,
    /// Why this view fell back to the whole BSP, when the build finished and it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    fell_back: Option<String>,
    /// What drew the picture: "presorted" or "bsp".
    drawn_by: &'static str,
    /// Where the certificate came from: built, built and saved, or loaded (`--presort-cache`).
    certificate: String,
}

impl PresortSummary {
    /// The summary line's words.
    fn words(&self) -> String {
        if let Some(refused) = &self.refused {
            return format!("presorted build refused ({refused}); drawn by the BSP instead");
        }
        let base = format!(
            "presorted: {} regions, {} orders, {} cores of {} pieces, {} threads, certificate {}",
            self.regions, self.orders, self.cores, self.core_pieces, self.threads, self.certificate
        );
        match &self.fell_back {
            Some(why) => format!("{base}; this view fell back to the BSP ({why})"),
            None => base,
        }
    }
}

/// `Presorted` for `--sorter presorted`: its sorter, or the BSP when the build is refused,
/// with what it did.
fn presorted(
    mesh: &PolygonMesh,
    geometry: &Geometry,
    cache: Option<&std::path::Path>,
) -> Result<(Box<dyn FaceSorter>, String, Option<PresortSummary>)> {
    let own = SorterKind::Presorted.geometry_for(mesh)?;
    Ok(match crate::presort_cache::load_or_build(&own, cache)? {
        Ok((sorter, source, _)) => {
            let (cores, core_pieces) = sorter.cores();
            let report = PresortSummary {
                regions: sorter.regions(),
                orders: sorter.orders(),
                cores,
                core_pieces,
                threads: sorter.threads(),
                drawn_by: "presorted",
                certificate: source.words(cache),
                ..PresortSummary::default()
            };
            (
                Box::new(sorter),
                "presorted (asked for)".to_owned(),
                Some(report),
            )
        }
        Err(error) => {
            let report = PresortSummary {
                refused: Some(error.to_string()),
                drawn_by: "bsp",
                certificate: "none".to_owned(),
                ..PresortSummary::default()
            };
            (
                SorterKind::Bsp.build(geometry),
                format!("presorted (asked for) refused: {error}; bsp instead"),
                Some(report),
            )
        }
    })
}

/// Builds the sorter; for `auto`, the planner's choice for one picture, and why.
fn plan(
    choice: SorterChoice,
    mesh: &PolygonMesh,
    geometry: &Geometry,
    cache: Option<&std::path::Path>,
) -> Result<(Box<dyn FaceSorter>, String, Option<PresortSummary>)> {
    let asked = |kind: SorterKind| {
        (
            kind.build(geometry),
            format!("{} (asked for)", kind.name()),
            None,
        )
    };
    Ok(match choice {
        SorterChoice::Auto => {
            // `render` draws one frame: the planner must not pay for a tree that only an
            // animation would amortise.
            let plan = Plan::analyse(geometry, PlanHint::ONE_FRAME);
            (plan.build(geometry), format!("auto: {}", plan.reason), None)
        }
        SorterChoice::Centroid => asked(SorterKind::Centroid),
        SorterChoice::Topological => asked(SorterKind::Topological),
        SorterChoice::Newell => asked(SorterKind::Newell),
        SorterChoice::Bsp => asked(SorterKind::Bsp),
        SorterChoice::BspMerged => asked(SorterKind::BspMerged),
        SorterChoice::Presorted => return presorted(mesh, geometry, cache),
    })
}

/// A camera on the command line: the model file's own, or a look-at built by hand.
#[derive(Debug, Args, Clone, Default)]
pub struct CameraFlags {
    /// Draw through the glTF file's camera N (its node's transform, `yfov`, `aspectRatio`,
    /// `znear`; orthographic `xmag`, `ymag`). The first node carrying camera N places it.
    #[arg(long, value_name = "N", conflicts_with = "look_at")]
    pub(crate) camera: Option<usize>,
    /// A look-at camera with its eye here, "X,Y,Z" in model units (perspective, see --fov).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true)]
    pub(crate) look_at: Option<[f64; 3]>,
    /// The look-at camera's target, "X,Y,Z". Default: the model's centre.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true, requires = "look_at")]
    pub(crate) target: Option<[f64; 3]>,
    /// The look-at camera's up direction, "X,Y,Z". Default: 0,1,0.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true, requires = "look_at")]
    pub(crate) up: Option<[f64; 3]>,
    /// The look-at camera's vertical field of view, degrees.
    #[arg(long, value_name = "DEG", default_value_t = 45.0, requires = "look_at")]
    pub(crate) fov: f64,
    /// The look-at camera's near plane, model units. Default: a thousandth of the eye's
    /// distance to the target.
    #[arg(long, value_name = "DIST", requires = "look_at")]
    pub(crate) near: Option<f64>,
}

impl CameraFlags {
    /// The camera these flags ask for (`None` when they ask for none), for `model` whose
    /// bounds are `bounds`.
    pub fn camera(
        &self,
        model: &std::path::Path,
        bounds: &face_sort::Bounds,
        allow_outside: bool,
    ) -> Result<Option<face_sort::Camera>> {
        use face_sort::{Camera, Lens};
        if let Some(n) = self.camera {
            let mut options = obj_quads::LoadOptions::default();
            options.allow_outside_paths = allow_outside;
            let cameras = obj_quads::load_gltf_cameras(model, &options)
                .map_err(|e| anyhow::anyhow!("--camera {n}: {e}"))?;
            let Some(found) = cameras.iter().find(|c| c.camera == n) else {
                bail!(
                    "--camera {n}: {} has {} camera node(s){}",
                    model.display(),
                    cameras.len(),
                    if cameras.is_empty() {
                        String::new()
                    } else {
                        format!(
                            ", of cameras {:?}",
                            cameras.iter().map(|c| c.camera).collect::<Vec<_>>()
                        )
                    }
                );
            };
            let lens = match found.projection {
                obj_quads::GltfProjection::Perspective {
                    yfov,
                    aspect_ratio,
                    znear,
                    ..
                } => Lens::Perspective {
                    fov_y_deg: yfov.to_degrees(),
                    near: znear,
                    aspect: aspect_ratio,
                },
                obj_quads::GltfProjection::Orthographic { xmag, ymag, .. } => Lens::Orthographic {
                    height: 2.0 * ymag,
                    aspect: Some(xmag / ymag),
                },
            };
            let camera = Camera::from_pose(found.world, lens)
                .map_err(|e| anyhow::anyhow!("--camera {n} (node {}): {e}", found.node))?;
            return Ok(Some(camera));
        }
        let Some(eye) = self.look_at else {
            return Ok(None);
        };
        let target = self.target.unwrap_or(bounds.centre().to_array());
        let distance = glam::DVec3::from(eye).distance(glam::DVec3::from(target));
        let near = self.near.unwrap_or(distance * 1e-3);
        let camera = Camera::look_at(
            eye,
            target,
            self.up.unwrap_or([0.0, 1.0, 0.0]),
            Lens::perspective(self.fov, near),
        )
        .map_err(|e| anyhow::anyhow!("--look-at: {e}"))?;
        Ok(Some(camera))
    }
}

/// Parses "X,Y,Z".
pub fn parse_point(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(format!("expected X,Y,Z, e.g. 0,1,5, got {s:?}"));
    };
    let parse = |v: &str| {
        v.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("bad coordinate {v:?} in {s:?}"))
    };
    Ok([parse(x)?, parse(y)?, parse(z)?])
}

/// Runs `render`.
pub fn run(args: &RenderArgs) -> Result<ExitCode> {
    if args.scene {
        return crate::scene_demo::run(args);
    }
    let demo = args.model.is_none();
    let model_path = args
        .model
        .clone()
        .unwrap_or_else(|| scenes::asset(DEMO_MODEL));
    let start = Instant::now();
    let (mesh, model_only) = load_mesh(&model_path, args.policy, args.allow_outside)?;
    let model_bounds = model_only
        .bounds()
        .ok_or_else(|| anyhow::anyhow!("{}: no faces", model_path.display()))?;
    // The ground grid is one more face (index = face count), sorted like any other.
    let grid = (args.grid || demo).then(|| {
        let extent = (model_bounds.max - model_bounds.min).max_element();
        (
            mesh.face_count() as u32,
            GroundGrid::new(&model_bounds, 2.0 * extent),
        )
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
        Geometry::new(&polygons).map_err(|e| anyhow::anyhow!("{}: {e}", model_path.display()))?;
    let load_ms = ms(start);

    let camera = args
        .camera
        .camera(&model_path, &model_bounds, args.allow_outside)?;
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
    let yaw = args.yaw.unwrap_or(if demo { DEMO_YAW } else { 0.0 });
    let pitch = args.pitch.unwrap_or(if demo { DEMO_PITCH } else { 0.0 });
    // Fit the model, not the (larger) grid: the grid leaves the frame and fades out.
    let scale = args.scale.or_else(|| {
        grid.is_some()
            .then(|| 0.9 * f64::from(width.min(height)) / model_bounds.diagonal())
    });
    let persp = match (args.persp, demo && !args.ortho) {
        (Some(d), _) => Some(d),
        (None, true) => Some(f64::from(width)),
        (None, false) => None,
    };
    let view = base_view(
        &geometry,
        &BaseView {
            size,
            yaw,
            pitch,
            roll: args.roll,
            cull: args.cull,
            cw: args.cw,
            margin: args.margin,
            scale,
            persp,
            camera,
        },
    )?;

    let start = Instant::now();
    // A glTF file of several mesh nodes, with `auto` and no ground grid, goes through the
    // scene path: each mesh once, its BSP built once, placed by its nodes
    // (`face_sort::SceneSorter`).
    let scene = (args.sorter == SorterChoice::Auto && grid.is_none())
        .then(|| gltf_scene(&model_path, args.allow_outside, &geometry))
        .flatten();
    let (mut sorter, plan, mut presorted) = match scene {
        Some((sorter, plan)) => (sorter, plan, None),
        None => plan(
            args.sorter,
            &polygons,
            &geometry,
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
        let stats = sorter.stats();
        report.fallback_frames = stats.fallback_frames;
        if let Some(reason) = stats.fallback.filter(|_| report.refused.is_none()) {
            report.fell_back = Some(reason.to_string());
            report.drawn_by = "bsp";
        }
    }

    let output = args
        .output
        .clone()
        .unwrap_or_else(|| crate::target_dir().join("render.png"));
    if let Some(parent) = output.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    let texture = match (&args.texture, demo) {
        (Some(path), _) => Some(path.clone()),
        (None, true) => Some(scenes::asset(DEMO_TEXTURE)),
        (None, false) => None,
    };
    let shade = (args.shade || demo).then_some(raster_sink::Light::DEFAULT);
    // ID images need no brushes (and no textures).
    let vector = args.svg.is_some() || args.html.is_some() || args.pdf.is_some();
    let (style, materials) = if args.ids && !vector {
        (
            raster_sink::Style::palette(),
            sprite_compose::Materials::palette(),
        )
    } else {
        raster::face_style(&geometry, &mesh, texture.clone(), grid.as_ref())?
    };
    // --wire / --points: the visible parts of the mesh's edges and vertices, drawn after the
    // faces by every writer (the ground grid's outline left out).
    let overlay = ((args.wire || args.points) && !args.ids).then(|| {
        let grid_face = grid.as_ref().map(|(face, _)| *face);
        let mut overlay = sprite_compose::Overlay::default();
        if args.wire {
            overlay = overlay.with(sprite_compose::Overlay::wireframe(
                &polygons,
                [0, 0, 0, 255],
                1.0,
            ));
        }
        if args.points {
            overlay = overlay.with(sprite_compose::Overlay::vertices(
                &polygons,
                [0, 0, 0, 255],
                2.0,
            ));
        }
        let model_face = |faces: &[u32]| faces.iter().any(|&f| Some(f) != grid_face);
        overlay.lines.retain(|l| model_face(&l.faces));
        overlay.points.retain(|p| model_face(&p.faces));
        sprite_compose::visible_overlay(&geometry, &view, &overlay)
    });
    let (mut svg_summary, mut pdf_summary) = (None, None);
    let hidden = if args.keep_hidden {
        vector_sink::HiddenParts::Keep
    } else {
        vector_sink::HiddenParts::Remove
    };
    if vector {
        // The sprite tree of the same geometry, sorter kind and view, in the materials'
        // colours (a texture as its mean colour), or ID colours with --ids.
        let brushes = style.sprite_brushes(&mesh, shade.as_ref().map(|light| (&view, light)));
        // The painter takes the sorter already built (a BSP build is the costly part).
        let mut painter = sprite_compose::SpritePainter::new(
            &geometry,
            sorter,
            view,
            sprite_compose::RecordingCompositor::new(),
        );
        painter.set_brushes(|face| {
            brushes
                .get(face as usize)
                .copied()
                .unwrap_or(sprite_compose::Brush::Palette)
        });
        painter.frame();
        let scene = painter.compositor().scene();
        // Textured faces in --svg/--html: one exact brush per sprite from the materials'
        // plane uv maps (the brushes above carry a texture's mean colour). Each image is
        // embedded once per file, or with --link-textures linked relative to the file.
        let textured_scene;
        let scene = if args.ids {
            scene
        } else {
            let mut textured = scene.clone();
            let space = sprite_compose::SpriteSpace::of_view(painter.view());
            if materials.set_textures(&mut textured, &space) > 0 {
                textured_scene = textured;
                &textured_scene
            } else {
                scene
            }
        };
        let texture_uri = |out: &std::path::Path| -> Vec<String> {
            if args.ids {
                return Vec::new();
            }
            materials
                .images()
                .iter()
                .map(|image| {
                    image
                        .file()
                        .filter(|_| args.link_textures)
                        .and_then(|file| relative_link(out, file))
                        .unwrap_or_else(|| vector_sink::image_data_uri(image))
                })
                .collect()
        };
        if let Some(path) = &args.svg {
            let start = Instant::now();
            let svg = vector_sink::write_svg(
                scene,
                &vector_sink::SvgOptions::DEFAULT
                    .with_size(width, height)
                    .with_ids(args.ids)
                    .with_hidden(hidden)
                    .with_textures(texture_uri(path))
                    .with_overlay(
                        overlay
                            .as_ref()
                            .map_or_else(String::new, vector_sink::overlay_svg),
                    ),
            );
            svg_summary = Some(VectorSummary {
                shapes: Some(svg.matches("<polygon").count() + svg.matches("<path").count()),
                bytes: svg.len(),
                write_ms: ms(start),
                keep_hidden: args.keep_hidden,
            });
            std::fs::write(path, svg).with_context(|| format!("writing {}", path.display()))?;
        }
        if let Some(path) = &args.pdf {
            let start = Instant::now();
            let mut options = vector_sink::PdfOptions::DEFAULT
                .with_size(width, height)
                .with_ids(args.ids)
                .with_background(args.ids.then_some([0, 0, 0, 255]))
                .with_hidden(hidden)
                .with_images(if args.ids {
                    Vec::new()
                } else {
                    materials.images().to_vec()
                });
            if let Some(overlay) = &overlay {
                options = options.with_overlay(overlay.clone());
            }
            let pdf = vector_sink::write_pdf(scene, &options);
            pdf_summary = Some(VectorSummary {
                shapes: None,
                bytes: pdf.len(),
                write_ms: ms(start),
                keep_hidden: args.keep_hidden,
            });
            std::fs::write(path, pdf).with_context(|| format!("writing {}", path.display()))?;
        }
        if let Some(path) = &args.html {
            let html = vector_sink::write_html(
                scene,
                &vector_sink::HtmlOptions::DEFAULT
                    .with_size(width, height)
                    .with_ids(args.ids)
                    .with_textures(texture_uri(path))
                    .with_overlay(
                        overlay
                            .as_ref()
                            .map_or_else(String::new, vector_sink::overlay_svg),
                    ),
            );
            std::fs::write(path, html).with_context(|| format!("writing {}", path.display()))?;
        }
    }
    let plot_summary = if args.plot.is_some() || args.hpgl.is_some() {
        let start = Instant::now();
        // The ground grid is left out: it is lines over a transparent face, so it hides
        // nothing, and its outline is not an edge of the model.
        let grid_face = grid.as_ref().map(|(face, _)| *face);
        let plot = sprite_compose::plot_edges_where(
            &polygons,
            &geometry,
            &view,
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
        Some(PlotSummary {
            edges: plot.edges.len(),
            visible_edges: plot.edges.iter().filter(|e| !e.visible.is_empty()).count(),
            polylines: plot.polylines.len(),
            pen_down_px: plot.pen_down_px,
            pen_up_px: plot.pen_up_px,
            bytes,
            plot_ms,
        })
    } else {
        None
    };
    let start = Instant::now();
    if args.ids {
        // ID images carry file-order face indices (a face split or merged by the loader
        // keeps its source index).
        let mut ids = list.clone();
        for item in ids.items_mut() {
            item.face = mesh
                .face_source(item.face as usize)
                .unwrap_or(item.face as usize) as u32;
        }
        raster_sink::render_ids(&view, &ids)
            .save_png(&output)
            .map_err(|e| anyhow::anyhow!("{}: {e}", output.display()))?;
    } else {
        let options = raster_sink::RasterOptions::DEFAULT
            .with_anti_alias(!args.no_aa)
            .with_shading(shade);
        let mut image = raster_sink::render_colour(&view, &list, &style, &options)
            .map_err(|e| anyhow::anyhow!("raster: {e}"))?;
        if let Some(overlay) = &overlay {
            raster_sink::draw_overlay(&mut image, overlay, !args.no_aa);
        }
        raster_sink::save_png(&image, &output)
            .map_err(|e| anyhow::anyhow!("{}: {e}", output.display()))?;
    }
    let raster_ms = ms(start);

    let (pixel_error, violations) = if args.check {
        let truth = raster_sink::truth(&view, &geometry);
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
        model: if demo {
            "demo (spot)".to_owned()
        } else {
            model_path.display().to_string()
        },
        output: output.display().to_string(),
        faces: mesh.face_count(),
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
        svg: svg_summary,
        pdf: pdf_summary,
        plot: plot_summary,
        presorted,
    };
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    } else {
        println!("{}", line(&summary));
    }
    Ok(ExitCode::SUCCESS)
}

/// The base view of `render` (and of `bake`): CONVENTIONS.md's camera from the flags.
#[derive(Clone, Copy, Debug)]
pub struct BaseView {
    /// Image size.
    pub size: (u32, u32),
    /// Yaw, degrees.
    pub yaw: f64,
    /// Pitch, degrees.
    pub pitch: f64,
    /// Roll, degrees.
    pub roll: f64,
    /// Cull mode.
    pub cull: CullChoice,
    /// Clockwise fronts.
    pub cw: bool,
    /// Cull margin, degrees.
    pub margin: f64,
    /// Scale in pixels per model unit; `None`: fit.
    pub scale: Option<f64>,
    /// Perspective eye distance in pixels; `None`: orthographic.
    pub persp: Option<f64>,
    /// A camera, which replaces yaw, pitch, roll, scale and `persp`.
    pub camera: Option<face_sort::Camera>,
}

/// The view of `geometry` for these flags; errors on a scale or distance that is not a
/// positive number.
pub fn base_view(geometry: &Geometry, flags: &BaseView) -> Result<View> {
    let (width, height) = flags.size;
    let base = match &flags.camera {
        Some(camera) => camera.view(geometry, width, height)?,
        None => View::fit(&geometry.bounds(), width, height).with_yaw_pitch_roll(
            flags.yaw,
            flags.pitch,
            flags.roll,
        ),
    };
    let mut view = base
        .with_cull(match flags.cull {
            CullChoice::Back => CullMode::Back,
            CullChoice::Front => CullMode::Front,
            CullChoice::None => CullMode::None,
        })
        .with_cull_margin(flags.margin);
    if flags.cw {
        view = view.with_front_face(FrontFace::Clockwise);
    }
    if flags.camera.is_some() {
        return Ok(view);
    }
    if let Some(scale) = flags.scale {
        if !(scale.is_finite() && scale > 0.0) {
            bail!("--scale must be a positive number, got {scale}");
        }
        view = view.with_scale(scale);
    }
    if let Some(d) = flags.persp {
        if !(d.is_finite() && d > 0.0) {
            bail!("--persp must be a positive distance in pixels, got {d}");
        }
        view = view.with_perspective(d);
    }
    Ok(view)
}

/// Loads a model as `render` does (face policy, paths outside the model's folder only when
/// allowed, warnings to stderr): the loader's mesh and the sorters' input.
pub fn load_mesh(
    path: &std::path::Path,
    policy: PolicyChoice,
    allow_outside: bool,
) -> Result<(obj_quads::Mesh, PolygonMesh)> {
    let policy = match policy {
        PolicyChoice::Quads => obj_quads::FacePolicy::QuadsOnly,
        PolicyChoice::Polygons => obj_quads::FacePolicy::Polygons,
        PolicyChoice::Merge => obj_quads::FacePolicy::MergeTriangles,
    };
    let load_options = obj_quads::LoadOptions::DEFAULT
        .with_face_policy(policy)
        .with_allow_outside_paths(allow_outside);
    let (mesh, report) =
        obj_quads::load(path, &load_options).map_err(|e| anyhow::anyhow!("{e}"))?;
    for warning in &report.warnings {
        eprintln!("warning: {}: {warning}", path.display());
    }
    let polygons = scenes::to_polygon_mesh(&mesh)?;
    Ok((mesh, polygons))
}

fn line(s: &Summary) -> String {
    let mut out = format!(
        "{}: {} faces, {} drawn, {} fragments ({}); load {:.1} ms, build {:.1} ms, sort {:.2} ms, raster {:.1} ms",
        s.model,
        s.faces,
        s.drawn,
        s.fragments,
        s.sorter,
        s.load_ms,
        s.build_ms,
        s.sort_ms,
        s.raster_ms
    );
    if let (Some(e), Some(v)) = (s.pixel_error, s.violations) {
        out.push_str(&format!(
            "; pixel error {:.4} %, {v} order violations",
            e * 100.0
        ));
    }
    for (name, written) in [("svg", &s.svg), ("pdf", &s.pdf)] {
        if let Some(v) = written {
            let shapes = v
                .shapes
                .map(|n| format!("{n} shapes, "))
                .unwrap_or_default();
            let kept = if v.keep_hidden { " (hidden kept)" } else { "" };
            out.push_str(&format!(
                "; {name} {shapes}{} bytes, {:.1} ms{kept}",
                v.bytes, v.write_ms
            ));
        }
    }
    if let Some(p) = &s.presorted {
        out.push_str(&format!("; {}", p.words()));
    }
    if let Some(p) = &s.plot {
        out.push_str(&format!(
            "; plot {} of {} edges visible, {} polylines, pen down {:.0} px, pen up {:.0} px, {:.1} ms",
            p.visible_edges, p.edges, p.polylines, p.pen_down_px, p.pen_up_px, p.plot_ms
        ));
    }
    out.push_str(&format!(" -> {}", s.output));
    out
}

fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
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
