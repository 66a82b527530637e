//! Truth and pixel error against a brute-force per-pixel loop; painter orders right and wrong.

use raster_sink::face_sort::glam::{DVec2, DVec3};
use raster_sink::face_sort::{
    Bsp, Centroid, CullMode, DrawList, FaceSorter, Geometry, ProjectionScratch, View,
};
use raster_sink::{IdImage, pixel_error, render_ids, truth};

use crate::common::{Rng, list_in_order, quads_mesh, spot_control, square, subdivided_cube};

/// Per pixel, every drawn piece: inside test, ray–plane depth, distance to every edge.
fn brute_force(view: &View, geometry: &Geometry) -> (Vec<u32>, Vec<bool>) {
    let (w, h) = (view.width(), view.height());
    let pieces = geometry.pieces();
    let cull = view.cull_test();
    let mut projected: Vec<(Vec<DVec2>, DVec3, f64, u32)> = Vec::new();
    let mut scratch = ProjectionScratch::default();
    for i in 0..pieces.len() {
        let corners = pieces.corners(i);
        if !cull.is_drawn(pieces.plane(i), corners[0]) {
            continue;
        }
        let mut pts = Vec::new();
        view.project_polygon(corners, &mut pts, &mut scratch);
        if pts.len() < 3 || raster_sink::face_sort::signed_area_2d(&pts).abs() < 1e-9 {
            continue;
        }
        let n = view.rotation() * pieces.plane(i).normal();
        projected.push((pts, n, pieces.plane(i).offset(), pieces.face(i)));
    }
    let mut ids = vec![0; (w * h) as usize];
    let mut unambiguous = vec![false; (w * h) as usize];
    let s = view.scale();
    for y in 0..h {
        for x in 0..w {
            let p = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
            // The ray in view space.
            let a = DVec3::new(
                (p.x - f64::from(w) / 2.0) / s,
                (f64::from(h) / 2.0 - p.y) / s,
                0.0,
            );
            let (origin, dir) = match view.eye_in_view() {
                None => (a, DVec3::NEG_Z),
                Some(e) => (e, a - e),
            };
            let mut depths: Vec<(f64, u32)> = Vec::new();
            let mut min_edge = f64::INFINITY;
            for (pts, n, offset, face) in &projected {
                let m = pts.len();
                let area = raster_sink::face_sort::signed_area_2d(pts).signum();
                let mut inside = true;
                for k in 0..m {
                    let (a, b) = (pts[k], pts[(k + 1) % m]);
                    if (b - a).perp_dot(p - a) * area < 0.0 {
                        inside = false;
                    }
                    let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    min_edge = min_edge.min((a + (b - a) * t).distance(p));
                }
                if inside {
                    let t = (offset - n.dot(origin)) / n.dot(dir);
                    depths.push(((origin + dir * t).z, face + 1));
                }
            }
            depths.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
            let k = (y * w + x) as usize;
            if let Some(&(z, id)) = depths.first() {
                ids[k] = id;
                let gap = depths.get(1).map_or(f64::INFINITY, |d| z - d.0);
                unambiguous[k] = min_edge >= 0.75 && gap > 1e-6 * view.diagonal();
            }
        }
    }
    (ids, unambiguous)
}

fn compare_with_brute_force(view: &View, geometry: &Geometry, min_unambiguous: usize) {
    let fast = truth(view, geometry);
    let (ids, unambiguous) = brute_force(view, geometry);
    let mut mask_diff = 0;
    for k in 0..ids.len() {
        if fast.unambiguous[k] != unambiguous[k] {
            mask_diff += 1;
        }
        if unambiguous[k] && fast.unambiguous[k] {
            assert_eq!(fast.ids[k], ids[k], "pixel {k}");
        }
    }
    assert_eq!(mask_diff, 0, "unambiguous masks differ");
    assert!(
        fast.unambiguous_count() >= min_unambiguous,
        "{}",
        fast.unambiguous_count()
    );
}

