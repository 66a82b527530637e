//! Plotter edges: the edges drawn and their visible parts, checked against an independent
//! hidden-line computation that samples every edge densely and casts a ray from the viewer
//! through each sample against every drawn piece (raster-sink's `OverlayTruth`, judged at
//! 1 px).

use raster_sink::tolerance::{OVERLAY_JUDGE_PX, OVERLAY_STEP_PX};
use raster_sink::{OverlayTruth, Seen};
use sprite_compose::face_sort::glam::DVec3;
use sprite_compose::face_sort::{CullMode, Geometry, PolygonMesh, View};
use sprite_compose::{EdgeKind, Plot, PlotOptions, plot_edges};

/// Counts of the comparison of one plot with the truth.
#[derive(Debug, Default)]
struct Tally {
    visible: usize,
    hidden: usize,
    ambiguous: usize,
    wrong: Vec<String>,
}

impl Tally {
    fn add(&mut self, other: Tally) {
        self.visible += other.visible;
        self.hidden += other.hidden;
        self.ambiguous += other.ambiguous;
        self.wrong.extend(other.wrong);
    }

    /// Prints the totals and asserts that nothing judged was wrong.
    fn report(&self, name: &str) {
        println!(
            "{name}: {} samples visible, {} hidden, {} not judged, {} wrong",
            self.visible,
            self.hidden,
            self.ambiguous,
            self.wrong.len()
        );
        assert!(
            self.wrong.is_empty(),
            "{:#?}",
            &self.wrong[..self.wrong.len().min(20)]
        );
    }
}

fn check(mesh: &PolygonMesh, view: &View, name: &str) -> (Plot, Tally) {
    let geometry = Geometry::new(mesh).expect("geometry");
    let plot = plot_edges(mesh, &geometry, view, &PlotOptions::DEFAULT);
    let truth = OverlayTruth::new(view, &geometry);
    let centre = geometry.bounds().centre();
    let mut tally = Tally::default();
    for (k, edge) in plot.edges.iter().enumerate() {
        let [a, b] = edge.ends;
        let pa = view.project_view_point(view.to_view(a)).expect("in front");
        let pb = view.project_view_point(view.to_view(b)).expect("in front");
        let n = (pa.distance(pb) / OVERLAY_STEP_PX).ceil().max(1.0) as usize;
        for s in 0..n {
            let t = (s as f64 + 0.5) / n as f64;
            // Within a pixel of an end: where other edges meet, and where the plot drops
            // visible parts shorter than PLOT_MIN_LENGTH_PX (sub-pixel intersection lines of
            // faces that barely cross). Not judged.
            let along = pa.distance(pb) * t.min(1.0 - t);
            if along < OVERLAY_JUDGE_PX {
                tally.ambiguous += 1;
                continue;
            }
            let shown = edge.visible.iter().any(|&[t0, t1]| t0 <= t && t <= t1);
            match truth.seen(a.lerp(b, t) + centre) {
                Seen::Ambiguous => tally.ambiguous += 1,
                Seen::Visible if shown => tally.visible += 1,
                Seen::Hidden if !shown => tally.hidden += 1,
                v => tally.wrong.push(format!(
                    "{name}: edge {k} ({:?}) at t = {t:.4}: brute force {v:?}, plot {}",
                    edge.kind,
                    if shown { "visible" } else { "hidden" }
                )),
            }
        }
    }
    (plot, tally)
}

fn views(geometry: &Geometry) -> Vec<View> {
    let base = View::fit(&geometry.bounds(), 256, 256);
    let ld = base.diagonal() * base.scale();
    vec![
        base.with_yaw_pitch_roll(30.0, 20.0, 0.0),
        base.with_yaw_pitch_roll(200.0, -35.0, 10.0),
        base.with_yaw_pitch_roll(0.0, 80.0, 0.0),
        base.with_yaw_pitch_roll(120.0, 25.0, 0.0)
            .with_perspective(1.6 * ld),
        base.with_yaw_pitch_roll(-60.0, 50.0, 0.0)
            .with_perspective(0.9 * ld),
    ]
}

/// A hexahedron on a quad (counter-clockwise seen from `up`) and the same quad moved by
/// `up`: six planar faces, outward.
fn prism(quad: [DVec3; 4], up: DVec3, positions: &mut Vec<DVec3>, faces: &mut Vec<Vec<u32>>) {
    let b = positions.len() as u32;
    positions.extend(quad);
    positions.extend(quad.map(|p| p + up));
    faces.push(vec![b + 3, b + 2, b + 1, b]); // bottom, facing −up
    faces.push(vec![b + 4, b + 5, b + 6, b + 7]); // top
    for k in 0..4u32 {
        let j = (k + 1) % 4;
        faces.push(vec![b + k, b + j, b + 4 + j, b + 4 + k]);
    }
}

