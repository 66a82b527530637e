//! A certificate kept on disk: [`Presorted::to_bytes`] and [`Presorted::from_bytes`].
//!
//! # Format (version 1, little-endian)
//! - `b"FSPRESRT"`, then the version (`u32`);
//! - the geometry's fingerprint (`u64`, FNV-1a over its pieces' faces and corner bits) and
//!   piece count (`u32`), then the piece count after cutting pieces that pass through each
//!   other and the cuts (`u32` each);
//! - `near` (`f64`), the build's figures: pairs, pair tests (`u64` each), threads (`u32`);
//! - the regions (`u32` count): three corners and two distances (`f64` each), then the
//!   kind: `0` a leaf (`u32`), `1` four children (`u32` first), `2` two children (`f64` mid,
//!   `u32` first), `3` uncertified;
//! - the orders (`u32` count): each its region's index (`u32`), step count (`u32`) and steps
//!   (`u32`: a piece, or `1 << 31 | k` for core `k`);
//! - the cores (`u32` count): each its piece count (`u32`) and pieces (`u32`, ascending).
//!
//! Nothing the geometry gives is stored: the pieces are cut again on load (the same cuts,
//! checked by count), the cores' BSP trees are built again from their pieces, and each
//! order's faces and planes are read from the pieces.
//!
//! # Validation
//! Every count is checked against the bytes left before anything is allocated, so hostile
//! bytes allocate at most a small multiple of their own length. Indices are checked against
//! what they index, children follow their parents (so the lookup ends), and distances and
//! corners must be numbers. A certificate of another geometry is refused by its
//! fingerprint. What cannot be checked short of building again is that the orders are the
//! ones a build certifies: bytes changed by hand load, and order wrongly without panicking.

use std::sync::Arc;
use web_time::Instant;

use glam::DVec3;

use super::build::{Core, share_cores};
use super::region::Region;
use super::{CORE, Leaf, Node, NodeKind, Presorted};
use crate::tolerance::PLANE_SIDE;
use crate::{Bsp, DrawList, Geometry, PolygonSet};

/// The first bytes of a saved certificate.
const MAGIC: &[u8; 8] = b"FSPRESRT";
/// The format [`Presorted::to_bytes`] writes.
pub const FORMAT_VERSION: u32 = 1;

/// Why [`Presorted::from_bytes`] refused its bytes.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PresortLoadError {
    /// The bytes do not start as a saved certificate does.
    #[error("not a presorted certificate (no FSPRESRT header)")]
    NotACertificate,
    /// A format this version cannot read.
    #[error("certificate format version {found}, this build reads version {FORMAT_VERSION}")]
    Version {
        /// The version in the bytes.
        found: u32,
    },
    /// The certificate was built for another geometry.
    #[error("the certificate was built for another geometry (fingerprint or piece count differs)")]
    OtherGeometry,
    /// The bytes end before `what`.
    #[error("the certificate ends inside {what} (byte {at})")]
    Truncated {
        /// What was being read.
        what: &'static str,
        /// Its offset.
        at: usize,
    },
    /// A value that cannot be right.
    #[error("bad {what} at byte {at}")]
    Invalid {
        /// What was being read.
        what: &'static str,
        /// Its offset.
        at: usize,
    },
    /// Bytes left over after the last core.
    #[error("{0} bytes after the end of the certificate")]
    Trailing(usize),
    /// A core's BSP tree could not be built again.
    #[error("a core's BSP tree: {0}")]
    Core(crate::BspError),
}

/// FNV-1a over the pieces' faces and corner bits: which geometry a certificate belongs to.
pub(super) fn fingerprint(pieces: &PolygonSet) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for i in 0..pieces.len() {
        eat(&pieces.face(i).to_le_bytes());
        for c in pieces.corners(i) {
            for v in c.to_array() {
                eat(&v.to_bits().to_le_bytes());
            }
        }
    }
    hash
}

struct Writer(Vec<u8>);

