//! Baked realisation: containers per cell, brushes-only material swaps, one-step swap, convex
//! facing predicates.

use sprite_compose::aspect_bake::{Axis, BakeOptions, BspSource, Spin, bake};
use sprite_compose::face_sort::{Geometry, View};
use sprite_compose::{
    AngleRange, Bake, BakedSpriteTree, BakedTreeSlot, Brush, convex_facing_predicates,
    rotation_from_yaw_pitch_roll,
};

use crate::support;

/// The exact BSP bake of a model under a yaw spin at pitch 20°.
fn exact_bake(geometry: Geometry) -> (Geometry, View, Bake) {
    let base = View::fit(&geometry.bounds(), 256, 256);
    let spin = Spin::new(
        base,
        Axis::Yaw {
            pitch: 20.0,
            roll: 0.0,
        },
    )
    .expect("a named axis");
    let bake = bake(&BspSource::of(&geometry), &spin, &BakeOptions::DEFAULT).expect("a bake");
    (geometry, base, bake)
}

fn spot_bake() -> (Geometry, View, Bake) {
    exact_bake(support::geometry(&support::load_obj(
        "keenan-crane/spot/spot_control_mesh.obj",
    )))
}

fn cube_bake() -> (Geometry, View, Bake) {
    exact_bake(support::geometry(&support::boxes(&[(
        glam::DVec3::ZERO,
        glam::DVec3::ONE,
    )])))
}

#[test]
fn one_container_per_cell_with_wrapping_predicates() {
    let (g, view, bake) = spot_bake();
    let graph = BakedSpriteTree::realise(&bake, &g, &view);
    let n = bake.cells().len();
    assert!(n > 2);
    assert_eq!(graph.containers().len(), n);
    let mut angles = vec![0.0, 29.9, 30.0, 359.0, 365.0, -1.0, 719.0];
    // Every cell boundary and a point inside every cell.
    for cell in bake.cells() {
        angles.extend([cell.range.lo, cell.range.lerp(0.5)]);
    }
    for angle in angles {
        let shown: Vec<usize> = (0..n)
            .filter(|&k| graph.containers()[k].visible_while.contains(angle))
            .collect();
        assert_eq!(shown.len(), 1, "exactly one container at {angle}");
        assert_eq!(graph.container_at(angle), Some(shown[0]));
        assert_eq!(bake.cell_at(angle), Some(shown[0]));
    }
    let wrap = AngleRange {
        lo: 350.0,
        hi: 370.0,
        period: Some(360.0),
    };
    assert!(wrap.contains(355.0) && wrap.contains(5.0) && !wrap.contains(15.0));
    assert_eq!(
        wrap.to_expression("a"),
        "((a % 360 + 360) % 360 >= 350 || (a % 360 + 360) % 360 < 10)"
    );
    // Every baked sprite has a transform; the first container shows the first cell's order.
    let c = &graph.containers()[0];
    assert_eq!(c.sprites.len(), bake.cells()[0].order.len());
    assert!(
        c.sprites
            .iter()
            .all(|s| graph.polygon_map(s.polygon).is_some())
    );
}

#[test]
fn materials_swap_brushes_only_and_bakes_swap_in_one_step() {
    let (g, view, bake) = spot_bake();
    let mut graph = BakedSpriteTree::realise(&bake, &g, &view);
    let before: Vec<_> = graph.containers().to_vec();
    let told = graph.set_brushes(|f| {
        if f == 3 {
            Brush::Solid([1, 2, 3, 255])
        } else {
            Brush::Palette
        }
    });
    let expected = before
        .iter()
        .flat_map(|c| &c.sprites)
        .filter(|s| s.face == 3)
        .count();
    assert_eq!(told, expected);
    assert_eq!(graph.containers(), &before[..], "containers reused");
    assert_eq!(graph.brush(3), Brush::Solid([1, 2, 3, 255]));
    let slot = BakedTreeSlot::new(graph);
    let reader = slot.clone();
    let spot_cells = bake.cells().len();
    let (g2, view2, bake2) = cube_bake();
    let worker = std::thread::spawn(move || BakedSpriteTree::realise(&bake2, &g2, &view2));
    assert_eq!(
        reader.load().containers().len(),
        spot_cells,
        "old bake shown while the new one builds"
    );
    slot.store(worker.join().expect("bake thread"));
    // A cube at pitch 20° turns a side face edge-on every quarter turn.
    assert_eq!(reader.load().containers().len(), 4);
}

#[test]
fn convex_facing_predicates_match_culling() {
    let g = support::geometry(&test_support::models::uv_sphere(10, 6));
    for view in [
        View::fit(&g.bounds(), 256, 256).with_yaw_pitch_roll(0.0, 25.0, 0.0),
        View::fit(&g.bounds(), 256, 256)
            .with_yaw_pitch_roll(0.0, -10.0, 0.0)
            .with_perspective(300.0),
    ] {
        let predicates = convex_facing_predicates(&g, &view);
        let pieces = g.pieces();
        for yaw in [0.0, 17.0, 123.0, 271.0] {
            let turned =
                view.with_rotation(rotation_from_yaw_pitch_roll(yaw, 0.0, 0.0) * view.rotation());
            for (i, p) in predicates.iter().enumerate() {
                assert_eq!(
                    p.is_drawn(yaw),
                    turned.is_drawn(pieces.plane(i), pieces.corners(i)[0]),
                    "piece {i} at {yaw}"
                );
            }
        }
        assert!(predicates[0].to_expression("a").contains("cos(a *"));
    }
}