/// Three thick sticks each lying over the next and under the previous one (a cyclic
/// overlap no order of whole faces can paint), on a ground slab.
fn cyclic_sticks() -> PolygonMesh {
    let (mut positions, mut faces) = (Vec::new(), Vec::new());
    for i in 0..3 {
        let angle = std::f64::consts::TAU * f64::from(i) / 3.0;
        let dir = DVec3::new(angle.cos(), angle.sin(), 0.0);
        let side = DVec3::new(-dir.y, dir.x, 0.0) * 0.15;
        let start = -dir * 0.3 + DVec3::new(0.0, 0.0, -0.12);
        let end = dir * 1.0 + DVec3::new(0.0, 0.0, 0.12);
        prism(
            [start - side, end - side, end + side, start + side],
            DVec3::new(0.0, 0.0, 0.1),
            &mut positions,
            &mut faces,
        );
    }
    let g = 1.3;
    prism(
        [
            DVec3::new(-g, -g, -0.5),
            DVec3::new(g, -g, -0.5),
            DVec3::new(g, g, -0.5),
            DVec3::new(-g, g, -0.5),
        ],
        DVec3::new(0.0, 0.0, 0.1),
        &mut positions,
        &mut faces,
    );
    PolygonMesh::new(positions, faces).expect("sticks")
}

/// A box with a smaller box poking out of it through one side, a box fully inside, and a
/// box standing on top.
fn nested_boxes() -> PolygonMesh {
    let v = DVec3::new;
    test_support::models::boxes(&[
        (v(-1.0, -1.0, -1.0), v(1.0, 1.0, 1.0)),
        (v(0.2, -0.4, -0.4), v(1.6, 0.3, 0.5)),
        (v(-0.5, -0.5, -0.5), v(0.0, 0.0, 0.0)),
        (v(-0.8, 1.0, -0.6), v(-0.1, 1.5, 0.2)),
    ])
}

#[test]
fn cube_from_a_corner_has_six_silhouettes_and_three_creases() {
    let cube = test_support::models::boxes(&[(DVec3::splat(-1.0), DVec3::splat(1.0))]);
    let geometry = Geometry::new(&cube).unwrap();
    let view = View::fit(&geometry.bounds(), 200, 200).with_yaw_pitch_roll(35.0, 25.0, 0.0);
    let plot = plot_edges(&cube, &geometry, &view, &PlotOptions::DEFAULT);
    let count = |kind| plot.edges.iter().filter(|e| e.kind == kind).count();
    assert_eq!(count(EdgeKind::Silhouette), 6, "{:?}", plot.edges);
    assert_eq!(count(EdgeKind::Crease), 3, "{:?}", plot.edges);
    assert_eq!(plot.edges.len(), 9);
    assert!(plot.edges.iter().all(|e| e.visible == vec![[0.0, 1.0]]));
    // Nine edges meeting at the near corner and around the outline: one closed outline and
    // the three creases from the near corner, in few strokes.
    assert!(plot.polylines.len() <= 3, "{:?}", plot.polylines);
    assert!(plot.pen_down_px > 0.0);
    // Crease angle above 90°: the cube's creases are no longer drawn.
    let plot = plot_edges(
        &cube,
        &geometry,
        &view,
        &PlotOptions::DEFAULT.with_crease_deg(91.0),
    );
    assert_eq!(plot.edges.len(), 6);
}

#[test]
fn coincident_vertices_are_one_and_a_flat_face_cut_in_two_has_no_line_across() {
    // Two quads in one plane sharing an edge by position only (an OBJ uv seam duplicates
    // the vertices), and a third, folded up by 20° (under the crease angle).
    let v = DVec3::new;
    let positions = vec![
        v(0.0, 0.0, 0.0),
        v(1.0, 0.0, 0.0),
        v(1.0, 1.0, 0.0),
        v(0.0, 1.0, 0.0),
        v(1.0, 0.0, 0.0), // 4 = 1
        v(2.0, 0.0, 0.0),
        v(2.0, 1.0, 0.0),
        v(1.0, 1.0, 0.0), // 7 = 2
        v(
            2.0 + 20f64.to_radians().cos(),
            0.0,
            20f64.to_radians().sin(),
        ),
        v(
            2.0 + 20f64.to_radians().cos(),
            1.0,
            20f64.to_radians().sin(),
        ),
    ];
    let faces = vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7], vec![5, 8, 9, 6]];
    let mesh = PolygonMesh::new(positions, faces).unwrap();
    let geometry = Geometry::new(&mesh).unwrap();
    let view = View::fit(&geometry.bounds(), 200, 200)
        .with_yaw_pitch_roll(10.0, 30.0, 0.0)
        .with_cull(CullMode::None);
    let plot = plot_edges(&mesh, &geometry, &view, &PlotOptions::DEFAULT);
    assert_eq!(plot.edges.len(), 8, "{:?}", plot.edges);
    assert!(plot.edges.iter().all(|e| e.kind == EdgeKind::Boundary));
    // The outline is one closed stroke.
    assert_eq!(plot.polylines.len(), 1, "{:?}", plot.polylines);
    assert_eq!(plot.pen_up_px, 0.0);
}

