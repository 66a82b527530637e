//! `render`'s command line: its options, the camera flags, the base view they make, and
//! loading a model as `render` does. Shared with `bake`, `turn` and the scene demo.

use anyhow::{Result, bail};
use clap::{Args, ValueEnum};
use face_sort::{CullMode, FrontFace, Geometry, PolygonMesh, View};
use std::path::PathBuf;

use crate::scenes;

/// The demo scene: spot the cow (Keenan Crane, CC0), textured, on a ground grid.
pub(super) const DEMO_MODEL: &str = "assets/models/keenan-crane/spot/spot_quadrangulated.obj";
/// The demo model's texture (its OBJ has uvs but no MTL).
pub(super) const DEMO_TEXTURE: &str = "assets/models/keenan-crane/spot/spot_texture.png";
/// The demo's view when no angle is given.
pub(super) const DEMO_YAW: f64 = 145.0;
pub(super) const DEMO_PITCH: f64 = -25.0;

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
    /// Also write an SVG of the same view (vector-sink's writer, in the model's materials,
    /// textures embedded).
    #[arg(long, value_name = "OUT.svg")]
    pub(crate) svg: Option<PathBuf>,
    /// Also write an HTML/CSS 3D page of the same view (vector-sink's writer, in the model's
    /// materials).
    #[arg(long, value_name = "OUT.html")]
    pub(crate) html: Option<PathBuf>,
    /// Also write a one-page PDF of the same view (vector-sink's writer, in the model's
    /// materials; one pixel to one point).
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
