//! `cargo xtask bake`: every painter order of a model along an animation axis (aspect-bake),
//! as JSON and as a spinning HTML page.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use face_sort::{Geometry, PolygonMesh};
use serde_json::{Value, json};
use sprite_compose::aspect_bake::{
    self, Axis, Bake, BakeOptions, BspSource, CentroidSource, EventSource, Method, PictureOptions,
    Progress, Spin,
};

use crate::progress;
use crate::render::{self, BaseView, CullChoice, PolicyChoice};

/// Options of `bake`.
#[derive(Debug, Args)]
pub struct BakeArgs {
    /// Model to bake (.obj, .gltf, .glb).
    model: PathBuf,
    /// The parameter that turns; the other two stay at their flags' values.
    #[arg(long, value_enum)]
    axis: AxisChoice,
    /// Base yaw in degrees (as in `render`).
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    yaw: f64,
    /// Base pitch in degrees.
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    pitch: f64,
    /// Base roll in degrees.
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    roll: f64,
    /// Perspective with the eye D pixels from the centre (the eye orbits with the model's
    /// rotation). Absent: orthographic.
    #[arg(long, value_name = "D")]
    persp: Option<f64>,
    /// Image size (scale "fit" and the HTML page's size).
    #[arg(long, value_name = "WxH", default_value = "512x512", value_parser = render::parse_size)]
    size: (u32, u32),
    /// A camera that starts the turn instead of yaw, pitch, roll and --persp (as in
    /// `render`); it must look at the model's centre, about which the model turns. The
    /// axis is then the camera's screen vertical (yaw), horizontal (pitch) or view direction
    /// (roll).
    #[command(flatten)]
    camera: render::CameraFlags,
    /// Which faces culling removes.
    #[arg(long, value_enum, default_value_t = CullChoice::Back)]
    cull: CullChoice,
    /// Clockwise faces are the front.
    #[arg(long)]
    cw: bool,
    /// Which faces the loader accepts.
    #[arg(long, value_enum, default_value_t = PolicyChoice::Polygons)]
    policy: PolicyChoice,
    /// What the cells keep constant: `picture` (default) the picture, with back faces culled
    /// by the sink (a handful of cells per turn); `bsp` or `centroid` that sorter's draw list.
    #[arg(long, value_enum, default_value_t = SorterChoice::Picture)]
    sorter: SorterChoice,
    /// Exact events, or the seed's sampling baseline.
    #[arg(long, value_enum, default_value_t = MethodChoice::Exact)]
    method: MethodChoice,
    /// Samples over the period for --method sampled.
    #[arg(long, value_name = "N", default_value_t = 720)]
    samples: usize,
    /// Bisection tolerance of --method sampled, degrees.
    #[arg(long, value_name = "DEG", default_value_t = 1e-3)]
    tolerance: f64,
    /// Check the bake against the live sorter (random angles in every cell, both sides of
    /// every breakpoint); exit 1 when it disagrees.
    #[arg(long)]
    verify: bool,
    /// Write the bake as JSON.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write the bake in its binary encoding (aspect-bake's `Bake::to_binary`).
    #[arg(long, value_name = "FILE")]
    bin: Option<PathBuf>,
    /// Write a self-contained spinning HTML page.
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    /// With `--sorter picture`: also write the canvas player (one `<canvas>` and a script that
    /// projects, looks up the cell, culls and fills; no per-element layers) to this path.
    /// `--period`, `--ids` and `--paused` apply; a page address `#S` pauses it at S seconds.
    #[arg(long, value_name = "PATH")]
    canvas: Option<PathBuf>,
    /// Seconds per turn of the HTML page.
    #[arg(long, value_name = "S", default_value_t = 8.0)]
    period: f64,
    /// The HTML page in ID colours (CONVENTIONS.md) instead of the model's own.
    #[arg(long)]
    ids: bool,
    /// Pause the HTML page S seconds into the turn (at time t the animated parameter is its
    /// base value + 360·t/period degrees).
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    paused: Option<f64>,
    /// With `--axis yaw`: bake over yaw × pitch, pitch in `[LO, HI)` degrees (the base pitch
    /// is ignored): cells over the two-dimensional domain (aspect-bake's `bake_two_axes`).
    /// `--verify` and `--json` apply; `--html` and `--method sampled` do not.
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true, value_parser = parse_range)]
    pitch_range: Option<(f64, f64)>,
    /// Stop when the per-cell lists would exceed this many MiB.
    #[arg(long, value_name = "MIB", default_value_t = 1024)]
    budget_mib: usize,
}

