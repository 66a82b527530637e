//! `cargo xtask render --scene`: the generated demo scene of many instances, through
//! `face_sort::SceneSorter`: interlocking objects, translucent ones, a cloud of translucent
//! billboards, a backdrop in the background layer and a marker in the overlay layer.

use face_sort::sorter_api::DrawListWriter;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result};
use face_sort::colours::golden_angle_colour;
use face_sort::glam::{DAffine3, DQuat, DVec3};
use face_sort::{DrawList, FaceSorter, Geometry, Instance, Layer, SceneSorter, oracle};
use serde::Serialize;

use super::args::{BaseView, RenderArgs, base_view};

/// Instances of the generated scene (before the backdrop and the marker).
const INSTANCES: usize = 30;
/// Billboards in the cloud.
const CLOUD: usize = 24;
/// Opacity of every third instance.
const TRANSLUCENT_ALPHA: u8 = 110;

/// What `render --scene --json` prints.
#[derive(Debug, Serialize)]
struct SceneSummary {
    output: String,
    instances: usize,
    faces: usize,
    drawn: usize,
    clusters: usize,
    objects_culled: usize,
    build_ms: f64,
    sort_ms: f64,
    raster_ms: f64,
    /// With --check: the oracle's order violations.
    #[serde(skip_serializing_if = "Option::is_none")]
    violations: Option<usize>,
    /// With --check: unambiguous pixels of an unshaded, aliased render off the per-pixel
    /// compositing reference (`raster_sink::composite_truth`) by more than 2/255.
    #[serde(skip_serializing_if = "Option::is_none")]
    composite_wrong: Option<usize>,
}

/// The scene: `instanced_scene`'s objects, a slab under them in the background layer, a
/// small marker cube at the scene's middle in the overlay layer; and the colour of each
/// instance (every third translucent).
fn demo_scene() -> (Vec<face_sort::PolygonMesh>, Vec<Instance>, Vec<[u8; 4]>) {
    let (mut meshes, mut instances) = test_support::models::instanced_scene(INSTANCES, 4);
    let mut colours: Vec<[u8; 4]> = (0..instances.len())
        .map(|k| {
            let [r, g, b, _] = golden_angle_colour(k as u32 * 7 + 3);
            [r, g, b, if k % 3 == 2 { TRANSLUCENT_ALPHA } else { 255 }]
        })
        .collect();
    let side = (INSTANCES as f64).sqrt().ceil() * 2.2;
    let slab = DAffine3::from_scale_rotation_translation(
        DVec3::new(side + 2.0, 0.2, side + 2.0),
        DQuat::IDENTITY,
        DVec3::new(side / 2.0 - 1.1, -1.6, side / 2.0 - 1.1),
    );
    instances.push(Instance::new(0, slab).with_layer(Layer::Background));
    colours.push([90, 96, 110, 255]);
    let marker = DAffine3::from_scale_rotation_translation(
        DVec3::splat(0.5),
        DQuat::from_rotation_y(0.6),
        DVec3::new(side / 2.0 - 1.1, 0.2, side / 2.0 - 1.1),
    );
    instances.push(Instance::new(0, marker).with_layer(Layer::Overlay));
    colours.push([255, 230, 0, 255]);
    // A cloud: translucent camera-facing quads over one corner of the scene.
    let quad = meshes.len();
    meshes.push(
        face_sort::PolygonMesh::new(
            vec![
                DVec3::new(-0.5, -0.5, 0.0),
                DVec3::new(0.5, -0.5, 0.0),
                DVec3::new(0.5, 0.5, 0.0),
                DVec3::new(-0.5, 0.5, 0.0),
            ],
            [[0u32, 1, 2, 3]],
        )
        .expect("a quad"),
    );
    let mut rng = test_support::Rng::new(8);
    for _ in 0..CLOUD {
        let at = DVec3::new(
            rng.range(0.0, 4.0),
            rng.range(0.8, 2.2),
            rng.range(0.0, 4.0),
        );
        let size = rng.range(1.2, 2.2);
        let placement =
            DAffine3::from_scale_rotation_translation(DVec3::splat(size), DQuat::IDENTITY, at);
        instances.push(Instance::new(quad, placement).as_billboard());
        colours.push([245, 248, 255, 55]);
    }
    (meshes, instances, colours)
}

