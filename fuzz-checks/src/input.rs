//! Numbers and small meshes drawn from fuzzer bytes.
//!
//! Most numbers are small multiples of 1/8 (so that faces meet, touch and lie in common
//! planes, where order decisions are hardest); some are nudged by a few ulps (near-singular
//! cases), and some are any bit pattern or a special value (NaN, infinities, huge, tiny).

use arbitrary::{Result, Unstructured};
use face_sort::{Geometry, PolygonMesh};
use glam::DVec3;

/// Values worth hitting on purpose.
const SPECIAL: [f64; 10] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    1e300,
    -1e300,
    1e-300,
    f64::MIN_POSITIVE,
    f64::EPSILON,
];

/// A number: a grid value mostly, sometimes nudged, special or any bits.
pub(crate) fn number(u: &mut Unstructured) -> Result<f64> {
    Ok(match u.int_in_range(0u8..=31)? {
        0 => f64::from_bits(u.arbitrary()?),
        1 => *u.choose(&SPECIAL)?,
        2..=4 => {
            let grid = grid(u)?;
            let ulps = i64::from(u.int_in_range(-4i8..=4)?);
            nudge(grid, ulps)
        }
        _ => grid(u)?,
    })
}

/// A finite number in `[lo, hi]`, on a grid of `1/8` mostly.
pub(crate) fn tame(u: &mut Unstructured, lo: f64, hi: f64) -> Result<f64> {
    let t = f64::from(u.int_in_range(0u16..=1024)?) / 1024.0;
    Ok(lo + (hi - lo) * t)
}

/// A number of modest dynamic range: a grid value, sometimes nudged by a few ulps. For
/// checks whose guarantee holds only for features above the error metric's ambiguity
/// (`1e-6 · L`): any bits would make slivers a billionth of the model wide.
pub(crate) fn modest(u: &mut Unstructured) -> Result<f64> {
    let grid = grid(u)?;
    Ok(if u.ratio(1u8, 8)? {
        nudge(grid, i64::from(u.int_in_range(-4i8..=4)?))
    } else {
        grid
    })
}

fn grid(u: &mut Unstructured) -> Result<f64> {
    Ok(f64::from(u.int_in_range(-32i8..=32)?) / 8.0)
}

/// `x` moved by `ulps` units in the last place.
fn nudge(x: f64, ulps: i64) -> f64 {
    if x == 0.0 || ulps == 0 {
        return x;
    }
    let bits = x.to_bits() as i64;
    f64::from_bits((bits + ulps) as u64)
}

/// A point of three [`number`]s.
pub(crate) fn point(u: &mut Unstructured) -> Result<DVec3> {
    Ok(DVec3::new(number(u)?, number(u)?, number(u)?))
}

/// How a soup's coordinates are drawn: [`number`] or [`modest`].
pub(crate) type Draw = fn(&mut Unstructured) -> Result<f64>;

/// A small polygon soup: 3 to `max_positions` positions (coordinates by `draw`) and 1 to `max_faces` faces of 3 to
/// 5 indices, some possibly out of range or repeated (the mesh constructors must refuse
/// those with a typed error).
pub(crate) fn soup(
    u: &mut Unstructured,
    draw: Draw,
    max_positions: usize,
    max_faces: usize,
) -> Result<(Vec<DVec3>, Vec<Vec<u32>>)> {
    let n = u.int_in_range(3..=max_positions)?;
    let positions = (0..n)
        .map(|_| Ok(DVec3::new(draw(u)?, draw(u)?, draw(u)?)))
        .collect::<Result<Vec<_>>>()?;
    let faces = (0..u.int_in_range(1..=max_faces)?)
        .map(|_| {
            let corners = u.int_in_range(3..=5)?;
            (0..corners)
                .map(|_| Ok(u32::from(u.int_in_range(0u8..=(n as u8))?)))
                .collect::<Result<Vec<u32>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    Ok((positions, faces))
}

/// A [`soup`] built into a mesh and its geometry; `None` when the bytes run out or the soup
/// is refused with a typed error (`MeshError`), which is what the checks accept of it.
pub(crate) fn soup_geometry(
    u: &mut Unstructured,
    draw: Draw,
    max_positions: usize,
    max_faces: usize,
) -> Option<(PolygonMesh, Geometry)> {
    let (positions, faces) = soup(u, draw, max_positions, max_faces).ok()?;
    let mesh = PolygonMesh::new(positions, faces).ok()?;
    let geometry = Geometry::new(&mesh).ok()?;
    Some((mesh, geometry))
}