/// `--axis`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AxisChoice {
    /// Yaw turns.
    Yaw,
    /// Pitch turns.
    Pitch,
    /// Roll turns.
    Roll,
}

/// `--sorter`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SorterChoice {
    /// Cells exact for the picture; the sink culls back faces.
    Picture,
    /// BSP (exact).
    Bsp,
    /// Centroid depth (the seed's, not exact).
    Centroid,
}

/// `--method`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MethodChoice {
    /// Closed-form events.
    Exact,
    /// Samples and bisection.
    Sampled,
}

/// A loaded model ready to bake.
pub struct Prepared {
    /// The loaded model (materials for the page's colours).
    pub source: obj_quads::Mesh,
    /// The sorters' input.
    pub mesh: PolygonMesh,
    /// Its pieces.
    pub geometry: Geometry,
    /// The spin.
    pub spin: Spin,
}

/// Loads the model and builds the spin from the flags.
pub fn prepare(args: &BakeArgs) -> Result<Prepared> {
    let (source, mesh) = render::load_mesh(&args.model, args.policy, false)?;
    let geometry =
        Geometry::new(&mesh).map_err(|e| anyhow::anyhow!("{}: {e}", args.model.display()))?;
    let (size, camera) = match args.camera.camera(&args.model, &geometry.bounds(), false)? {
        Some(camera) => (camera.image_size(args.size.0), Some(camera)),
        None => (args.size, None),
    };
    let view = render::base_view(
        &geometry,
        &BaseView {
            size,
            yaw: args.yaw,
            pitch: args.pitch,
            roll: args.roll,
            cull: args.cull,
            cw: args.cw,
            margin: 0.0,
            scale: None,
            persp: args.persp,
            camera,
        },
    )?;
    if camera.is_some() {
        let view = aimed_at_centre(view)?;
        let k = match args.axis {
            AxisChoice::Yaw => [0.0, 1.0, 0.0],
            AxisChoice::Pitch => [1.0, 0.0, 0.0],
            AxisChoice::Roll => [0.0, 0.0, 1.0],
        };
        let axis = Axis::Direction {
            axis: k,
            base: view.rotation().to_cols_array_2d(),
        };
        let spin = Spin::new(view, axis).context("axis")?;
        return Ok(Prepared {
            source,
            mesh,
            geometry,
            spin,
        });
    }
    let axis = match args.axis {
        AxisChoice::Yaw => Axis::Yaw {
            pitch: args.pitch,
            roll: args.roll,
        },
        AxisChoice::Pitch => Axis::Pitch {
            yaw: args.yaw,
            roll: args.roll,
        },
        AxisChoice::Roll => Axis::Roll {
            yaw: args.yaw,
            pitch: args.pitch,
        },
    };
    let spin = Spin::new(view, axis).context("axis")?;
    Ok(Prepared {
        source,
        mesh,
        geometry,
        spin,
    })
}

/// A camera's view as a spin template: the model turns about its centre with the eye fixed,
/// so the camera must look at the centre (no view offset across the view axis, the
/// principal point at the image centre). Along the axis the offset folds into the scale:
/// with the eye `D = d/s − t.z` from the centre, scale `d/D` and no offset project every
/// point to the same pixel.
fn aimed_at_centre(view: face_sort::View) -> Result<face_sort::View> {
    let t = view.view_offset();
    let centre = glam::DVec2::new(f64::from(view.width()), f64::from(view.height())) * 0.5;
    if t.x.abs().max(t.y.abs()) > 1e-9 * view.diagonal() || view.principal_point() != centre {
        bail!(
            "bake turns the model about its centre: the camera must look at the model's centre \
             (--target defaults to it) with a centred principal point"
        );
    }
    let view = view.with_view_offset(glam::DVec3::ZERO);
    Ok(match view.projection() {
        face_sort::Projection::Orthographic => view,
        face_sort::Projection::Perspective { distance } => {
            let eye = distance / view.scale() - t.z;
            if eye.is_nan() || eye <= 0.0 {
                bail!("the camera's eye is not in front of the model's centre");
            }
            view.with_scale(distance / eye)
        }
    })
}

