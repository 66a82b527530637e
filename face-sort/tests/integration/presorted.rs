//! `Presorted`: certified orders at views the build never saw, its fallbacks, its budgets.

use crate::common::{asset, read_obj};
use face_sort::glam::{DQuat, DVec3};
use face_sort::{
    CertifiedOrdersError, CullMode, DrawList, FaceSorter, FallbackReason, Geometry, PresortError,
    PresortLoadError, PresortOptions, Presorted, View, oracle,
};

/// Views at seeded random rotations (any yaw, pitch and roll), orthographic and perspective
/// with the eye from 1.6 to 4 bounding radii away.
fn random_views(geometry: &Geometry, count: usize, seed: u64) -> Vec<View> {
    let mut rng = face_sort::generate::Rng::new(seed);
    let base = View::fit(&geometry.bounds(), 384, 384);
    let radius = 0.5 * geometry.bounds().diagonal();
    (0..count)
        .flat_map(|_| {
            let axis = rng.direction();
            let angle = rng.range(0.0, std::f64::consts::TAU);
            let view = base.with_quaternion(DQuat::from_axis_angle(axis, angle));
            // The eye distance in pixels is the distance in model units times the scale.
            let distance = rng.range(1.6, 4.0) * radius * view.scale();
            [view, view.with_perspective(distance)]
        })
        .collect()
}

#[test]
fn certified_orders_leave_no_violation_at_random_views() {
    for model in [
        "keenan-crane/spot/spot_control_mesh.obj",
        "fandisk-quads/fandisk_quads.converted.obj",
        "opensubdiv-torus/catmark_torus_creases0.obj",
        "suzanne/suzanne.obj",
    ] {
        let geometry = Geometry::with_exact_corners(&read_obj(&asset(model))).unwrap();
        let mut sorter = Presorted::try_new(&geometry, &PresortOptions::default()).unwrap();
        assert!(sorter.orders() > 0, "{model}");
        let mut list = DrawList::new();
        let views = random_views(&geometry, 24, 7);
        for view in &views {
            sorter.sort(view, &mut list);
            assert!(!sorter.last_frame_fell_back(), "{model}: {view:?}");
            let found = oracle::find_violations(view, &list, 3);
            assert!(found.is_empty(), "{model} at {view:?}: {found:?}");
        }
        assert_eq!(sorter.fallback_frames(), 0, "{model}");
    }
}

#[test]
fn uncovered_views_fall_back_to_the_bsp_and_stay_exact() {
    let geometry =
        Geometry::with_exact_corners(&read_obj(&asset("keenan-crane/spot/spot_control_mesh.obj")))
            .unwrap();
    let mut sorter = Presorted::new(&geometry);
    let base = View::fit(&geometry.bounds(), 256, 256).with_yaw_pitch_roll(40.0, 25.0, 0.0);
    let radius = 0.5 * geometry.bounds().diagonal();
    // An eye 1.2 radii from the centre (the default certifies from 1.5), back faces kept, and
    // a cull margin: none is what the certificate assumes.
    let uncovered = [
        base.with_perspective(1.2 * radius * base.scale()),
        base.with_cull(CullMode::None),
        base.with_cull_margin(2.0),
    ];
    let reasons = [
        FallbackReason::EyeTooNear,
        FallbackReason::CullMode,
        FallbackReason::CullMode,
    ];
    let mut list = DrawList::new();
    for (k, view) in uncovered.iter().enumerate() {
        sorter.sort(view, &mut list);
        assert_eq!(sorter.last_fallback(), Some(reasons[k]), "view {k}");
        assert_eq!(sorter.stats().fallback, Some(reasons[k]), "view {k}");
        assert!(sorter.last_frame_fell_back(), "view {k}");
        assert_eq!(oracle::count_violations(view, &list), 0, "view {k}");
        assert_eq!(sorter.fallback_frames(), k + 1);
    }
    sorter.sort(&base, &mut list);
    assert!(!sorter.last_frame_fell_back());
    assert_eq!(sorter.last_fallback(), None);
    assert_eq!(sorter.stats().fallback_frames, 3);
    assert!(sorter.refusal().is_none());
}