#[test]
fn plot_matches_the_brute_force_on_boxy_scenes() {
    for (name, mesh) in [
        ("cyclic sticks", cyclic_sticks()),
        ("nested boxes", nested_boxes()),
    ] {
        let geometry = Geometry::new(&mesh).unwrap();
        let mut total = Tally::default();
        for (k, view) in views(&geometry).into_iter().enumerate() {
            for cull in [CullMode::Back, CullMode::None] {
                let (plot, tally) = check(
                    &mesh,
                    &view.with_cull(cull),
                    &format!("{name} view {k} {cull:?}"),
                );
                assert!(!plot.polylines.is_empty());
                total.add(tally);
            }
        }
        total.report(name);
        // The check must see both verdicts, and judge most samples (the rest lie within a
        // pixel of another piece's outline: thin sides, ends where faces meet).
        assert!(total.visible > 1_000 && total.hidden > 200, "{total:?}");
        assert!(total.ambiguous < total.visible + total.hidden, "{total:?}");
    }
}

#[test]
fn interpenetrating_boxes_draw_their_intersection_lines() {
    // The small box pokes through the big box's +x side: four intersection segments on the
    // plane x = 1, around y in [-0.4, 0.3], z in [-0.4, 0.5].
    let mesh = nested_boxes();
    let geometry = Geometry::new(&mesh).unwrap();
    let view = View::fit(&geometry.bounds(), 256, 256)
        .with_yaw_pitch_roll(30.0, 20.0, 0.0)
        .with_cull(CullMode::None);
    let plot = plot_edges(&mesh, &geometry, &view, &PlotOptions::DEFAULT);
    let centre = geometry.bounds().centre();
    let mut lengths: Vec<f64> = plot
        .edges
        .iter()
        .filter(|e| e.kind == EdgeKind::Intersection)
        .map(|e| {
            for end in e.ends {
                assert!(((end + centre).x - 1.0).abs() < 1e-12, "{e:?}");
            }
            e.ends[0].distance(e.ends[1])
        })
        .collect();
    lengths.sort_by(f64::total_cmp);
    let expected = [0.7, 0.7, 0.9, 0.9];
    assert_eq!(lengths.len(), 4, "{lengths:?}");
    for (l, e) in lengths.iter().zip(expected) {
        assert!((l - e).abs() < 1e-12, "{lengths:?}");
    }
}

#[test]
fn plot_matches_the_brute_force_on_suzanne() {
    let mesh = test_support::load_polygon_mesh("suzanne/suzanne.obj");
    let geometry = Geometry::new(&mesh).unwrap();
    let mut total = Tally::default();
    for (k, view) in views(&geometry).into_iter().enumerate().take(3) {
        let (_, tally) = check(&mesh, &view, &format!("suzanne view {k}"));
        total.add(tally);
    }
    total.report("suzanne");
    assert!(total.visible > 1_000 && total.hidden > 100, "{total:?}");
}

#[test]
fn svg_and_hpgl_hold_the_polylines() {
    let mesh = nested_boxes();
    let geometry = Geometry::new(&mesh).unwrap();
    let view = views(&geometry)[0];
    let plot = plot_edges(&mesh, &geometry, &view, &PlotOptions::DEFAULT);
    let svg = vector_sink::plot_svg(&plot, 1.0);
    assert_eq!(svg.matches("<path").count(), plot.polylines.len());
    assert!(!svg.contains("fill=\"black\"") && svg.contains("fill=\"none\""));
    let hpgl = vector_sink::plot_hpgl(&plot, 40.0);
    assert!(hpgl.starts_with("IN;SP1;") && hpgl.trim_end().ends_with("PU;SP0;"));
    assert_eq!(hpgl.matches("PD").count(), plot.polylines.len());
    // Every polyline vertex lies on the image (ends are on visible edges of a fitted view).
    let (w, h) = (256.0, 256.0);
    for p in plot.polylines.iter().flatten() {
        assert!(
            (-1.0..=w + 1.0).contains(&p.x) && (-1.0..=h + 1.0).contains(&p.y),
            "{p}"
        );
    }
}

#[test]
fn plot_matches_the_brute_force_on_spot_in_the_demo_view() {
    // Spot quadrangulated: many non-planar quads, whose fan triangles may cover their own
    // face's edges near the silhouette.
    let mesh = test_support::load_polygon_mesh("keenan-crane/spot/spot_quadrangulated.obj");
    let geometry = Geometry::new(&mesh).unwrap();
    let view = View::fit(&geometry.bounds(), 512, 512)
        .with_yaw_pitch_roll(145.0, -25.0, 0.0)
        .with_perspective(512.0);
    let (plot, tally) = check(&mesh, &view, "spot");
    println!(
        "spot: {} of {} edges visible",
        plot.edges.iter().filter(|e| !e.visible.is_empty()).count(),
        plot.edges.len()
    );
    tally.report("spot");
    assert!(tally.visible > 1_000 && tally.hidden > 100, "{tally:?}");
}