/// Runs `bake`.
pub fn run(args: &BakeArgs) -> Result<ExitCode> {
    if !(args.period.is_finite() && args.period > 0.0) {
        bail!(
            "--period must be a positive number of seconds, got {}",
            args.period
        );
    }
    if args.canvas.is_some() && (args.sorter != SorterChoice::Picture || args.pitch_range.is_some())
    {
        bail!(
            "--canvas plays a one-axis picture bake: use it with --sorter picture and no --pitch-range"
        );
    }
    let prepared = prepare(args)?;
    if let Some(range) = args.pitch_range {
        return run_two_axes(args, &prepared, range);
    }
    if args.sorter == SorterChoice::Picture {
        return run_picture(args, &prepared);
    }
    let (geometry, spin) = (&prepared.geometry, &prepared.spin);
    let source = event_source(args.sorter, geometry)?;
    let source = source.as_ref();
    let bar = progress::bar(0, "bake");
    let report = |p: Progress| {
        bar.set_length(p.total as u64);
        bar.set_position(p.done as u64);
    };
    let options = BakeOptions {
        budget_bytes: args.budget_mib.saturating_mul(1 << 20),
        progress: Some(&report),
        ..BakeOptions::DEFAULT
    };
    let exact = aspect_bake::bake(source, spin, &options)?;
    let (baked, missed) = match args.method {
        MethodChoice::Exact => (exact, None),
        MethodChoice::Sampled => {
            let sampled =
                aspect_bake::bake_sampled(source, spin, args.samples, args.tolerance, &options)?;
            let missed = sampled.missed(&exact, 2.0 * args.tolerance).len();
            (sampled, Some(missed))
        }
    };
    bar.finish_and_clear();
    let sizes = baked.sizes();
    let mut line = format!(
        "{} {} {}: {:.1} ms, {} breakpoints, {} cells, {} events, {} B full lists, {} B delta timeline",
        args.axis_name(),
        baked.sorter(),
        method_name(&baked),
        baked.bake_ms(),
        baked.breakpoints().len(),
        baked.cells().len(),
        baked.events(),
        sizes.full_bytes,
        sizes.delta_bytes,
    );
    if let Some(m) = missed {
        line.push_str(&format!(", {m} exact breakpoints missed"));
    }
    let mut code = ExitCode::SUCCESS;
    if args.verify {
        let checked = aspect_bake::verify(&baked, source, spin, 4, 0x5EED).map(|r| {
            format!(
                "{} interior angles, {} breakpoints",
                r.interior_checks, r.breakpoint_checks
            )
        });
        code = report_verify(&mut line, checked);
    }
    if let Some(path) = &args.json {
        let value = bake_json(&baked, &prepared, missed);
        write(path, &serde_json::to_string(&value)?)?;
    }
    if let Some(path) = &args.html {
        let page = vector_sink::write_spin_html(
            &baked,
            spin,
            geometry,
            &vector_sink::SpinOptions::DEFAULT.with_period(args.period),
        );
        write(path, &page)?;
        let model_bytes = std::fs::metadata(&args.model).map_or(0, |m| m.len());
        line.push_str(&format!(
            ", page {} B (model file {model_bytes} B)",
            page.len()
        ));
    }
    println!("{line}");
    Ok(code)
}

impl BakeArgs {
    fn axis_name(&self) -> &'static str {
        match self.axis {
            AxisChoice::Yaw => "yaw",
            AxisChoice::Pitch => "pitch",
            AxisChoice::Roll => "roll",
        }
    }
}