/// Renders the demo scene (see the module docs).
pub fn run(args: &RenderArgs) -> Result<ExitCode> {
    let start = Instant::now();
    let (meshes, instances, colours) = demo_scene();
    let count = instances.len();
    // The colour of instance k is material k (an override of the meshes' own materials).
    let instances: Vec<Instance> = instances
        .into_iter()
        .enumerate()
        .map(|(k, i)| i.with_material(k as u32))
        .collect();
    let mut scene = SceneSorter::new(meshes, instances)?;
    let build_ms = ms(start);
    // For the view's fit and face count only: billboards are turned to the view by the sort.
    let flat = scene.flattened();
    let geometry = Geometry::new_in_frame(&flat, scene.bounds())?;
    let view = base_view(
        &geometry,
        &BaseView {
            camera: None,
            size: args.size,
            yaw: args.yaw.unwrap_or(25.0),
            pitch: args.pitch.unwrap_or(35.0),
            roll: args.roll,
            cull: args.cull,
            cw: args.cw,
            margin: args.margin,
            scale: args.scale,
            persp: if args.ortho {
                None
            } else {
                Some(args.persp.unwrap_or(f64::from(args.size.0)))
            },
        },
    )?;
    // Each scene face in its instance's material (its colour).
    let colour_of = |face: u32| {
        scene
            .material_of_face(face)
            .map_or([255, 0, 255, 255], |m| colours[m as usize])
    };
    let mut style = raster_sink::Style::solid([255, 0, 255, 255]);
    let face_colours: Vec<[u8; 4]> = (0..flat.face_count() as u32).map(colour_of).collect();
    for (face, colour) in face_colours.iter().enumerate() {
        style.set_face(face as u32, raster_sink::Brush::Solid(*colour));
    }
    let mut list = DrawList::new();
    let start = Instant::now();
    scene.sort(&view, &mut list);
    let sort_ms = ms(start);
    let stats = scene.stats();
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| crate::target_dir().join("scene.png"));
    if let Some(parent) = output.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    let background = [225, 232, 240, 255];
    let start = Instant::now();
    let image = raster_sink::render_colour(
        &view,
        &list,
        &style,
        &raster_sink::RasterOptions::DEFAULT
            .with_anti_alias(!args.no_aa)
            .with_background(background)
            .with_shading(Some(raster_sink::Light::DEFAULT)),
    )
    .map_err(|e| anyhow::anyhow!("raster: {e}"))?;
    raster_sink::save_png(&image, &output)
        .map_err(|e| anyhow::anyhow!("{}: {e}", output.display()))?;
    let raster_ms = ms(start);
    let (violations, composite_wrong) = if args.check {
        // Layers are queues: the oracle judges the main layer's order (the backdrop and the
        // marker are drawn first and last on purpose).
        let main: Vec<face_sort::DrawItem> = list
            .items()
            .iter()
            .copied()
            .filter(|item| {
                scene
                    .instance_of_face(item.face)
                    .is_some_and(|i| scene.instances()[i].layer == Layer::Main)
            })
            .collect();
        let mut main_list = list.clone();
        *main_list.items_mut() = main;
        let violations = oracle::count_violations(&view, &main_list);
        let reference = raster_sink::composite_truth(
            &view,
            // The flattened scene as this frame placed it (billboards turned to the view).
            &Geometry::new_in_frame(&main_only(&scene, &scene.flattened()), scene.bounds())?,
            |face| face_colours[face as usize],
            background,
        )?;
        let flat_image = raster_sink::render_colour(
            &view,
            &main_list,
            &style,
            &raster_sink::RasterOptions::DEFAULT
                .with_anti_alias(false)
                .with_background(background),
        )
        .map_err(|e| anyhow::anyhow!("raster: {e}"))?;
        let wrong = reference.wrong_pixels(&flat_image);
        (Some(violations), Some(wrong))
    } else {
        (None, None)
    };
    let summary = SceneSummary {
        output: output.display().to_string(),
        instances: count,
        faces: flat.face_count(),
        drawn: list.len(),
        clusters: stats.clusters,
        objects_culled: stats.objects_culled,
        build_ms,
        sort_ms,
        raster_ms,
        violations,
        composite_wrong,
    };
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    } else {
        let mut line = format!(
            "scene: {} instances ({} interlocking clusters, {} culled), {} faces, {} drawn; build {:.1} ms, sort {:.2} ms, raster {:.1} ms",
            summary.instances,
            summary.clusters,
            summary.objects_culled,
            summary.faces,
            summary.drawn,
            build_ms,
            sort_ms,
            raster_ms
        );
        if let (Some(v), Some(w)) = (violations, composite_wrong) {
            line.push_str(&format!(
                "; {v} order violations, {w} pixels off the compositing reference"
            ));
        }
        println!("{line} -> {}", summary.output);
    }
    Ok(ExitCode::SUCCESS)
}

/// The flattened scene with only the main layer's faces kept (the others made degenerate,
/// so that face numbers stay).
fn main_only(scene: &SceneSorter, flat: &face_sort::PolygonMesh) -> face_sort::PolygonMesh {
    let faces: Vec<Vec<u32>> = flat
        .faces()
        .enumerate()
        .map(|(face, corners)| {
            let main = scene
                .instance_of_face(face as u32)
                .is_some_and(|i| scene.instances()[i].layer == Layer::Main);
            if main {
                corners.to_vec()
            } else {
                vec![corners[0]; 3]
            }
        })
        .collect();
    face_sort::PolygonMesh::new(flat.positions().to_vec(), faces)
        .expect("the flattened scene's faces are valid")
}

fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}