fn layered_scene(seed: u64, count: usize) -> Geometry {
    let mut rng = Rng::new(seed);
    let quads: Vec<[DVec3; 4]> = (0..count)
        .map(|i| {
            square(
                DVec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
                rng.range(0.3, 0.8),
                i as f64 * 0.1 + rng.range(0.0, 0.05),
            )
        })
        .collect();
    Geometry::new(&quads_mesh(&quads)).expect("geometry")
}

#[test]
fn truth_matches_brute_force_orthographic() {
    let geometry = layered_scene(1, 6);
    let view = View::fit(&geometry.bounds(), 48, 40).with_yaw_pitch_roll(20.0, -15.0, 5.0);
    compare_with_brute_force(&view, &geometry, 100);
    let cube = Geometry::new(&subdivided_cube(3)).expect("cube");
    let view = View::fit(&cube.bounds(), 40, 40).with_yaw_pitch_roll(35.0, 25.0, 0.0);
    compare_with_brute_force(&view, &cube, 100);
}

#[test]
fn truth_matches_brute_force_perspective() {
    let geometry = layered_scene(2, 6);
    let view = View::fit(&geometry.bounds(), 48, 40)
        .with_yaw_pitch_roll(-25.0, 10.0, 0.0)
        .with_perspective(60.0);
    compare_with_brute_force(&view, &geometry, 100);
    // Close enough that the near plane clips.
    let cube = Geometry::new(&subdivided_cube(2)).expect("cube");
    let view = View::fit(&cube.bounds(), 40, 40)
        .with_yaw_pitch_roll(30.0, 20.0, 0.0)
        .with_cull(raster_sink::face_sort::CullMode::None)
        .with_perspective(30.0);
    compare_with_brute_force(&view, &cube, 100);
}

#[test]
fn truth_matches_brute_force_on_spot() {
    // The control mesh (180 non-planar quads): big enough pieces for unambiguous pixels.
    let geometry = Geometry::new(&spot_control()).expect("spot");
    let view = View::fit(&geometry.bounds(), 80, 80).with_yaw_pitch_roll(40.0, 20.0, 0.0);
    compare_with_brute_force(&view, &geometry, 150);
    let view = view.with_perspective(90.0);
    compare_with_brute_force(&view, &geometry, 150);
}

/// Parallel layers facing the viewer: back to front is by plane offset along the normal.
fn layered_orders(geometry: &Geometry) -> (Vec<usize>, Vec<usize>) {
    let pieces = geometry.pieces();
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&a, &b| {
        pieces
            .plane(a)
            .offset()
            .total_cmp(&pieces.plane(b).offset())
    });
    let mut reversed = order.clone();
    reversed.reverse();
    (order, reversed)
}

#[test]
fn right_order_gives_zero_error_and_reversed_order_does_not() {
    let geometry = layered_scene(3, 8);
    for view in [
        View::fit(&geometry.bounds(), 96, 96).with_yaw_pitch_roll(15.0, -10.0, 0.0),
        View::fit(&geometry.bounds(), 96, 96)
            .with_yaw_pitch_roll(-20.0, 15.0, 10.0)
            .with_perspective(120.0),
    ] {
        let t = truth(&view, &geometry);
        let (order, reversed) = layered_orders(&geometry);
        let right = pixel_error(&render_ids(&view, &list_in_order(&geometry, &order)), &t);
        assert!(right.pixels > 1000);
        assert_eq!(right.wrong, 0, "{right:?}");
        assert_eq!(right.error, 0.0);
        let wrong = pixel_error(&render_ids(&view, &list_in_order(&geometry, &reversed)), &t);
        assert!(wrong.error > 0.05, "{wrong:?}");
        assert_eq!(wrong.pixels, right.pixels);
    }
}

#[test]
fn convex_mesh_any_order_is_exact_and_blank_image_is_all_wrong() {
    // A convex closed mesh with back faces culled never overlaps itself: any order is exact.
    let cube = Geometry::new(&subdivided_cube(4)).expect("cube");
    let view = View::fit(&cube.bounds(), 80, 80)
        .with_yaw_pitch_roll(30.0, 25.0, 0.0)
        .with_perspective(100.0);
    let t = truth(&view, &cube);
    let mut list = DrawList::new();
    Centroid::new(&cube).sort(&view, &mut list);
    let e = pixel_error(&render_ids(&view, &list), &t);
    assert!(e.pixels > 1000);
    assert_eq!(e.wrong, 0);
    let blank = pixel_error(&IdImage::blank(80, 80), &t);
    assert_eq!(blank.wrong, blank.pixels);
    assert_eq!(blank.error, 1.0);
}