/// Appends `--verify`'s outcome to the summary line; failure when the bake disagrees.
fn report_verify(line: &mut String, checked: Result<String, impl std::fmt::Display>) -> ExitCode {
    match checked {
        Ok(what) => {
            line.push_str(&format!(", verified ({what})"));
            ExitCode::SUCCESS
        }
        Err(e) => {
            line.push_str(&format!(", VERIFY FAILED: {e}"));
            ExitCode::FAILURE
        }
    }
}

/// `--sorter picture`: cells exact for the picture (aspect-bake's `bake_picture`).
fn run_picture(args: &BakeArgs, prepared: &Prepared) -> Result<ExitCode> {
    if args.method == MethodChoice::Sampled {
        bail!("--method sampled bakes a sorter's lists: use it with --sorter bsp or centroid");
    }
    let options = PictureOptions {
        budget_bytes: args.budget_mib.saturating_mul(1 << 20),
        ..PictureOptions::DEFAULT
    };
    // Pieces that share their corners exactly (no snapped planar faces twisting against
    // their neighbours).
    let geometry = Geometry::with_exact_corners(&prepared.mesh)
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.model.display()))?;
    let (baked, stats) = aspect_bake::bake_picture(&geometry, &prepared.spin, &options)?;
    let moved: Vec<String> = stats.moved.iter().map(usize::to_string).collect();
    let mut line = format!(
        "{} picture: {:.1} ms, {} cells, {} pieces ({} cuts), {} candidate pairs, {} constraints, moved per boundary [{}]",
        args.axis_name(),
        baked.bake_ms(),
        baked.cells().len(),
        stats.pieces,
        stats.cuts,
        stats.candidate_pairs,
        stats.constraints,
        moved.join(", "),
    );
    let mut code = ExitCode::SUCCESS;
    if args.verify {
        let checked = aspect_bake::verify_picture(&baked, &prepared.spin, 4, 0x5EED).map(|r| {
            format!(
                "oracle at {} interior angles and {} angles 1e-6 deg inside cell ends",
                r.interior_checks, r.breakpoint_checks
            )
        });
        code = report_verify(&mut line, checked);
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string(&picture_json(&baked, &geometry, prepared))?;
        write(path, &text)?;
        line.push_str(&format!(", json {} B", text.len()));
    }
    if let Some(path) = &args.bin {
        let bytes = baked
            .to_binary()
            .map_err(|e| anyhow::anyhow!("binary encoding: {e}"))?;
        std::fs::write(path, &bytes).with_context(|| format!("writing {}", path.display()))?;
        line.push_str(&format!(", binary {} B", bytes.len()));
    }
    if args.html.is_some() || args.canvas.is_some() {
        let lists = aspect_bake::drawn_lists(&baked, &prepared.spin)?;
        let (_, materials) = crate::raster::face_style(&geometry, &prepared.source, None, None)?;
        let options = vector_sink::SpinOptions::DEFAULT
            .with_period(args.period)
            .with_ids(args.ids)
            .with_paused_at(args.paused)
            .with_materials(&materials);
        type Writer = fn(
            &Bake,
            &[Vec<u32>],
            &aspect_bake::Spin,
            &Geometry,
            &vector_sink::SpinOptions,
        ) -> String;
        let pages: [(&Option<PathBuf>, Writer, &str); 2] = [
            (&args.html, vector_sink::write_culled_spin_html, "page"),
            (
                &args.canvas,
                vector_sink::write_canvas_spin_html,
                "canvas page",
            ),
        ];
        for (path, write_page, what) in pages {
            let Some(path) = path else { continue };
            let page = write_page(&baked, &lists, &prepared.spin, &geometry, &options);
            write(path, &page)?;
            let elements = page.matches("<i class=").count() + page.matches("<b class=").count();
            line.push_str(&format!(", {what} {} B", page.len()));
            if elements > 0 {
                line.push_str(&format!(" ({elements} elements)"));
            }
        }
    }
    println!("{line}");
    Ok(code)
}

