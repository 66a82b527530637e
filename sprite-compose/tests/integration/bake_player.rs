//! A picture bake played on a retained compositor: sprites made once with their backs
//! hidden; at any angle the sprites the compositor shows, in stack order, are an exact order
//! of the pieces the view draws (the oracle), and entering a cell switches only the sprites
//! whose visibility changes.

use face_sort::sorter_api::DrawListWriter;
use sprite_compose::aspect_bake::{Axis, PictureOptions, Spin, bake_picture, drawn_lists};
use sprite_compose::face_sort::{DrawList, Geometry, View, oracle};
use sprite_compose::{BakePlayer, Brush, RecordingCompositor};

use crate::support;

#[test]
fn a_played_bake_shows_an_exact_order_and_switches_only_what_changes() {
    let mesh = support::load_obj("keenan-crane/spot/spot_control_mesh.obj");
    let g = Geometry::with_exact_corners(&mesh).unwrap();
    for persp in [None, Some(512.0)] {
        let mut view = View::fit(&g.bounds(), 256, 256);
        if let Some(d) = persp {
            view = view.with_perspective(d);
        }
        let axis = Axis::Yaw {
            pitch: 20.0,
            roll: 0.0,
        };
        let spin = Spin::new(view, axis).unwrap();
        let (baked, _) = bake_picture(&g, &spin, &PictureOptions::DEFAULT).unwrap();
        assert!(baked.cells().len() > 1, "the turn needs several cells");
        let lists = drawn_lists(&baked, &spin).unwrap();
        let polygons = std::sync::Arc::clone(baked.polygons());
        let cells = baked.cells().to_vec();
        let mut player = BakePlayer::new(
            baked,
            &lists,
            spin,
            &g,
            |_| Brush::Palette,
            RecordingCompositor::new(),
        );
        let made = player.compositor_mut().take_frame();
        assert_eq!(made.create, player.sprite_count());
        assert_eq!(made.back, player.sprite_count());
        let mut switches = 0;
        // Each cell at a few angles, in turn order.
        let mut previous: Option<Vec<bool>> = None;
        for (c, cell) in cells.iter().enumerate() {
            for f in [0.1, 0.5, 0.9] {
                let degrees = cell.range.lerp(f);
                let before: Vec<bool> = (0..player.sprite_count() as u32)
                    .map(|e| {
                        player
                            .compositor()
                            .scene()
                            .sprite(sprite_compose::SpriteId(e))
                            .is_some_and(|s| s.visible)
                    })
                    .collect();
                assert_eq!(player.play(degrees), Some(c));
                let ops = player.compositor_mut().take_frame();
                let scene = player.compositor().scene();
                let after: Vec<bool> = (0..player.sprite_count() as u32)
                    .map(|e| {
                        scene
                            .sprite(sprite_compose::SpriteId(e))
                            .is_some_and(|s| s.visible)
                    })
                    .collect();
                // What the compositor shows is an exact order of what the view draws.
                let view = spin.view_at(degrees);
                let mut list = DrawList::new();
                list.begin(&polygons);
                for (id, s) in scene.visible() {
                    list.push(player.polygon_of(id).unwrap(), s.face);
                }
                let test = view.cull_test();
                let drawn = (0..polygons.len())
                    .filter(|&p| test.is_drawn(polygons.plane(p), polygons.corners(p)[0]))
                    .count();
                assert_eq!(
                    list.len(),
                    drawn,
                    "cell {c} at {degrees}°: drawn pieces shown once"
                );
                assert_eq!(
                    oracle::count_violations(&view, &list),
                    0,
                    "cell {c} at {degrees}°"
                );
                if let Some(prev) = &previous {
                    // Within a cell nothing switches.
                    if f > 0.1 {
                        assert_eq!(prev, &after);
                    }
                }
                // Only the root moves, and only the sprites whose visibility changes switch
                // (all of them on the first frame).
                let changed = before.iter().zip(&after).filter(|(a, b)| a != b).count();
                assert_eq!((ops.create, ops.root), (0, 1));
                if c > 0 || f > 0.1 {
                    assert_eq!(ops.visible, changed, "cell {c} at {degrees}°");
                }
                switches += ops.visible;
                previous = Some(after);
            }
        }
        println!(
            "{persp:?}: {} sprites for {} pieces, {} cells, {switches} visibility switches \
             (first frame included)",
            player.sprite_count(),
            polygons.len(),
            cells.len()
        );
    }
}