#[test]
fn bsp_order_gives_zero_error_on_overlapping_scene() {
    // Exact sorters must reach 0 (face-sort's Bsp; until it lands it is the centroid order,
    // which is exact on this layered scene too).
    let geometry = layered_scene(4, 8);
    let view = View::fit(&geometry.bounds(), 96, 96).with_yaw_pitch_roll(10.0, 10.0, 0.0);
    let mut list = DrawList::new();
    Bsp::new(&geometry).sort(&view, &mut list);
    let e = pixel_error(&render_ids(&view, &list), &truth(&view, &geometry));
    assert!(e.pixels > 1000);
    assert_eq!(e.wrong, 0, "{e:?}");
}

#[test]
fn id_png_round_trips() {
    let geometry = layered_scene(5, 4);
    let view = View::fit(&geometry.bounds(), 32, 24);
    let (order, _) = layered_orders(&geometry);
    let mut image = render_ids(&view, &list_in_order(&geometry, &order));
    image.ids[0] = 0x12_34_56;
    let dir = std::env::temp_dir().join(format!("raster-sink-ids-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("ids.png");
    image.save_png(&path).expect("saved");
    let back = IdImage::load_png(&path).expect("loaded");
    assert_eq!(back, image);
    assert_eq!(&image.to_rgb_bytes()[..3], &[0x12, 0x34, 0x56]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bsp_order_gives_zero_error_on_spot() {
    let geometry = Geometry::new(&spot_control()).expect("spot");
    for view in [
        View::fit(&geometry.bounds(), 160, 160).with_yaw_pitch_roll(40.0, 20.0, 0.0),
        View::fit(&geometry.bounds(), 160, 160)
            .with_yaw_pitch_roll(200.0, -30.0, 0.0)
            .with_perspective(200.0),
    ] {
        let mut list = DrawList::new();
        Bsp::new(&geometry).sort(&view, &mut list);
        let e = pixel_error(&render_ids(&view, &list), &truth(&view, &geometry));
        assert!(e.pixels > 1000, "{e:?}");
        assert_eq!(e.wrong, 0, "{e:?}");
    }
}

/// Split pieces drawn whole ([`Bsp::with_fragment_merge`]): fewer items, every unambiguous
/// pixel still the truth's, on the quadrangulated spot (fans of triangles, whose shared edges
/// the merge recognises) and on suzanne (planar quads snapped apart), with and without
/// culling.
#[test]
fn merged_bsp_order_gives_zero_error() {
    for (mesh, cull) in [
        (
            test_support::load_polygon_mesh("keenan-crane/spot/spot_quadrangulated.obj"),
            CullMode::Back,
        ),
        (
            test_support::load_polygon_mesh("suzanne/suzanne.obj"),
            CullMode::None,
        ),
    ] {
        let geometry = Geometry::new(&mesh).expect("model");
        let mut plain = Bsp::new(&geometry);
        let mut merged = Bsp::new(&geometry).with_fragment_merge(true);
        for view in [
            View::fit(&geometry.bounds(), 640, 640).with_yaw_pitch_roll(40.0, 20.0, 0.0),
            View::fit(&geometry.bounds(), 640, 640)
                .with_yaw_pitch_roll(200.0, -30.0, 0.0)
                .with_perspective(800.0),
        ] {
            let view = view.with_cull(cull);
            let (mut a, mut b) = (DrawList::new(), DrawList::new());
            plain.sort(&view, &mut a);
            merged.sort(&view, &mut b);
            assert!(
                b.len() < a.len(),
                "{} items merged, {} not",
                b.len(),
                a.len()
            );
            let e = pixel_error(&render_ids(&view, &b), &truth(&view, &geometry));
            assert!(e.pixels > 1000, "{e:?}");
            assert_eq!(e.wrong, 0, "{e:?}");
        }
    }
}

/// A scene of instances (rotated, non-uniformly scaled, mirrored, interlocking) ordered by
/// `SceneSorter`: every unambiguous pixel shows the truth's face of the flattened scene,
/// orthographic and perspective, with and without culling.
#[test]
fn instanced_scenes_render_exactly() {
    use raster_sink::face_sort::{CullMode, FaceSorter, SceneSorter};
    let (meshes, instances) = test_support::models::instanced_scene(24, 7);
    let mut scene = SceneSorter::new(meshes, instances).unwrap();
    let geometry = Geometry::new(&scene.flattened()).unwrap();
    let base = View::fit(&scene.bounds(), 480, 480);
    let ld = base.diagonal() * base.scale();
    let mut judged = 0;
    for view in [
        base.with_yaw_pitch_roll(30.0, 35.0, 0.0),
        base.with_yaw_pitch_roll(95.0, 60.0, 0.0)
            .with_cull(CullMode::None),
        base.with_yaw_pitch_roll(140.0, 25.0, 0.0)
            .with_perspective(1.2 * ld),
        base.with_yaw_pitch_roll(-40.0, 15.0, 0.0)
            .with_perspective(0.6 * ld),
    ] {
        let mut list = DrawList::new();
        scene.sort(&view, &mut list);
        let truth = truth(&view, &geometry);
        let error = pixel_error(&render_ids(&view, &list), &truth);
        assert_eq!(error.wrong, 0, "{view:?}: {error:?}");
        judged += error.pixels;
    }
    println!("instanced scene: {judged} unambiguous pixels, 0 wrong");
    assert!(judged > 10_000, "{judged}");
}

/// A glTF scene through the scene path (`obj_quads::load_gltf_scene` → `SceneSorter`):
/// instancing, nested and non-uniform scales, a mirroring matrix node, a mirroring scale,
/// interlocking instances. Exact against the truth of the same file loaded flattened
/// (`load_gltf`), whose faces the scene's numbering must match, with back-face culling.
#[test]
fn gltf_scenes_render_exactly_through_the_scene_path() {
    use raster_sink::face_sort::{FaceSorter, Instance, SceneSorter, oracle};
    let json = test_support::gltf_scene::cube_scene_gltf();
    let options = obj_quads::LoadOptions::DEFAULT;
    let gltf = obj_quads::load_gltf_scene_slice(json.as_bytes(), &options).unwrap();
    assert_eq!(gltf.meshes.len(), 1, "one mesh, carried by every node");
    assert_eq!(gltf.instances.len(), 5);
    assert_eq!(
        gltf.instances
            .iter()
            .filter(|i| i.world.matrix3.determinant() < 0.0)
            .count(),
        2,
        "two mirrored instances"
    );
    let meshes = gltf.meshes.iter().map(test_support::polygon_mesh).collect();
    let instances = gltf
        .instances
        .iter()
        .map(|i| Instance::new(i.mesh, i.world))
        .collect();
    let mut scene = SceneSorter::new(meshes, instances).unwrap();
    let (flat, _) = obj_quads::load_gltf_slice(json.as_bytes(), &options).unwrap();
    let geometry = Geometry::new(&test_support::polygon_mesh(&flat)).unwrap();
    assert_eq!(geometry.bounds(), scene.bounds());
    let base = View::fit(&scene.bounds(), 320, 320);
    let ld = base.diagonal() * base.scale();
    let mut judged = 0;
    let mut clusters = 0;
    for view in [
        base.with_yaw_pitch_roll(30.0, 25.0, 0.0),
        base.with_yaw_pitch_roll(160.0, -30.0, 0.0),
        base.with_yaw_pitch_roll(250.0, 50.0, 15.0)
            .with_perspective(1.5 * ld),
    ] {
        let mut list = DrawList::new();
        scene.sort(&view, &mut list);
        clusters += scene.stats().clusters;
        assert_eq!(oracle::count_violations(&view, &list), 0, "{view:?}");
        let error = pixel_error(&render_ids(&view, &list), &truth(&view, &geometry));
        assert_eq!(error.wrong, 0, "{view:?}: {error:?}");
        judged += error.pixels;
    }
    assert!(
        clusters > 0,
        "the interlocking pair is ordered as a cluster"
    );
    assert!(judged > 10_000, "{judged}");
}

/// Translucent faces composited in the painter's order against the per-pixel compositing
/// reference (every pixel's fragments sorted by depth): exact with the scene's order of
/// interlocking instances, and with the flattened BSP; the centroid order gets pixels wrong.
#[test]
fn translucent_scenes_composite_exactly() {
    use raster_sink::face_sort::colours::golden_angle_colour;
    use raster_sink::face_sort::{Centroid, CullMode, FaceSorter, SceneSorter};
    use raster_sink::{Brush, RasterOptions, Style, composite_truth, render_colour};
    let (meshes, instances) = test_support::models::instanced_scene(12, 9);
    let mut scene = SceneSorter::new(meshes, instances).unwrap();
    let geometry = Geometry::new(&scene.flattened()).unwrap();
    let colour = |face: u32| {
        let [r, g, b, _] = golden_angle_colour(face);
        [r, g, b, 150]
    };
    let mut style = Style::solid([0, 0, 0, 0]);
    for face in 0..geometry.face_count() as u32 {
        style.set_face(face, Brush::Solid(colour(face)));
    }
    let background = [20, 30, 40, 255];
    let options = RasterOptions::DEFAULT
        .with_anti_alias(false)
        .with_background(background);
    let base = View::fit(&scene.bounds(), 320, 320).with_cull(CullMode::None);
    let ld = base.diagonal() * base.scale();
    let (mut judged, mut centroid_wrong) = (0, 0);
    for view in [
        base.with_yaw_pitch_roll(30.0, 35.0, 0.0),
        base.with_yaw_pitch_roll(140.0, 25.0, 0.0)
            .with_perspective(1.2 * ld),
    ] {
        let reference = composite_truth(&view, &geometry, colour, background).unwrap();
        let wrong = |list: &DrawList| {
            reference.wrong_pixels(&render_colour(&view, list, &style, &options).unwrap())
        };
        let mut list = DrawList::new();
        scene.sort(&view, &mut list);
        assert_eq!(wrong(&list), 0, "scene order, {view:?}");
        Centroid::new(&geometry).sort(&view, &mut list);
        centroid_wrong += wrong(&list);
        judged += reference.unambiguous.iter().filter(|&&u| u).count();
    }
    println!(
        "translucent scene: {judged} unambiguous pixels (background included): scene order 0 wrong, centroid {centroid_wrong}"
    );
    assert!(judged > 10_000, "{judged}");
    assert!(
        centroid_wrong > 0,
        "the scene must be hard for the centroid sort"
    );
}

/// Layers are rendering queues: a backdrop in the background layer is drawn first even
/// where it stands in front, a marker in the overlay layer last even where it stands
/// behind; a render step can take one layer and override its brush.
#[test]
fn layers_are_queues_and_steps_filter_them() {
    use raster_sink::face_sort::glam::DAffine3;
    use raster_sink::face_sort::{FaceSorter, Instance, Layer, SceneSorter};
    use raster_sink::{Override, RasterOptions, Step, Style, run_steps};
    let cube = test_support::models::boxes(&[(DVec3::splat(-0.5), DVec3::splat(0.5))]);
    let at = |x: f64, z: f64, s: f64| {
        DAffine3::from_scale_rotation_translation(
            DVec3::splat(s),
            raster_sink::face_sort::glam::DQuat::IDENTITY,
            DVec3::new(x, 0.0, z),
        )
    };
    // Seen from +z: the main cube at the back, a big "backdrop" cube in front of it (in the
    // background layer), a small "marker" cube behind the main one (in the overlay layer).
    let instances = vec![
        Instance::new(0, at(0.0, 0.0, 1.0)),
        Instance::new(0, at(0.0, 2.0, 3.0)).with_layer(Layer::Background),
        Instance::new(0, at(0.0, -2.0, 0.6)).with_layer(Layer::Overlay),
    ];
    let mut scene = SceneSorter::new(vec![cube], instances).unwrap();
    let view = View::fit(&scene.bounds(), 120, 120);
    let mut list = DrawList::new();
    scene.sort(&view, &mut list);
    let layers: Vec<Layer> = list
        .items()
        .iter()
        .map(|item| scene.instances()[scene.instance_of_face(item.face).unwrap()].layer)
        .collect();
    let mut sorted = layers.clone();
    sorted.sort();
    assert_eq!(layers, sorted, "background, then main, then overlay");
    assert!(layers.contains(&Layer::Background) && layers.contains(&Layer::Overlay));
    // A step drawing only the overlay layer, in one colour, over a cleared canvas.
    let overlay_only = |item: face_sort::DrawItem| {
        scene
            .instance_of_face(item.face)
            .is_some_and(|i| scene.instances()[i].layer == Layer::Overlay)
    };
    let steps = [
        Step::Clear([0, 0, 0, 255]),
        Step::Draw {
            filter: Some(&overlay_only),
            brush: Override::Solid([255, 0, 0, 255]),
        },
        Step::Resolve,
    ];
    let image = run_steps(
        &view,
        &list,
        &Style::palette(),
        &RasterOptions::DEFAULT.with_anti_alias(false),
        &steps,
    )
    .unwrap();
    let red = image
        .pixels()
        .iter()
        .filter(|p| p.red() == 255 && p.green() == 0)
        .count();
    let drawn = image
        .pixels()
        .iter()
        .filter(|p| p.red() > 0 || p.green() > 0 || p.blue() > 0)
        .count();
    // The marker is small: some pixels, all of them red.
    assert!(red > 50 && red == drawn, "{red} red of {drawn}");
    // In ID images: the overlay marker shows although the main cube stands in front of it;
    // the backdrop shows only where the main cube does not cover it.
    let marker_pixels = |list: &DrawList| {
        render_ids(&view, list)
            .ids
            .iter()
            .filter(|&&id| id > 12)
            .count()
    };
    assert!(marker_pixels(&list) > 50);
    let mut all_main = SceneSorter::new(
        vec![test_support::models::boxes(&[(
            DVec3::splat(-0.5),
            DVec3::splat(0.5),
        )])],
        scene
            .instances()
            .iter()
            .map(|i| Instance::new(i.mesh, i.transform))
            .collect(),
    )
    .unwrap();
    all_main.sort(&view, &mut list);
    assert_eq!(
        marker_pixels(&list),
        0,
        "in the main layer the marker is hidden"
    );
}

/// A cloud of translucent billboards (camera-facing quads) around an opaque suzanne that
/// pokes through it: every billboard faces the viewer in every view, and the picture
/// composites exactly against the per-pixel reference.
#[test]
fn billboard_clouds_face_the_viewer_and_composite_exactly() {
    use raster_sink::face_sort::glam::DAffine3;
    use raster_sink::face_sort::{CullMode, FaceSorter, Instance, PolygonMesh, SceneSorter};
    use raster_sink::{Brush, RasterOptions, Style, composite_truth, render_colour};
    let quad = PolygonMesh::new(
        vec![
            DVec3::new(-0.5, -0.5, 0.0),
            DVec3::new(0.5, -0.5, 0.0),
            DVec3::new(0.5, 0.5, 0.0),
            DVec3::new(-0.5, 0.5, 0.0),
        ],
        [[0u32, 1, 2, 3]],
    )
    .unwrap();
    let suzanne = test_support::load_polygon_mesh("suzanne/suzanne.obj");
    let mut rng = test_support::Rng::new(21);
    let mut instances: Vec<Instance> = (0..40)
        .map(|_| {
            let at = DVec3::new(
                rng.range(-2.0, 2.0),
                rng.range(-1.0, 1.0),
                rng.range(-2.0, 2.0),
            );
            Instance::new(
                0,
                DAffine3::from_scale_rotation_translation(
                    DVec3::splat(rng.range(1.0, 2.0)),
                    raster_sink::face_sort::glam::DQuat::IDENTITY,
                    at,
                ),
            )
            .as_billboard()
        })
        .collect();
    instances.push(Instance::new(1, DAffine3::IDENTITY));
    let mut scene = SceneSorter::new(vec![quad, suzanne], instances).unwrap();
    let colour = |face: u32| {
        if face < 40 {
            [230, 235, 250, 70]
        } else {
            let [r, g, b, _] = raster_sink::face_sort::colours::golden_angle_colour(face);
            [r, g, b, 255]
        }
    };
    let faces = 40 + 500;
    let mut style = Style::solid([0, 0, 0, 0]);
    for face in 0..faces {
        style.set_face(face, Brush::Solid(colour(face)));
    }
    let background = [30, 40, 60, 255];
    let options = RasterOptions::DEFAULT
        .with_anti_alias(false)
        .with_background(background);
    let base = View::fit(&scene.bounds(), 240, 240).with_cull(CullMode::Back);
    let ld = base.diagonal() * base.scale();
    let mut judged = 0;
    for view in [
        base.with_yaw_pitch_roll(20.0, 15.0, 0.0),
        base.with_yaw_pitch_roll(130.0, -40.0, 10.0)
            .with_perspective(1.5 * ld),
    ] {
        let mut list = DrawList::new();
        scene.sort(&view, &mut list);
        let billboards: std::collections::BTreeSet<u32> = list
            .items()
            .iter()
            .map(|i| i.face)
            .filter(|&f| f < 40)
            .collect();
        assert_eq!(billboards.len(), 40, "every billboard faces the viewer");
        assert_eq!(
            raster_sink::face_sort::oracle::count_violations(&view, &list),
            0
        );
        let geometry = Geometry::new_in_frame(&scene.flattened(), scene.bounds()).unwrap();
        let reference = composite_truth(&view, &geometry, colour, background).unwrap();
        let image = render_colour(&view, &list, &style, &options).unwrap();
        let wrong = reference.wrong_pixels(&image);
        assert_eq!(wrong, 0, "{view:?}");
        judged += reference.unambiguous.iter().filter(|&&u| u).count();
    }
    assert!(judged > 20_000, "{judged}");
}

/// The truth for lines judges drawings of lines among faces: the exact visible parts pass,
/// lines drawn whole (their hidden parts too) fail.
#[test]
fn the_truth_for_lines_tells_a_right_drawing_from_a_wrong_one() {
    use raster_sink::OverlayTruth;
    use raster_sink::sprite_compose::{DrawnOverlay, Line, Overlay, Stroke, visible_overlay};
    let mesh = test_support::models::boxes(&[
        (DVec3::splat(-1.0), DVec3::splat(1.0)),
        (DVec3::new(1.5, -0.5, -0.5), DVec3::new(2.5, 0.5, 0.5)),
    ]);
    let geometry = Geometry::new(&mesh).unwrap();
    let line = |a: DVec3, b: DVec3| Line {
        ends: [a, b],
        colour: [255, 0, 0, 255],
        width_px: 1.0,
        faces: Vec::new(),
    };
    let overlay = Overlay {
        lines: vec![
            line(DVec3::new(-3.0, 0.2, 0.1), DVec3::new(4.0, 0.2, 0.1)),
            line(DVec3::new(0.3, -3.0, -0.2), DVec3::new(0.3, 3.0, -0.2)),
        ],
        points: Vec::new(),
    };
    let view = View::fit(&geometry.bounds(), 200, 200)
        .with_yaw_pitch_roll(30.0, 20.0, 0.0)
        .with_perspective(300.0);
    let truth = OverlayTruth::new(&view, &geometry);
    let right = truth.compare(&overlay, &visible_overlay(&geometry, &view, &overlay));
    assert_eq!(right.wrong, 0, "{:?}", right.examples);
    assert!(right.judged > 300 && right.hidden > 100, "{right:?}");
    // Every line drawn whole: its hidden parts are wrong.
    let centre = geometry.bounds().centre();
    let whole = DrawnOverlay {
        strokes: overlay
            .lines
            .iter()
            .enumerate()
            .map(|(n, l)| Stroke {
                ends: l
                    .ends
                    .map(|p| view.project_view_point(view.to_view(p - centre)).unwrap()),
                colour: l.colour,
                width_px: l.width_px,
                line: n,
            })
            .collect(),
        dots: Vec::new(),
    };
    let wrong = truth.compare(&overlay, &whole);
    assert_eq!(wrong.wrong, right.hidden, "{wrong:?}");
}
