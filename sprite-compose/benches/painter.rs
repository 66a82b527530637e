//! Per-frame SpritePainter update on spot (2,928 quads) under a slow and a fast yaw spin,
//! beside a naive "clear and re-add every sprite" backend update. Both drive a null backend
//! that only counts operations, so the time is the painter's (sort included).
//!
//! `cargo bench -p sprite-compose --bench painter -- --warm-up-time 0.5 --measurement-time 1 --sample-size 10`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use sprite_compose::face_sort::{DrawList, FaceSorter, Geometry, SorterKind, View};
use sprite_compose::glam::{DMat4, DVec2};
use sprite_compose::{
    Brush, Compositor, OpCounts, PieceMaps, SpriteId, SpritePainter, SpriteTransform,
    rotation_from_yaw_pitch_roll,
};

/// Counts operations, does nothing else.
#[derive(Default)]
struct Null(OpCounts);

impl Compositor for Null {
    fn create_sprite(&mut self, _: SpriteId, _: u32) {
        self.0.create += 1;
    }
    fn destroy_sprite(&mut self, _: SpriteId) {
        self.0.destroy += 1;
    }
    fn set_transform(&mut self, _: SpriteId, t: &SpriteTransform) {
        black_box(t);
        self.0.transform += 1;
    }
    fn set_clip(&mut self, _: SpriteId, c: Option<&[DVec2]>) {
        black_box(c);
        self.0.clip += 1;
    }
    fn set_brush(&mut self, _: SpriteId, _: &Brush) {
        self.0.brush += 1;
    }
    fn set_visible(&mut self, _: SpriteId, _: bool) {
        self.0.visible += 1;
    }
    fn set_back_visible(&mut self, _: SpriteId, _: bool) {
        self.0.back += 1;
    }
    fn move_to_top(&mut self, _: SpriteId) {
        self.0.reorder += 1;
    }
    fn move_before(&mut self, _: SpriteId, _: SpriteId) {
        self.0.reorder += 1;
    }
    fn set_root_transform(&mut self, r: &DMat4) {
        black_box(r);
        self.0.root += 1;
    }
}

fn spot() -> Geometry {
    let mesh = test_support::load_polygon_mesh("keenan-crane/spot/spot_quadrangulated.obj");
    Geometry::new(&mesh).expect("geometry")
}

/// The naive update: sort, then destroy every sprite and re-add the drawn ones in order.
struct Naive {
    sorter: Box<dyn FaceSorter>,
    list: DrawList,
    maps: PieceMaps,
    live: Vec<SpriteId>,
}

impl Naive {
    fn frame(&mut self, view: &View, out: &mut Null) {
        self.sorter.sort(view, &mut self.list);
        for id in self.live.drain(..) {
            out.destroy_sprite(id);
        }
        out.set_root_transform(&sprite_compose::root_transform(view));
        for (k, item) in self.list.items().iter().enumerate() {
            let Some(map) = self.maps.get(item.polygon as usize) else {
                continue;
            };
            let id = SpriteId(k as u32);
            out.create_sprite(id, item.face);
            out.set_transform(id, &map.transform);
            if let Some(clip) = &map.clip {
                out.set_clip(id, Some(clip));
            }
            out.set_brush(id, &Brush::Palette);
            out.set_visible(id, true);
            self.live.push(id);
        }
    }
}

const FRAMES: u32 = 720;

fn bench(c: &mut Criterion) {
    let g = spot();
    let base = View::fit(&g.bounds(), 512, 512).with_cull_margin(1.0);
    let view_at = |k: u32, step: f64| {
        base.with_rotation(rotation_from_yaw_pitch_roll(f64::from(k) * step, 20.0, 0.0))
    };
    let mut group = c.benchmark_group("painter/spot_quadrangulated");
    for (name, step) in [("slow 0.25deg", 0.25), ("fast 5deg", 5.0)] {
        for kind in [SorterKind::Centroid, SorterKind::Bsp] {
            // Operations per frame over FRAMES frames (printed for the README).
            let mut p = SpritePainter::new(&g, kind.build(&g), base, Null::default());
            p.frame();
            p.compositor_mut().0 = OpCounts::default();
            let mut drawn = 0;
            for k in 1..=FRAMES {
                p.set_view(view_at(k, step));
                drawn += p.frame().drawn;
            }
            let ops = p.compositor().0;
            let mut naive = Naive {
                sorter: kind.build(&g),
                list: DrawList::new(),
                maps: PieceMaps::new(&g, &base),
                live: Vec::new(),
            };
            let mut naive_ops = Null::default();
            for k in 1..=FRAMES {
                naive.frame(&view_at(k, step), &mut naive_ops);
            }
            let per = |n: usize| n as f64 / f64::from(FRAMES);
            eprintln!(
                "{name} {}: drawn {:.0}/frame; diff ops/frame {:.1} (visible {:.1}, reorder {:.1}, root {:.1}); naive ops/frame {:.0}",
                kind.name(),
                per(drawn),
                per(ops.total()),
                per(ops.visible),
                per(ops.reorder),
                per(ops.root),
                per(naive_ops.0.total())
            );
            let mut k = 0;
            group.bench_function(format!("diff {name} {}", kind.name()), |b| {
                b.iter(|| {
                    k += 1;
                    p.set_view(view_at(k, step));
                    black_box(p.frame())
                })
            });
            let mut k = 0;
            let mut sink = Null::default();
            group.bench_function(format!("naive {name} {}", kind.name()), |b| {
                b.iter(|| {
                    k += 1;
                    naive.frame(&view_at(k, step), &mut sink);
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
