//! Turns raw faces read by a loader into a [`Mesh`] under the caller's policies.

use std::collections::HashMap;

use glam::{DVec3, Vec2};

use crate::error::FaceLocation;
use crate::geometry::{Shape, ear_clip, is_convex, is_good_quad};
use crate::{
    FacePolicy, LoadError, LoadOptions, LoadReport, Material, Mesh, NonConvexPolicy,
    NonPlanarPolicy,
};

/// Faces as read, before any policy is applied. Indices are already checked
/// to be in range by the loader.
#[derive(Debug, Default)]
pub(crate) struct RawMesh {
    pub file: String,
    pub positions: Vec<DVec3>,
    pub indices: Vec<u32>,
    pub offsets: Vec<usize>,
    pub uvs: Option<Vec<Vec2>>,
    pub face_materials: Vec<Option<u32>>,
    pub face_objects: Vec<u32>,
    pub face_lines: Vec<Option<usize>>,
    pub objects: Vec<String>,
    pub materials: Vec<Material>,
    pub report: LoadReport,
}

impl RawMesh {
    pub(crate) fn new(file: String) -> RawMesh {
        RawMesh {
            file,
            offsets: vec![0],
            ..RawMesh::default()
        }
    }

    pub(crate) fn face_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    pub(crate) fn location(&self, face: usize) -> FaceLocation {
        let object = self
            .face_objects
            .get(face)
            .and_then(|&o| self.objects.get(o as usize))
            .cloned()
            .unwrap_or_default();
        FaceLocation {
            object,
            face,
            line: self.face_lines.get(face).copied().flatten(),
        }
    }
}

/// Output faces being assembled.
#[derive(Default)]
struct Out {
    indices: Vec<u32>,
    offsets: Vec<usize>,
    uvs: Vec<Vec2>,
    materials: Vec<Option<u32>>,
    sources: Vec<usize>,
}

impl Out {
    fn push(
        &mut self,
        corners: &[u32],
        uvs: Option<&[Vec2]>,
        material: Option<u32>,
        source: usize,
    ) {
        self.indices.extend_from_slice(corners);
        if let Some(uvs) = uvs {
            self.uvs.extend_from_slice(uvs);
        }
        self.offsets.push(self.indices.len());
        self.materials.push(material);
        self.sources.push(source);
    }