/// The event source of `--sorter`.
fn event_source(sorter: SorterChoice, geometry: &Geometry) -> Result<Box<dyn EventSource>> {
    Ok(match sorter {
        SorterChoice::Picture => {
            bail!("two-axis bakes (--pitch-range) take --sorter bsp or centroid")
        }
        SorterChoice::Bsp => Box::new(BspSource::of(geometry)),
        SorterChoice::Centroid => Box::new(CentroidSource::of(geometry)),
    })
}

fn method_name(bake: &Bake) -> &'static str {
    match bake.method() {
        Method::Exact => "exact",
        Method::Sampled { .. } => "sampled",
        Method::Picture => "picture",
    }
}

fn write(path: &std::path::Path, text: &str) -> Result<()> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

/// The JSON of the issue: angles in degrees of the animated parameter; each draw list back
/// to front; an item is the face index when the polygon is the whole face, else the face and
/// the polygon's corners in model space.
pub fn bake_json(bake: &Bake, prepared: &Prepared, missed: Option<usize>) -> Value {
    let items = item_values(bake.polygons(), &prepared.geometry, prepared);
    let cells: Vec<Value> = bake
        .cells()
        .iter()
        .map(|c| {
            let list: Vec<&Value> = c.order.iter().map(|&p| &items[p as usize]).collect();
            json!({"lo": c.range.lo, "hi": c.range.hi, "draw_list": list})
        })
        .collect();
    json!({
        "axis": bake.axis().name(),
        "sorter": bake.sorter(),
        "method": method_name(bake),
        "bake_ms": bake.bake_ms(),
        "breakpoints": bake.breakpoints().iter().map(|b| b.degrees).collect::<Vec<_>>(),
        "cells": cells,
        "missed": missed,
    })
}

/// The JSON of a picture bake: the keys of [`bake_json`], except that the items are written
/// once, in `"pieces"` (each a face index or `{"face", "polygon"}` as there), and each cell's
/// `"draw_list"` lists indices into `"pieces"` (`"draw_list_items": "piece indices"`), back
/// to front; `"culling": "sink"`: a list holds every piece, and the sink must hide those that
/// face away.
fn picture_json(bake: &Bake, geometry: &Geometry, prepared: &Prepared) -> Value {
    let pieces = item_values(bake.polygons(), geometry, prepared);
    let cells: Vec<Value> = bake
        .cells()
        .iter()
        .map(|c| json!({"lo": c.range.lo, "hi": c.range.hi, "draw_list": c.order}))
        .collect();
    json!({
        "axis": bake.axis().name(),
        "sorter": bake.sorter(),
        "method": method_name(bake),
        "culling": "sink",
        "bake_ms": bake.bake_ms(),
        "breakpoints": bake.breakpoints().iter().map(|b| b.degrees).collect::<Vec<_>>(),
        "pieces": pieces,
        "draw_list_items": "piece indices",
        "cells": cells,
    })
}

/// Each polygon of a bake's set as a draw-list item: the face index when the polygon is the
/// whole face, else the face and the polygon's corners in model space.
fn item_values(
    set: &face_sort::PolygonSet,
    geometry: &Geometry,
    prepared: &Prepared,
) -> Vec<Value> {
    let pieces = geometry.pieces();
    let faces = prepared.mesh.face_count();
    // A face is whole when it is one piece with all its corners (planar, not cut).
    let mut piece_of: Vec<Option<usize>> = vec![None; faces];
    let mut count = vec![0usize; faces];
    for p in 0..pieces.len() {
        let f = pieces.face(p) as usize;
        count[f] += 1;
        piece_of[f] = Some(p);
    }
    let face_len: Vec<usize> = prepared.mesh.faces().map(<[u32]>::len).collect();
    let centre = prepared.spin.template().centre();
    (0..set.len())
        .map(|i| {
            let f = set.face(i) as usize;
            let whole = count[f] == 1
                && piece_of[f].is_some_and(|p| {
                    pieces.corners(p) == set.corners(i) && set.corners(i).len() == face_len[f]
                });
            if whole {
                json!(f)
            } else {
                let polygon: Vec<[f64; 3]> = set
                    .corners(i)
                    .iter()
                    .map(|&c| (c + centre).to_array())
                    .collect();
                json!({"face": f, "polygon": polygon})
            }
        })
        .collect()
}