impl Writer {
    fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn len(&mut self, n: usize) {
        self.u32(u32::try_from(n).unwrap_or(u32::MAX));
    }
    fn region(&mut self, r: &Region) {
        for c in r.corners {
            for v in c.to_array() {
                self.f64(v);
            }
        }
        self.f64(r.near);
        self.f64(r.far);
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self, what: &'static str) -> Result<[u8; N], PresortLoadError> {
        let end = self.at.checked_add(N).filter(|&e| e <= self.bytes.len());
        let Some(end) = end else {
            return Err(PresortLoadError::Truncated { what, at: self.at });
        };
        let mut out = [0u8; N];
        out.copy_from_slice(&self.bytes[self.at..end]);
        self.at = end;
        Ok(out)
    }
    fn u32(&mut self, what: &'static str) -> Result<u32, PresortLoadError> {
        self.take::<4>(what).map(u32::from_le_bytes)
    }
    fn u64(&mut self, what: &'static str) -> Result<u64, PresortLoadError> {
        self.take::<8>(what).map(u64::from_le_bytes)
    }
    fn f64(&mut self, what: &'static str) -> Result<f64, PresortLoadError> {
        self.take::<8>(what).map(f64::from_le_bytes)
    }
    fn invalid(&self, what: &'static str) -> PresortLoadError {
        PresortLoadError::Invalid { what, at: self.at }
    }
    /// A count of items of at least `item_bytes` each: refused when the bytes left cannot
    /// hold them, so nothing larger than the input is ever allocated for it.
    fn count(&mut self, what: &'static str, item_bytes: usize) -> Result<usize, PresortLoadError> {
        let n = self.u32(what)? as usize;
        if n.saturating_mul(item_bytes) > self.bytes.len() - self.at {
            return Err(PresortLoadError::Truncated { what, at: self.at });
        }
        Ok(n)
    }
    fn region(&mut self) -> Result<Region, PresortLoadError> {
        let mut corners = [DVec3::ZERO; 3];
        for c in &mut corners {
            let v = [
                self.f64("a region corner")?,
                self.f64("a region corner")?,
                self.f64("a region corner")?,
            ];
            *c = DVec3::from_array(v);
            let length = c.length();
            if !(length.is_finite() && (length - 1.0).abs() < 1e-6) {
                return Err(self.invalid("a region corner (not a unit vector)"));
            }
        }
        let (near, far) = (
            self.f64("a region distance")?,
            self.f64("a region distance")?,
        );
        if near.is_nan() || far.is_nan() || near < 0.0 || far < near {
            return Err(self.invalid("a region's distances"));
        }
        Ok(Region { corners, near, far })
    }
}

impl Presorted {
    /// The certificate as bytes, to keep on disk and load with
    /// [`from_bytes`](Self::from_bytes) for the same geometry (the format is in the module
    /// docs of `presorted/bytes.rs`: versioned, and free of anything the geometry gives).
    #[must_use]
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut w = Writer(Vec::new());
        w.0.extend_from_slice(MAGIC);
        w.u32(FORMAT_VERSION);
        w.u64(self.fingerprint);
        w.len(self.geometry_pieces);
        w.len(self.pieces);
        w.len(self.cuts);
        w.f64(self.near);
        w.u64(self.candidate_pairs as u64);
        w.u64(self.pair_tests as u64);
        w.len(self.threads);
        w.len(self.nodes.len());
        for node in &self.nodes {
            w.region(&node.region);
            match node.kind {
                NodeKind::Leaf(l) => {
                    w.u32(0);
                    w.u32(l);
                }
                NodeKind::Directions { first } => {
                    w.u32(1);
                    w.u32(first);
                }
                NodeKind::Distance { mid, first } => {
                    w.u32(2);
                    w.f64(mid);
                    w.u32(first);
                }
                NodeKind::Uncertified => w.u32(3),
            }
        }
        w.len(self.leaves.len());
        for leaf in &self.leaves {
            w.region(&leaf.region);
            w.len(leaf.pieces.len());
            for &step in &leaf.pieces {
                w.u32(step);
            }
        }
        w.len(self.cores.len());
        for core in &self.cores {
            w.len(core.set.len());
            for &p in &core.set {
                w.u32(p);
            }
        }
        w.0
    }

    /// Loads a certificate that [`to_bytes`](Self::to_bytes) wrote for `geometry` (built
    /// from the same mesh as the saved one, e.g. by [`Geometry::with_exact_corners`]). The
    /// pieces are cut again, the cores' trees and the fallback BSP built again: far less
    /// work than certifying.
    ///
    /// # Errors
    /// [`PresortLoadError`]: bytes that are not a certificate of this format, of another geometry,
    /// cut short, or holding a value that cannot be right. Never panics, and allocates at
    /// most a small multiple of `bytes.len()` beyond what the geometry needs.
    pub fn from_bytes(bytes: &[u8], geometry: &Geometry) -> Result<Presorted, PresortLoadError> {
        let start = Instant::now();
        let mut r = Reader { bytes, at: 0 };
        if r.take::<8>("the header").ok().as_ref() != Some(MAGIC) {
            return Err(PresortLoadError::NotACertificate);
        }
        let version = r.u32("the version")?;
        if version != FORMAT_VERSION {
            return Err(PresortLoadError::Version { found: version });
        }
        let print = r.u64("the fingerprint")?;
        let geometry_pieces = r.u32("the piece count")? as usize;
        if print != fingerprint(geometry.pieces()) || geometry_pieces != geometry.pieces().len() {
            return Err(PresortLoadError::OtherGeometry);
        }
        let piece_count = r.u32("the cut piece count")? as usize;
        let cuts = r.u32("the cuts")? as usize;
        let near = r.f64("near")?;
        if near.is_nan() || near < 0.0 {
            return Err(r.invalid("near"));
        }
        let candidate_pairs = r.u64("the pairs")? as usize;
        let pair_tests = r.u64("the pair tests")? as usize;
        let threads = r.u32("the threads")? as usize;
        let (nodes, leaf_refs) = read_nodes(&mut r)?;
        // Orders: a region and a step count at least.
        let leaf_count = r.count("the orders", 92)?;
        if leaf_refs.iter().any(|&l| l as usize >= leaf_count) {
            return Err(r.invalid("a region's order (no such order)"));
        }
        // The pieces, cut again exactly as the build cut them.
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        let (pieces, recut) = crate::split_crossing(geometry.pieces(), tolerance, piece_count)
            .map_err(|_| PresortLoadError::OtherGeometry)?;
        if pieces.len() != piece_count || recut != cuts {
            return Err(PresortLoadError::OtherGeometry);
        }
        let mut leaves = Vec::with_capacity(leaf_count);
        let mut core_refs = Vec::new();
        for _ in 0..leaf_count {
            let region = r.region()?;
            let steps = r.count("an order's steps", 4)?;
            let mut leaf = Leaf {
                region,
                edges: region.edge_normals(),
                pieces: Vec::with_capacity(steps),
            };
            for _ in 0..steps {
                let step = r.u32("an order's step")?;
                if step & CORE != 0 {
                    core_refs.push(step & !CORE);
                    leaf.pieces.push(step);
                } else if (step as usize) < pieces.len() {
                    leaf.pieces.push(step);
                } else {
                    return Err(r.invalid("an order's step (no such piece)"));
                }
            }
            leaves.push(leaf);
        }
        let core_count = r.count("the cores", 4)?;
        if core_refs.iter().any(|&k| k as usize >= core_count) {
            return Err(r.invalid("an order's step (no such core)"));
        }
        let mut cores = Vec::with_capacity(core_count);
        for _ in 0..core_count {
            let size = r.count("a core's pieces", 4)?;
            let mut set = Vec::with_capacity(size);
            for _ in 0..size {
                set.push(r.u32("a core's piece")?);
            }
            let ascending = set.windows(2).all(|w| w[0] < w[1]);
            if size == 0 || !ascending || set.iter().any(|&p| p as usize >= pieces.len()) {
                return Err(r.invalid("a core's pieces"));
            }
            cores.push(
                Core::of(&pieces, &set, geometry.bounds()).map_err(|e| match e {
                    super::PresortError::Core(e) => PresortLoadError::Core(e),
                    _ => PresortLoadError::OtherGeometry,
                })?,
            );
        }
        if r.at != bytes.len() {
            return Err(PresortLoadError::Trailing(bytes.len() - r.at));
        }
        let shared = share_cores(&pieces, &mut cores);
        let core_sorters = cores
            .iter()
            .map(|c| Bsp::from_tree(Arc::clone(&c.tree)))
            .collect();
        Ok(Presorted {
            shared: Arc::new(shared),
            nodes,
            leaves,
            cores,
            core_sorters,
            core_list: DrawList::new(),
            near,
            fallback: Bsp::new(geometry),
            last_leaf: None,
            last_fallback: None,
            fallback_frames: 0,
            refusal: None,
            threads,
            build_ms: start.elapsed().as_secs_f64() * 1e3,
            pair_tests,
            candidate_pairs,
            cuts,
            fingerprint: print,
            geometry_pieces,
            pieces: piece_count,
        })
    }
}

