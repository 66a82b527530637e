//! `render`'s sorter: the planner's choice or the one asked for, a glTF file's scene of
//! instances, or `Presorted` with what it did.

use anyhow::Result;
use face_sort::{FaceSorter, Geometry, Plan, PlanHint, PolygonMesh, SorterKind};

use super::args::SorterChoice;
use super::report::PresortSummary;
use crate::scenes;

/// The scene path for a glTF file: its meshes and nodes as a `SceneSorter`, when the file
/// is glTF with at least two mesh nodes and the scene's faces and frame of reference are
/// those of the flattened load (`geometry`); else `None` (the flattened path).
pub(super) fn gltf_scene(
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
pub(super) fn plan(
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