    fn face(&self, i: usize) -> &[u32] {
        match (self.offsets.get(i), self.offsets.get(i + 1)) {
            (Some(&a), Some(&b)) => self.indices.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }

    fn face_uvs(&self, i: usize) -> Option<&[Vec2]> {
        match (self.offsets.get(i), self.offsets.get(i + 1)) {
            (Some(&a), Some(&b)) => self.uvs.get(a..b),
            _ => None,
        }
    }
}

/// Applies the policies of `options` to `raw` and builds the mesh.
pub(crate) fn finish(raw: RawMesh, options: &LoadOptions) -> Result<(Mesh, LoadReport), LoadError> {
    let mut report = raw.report.clone();
    let faces = raw.face_count();
    report.faces_read = faces;
    let has_uvs = raw
        .uvs
        .as_ref()
        .is_some_and(|u| u.len() == raw.indices.len());
    let mut out = Out {
        offsets: vec![0],
        ..Out::default()
    };
    let mut keep: Vec<usize> = Vec::new();
    let mut pts: Vec<DVec3> = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    let mut corner_uvs: Vec<Vec2> = Vec::new();
    for face in 0..faces {
        let (Some(&start), Some(&end)) = (raw.offsets.get(face), raw.offsets.get(face + 1)) else {
            break;
        };
        let idx = raw.indices.get(start..end).unwrap_or(&[]);
        let uvs = if has_uvs {
            raw.uvs.as_ref().and_then(|u| u.get(start..end))
        } else {
            None
        };
        let material = raw.face_materials.get(face).copied().flatten();
        let n = idx.len();
        check_corners(&raw, face, n, options)?;
        let quads_only = options.face_policy == FacePolicy::QuadsOnly;
        // Drop consecutive duplicate corners (same index or same position).
        let pos = |k: usize| -> DVec3 {
            idx.get(k)
                .and_then(|&v| raw.positions.get(v as usize))
                .copied()
                .unwrap_or(DVec3::ZERO)
        };
        distinct_corners(idx, &pos, &mut keep);
        if keep.len() < 3 {
            report.degenerate_dropped += 1;
            continue;
        }
        if quads_only && keep.len() != 4 {
            return Err(LoadError::NotAQuad {
                file: raw.file.clone(),
                at: raw.location(face),
                corners: keep.len(),
            });
        }
        pts.clear();
        pts.extend(keep.iter().map(|&k| pos(k)));
        corners.clear();
        corners.extend(keep.iter().map(|&k| idx[k]));
        corner_uvs.clear();
        if let Some(uvs) = uvs {
            corner_uvs.extend(
                keep.iter()
                    .map(|&k| uvs.get(k).copied().unwrap_or(Vec2::ZERO)),
            );
        }
        let cuv = uvs.map(|_| corner_uvs.as_slice());
        let shape = Shape::of(&pts);
        if shape.degenerate {
            report.degenerate_dropped += 1;
            continue;
        }
        if !shape.planar {
            report.non_planar += 1;
            let reject = || LoadError::NonPlanarFace {
                file: raw.file.clone(),
                at: raw.location(face),
                distance: shape.off_plane,
                limit: shape.planar_limit(),
            };
            match options.non_planar {
                NonPlanarPolicy::Reject => return Err(reject()),
                NonPlanarPolicy::SplitFan if quads_only => return Err(reject()),
                NonPlanarPolicy::SplitFan => {
                    for k in 1..corners.len() - 1 {
                        emit_triangle(&mut out, &pts, &corners, cuv, [0, k, k + 1], material, face);
                    }
                    continue;
                }
                _ => {}
            }
        }
        // Non-planar faces that are kept are not tested for convexity: they
        // are fan triangles downstream.
        if corners.len() > 3 && shape.planar {
            let q = shape.project(&pts);
            if !is_convex(&q, shape.diameter) {
                if quads_only || options.non_convex == NonConvexPolicy::Reject {
                    return Err(LoadError::NonConvexFace {
                        file: raw.file.clone(),
                        at: raw.location(face),
                    });
                }
                report.non_convex_split += 1;
                for tri in ear_clip(&q, shape.diameter) {
                    emit_triangle(&mut out, &pts, &corners, cuv, tri, material, face);
                }
                continue;
            }
        }
        out.push(&corners, cuv, material, face);
    }
    if options.face_policy == FacePolicy::MergeTriangles {
        out = merge_triangles(out, &raw.positions, has_uvs, &mut report);
    }
    let kept = out.materials.len();
    if kept == 0 {
        return Err(LoadError::EmptyModel {
            file: raw.file,
            detail: format!(
                "{faces} faces read, {} dropped as degenerate",
                report.degenerate_dropped
            ),
        });
    }
    report.faces_kept = kept;
    let mesh = Mesh::from_parts(
        raw.positions,
        out.indices,
        out.offsets,
        out.materials,
        out.sources,
        has_uvs.then_some(out.uvs),
        raw.materials,
    )
    .map_err(|e| match e {
        LoadError::InvalidMesh { detail } => LoadError::Parse {
            file: raw.file.clone(),
            line: None,
            detail,
        },
        other => other,
    })?;
    Ok((mesh, report))
}

/// A face of `n` corners: at least 3, at most `options.max_face_corners`, and 4 under
/// [`FacePolicy::QuadsOnly`].
fn check_corners(
    raw: &RawMesh,
    face: usize,
    n: usize,
    options: &LoadOptions,
) -> Result<(), LoadError> {
    if n < 3 {
        return Err(LoadError::TooFewCorners {
            file: raw.file.clone(),
            at: raw.location(face),
            corners: n,
        });
    }
    if n > options.max_face_corners {
        return Err(LoadError::TooManyCorners {
            file: raw.file.clone(),
            at: raw.location(face),
            corners: n,
            max: options.max_face_corners,
        });
    }
    if options.face_policy == FacePolicy::QuadsOnly && n != 4 {
        return Err(LoadError::NotAQuad {
            file: raw.file.clone(),
            at: raw.location(face),
            corners: n,
        });
    }
    Ok(())
}

/// The corners of a face (indices `idx`, positions `pos(k)`) to keep, into `keep`:
/// consecutive duplicates (same index or same position) dropped, around the end too.
fn distinct_corners(idx: &[u32], pos: &impl Fn(usize) -> DVec3, keep: &mut Vec<usize>) {
    keep.clear();
    for k in 0..idx.len() {
        let same_as_last = keep
            .last()
            .is_some_and(|&l| idx[l] == idx[k] || pos(l) == pos(k));
        if !same_as_last {
            keep.push(k);
        }
    }
    while keep.len() > 1 {
        let (Some(&first), Some(&last)) = (keep.first(), keep.last()) else {
            break;
        };
        if idx[first] == idx[last] || pos(first) == pos(last) {
            keep.pop();
        } else {
            break;
        }
    }
}

/// Emits one triangle of a split face, skipping zero-area pieces.
fn emit_triangle(
    out: &mut Out,
    pts: &[DVec3],
    corners: &[u32],
    uvs: Option<&[Vec2]>,
    tri: [usize; 3],
    material: Option<u32>,
    source: usize,
) {
    let (Some(a), Some(b), Some(c)) = (pts.get(tri[0]), pts.get(tri[1]), pts.get(tri[2])) else {
        return;
    };
    if Shape::of(&[*a, *b, *c]).degenerate {
        return;
    }
    let idx = tri.map(|k| corners.get(k).copied().unwrap_or(0));
    let tri_uvs = uvs.map(|u| tri.map(|k| u.get(k).copied().unwrap_or(Vec2::ZERO)));
    out.push(&idx, tri_uvs.as_ref().map(|u| &u[..]), material, source);
}

/// Position key for welding: exact bit pattern, with `-0.0` folded into `0.0`.
fn weld_key(p: DVec3) -> [u64; 3] {
    [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits())
}

/// Pairs adjacent coplanar triangles whose union is a strictly convex planar
/// quad into quads. A pair sits at the lower face's position.
fn merge_triangles(out: Out, positions: &[DVec3], has_uvs: bool, report: &mut LoadReport) -> Out {
    let count = out.materials.len();
    let pos = |v: u32| positions.get(v as usize).copied().unwrap_or(DVec3::ZERO);
    let mut weld: HashMap<[u64; 3], u32> = HashMap::new();
    let mut canon = |v: u32| -> u32 {
        let next = weld.len() as u32;
        *weld.entry(weld_key(pos(v))).or_insert(next)
    };
    // Canonical corners of every triangle (None for other faces).
    let tris: Vec<Option<[u32; 3]>> = (0..count)
        .map(|i| match out.face(i) {
            &[a, b, c] => Some([canon(a), canon(b), canon(c)]),
            _ => None,
        })
        .collect();
    let mut edges: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (i, t) in tris.iter().enumerate() {
        if let Some(t) = t {
            for k in 0..3 {
                edges.entry((t[k], t[(k + 1) % 3])).or_default().push(i);
            }
        }
    }
    // partner[i] = Some((quad corners, quad uvs)) for the lower face of a pair;
    // absorbed[j] = true for the higher one.
    let mut paired = vec![false; count];
    let mut quads: HashMap<usize, ([u32; 4], [Vec2; 4])> = HashMap::new();
    for t in 0..count {
        let Some(ct) = tris[t] else { continue };
        if paired[t] {
            continue;
        }
        let face_t = out.face(t);
        let uv_t = out.face_uvs(t);
        let pt = [0, 1, 2].map(|k| pos(face_t.get(k).copied().unwrap_or(0)));
        let len2 = |k: usize| pt[k].distance_squared(pt[(k + 1) % 3]);
        let longest = (0..3)
            .max_by(|&a, &b| len2(a).total_cmp(&len2(b)))
            .unwrap_or(0);
        let mut best: Option<(bool, usize, [u32; 4], [Vec2; 4])> = None;
        for k in 0..3 {
            let (x, y) = (ct[k], ct[(k + 1) % 3]);
            let Some(cands) = edges.get(&(y, x)) else {
                continue;
            };
            for &u in cands {
                if u == t || paired[u] || out.materials.get(u) != out.materials.get(t) {
                    continue;
                }
                let Some(cu) = tris[u] else { continue };
                let Some(j) = (0..3).find(|&j| cu[j] == y && cu[(j + 1) % 3] == x) else {
                    continue;
                };
                let face_u = out.face(u);
                let uv_u = out.face_uvs(u);
                let get = |f: &[u32], i: usize| f.get(i % 3).copied().unwrap_or(0);
                let getuv = |f: Option<&[Vec2]>, i: usize| {
                    f.and_then(|f| f.get(i % 3)).copied().unwrap_or(Vec2::ZERO)
                };
                if has_uvs
                    && (getuv(uv_t, k) != getuv(uv_u, j + 1)
                        || getuv(uv_t, k + 1) != getuv(uv_u, j))
                {
                    continue;
                }
                let quad = [
                    get(face_t, k + 2),
                    get(face_t, k),
                    get(face_u, j + 2),
                    get(face_t, k + 1),
                ];
                let quad_uv = [
                    getuv(uv_t, k + 2),
                    getuv(uv_t, k),
                    getuv(uv_u, j + 2),
                    getuv(uv_t, k + 1),
                ];
                if !is_good_quad(&quad.map(pos)) {
                    continue;
                }
                let pref = k == longest;
                let better = match &best {
                    None => true,
                    Some((bp, bu, _, _)) => (pref && !bp) || (pref == *bp && u < *bu),
                };
                if better {
                    best = Some((pref, u, quad, quad_uv));
                }
            }
        }
        if let Some((_, u, quad, quad_uv)) = best {
            paired[t] = true;
            paired[u] = true;
            quads.insert(t.min(u), (quad, quad_uv));
        }
    }
    let mut merged = Out {
        offsets: vec![0],
        ..Out::default()
    };
    for i in 0..count {
        let material = out.materials.get(i).copied().flatten();
        let source = out.sources.get(i).copied().unwrap_or(0);
        if let Some((quad, quad_uv)) = quads.get(&i) {
            report.triangles_merged += 2;
            merged.push(quad, has_uvs.then_some(&quad_uv[..]), material, source);
        } else if paired.get(i).copied().unwrap_or(false) {
            continue;
        } else {
            merged.push(out.face(i), out.face_uvs(i), material, source);
        }
    }
    merged
}
