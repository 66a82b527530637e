//! `cargo xtask truth`: raster-sink's references for triangles seen by an engine's camera,
//! for checks outside Rust (the npm package's browser tests): the ID truth with its
//! unambiguous pixels, and the exact compositing of translucent triangles.
//!
//! The scene is JSON: `positions` (x, y, z per vertex), `indices` (three per triangle;
//! triangle `i` is face `i`), `colours` (sRGB RGBA bytes per triangle, for the composite;
//! opaque grey when absent),
//! `view` and `projection` (column-major 4 × 4, WebGL clip space), `width`, `height`,
//! `cull` (`"back"`, `"front"` or `"none"`) and `background` (RGBA). Written into `--out`:
//! `ids.bin` (u32 little-endian per pixel, 0 = background), `ids_mask.bin` (1 where the ID
//! truth is unambiguous, CONVENTIONS.md), `composite_mask.bin` (1 where the composite is:
//! also no two fragments change places within the edge margin, so not by an
//! interpenetration line) and `composite.rgba` (straight-alpha RGBA per pixel); one byte
//! per mask pixel, row-major from the top-left.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use face_sort::{Camera, ClipSpace, CullMode, Geometry, PolygonMesh};
use glam::DMat4;
use serde::Deserialize;

/// `cargo xtask truth` arguments.
#[derive(Debug, clap::Args)]
pub struct TruthArgs {
    /// The scene (JSON, module docs).
    #[arg(long)]
    scene: PathBuf,
    /// Directory to write the references into (created if missing).
    #[arg(long)]
    out: PathBuf,
}

#[derive(Deserialize)]
struct SceneFile {
    positions: Vec<f64>,
    indices: Vec<u32>,
    #[serde(default)]
    colours: Vec<u8>,
    view: Vec<f64>,
    projection: Vec<f64>,
    width: u32,
    height: u32,
    cull: String,
    #[serde(default = "white")]
    background: [u8; 4],
}

fn white() -> [u8; 4] {
    [255; 4]
}

fn matrix(m: &[f64], what: &str) -> Result<DMat4> {
    if m.len() != 16 {
        bail!("{what} needs 16 numbers, got {}", m.len());
    }
    Ok(DMat4::from_cols_slice(m))
}

pub fn run(args: &TruthArgs) -> Result<ExitCode> {
    let text = std::fs::read_to_string(&args.scene)
        .with_context(|| format!("reading {}", args.scene.display()))?;
    let scene: SceneFile = serde_json::from_str(&text).context("scene JSON")?;
    if !scene.positions.len().is_multiple_of(3) || !scene.indices.len().is_multiple_of(3) {
        bail!("positions and indices must come in threes");
    }
    let positions: Vec<[f64; 3]> = scene
        .positions
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    let faces: Vec<[u32; 3]> = scene
        .indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    let geometry = Geometry::new(&PolygonMesh::new(positions, &faces)?)?;
    let Some(cull) = CullMode::from_name(&scene.cull) else {
        bail!("cull must be back, front or none, not {:?}", scene.cull);
    };
    let camera = Camera::from_matrices(
        matrix(&scene.view, "view")?,
        matrix(&scene.projection, "projection")?,
        ClipSpace::MinusOneToOne,
    )?;
    let view = camera
        .view(&geometry, scene.width, scene.height)?
        .with_cull(cull);
    std::fs::create_dir_all(&args.out)?;
    let write = |name: &str, bytes: Vec<u8>| {
        std::fs::write(args.out.join(name), bytes)
            .with_context(|| format!("writing {name} in {}", args.out.display()))
    };
    let truth = raster_sink::truth(&view, &geometry);
    write(
        "ids.bin",
        truth.ids.iter().flat_map(|id| id.to_le_bytes()).collect(),
    )?;
    write(
        "ids_mask.bin",
        truth.unambiguous.iter().map(|&u| u8::from(u)).collect(),
    )?;
    // Without colours, every face opaque grey: the composite's mask still says where two
    // fragments change places within the edge margin (an interpenetration line).
    if !scene.colours.is_empty() && scene.colours.len() != 4 * faces.len() {
        bail!("colours must be 4 bytes per triangle");
    }
    {
        let colour = |face: u32| {
            scene
                .colours
                .get(4 * face as usize..4 * face as usize + 4)
                .map_or([128, 128, 128, 255], |c| [c[0], c[1], c[2], c[3]])
        };
        let composite = raster_sink::composite_truth(&view, &geometry, colour, scene.background)?;
        let mut rgba = Vec::with_capacity(composite.image.pixels().len() * 4);
        for p in composite.image.pixels() {
            let c = p.demultiply();
            rgba.extend_from_slice(&[c.red(), c.green(), c.blue(), c.alpha()]);
        }
        write("composite.rgba", rgba)?;
        write(
            "composite_mask.bin",
            composite.unambiguous.iter().map(|&u| u8::from(u)).collect(),
        )?;
    }
    Ok(ExitCode::SUCCESS)
}