fn parse_range(text: &str) -> Result<(f64, f64), String> {
    let (lo, hi) = text
        .split_once(',')
        .ok_or_else(|| format!("expected LO,HI in degrees, got {text:?}"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f64>()
            .map_err(|e| format!("{v:?} is not a number: {e}"))
    };
    Ok((parse(lo)?, parse(hi)?))
}

/// `--axis yaw --pitch-range LO,HI`: the two-axis bake, its summary line, `--verify`, and
/// `--json` (`{"axes", "sorter", "bake_ms", "yaw": [0, 360], "pitch": [lo, hi], "circles":
/// [{"normal", "offset"}], "slabs": [{"lo", "hi", "curves": [{"circle", "down", "mid_yaw"}],
/// "cells"}],
/// "cells": [{"draw_list"}], "missed_by_1deg_grid"}`): a point's cell is found in the slab
/// of its pitch, between the curves — circle `normal·d = offset` roots in yaw — around it).
fn run_two_axes(args: &BakeArgs, prepared: &Prepared, pitch: (f64, f64)) -> Result<ExitCode> {
    if args.axis != AxisChoice::Yaw {
        bail!("--pitch-range bakes yaw x pitch: use it with --axis yaw");
    }
    if args.html.is_some() || args.method == MethodChoice::Sampled {
        bail!("--pitch-range does not write --html or bake --method sampled");
    }
    let geometry = &prepared.geometry;
    let source = event_source(args.sorter, geometry)?;
    let source = source.as_ref();
    let domain = aspect_bake::YawPitch {
        template: *prepared.spin.template(),
        yaw: None,
        pitch,
        roll: args.roll,
    };
    let options = aspect_bake::TwoAxisOptions {
        budget_bytes: args.budget_mib.saturating_mul(1 << 20),
        ..aspect_bake::TwoAxisOptions::default()
    };
    let baked = aspect_bake::bake_two_axes(source, &domain, &options)?;
    let columns = 360;
    let rows = ((pitch.1 - pitch.0).ceil() as usize).max(1);
    let missed = baked.missed_by_grid(columns, rows);
    let mut line = format!(
        "yaw x pitch [{}, {}) {}: {:.1} ms, {} circles, {} slabs, {} cells, {} B full lists, \
         a 1-degree grid ({columns} x {rows} samples) misses {missed} cells",
        pitch.0,
        pitch.1,
        baked.sorter(),
        baked.bake_ms(),
        baked.circles().len(),
        baked.slabs().len(),
        baked.cells().len(),
        baked.full_bytes(),
    );
    let mut code = ExitCode::SUCCESS;
    if args.verify {
        let checked = aspect_bake::verify_two_axes(&baked, source, 2, 0x5EED).map(|r| {
            format!(
                "{} interior points, {} curves",
                r.interior_checks, r.curve_checks
            )
        });
        code = report_verify(&mut line, checked);
    }
    if let Some(path) = &args.json {
        let items = item_values(baked.polygons(), &prepared.geometry, prepared);
        let value = json!({
            "axes": ["yaw", "pitch"],
            "sorter": baked.sorter(),
            "bake_ms": baked.bake_ms(),
            "yaw": [0.0, 360.0],
            "pitch": [pitch.0, pitch.1],
            "roll": args.roll,
            "circles": baked.circles().iter().map(|c| json!({
                "normal": c.normal.to_array(),
                "offset": c.offset,
            })).collect::<Vec<_>>(),
            "slabs": baked.slabs().iter().map(|s| json!({
                "lo": s.lo,
                "hi": s.hi,
                "curves": s.curves.iter().zip(&s.mid_yaws).map(|(c, y)| json!({"circle": c.circle, "down": c.down, "mid_yaw": y})).collect::<Vec<_>>(),
                "cells": s.cells,
            })).collect::<Vec<_>>(),
            "cells": baked.cells().iter().map(|c| json!({
                "draw_list": c.iter().map(|&p| &items[p as usize]).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
            "missed_by_1deg_grid": missed,
        });
        write(path, &serde_json::to_string(&value)?)?;
    }
    println!("{line}");
    Ok(code)
}
