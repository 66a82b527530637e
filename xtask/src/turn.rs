//! `cargo xtask turn`: a model as a page that turns with the pointer, showing orders
//! certified by `face_sort::Presorted` (no script orders anything).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;
use face_sort::{SorterKind, View};

use crate::render::{self, PolicyChoice};

/// Options of `turn`.
#[derive(Debug, Args)]
pub struct TurnArgs {
    /// Model (.obj, .gltf, .glb).
    model: PathBuf,
    /// The CSS page to write (one element per piece, z-index switched by the script).
    #[arg(long, value_name = "FILE", required_unless_present = "canvas")]
    html: Option<PathBuf>,
    /// The canvas player to write (one `<canvas>`; the script projects, looks up the region,
    /// culls and fills).
    #[arg(long, value_name = "FILE")]
    canvas: Option<PathBuf>,
    /// Yaw in degrees shown until the pointer moves (the page's address may override it with
    /// `#yaw,pitch`).
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    yaw: f64,
    /// Pitch in degrees shown until the pointer moves.
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    pitch: f64,
    /// Perspective with the eye D pixels from the centre (as in `render`); orthographic
    /// without.
    #[arg(long, value_name = "D")]
    persp: Option<f64>,
    /// Page size (scale "fit").
    #[arg(long, value_name = "WxH", default_value = "512x512", value_parser = render::parse_size)]
    size: (u32, u32),
    /// ID colours (CONVENTIONS.md) instead of the model's own.
    #[arg(long)]
    ids: bool,
    /// Which faces the loader accepts.
    #[arg(long, value_enum, default_value_t = PolicyChoice::Polygons)]
    policy: PolicyChoice,
    /// Load the certificate from FILE when it holds one for this model, else build it and
    /// save it there.
    #[arg(long, value_name = "FILE")]
    presort_cache: Option<PathBuf>,
}

/// Runs `turn`.
pub fn run(args: &TurnArgs) -> Result<ExitCode> {
    let (source, mesh) = render::load_mesh(&args.model, args.policy, false)?;
    let geometry = SorterKind::Presorted
        .geometry_for(&mesh)
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.model.display()))?;
    let mut view = View::fit(&geometry.bounds(), args.size.0, args.size.1);
    if let Some(d) = args.persp {
        anyhow::ensure!(
            d.is_finite() && d > 0.0,
            "--persp must be a positive number of pixels"
        );
        view = view.with_perspective(d);
    }
    let (sorter, had, build_ms) =
        crate::presort_cache::load_or_build(&geometry, args.presort_cache.as_deref())??;
    let certificate = had.words(args.presort_cache.as_deref());
    let (_, materials) = crate::raster::face_style(&geometry, &source, None, None)?;
    let options = vector_sink::TurnPageOptions::DEFAULT
        .with_ids(args.ids)
        .with_start(args.yaw, args.pitch)
        .with_materials(&materials);
    type Writer = fn(
        &face_sort::Presorted,
        &face_sort::Geometry,
        &View,
        &vector_sink::TurnPageOptions,
    ) -> Result<vector_sink::TurnPage, face_sort::CertifiedOrdersError>;
    let pages: [(&Option<PathBuf>, Writer, &str); 2] = [
        (&args.html, vector_sink::write_turn_html, "page"),
        (
            &args.canvas,
            vector_sink::write_canvas_turn_html,
            "canvas page",
        ),
    ];
    for (path, write, what) in pages {
        let Some(path) = path else { continue };
        let page = write(&sorter, &geometry, &view, &options)
            .with_context(|| format!("{}: the {what}", args.model.display()))?;
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("creating {}", parent.display()))?;
        }
        std::fs::write(path, &page.html).with_context(|| format!("writing {}", path.display()))?;
        println!(
            "{}: presorted in {build_ms:.0} ms (certificate {certificate}); {what} {} B: {} regions, {} orders, {} cycles, {} elements{}",
            args.model.display(),
            page.html.len(),
            page.regions,
            page.orders,
            page.cycles,
            page.elements,
            if sorter.one_order_for_every_view() {
                "; one order serves every view"
            } else {
                ""
            }
        );
    }
    Ok(ExitCode::SUCCESS)
}