/// A saved certificate loads and orders every view exactly as the built one: the same draw
/// list, item for item, with no violation, orthographic and perspective.
#[test]
fn a_saved_certificate_orders_exactly_as_the_built_one() {
    for model in [
        "keenan-crane/spot/spot_control_mesh.obj",
        "suzanne/suzanne.obj",
    ] {
        let geometry = Geometry::with_exact_corners(&read_obj(&asset(model))).unwrap();
        let mut built = Presorted::try_new(&geometry, &PresortOptions::default()).unwrap();
        let bytes = built.to_bytes();
        let mut loaded = Presorted::from_bytes(&bytes, &geometry).unwrap();
        assert_eq!(loaded.regions(), built.regions(), "{model}");
        assert_eq!(loaded.orders(), built.orders(), "{model}");
        assert_eq!(loaded.cores(), built.cores(), "{model}");
        assert_eq!(
            loaded.to_bytes(),
            bytes,
            "{model}: saving again changes nothing"
        );
        let (mut a, mut b) = (DrawList::new(), DrawList::new());
        for view in &random_views(&geometry, 12, 11) {
            built.sort(view, &mut a);
            loaded.sort(view, &mut b);
            assert_eq!(a.items(), b.items(), "{model} at {view:?}");
            assert!(!loaded.last_frame_fell_back(), "{model}");
            assert_eq!(oracle::count_violations(view, &b), 0, "{model} at {view:?}");
        }
    }
}

/// Bytes that are not this geometry's certificate give a typed error and never a panic: no
/// header, another version, another geometry, every cut-short prefix, and single bytes
/// changed (each either refused or loaded and sorting without a panic).
#[test]
fn hostile_certificate_bytes_give_errors_not_panics() {
    let geometry = Geometry::with_exact_corners(&read_obj(&asset("suzanne/suzanne.obj"))).unwrap();
    let other =
        Geometry::with_exact_corners(&read_obj(&asset("keenan-crane/spot/spot_control_mesh.obj")))
            .unwrap();
    let bytes = Presorted::try_new(&geometry, &PresortOptions::default())
        .unwrap()
        .to_bytes();
    assert_eq!(
        Presorted::from_bytes(b"not a certificate", &geometry).err(),
        Some(PresortLoadError::NotACertificate)
    );
    let mut newer = bytes.clone();
    newer[8] = 99;
    assert!(matches!(
        Presorted::from_bytes(&newer, &geometry),
        Err(PresortLoadError::Version { found: 99 })
    ));
    assert_eq!(
        Presorted::from_bytes(&bytes, &other).err(),
        Some(PresortLoadError::OtherGeometry)
    );
    for cut in (0..bytes.len()).step_by((bytes.len() / 300).max(1)) {
        assert!(
            Presorted::from_bytes(&bytes[..cut], &geometry).is_err(),
            "a prefix of {cut} bytes loaded"
        );
    }
    let mut long = bytes.clone();
    long.push(0);
    assert_eq!(
        Presorted::from_bytes(&long, &geometry).err(),
        Some(PresortLoadError::Trailing(1))
    );
    let view = View::fit(&geometry.bounds(), 64, 64).with_yaw_pitch_roll(30.0, 20.0, 0.0);
    let mut list = DrawList::new();
    let mut rng = face_sort::generate::Rng::new(5);
    let mut refused = 0;
    for _ in 0..300 {
        let mut changed = bytes.clone();
        let at = (rng.range(0.0, 1.0) * changed.len() as f64) as usize % changed.len();
        changed[at] ^= 1 << ((rng.range(0.0, 8.0) as u32) % 8);
        match Presorted::from_bytes(&changed, &geometry) {
            Ok(mut sorter) => sorter.sort(&view, &mut list),
            Err(_) => refused += 1,
        }
    }
    assert!(refused > 0, "no changed byte was refused");
}

#[test]
fn options_out_of_range_and_budgets_give_typed_errors() {
    let geometry = Geometry::with_exact_corners(&read_obj(&asset("suzanne/suzanne.obj"))).unwrap();
    for bad in [1.0, 0.5, f64::NAN, f64::INFINITY] {
        let options = PresortOptions {
            min_eye_distance: bad,
            ..PresortOptions::default()
        };
        assert!(matches!(
            Presorted::try_new(&geometry, &options),
            Err(PresortError::EyeDistance(_))
        ));
    }
    let tight = PresortOptions {
        max_pairs: 1000,
        ..PresortOptions::default()
    };
    assert_eq!(
        Presorted::try_new(&geometry, &tight).unwrap_err(),
        PresortError::PairBudget { limit: 1000 }
    );
}

#[test]
fn the_build_is_the_same_on_any_number_of_threads() {
    let geometry =
        Geometry::with_exact_corners(&read_obj(&asset("keenan-crane/spot/spot_control_mesh.obj")))
            .unwrap();
    let build = |threads| {
        Presorted::try_new(
            &geometry,
            &PresortOptions {
                threads,
                ..PresortOptions::default()
            },
        )
        .unwrap()
    };
    let (mut one, mut three) = (build(1), build(3));
    assert_eq!(one.regions(), three.regions());
    assert_eq!(one.orders(), three.orders());
    let (mut a, mut b) = (DrawList::new(), DrawList::new());
    for view in random_views(&geometry, 8, 11) {
        one.sort(&view, &mut a);
        three.sort(&view, &mut b);
        assert_eq!(a.items(), b.items());
    }
}

