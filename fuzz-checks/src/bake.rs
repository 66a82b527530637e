//! The bake target: a small mesh and a spin (yaw, pitch, roll or a free axis; orthographic
//! or perspective) give a typed error, or bakes that their `verify` passes: the picture bake
//! ([`aspect_bake::bake_picture`], checked by [`aspect_bake::verify_picture`]) and the exact
//! BSP-signature bake ([`aspect_bake::bake`], checked by [`aspect_bake::verify`]).
//!
//! Coordinates have a modest dynamic range ([`crate::input`]'s `modest`): the bakes'
//! guarantee, like the error metric's, holds for features above `1e-6 · L`, and any bits
//! make slivers a billionth of the model wide (docs/ROBUSTNESS.md). The spin's free axis
//! still takes any numbers.
//!
//! Budgets keep every execution small: at most 256 pieces, 10,000 candidate pairs, 100,000
//! events and 1 MiB of lists; a bake over them is a typed error.

use aspect_bake::{Axis, BakeOptions, BspSource, PictureOptions, Spin};
use face_sort::{Geometry, View};

use arbitrary::{Result, Unstructured};

use crate::input::{modest, number, soup_geometry, tame};

/// The budgets of one execution.
const PICTURE: PictureOptions = PictureOptions {
    bins: 16,
    max_pieces: 256,
    max_pairs: 10_000,
    budget_bytes: 1 << 20,
    max_cycle_cuts: 8,
    max_boundary_cuts: 4,
};
const EXACT: BakeOptions<'static> = BakeOptions {
    range_deg: None,
    budget_bytes: 1 << 20,
    max_events: 100_000,
    progress: None,
};

fn spin(u: &mut Unstructured, geometry: &Geometry) -> Result<Option<Spin>> {
    let size = u.int_in_range(8u32..=64)?;
    let mut view = View::fit(&geometry.bounds(), size, size);
    if u.arbitrary()? {
        view = view.with_perspective(f64::from(size) * tame(u, 0.5, 4.0)?);
    }
    let (a, b) = (tame(u, -90.0, 90.0)?, tame(u, -180.0, 180.0)?);
    let axis = match u.int_in_range(0u8..=3)? {
        0 => Axis::Yaw { pitch: a, roll: b },
        1 => Axis::Pitch { yaw: b, roll: a },
        2 => Axis::Roll { yaw: b, pitch: a },
        _ => Axis::Direction {
            axis: [number(u)?, number(u)?, number(u)?],
            base: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        },
    };
    Ok(Spin::new(view, axis).ok())
}

/// The check. Panics when a bake fails its verification.
pub fn bake(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let Some((mesh, geometry)) = soup_geometry(&mut u, modest, 8, 4) else {
        return;
    };
    let Ok(Some(spin)) = spin(&mut u, &geometry) else {
        return;
    };
    if let Ok((baked, _)) = aspect_bake::bake_picture(&geometry, &spin, &PICTURE)
        && let Err(e) = aspect_bake::verify_picture(&baked, &spin, 2, 1)
    {
        panic!("picture bake: {e}; mesh {mesh:?}; spin {spin:?}");
    }
    let source = BspSource::of(&geometry);
    if let Ok(baked) = aspect_bake::bake(&source, &spin, &EXACT)
        && let Err(e) = aspect_bake::verify(&baked, &source, &spin, 2, 1)
    {
        panic!("BSP bake: {e}; mesh {mesh:?}; spin {spin:?}");
    }
}