/// The region tree: each node's region and kind, children after their parent; with the
/// orders its leaves name (checked against the order count by the caller).
fn read_nodes(r: &mut Reader<'_>) -> Result<(Vec<Node>, Vec<u32>), PresortLoadError> {
    // Regions: 88 bytes of region and at least 4 of kind each.
    let node_count = r.count("the regions", 92)?;
    if node_count != 0 && node_count < 8 {
        return Err(r.invalid("the regions (fewer than the eight octants)"));
    }
    let mut nodes = Vec::with_capacity(node_count);
    let mut leaf_refs = Vec::new();
    for index in 0..node_count {
        let region = r.region()?;
        let kind = match r.u32("a region's kind")? {
            0 => {
                let l = r.u32("a region's order")?;
                leaf_refs.push(l);
                NodeKind::Leaf(l)
            }
            1 => {
                let first = r.u32("a region's children")?;
                children_follow(r, index, first, 4, node_count)?;
                NodeKind::Directions { first }
            }
            2 => {
                let mid = r.f64("a distance split")?;
                if !(mid.is_finite() && mid > 0.0) {
                    return Err(r.invalid("a distance split"));
                }
                let first = r.u32("a region's children")?;
                children_follow(r, index, first, 2, node_count)?;
                NodeKind::Distance { mid, first }
            }
            3 => NodeKind::Uncertified,
            _ => return Err(r.invalid("a region's kind")),
        };
        nodes.push(Node { region, kind });
    }
    Ok((nodes, leaf_refs))
}

/// Children at `first .. first + count` must come after their parent `index` and exist, so
/// that the lookup walks forward and ends.
fn children_follow(
    r: &Reader<'_>,
    index: usize,
    first: u32,
    count: usize,
    nodes: usize,
) -> Result<(), PresortLoadError> {
    let first = first as usize;
    if first > index && first.saturating_add(count) <= nodes {
        Ok(())
    } else {
        Err(r.invalid("a region's children"))
    }
}