#[test]
fn one_order_serves_every_view_where_no_pair_can_cycle() {
    // A convex body: no piece can ever hide another it faces with. A closed curved model:
    // regions needed.
    for (model, single) in [
        ("combobulate-samples/octahedron.obj", true),
        ("assimp-obj/box.obj", true),
        ("keenan-crane/spot/spot_control_mesh.obj", false),
    ] {
        let geometry = Geometry::with_exact_corners(&read_obj(&asset(model))).unwrap();
        let mut sorter = Presorted::new(&geometry);
        assert_eq!(sorter.one_order_for_every_view(), single, "{model}");
        if single {
            assert_eq!(sorter.orders(), 1);
            let mut list = DrawList::new();
            // Any view, the eye even near the model: still the one order, exact.
            for view in random_views(&geometry, 6, 3) {
                let near =
                    view.with_perspective(1.1 * 0.5 * geometry.bounds().diagonal() * view.scale());
                for view in [view, near] {
                    sorter.sort(&view, &mut list);
                    assert!(!sorter.last_frame_fell_back(), "{model}");
                    assert_eq!(oracle::count_violations(&view, &list), 0, "{model}");
                }
            }
        }
    }
}

/// The certificate as data (what a page that turns with the pointer carries), played as its
/// script plays it, leaves no violation: at random views of the kind it was made for, and a
/// millionth of a radian either side of region edges. Cycles are flattened for every side of
/// their planes; where too many planes vary over a region, the region is quartered.
#[test]
fn certified_orders_played_as_a_page_leave_no_violation() {
    for model in [
        "keenan-crane/spot/spot_control_mesh.obj",
        "suzanne/suzanne.obj",
        "combobulate-samples/book.obj",
    ] {
        let geometry = Geometry::with_exact_corners(&read_obj(&asset(model))).unwrap();
        let sorter = Presorted::new(&geometry);
        let radius = 0.5 * geometry.bounds().diagonal();
        let base = View::fit(&geometry.bounds(), 384, 384);
        let mut rng = face_sort::generate::Rng::new(11);
        for eye in [None, Some(2.0 * radius), Some(3.5 * radius)] {
            let orders = sorter.certified_orders(eye).unwrap();
            assert!(!orders.regions.is_empty(), "{model}");
            let view_of = |u: DVec3| {
                // A rotation taking u to +z (the direction toward the viewer), any roll.
                let view = base.with_quaternion(DQuat::from_rotation_arc(u.normalize(), DVec3::Z));
                match eye {
                    None => view,
                    Some(t) => view.with_perspective(t * view.scale()),
                }
            };
            let mut directions: Vec<DVec3> = (0..16).map(|_| rng.direction()).collect();
            for r in orders.regions.iter().step_by(5) {
                let [a, b, _] = r.corners;
                let (m, n) = ((a + b).normalize(), r.edge_normals[0].normalize());
                directions.extend([m + n * 1e-6, m - n * 1e-6]);
            }
            let mut list = DrawList::new();
            for u in directions {
                let view = view_of(u);
                orders.play(&view, &mut list);
                assert!(!list.is_empty(), "{model}: nothing drawn at {u}");
                let found = oracle::find_violations(&view, &list, 3);
                assert!(found.is_empty(), "{model}, eye {eye:?}, at {u}: {found:?}");
            }
        }
    }
}

#[test]
fn certified_orders_refuse_eyes_nearer_than_the_certificate() {
    let geometry =
        Geometry::with_exact_corners(&read_obj(&asset("keenan-crane/spot/spot_control_mesh.obj")))
            .unwrap();
    let sorter = Presorted::new(&geometry);
    let radius = 0.5 * geometry.bounds().diagonal();
    assert!(matches!(
        sorter.certified_orders(Some(1.2 * radius)),
        Err(CertifiedOrdersError::TooNear { .. })
    ));
    assert!(matches!(
        sorter.certified_orders(Some(f64::NAN)),
        Err(CertifiedOrdersError::TooNear { .. })
    ));
    // boxes: regions of near eyes are left uncertified.
    let boxes = Geometry::with_exact_corners(&read_obj(&asset("compas/boxes.obj"))).unwrap();
    let boxes_sorter = Presorted::new(&boxes);
    let near = 0.5 * boxes.bounds().diagonal() * 2.0;
    assert!(matches!(
        boxes_sorter.certified_orders(Some(near)),
        Err(CertifiedOrdersError::Uncertified { regions }) if regions > 0
    ));
}

