//! The stress cases: transformed copies of the repository's models and generated scenes, per
//! group of the list (position, scale, coplanar, degenerate, views, generated).

use super::*;

/// Positions of `mesh` mapped by `f` (computed in f64, then stored: the rounding a file at
/// that position or scale would carry).
pub(super) fn mapped(
    mesh: &PolygonMesh,
    f: impl Fn(DVec3) -> DVec3,
) -> Result<PolygonMesh, String> {
    let positions: Vec<DVec3> = mesh.positions().iter().map(|&p| f(p)).collect();
    PolygonMesh::new(positions, mesh.faces()).map_err(|e| format!("MeshError: {e}"))
}

/// A polygon mesh from loose polygons (every polygon its own vertices).
pub(super) fn soup(polygons: &[Vec<DVec3>]) -> Result<PolygonMesh, String> {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for poly in polygons {
        let start = positions.len() as u32;
        positions.extend_from_slice(poly);
        faces.push((start..start + poly.len() as u32).collect::<Vec<u32>>());
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// A rectangle centred at `centre` spanned by the half axes `u`, `v` (counter-clockwise
/// seen from `u × v`).
pub(super) fn rect(centre: DVec3, u: DVec3, v: DVec3) -> Vec<DVec3> {
    vec![
        centre - u - v,
        centre + u - v,
        centre + u + v,
        centre - u + v,
    ]
}

/// A generic rotation (no axis alignment), so that planes are not exact in f64.
pub(super) fn tilt() -> DMat3 {
    DMat3::from_euler(EulerRot::YXZ, 0.61, 0.37, 0.23)
}

/// The repository models the position and scale cases transform, with their cull mode.
pub(super) fn base_models() -> Result<Vec<(String, PolygonMesh, CullMode)>> {
    let mut out = Vec::new();
    for (name, path) in [
        ("suzanne", "assets/models/suzanne/suzanne.obj"),
        ("cornell-box", "assets/models/cornell-box/cornell_box.obj"),
        (
            "spot-control",
            "assets/models/keenan-crane/spot/spot_control_mesh.obj",
        ),
    ] {
        let scene = scenes::model_scene(name, path)?;
        out.push((name.to_owned(), scene.mesh, scene.cull));
    }
    // spot's quadrangulated mesh: most of its quads are not planar (fans of triangles).
    let spot = scenes::model_scene(
        "spot",
        "assets/models/keenan-crane/spot/spot_quadrangulated.obj",
    )?;
    out.push(("spot".to_owned(), spot.mesh, spot.cull));
    // fandisk: a CAD model, flat regions split into many coplanar quads.
    let fandisk = scenes::model_scene(
        "fandisk",
        "assets/models/fandisk-quads/fandisk_quads.converted.obj",
    )?;
    out.push(("fandisk".to_owned(), fandisk.mesh, fandisk.cull));
    // Meshes in convex position, where the planner orders by culling alone.
    let cube = scenes::model_scene("box", "assets/models/assimp-obj/box.obj")?;
    out.push(("box".to_owned(), cube.mesh, CullMode::Back));
    out.push((
        "uv-sphere-512".to_owned(),
        face_sort::generate::uv_sphere(32, 16),
        CullMode::Back,
    ));
    out.push((
        "uv-sphere-8k".to_owned(),
        face_sort::generate::uv_sphere(128, 64),
        CullMode::Back,
    ));
    let quads = scenes::random_quads(40, 11)?;
    out.push(("random-quads-40".to_owned(), quads.mesh, CullMode::None));
    out.push((
        "bumpy-torus-1k".to_owned(),
        face_sort::generate::torus(1_000),
        CullMode::Back,
    ));
    Ok(out)
}

/// Position and scale: every base model translated and scaled.
pub(super) fn transform_cases(
    models: &[(String, PolygonMesh, CullMode)],
    quick: bool,
) -> Vec<Case> {
    let mut out = Vec::new();
    let translations: &[f64] = if quick {
        &[1e7]
    } else {
        &[1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9]
    };
    // 1e±100 are outside what face-sort accepts: the typed error is the expected outcome.
    let scales: &[f64] = if quick {
        &[1e-6, 1e6, 1e100]
    } else {
        &[1e-6, 1e-4, 1e-2, 1e2, 1e4, 1e6, 1e-50, 1e50, 1e-100, 1e100]
    };
    let direction = DVec3::new(1.0, -0.6, 0.35);
    for (name, mesh, cull) in models {
        let shots = if quick {
            vec![Shot::ortho(30.0, 20.0, 0.0, *cull)]
        } else {
            general_shots(*cull)
        };
        for &t in translations {
            out.push(Case {
                group: "position",
                name: format!("{name} moved {t:e}"),
                mesh: mapped(mesh, |p| p + direction * t),
                shots: shots.clone(),
                judged: true,
                expect_error: false,
            });
        }
        for &s in scales {
            out.push(Case {
                group: "scale",
                name: format!("{name} scaled {s:e}"),
                mesh: mapped(mesh, |p| p * s),
                shots: shots.clone(),
                judged: true,
                // Outside face-sort's range (1e-60 to 1e60): refused.
                expect_error: !(1e-60..=1e60).contains(&s),
            });
        }
        if !quick {
            // Small and far: the stored positions keep about 1e-7 (1e6) and 1e-6 (1e7) of
            // the model's size.
            for t in [1e6, 1e7] {
                out.push(Case {
                    group: "position",
                    name: format!("{name} scaled 1e-3 moved {t:e}"),
                    mesh: mapped(mesh, |p| p * 1e-3 + direction * t),
                    shots: shots.clone(),
                    judged: true,
                    expect_error: false,
                });
            }
        }
    }
    out
}

/// Three overlapping parallel squares `gap · L` apart (tilted), seen from general views.
pub(super) fn separated(gap_rel: f64) -> Result<PolygonMesh, String> {
    let r = tilt();
    let (u, v, n) = (r * DVec3::X, r * DVec3::Y, r * DVec3::Z);
    // L of three unit squares shifted by 0.4: about 2.6; the gap is relative to it.
    let gap = gap_rel * 2.6;
    let polygons: Vec<Vec<DVec3>> = (0..3)
        .map(|k| {
            let k = f64::from(k);
            rect(u * (0.4 * k) + v * (0.25 * k) + n * (gap * k), u, v)
        })
        .collect();
    soup(&polygons)
}

/// Exactly coplanar overlapping polygons (axis-aligned, so exact in f64; and tilted,
/// coplanar up to round-off), some with opposite winding.
pub(super) fn coplanar(tilted: bool) -> Result<PolygonMesh, String> {
    let r = if tilted { tilt() } else { DMat3::IDENTITY };
    let (u, v) = (r * DVec3::X, r * DVec3::Y);
    let mut polygons = Vec::new();
    let mut rng = Rng::new(5);
    for k in 0..12 {
        let c = u * rng.range(-1.0, 1.0) + v * rng.range(-1.0, 1.0);
        let mut p = rect(c, u * rng.range(0.2, 0.9), v * rng.range(0.2, 0.9));
        if k % 3 == 0 {
            p.reverse();
        }
        polygons.push(p);
    }
    // A crossing quad, so the coplanar set is not alone in the scene.
    let n = r * DVec3::Z;
    polygons.push(rect(DVec3::ZERO, u * 1.2, n * 0.8));
    soup(&polygons)
}

/// Every face of `mesh` twice: as is, and reversed (opposite winding, same place).
pub(super) fn doubled(mesh: &PolygonMesh) -> Result<PolygonMesh, String> {
    let mut faces: Vec<Vec<u32>> = mesh.faces().map(<[u32]>::to_vec).collect();
    let reversed: Vec<Vec<u32>> = faces
        .iter()
        .map(|f| f.iter().rev().copied().collect())
        .collect();
    faces.extend(reversed);
    PolygonMesh::new(mesh.positions().to_vec(), &faces).map_err(|e| format!("MeshError: {e}"))
}

/// Slivers of aspect ratio `aspect` crossing each other over a background square.
pub(super) fn slivers(aspect: f64) -> Result<PolygonMesh, String> {
    let mut rng = Rng::new(17);
    let mut polygons = vec![rect(
        DVec3::new(0.0, 0.0, -0.6),
        DVec3::X * 1.2,
        DVec3::Y * 1.2,
    )];
    for _ in 0..24 {
        let along = rng.direction() * 0.5;
        let side = along.any_orthonormal_vector() * (1.0 / aspect);
        let centre = DVec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        polygons.push(rect(centre, along, side));
    }
    soup(&polygons)
}

/// Random quads plus near-degenerate faces: triangles whose apex is `1e-10 · D` off the base
/// line, and quads with two corners `1e-12 · D` apart.
pub(super) fn near_degenerate() -> Result<PolygonMesh, String> {
    let mut rng = Rng::new(23);
    let mut polygons = Vec::new();
    for _ in 0..30 {
        let a = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let d = rng.direction() * 0.8;
        let off = d.any_orthonormal_vector();
        if rng.unit() < 0.5 {
            polygons.push(vec![a, a + d, a + d * 0.5 + off * (0.8e-10)]);
        } else {
            let b = a + d;
            polygons.push(vec![a, b, b + off * 1e-12, a + off * 0.6]);
        }
        polygons.push(rect(a, d * 0.5, off * 0.4));
    }
    soup(&polygons)
}

/// A sheet of quads with exactly degenerate faces mixed in: collinear corners, a repeated
/// index, all corners at one point.
pub(super) fn degenerate() -> Result<PolygonMesh, String> {
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let r = tilt();
    for k in 0..6 {
        let z = f64::from(k) * 0.15;
        let start = positions.len() as u32;
        for p in rect(DVec3::new(0.1 * f64::from(k), 0.0, z), DVec3::X, DVec3::Y) {
            positions.push(r * p);
        }
        faces.push((start..start + 4).collect());
        // Collinear: three points on one edge.
        let e = positions.len() as u32;
        let (a, b) = (positions[start as usize], positions[start as usize + 1]);
        positions.extend([a, (a + b) * 0.5, b]);
        faces.push(vec![e, e + 1, e + 2]);
        // A repeated index.
        faces.push(vec![start, start + 1, start + 1]);
        // One point.
        faces.push(vec![start + 2, start + 2, start + 2, start + 2]);
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// A NaN and an infinite position: the typed error `MeshError::NonFinitePosition` is the
/// right outcome.
pub(super) fn non_finite_positions() -> Result<PolygonMesh, String> {
    let mut positions = rect(DVec3::ZERO, DVec3::X, DVec3::Y);
    positions.push(DVec3::new(f64::NAN, 0.0, 0.0));
    positions.push(DVec3::new(0.0, f64::INFINITY, 0.0));
    PolygonMesh::new(
        positions,
        [vec![0u32, 1, 2, 3], vec![0, 1, 4], vec![1, 2, 5]],
    )
    .map_err(|e| format!("MeshError: {e}"))
}

/// Only degenerate faces: the typed error `MeshError::Empty` is the right outcome.
pub(super) fn all_degenerate() -> Result<PolygonMesh, String> {
    let positions = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::X * 2.0,
        DVec3::new(1.0, 1.0, 1.0),
    ];
    PolygonMesh::new(positions, [[0u32, 1, 2], [3, 3, 3]]).map_err(|e| format!("MeshError: {e}"))
}

/// Two crossing sheets of `n × n` quads, every quad's corners lifted by up to
/// `angle · size` off its plane (non-planar by about `angle` radians).
pub(super) fn twisted(angle: f64) -> Result<PolygonMesh, String> {
    let n = 8;
    let mut rng = Rng::new(31);
    let mut polygons = Vec::new();
    for sheet in 0..2 {
        let r = if sheet == 0 {
            tilt()
        } else {
            tilt() * DMat3::from_rotation_x(1.1)
        };
        let cell = 2.0 / f64::from(n);
        for i in 0..n {
            for j in 0..n {
                let c = DVec3::new(
                    -1.0 + cell * (f64::from(i) + 0.5),
                    -1.0 + cell * (f64::from(j) + 0.5),
                    0.0,
                );
                let h = cell * 0.5;
                // The second sheet is shifted by a third of a cell, so that the line where
                // the sheets cross runs through cells, not along their edges.
                let shift = DVec3::Y * (cell / 3.0) * f64::from(sheet);
                let mut q = rect(c + shift, DVec3::X * h, DVec3::Y * h);
                // Opposite corners up and down: a twist of about `angle`.
                let lift = angle * cell * rng.range(0.5, 1.0);
                q[0].z += lift;
                q[2].z += lift;
                q[1].z -= lift;
                q[3].z -= lift;
                polygons.push(q.into_iter().map(|p| r * p).collect());
            }
        }
    }
    soup(&polygons)
}

/// A box whose faces are split unevenly (2 × 2, 1 × 3, …), so that edges end in the middle
/// of neighbours' edges (T-junctions); and a second, smaller box inside it.
pub(super) fn t_junctions() -> Result<PolygonMesh, String> {
    let mut positions: Vec<DVec3> = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut push = |quad: [DVec3; 4]| {
        let start = positions.len() as u32;
        positions.extend(quad);
        faces.push((start..start + 4).collect());
    };
    for (scale, offset) in [(1.0, DVec3::ZERO), (0.35, DVec3::new(0.1, -0.2, 0.15))] {
        // Each face of the cube [-1, 1]³ as (normal axis, sign), split into a × b cells.
        for (axis, sign, a, b) in [
            (0usize, 1.0, 2usize, 2usize),
            (0, -1.0, 1, 3),
            (1, 1.0, 3, 1),
            (1, -1.0, 2, 1),
            (2, 1.0, 1, 2),
            (2, -1.0, 3, 3),
        ] {
            let n = DVec3::AXES[axis] * sign;
            let u = DVec3::AXES[(axis + 1) % 3];
            let v = n.cross(u);
            for i in 0..a {
                for j in 0..b {
                    let (u0, u1) = (
                        -1.0 + 2.0 * i as f64 / a as f64,
                        -1.0 + 2.0 * (i + 1) as f64 / a as f64,
                    );
                    let (v0, v1) = (
                        -1.0 + 2.0 * j as f64 / b as f64,
                        -1.0 + 2.0 * (j + 1) as f64 / b as f64,
                    );
                    let p = |s: f64, t: f64| (n + u * s + v * t) * scale + offset;
                    push([p(u0, v0), p(u1, v0), p(u1, v1), p(u0, v1)]);
                }
            }
        }
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// `mesh` unwelded (every face its own copies of its vertices) and every position listed
/// twice; plus each quad's first corner repeated (a zero-length edge).
pub(super) fn duplicate_vertices(mesh: &PolygonMesh) -> Result<PolygonMesh, String> {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for face in mesh.faces() {
        let start = positions.len() as u32;
        for &i in face {
            let p = mesh.positions()[i as usize];
            positions.push(p);
            positions.push(p);
        }
        let mut f: Vec<u32> = (0..face.len() as u32).map(|k| start + 2 * k).collect();
        if face.len() == 4 {
            f.insert(1, start + 1);
        }
        faces.push(f);
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// Pages of a book opened all the way round the z axis: quads in planes through the axis, so
/// that a view down the axis (orthographic, or perspective with the eye on it) sees every
/// page exactly edge-on; a closing square at each end.
pub(super) fn pages() -> Result<PolygonMesh, String> {
    let mut polygons = Vec::new();
    for k in 0..8 {
        let a = f64::from(k) * std::f64::consts::TAU / 8.0 + 0.1;
        let d = DVec3::new(a.cos(), a.sin(), 0.0);
        polygons.push(vec![
            d * 0.2 + DVec3::Z * -1.0,
            d + DVec3::Z * -1.0,
            d + DVec3::Z,
            d * 0.2 + DVec3::Z,
        ]);
    }
    polygons.push(rect(DVec3::Z * -1.3, DVec3::X * 0.9, DVec3::Y * 0.9));
    polygons.push(rect(DVec3::Z * 1.3, DVec3::X * 0.5, DVec3::Y * 0.5));
    soup(&polygons)
}

/// Views along the axes (edge-on to every axis-aligned face), and perspective with the eye
/// close to, at the surface of, and inside the model (down to `0.01 · L` from its centre;
/// closer, the oracle's own pixel-space round-off decides: docs/ROBUSTNESS.md).
pub(super) fn view_shots(cull: CullMode) -> Vec<Shot> {
    vec![
        Shot::ortho(0.0, 0.0, 0.0, cull),
        Shot::ortho(90.0, 0.0, 0.0, cull),
        Shot::ortho(180.0, 0.0, 0.0, cull),
        Shot::ortho(0.0, 90.0, 0.0, cull),
        Shot::ortho(0.0, -90.0, 0.0, cull),
        Shot::persp(0.0, 0.0, 0.55, cull),
        Shot::persp(90.0, 0.0, 0.3, cull),
        Shot::persp(35.0, 20.0, 0.1, CullMode::None),
        Shot::persp(200.0, -30.0, 0.01, CullMode::None),
    ]
}

/// Every case of the list.
pub(super) fn all_cases() -> Result<Vec<Case>> {
    let models = base_models()?;
    let mut out = transform_cases(&models, false);
    out.extend(generated_cases(&models, false)?);
    Ok(out)
}

/// The fast subset `cargo test` runs: small models, one or two instances per class.
pub fn quick_cases() -> Result<Vec<Case>> {
    let box_scene =
        scenes::model_scene("cornell-box", "assets/models/cornell-box/cornell_box.obj")?;
    let quads = scenes::random_quads(16, 11)?;
    let models = vec![
        ("cornell-box".to_owned(), box_scene.mesh, CullMode::None),
        ("random-quads-16".to_owned(), quads.mesh, CullMode::None),
        (
            "uv-sphere-128".to_owned(),
            face_sort::generate::uv_sphere(16, 8),
            CullMode::Back,
        ),
    ];
    let mut out = transform_cases(&models, true);
    out.extend(generated_cases(&models, true)?);
    Ok(out)
}

/// Scenes of `face_sort::strategies::any_scene` (non-intersecting, interpenetrating, cyclic,
/// crossing; tiny and huge coordinates), drawn with a fixed seed.
pub(super) fn strategy_scenes(count: usize) -> Result<Vec<PolygonMesh>> {
    use proptest::strategy::{Strategy as _, ValueTree as _};
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]),
    );
    let strategy = face_sort::strategies::any_scene();
    (0..count)
        .map(|i| {
            strategy
                .new_tree(&mut runner)
                .map(|tree| tree.current())
                .map_err(|e| anyhow::anyhow!("generating strategy scene {i}: {e}"))
        })
        .collect()
}

pub(super) fn generated_cases(
    models: &[(String, PolygonMesh, CullMode)],
    quick: bool,
) -> Result<Vec<Case>> {
    let mut out = strategy_cases(quick)?;
    coplanar_cases(models, quick, &mut out);
    degenerate_cases(models, quick, &mut out);
    view_cases(models, quick, &mut out)?;
    Ok(out)
}

/// proptest's scenes, as generated and moved 1e7 away.
fn strategy_cases(quick: bool) -> Result<Vec<Case>> {
    let mut out = Vec::new();
    let direction = DVec3::new(-0.3, 1.0, 0.8);
    for (i, scene) in strategy_scenes(if quick { 2 } else { 12 })?
        .iter()
        .enumerate()
    {
        let shots = general_shots(CullMode::None);
        let shots: Vec<Shot> = shots.into_iter().take(if quick { 1 } else { 5 }).collect();
        out.push(Case {
            group: "generated",
            name: format!("strategies scene {i}"),
            mesh: Ok(scene.clone()),
            shots: shots.clone(),
            judged: true,
            expect_error: false,
        });
        out.push(Case {
            group: "generated",
            name: format!("strategies scene {i} moved 1e7"),
            mesh: mapped(scene, |p| p + direction * 1e7),
            shots,
            judged: true,
            expect_error: false,
        });
    }
    Ok(out)
}

/// Squares a hair apart, coplanar overlapping squares, a closed model doubled with the
/// opposite winding.
fn coplanar_cases(models: &[(String, PolygonMesh, CullMode)], quick: bool, out: &mut Vec<Case>) {
    let general = general_shots(CullMode::None);
    let two =
        |s: &[Shot]| -> Vec<Shot> { s.iter().take(if quick { 1 } else { 5 }).copied().collect() };
    let gaps: &[i32] = if quick { &[3, 9] } else { &[3, 5, 7, 8, 9] };
    for &k in gaps {
        let gap = 10f64.powi(-k);
        out.push(Case {
            group: "coplanar",
            name: format!("squares 1e-{k} L apart"),
            mesh: separated(gap),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    for tilted in [false, true] {
        out.push(Case {
            group: "coplanar",
            name: format!(
                "coplanar overlapping ({})",
                if tilted { "tilted" } else { "axis-aligned" }
            ),
            mesh: coplanar(tilted),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    let closed = &models[0];
    for cull in [CullMode::Back, CullMode::None] {
        let label = if cull == CullMode::Back {
            "back"
        } else {
            "none"
        };
        out.push(Case {
            group: "coplanar",
            name: format!("{} doubled, opposite winding, cull {label}", closed.0),
            mesh: doubled(&closed.1),
            shots: two(&general_shots(cull)),
            judged: true,
            expect_error: false,
        });
    }
}

/// Slivers, near-degenerate and degenerate faces, non-finite positions, twisted quads,
/// T-junctions, duplicate vertices.
fn degenerate_cases(models: &[(String, PolygonMesh, CullMode)], quick: bool, out: &mut Vec<Case>) {
    let general = general_shots(CullMode::None);
    let two =
        |s: &[Shot]| -> Vec<Shot> { s.iter().take(if quick { 1 } else { 5 }).copied().collect() };
    let aspects: &[f64] = if quick { &[1e6] } else { &[1e3, 1e6] };
    for &a in aspects {
        out.push(Case {
            group: "degenerate",
            name: format!("slivers aspect {a:e}"),
            mesh: slivers(a),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    out.push(Case {
        group: "degenerate",
        name: "near-degenerate faces".to_owned(),
        mesh: near_degenerate(),
        shots: two(&general),
        judged: true,
        expect_error: false,
    });
    out.push(Case {
        group: "degenerate",
        name: "degenerate faces mixed in".to_owned(),
        mesh: degenerate(),
        shots: two(&general),
        judged: true,
        expect_error: false,
    });
    out.push(Case {
        group: "degenerate",
        name: "only degenerate faces (typed error expected)".to_owned(),
        mesh: all_degenerate(),
        shots: two(&general),
        judged: true,
        expect_error: true,
    });
    out.push(Case {
        group: "degenerate",
        name: "NaN and infinite positions (typed error expected)".to_owned(),
        mesh: non_finite_positions(),
        shots: two(&general),
        judged: true,
        expect_error: true,
    });
    let angles: &[f64] = if quick {
        &[1e-6]
    } else {
        &[1e-9, 1e-7, 1e-6, 1e-5, 1e-3]
    };
    for &a in angles {
        out.push(Case {
            group: "degenerate",
            name: format!("quads twisted {a:e} rad"),
            mesh: twisted(a),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    out.push(Case {
        group: "degenerate",
        name: "T-junctions (split box faces)".to_owned(),
        mesh: t_junctions(),
        shots: two(&general_shots(CullMode::Back)),
        judged: true,
        expect_error: false,
    });
    for (name, mesh, cull) in models.iter().take(if quick { 1 } else { 2 }) {
        out.push(Case {
            group: "degenerate",
            name: format!("{name} duplicate vertices"),
            mesh: duplicate_vertices(mesh),
            shots: two(&general_shots(*cull)),
            judged: true,
            expect_error: false,
        });
    }
}

/// Views along the axes, edge-on, with the eye close and inside, of the models and of the
/// hard scenes.
fn view_cases(
    models: &[(String, PolygonMesh, CullMode)],
    quick: bool,
    out: &mut Vec<Case>,
) -> Result<()> {
    let view_models: Vec<(String, Result<PolygonMesh, String>, CullMode)> = if quick {
        vec![(models[0].0.clone(), Ok(models[0].1.clone()), CullMode::None)]
    } else {
        let mut v: Vec<_> = models
            .iter()
            .take(3)
            .map(|(n, m, c)| (n.clone(), Ok(m.clone()), *c))
            .collect();
        v.push(("T-junction boxes".to_owned(), t_junctions(), CullMode::Back));
        v.push((
            "book pages round the view axis".to_owned(),
            pages(),
            CullMode::None,
        ));
        let nested = scenes::nested_boxes()?;
        v.push(("nested-boxes".to_owned(), Ok(nested.mesh), CullMode::None));
        // Exactly edge-on views of faces whose stored positions are rounded far from the
        // origin.
        let far = DVec3::new(1.0, -0.6, 0.35) * 1e7;
        for (name, mesh, cull) in models.iter().take(3) {
            v.push((
                format!("{name} moved 1e7"),
                mapped(mesh, |p| p + far),
                *cull,
            ));
        }
        v
    };
    for (name, mesh, cull) in view_models {
        let shots = view_shots(cull);
        let shots = if quick {
            vec![shots[0], shots[3], shots[6], shots[8]]
        } else {
            shots
        };
        out.push(Case {
            group: "views",
            name: format!("{name}: axes, edge-on, eye close and inside"),
            mesh,
            shots,
            judged: true,
            expect_error: false,
        });
    }
    Ok(())
}