/// `Presorted::with_options` never falls back silently: a build refused by its pair budget
/// keeps the error (`refusal`), and every frame says it was drawn by the BSP because of it
/// (`last_fallback`, `stats().fallback`, `fallback_frames`), exactly.
#[test]
fn a_refused_build_is_reported_on_every_frame() {
    let geometry =
        Geometry::with_exact_corners(&read_obj(&asset("keenan-crane/spot/spot_control_mesh.obj")))
            .unwrap();
    let options = PresortOptions {
        max_pairs: 10,
        ..PresortOptions::default()
    };
    let mut sorter = Presorted::with_options(&geometry, &options);
    assert!(
        matches!(
            sorter.refusal(),
            Some(PresortError::PairBudget { limit: 10, .. })
        ),
        "{:?}",
        sorter.refusal()
    );
    let view = View::fit(&geometry.bounds(), 256, 256).with_yaw_pitch_roll(40.0, 25.0, 0.0);
    let mut list = DrawList::new();
    for frame in 1..=3 {
        sorter.sort(&view, &mut list);
        assert_eq!(sorter.last_fallback(), Some(FallbackReason::Refused));
        assert_eq!(sorter.stats().fallback, Some(FallbackReason::Refused));
        assert_eq!(sorter.fallback_frames(), frame);
        assert_eq!(oracle::count_violations(&view, &list), 0);
    }
}

/// Builds the certificate of `face_sort::generate::scan_blob(segments, rings)` within the
/// default budgets and checks `views` random views (eyes from 1.6 radii, outside
/// `min_eye_distance`): none falls back, none leaves an order violation.
fn scan_is_certified_and_exact(segments: usize, rings: usize, views: usize) {
    let mesh = face_sort::generate::scan_blob(segments, rings);
    let geometry = face_sort::SorterKind::Presorted
        .geometry_for(&mesh)
        .unwrap();
    let mut sorter = Presorted::try_new(&geometry, &PresortOptions::default()).unwrap();
    eprintln!(
        "scan_blob({segments}, {rings}): {} triangles, {} pieces, {} regions, {} orders, {:?} cores, {} uncertified regions, built in {:.0} ms",
        mesh.face_count(),
        geometry.pieces().len(),
        sorter.regions(),
        sorter.orders(),
        sorter.cores(),
        sorter.uncertified_regions(),
        sorter.stats().build_ms
    );
    let mut list = DrawList::new();
    for view in &random_views(&geometry, views, 23) {
        sorter.sort(view, &mut list);
        assert!(!sorter.last_frame_fell_back(), "{view:?}");
        let found = oracle::find_violations(view, &list, 3);
        assert!(found.is_empty(), "at {view:?}: {found:?}");
    }
    assert_eq!(sorter.fallback_frames(), 0);
}

#[test]
fn a_scan_like_blob_is_certified_and_exact_at_random_views() {
    scan_is_certified_and_exact(48, 24, 6);
}

/// The scan-like blob at a laser scan's size (69,168 triangles): seconds of build in a
/// release build, far longer in a debug one, so it runs on request:
/// `cargo test --release -p face-sort --test integration -- --ignored scan --nocapture`.
#[test]
#[ignore = "a release build's minute: cargo test --release -p face-sort --test integration -- --ignored scan"]
fn a_seventy_thousand_face_scan_is_certified_and_exact_at_random_views() {
    scan_is_certified_and_exact(264, 132, 12);
}

/// A build tells its progress: every region it orders from all its pieces once, counted up to
/// the total it announced, and a last call with all done.
#[test]
fn a_build_tells_its_progress() {
    let geometry =
        Geometry::with_exact_corners(&read_obj(&asset("keenan-crane/spot/spot_control_mesh.obj")))
            .unwrap();
    let calls = std::sync::Mutex::new(Vec::new());
    let record = |p: face_sort::PresortProgress| calls.lock().unwrap().push(p);
    let sorter =
        Presorted::try_new_with_progress(&geometry, &PresortOptions::default(), &record).unwrap();
    let calls = calls.into_inner().unwrap();
    let total = calls[0].total;
    // The octants' quarters, each ordered once, then the last call.
    assert_eq!(total, 32);
    assert_eq!(calls.len(), total + 1);
    assert!(calls.iter().all(|p| p.total == total && p.done <= total));
    let mut done: Vec<usize> = calls[..total].iter().map(|p| p.done).collect();
    done.sort_unstable();
    assert_eq!(done, (1..=total).collect::<Vec<_>>());
    assert_eq!(calls[total].done, total);
    assert!(sorter.orders() > 0);
}
