//! The sorter target: a small mesh and a view, with any numbers (NaN, infinities, huge and
//! tiny values, degenerate and near-singular faces), give a typed error, or a draw list
//! that the order-violation oracle passes from every exact sorter.
//!
//! The errors come from where a caller's numbers enter: [`face_sort::PolygonMesh::new`],
//! [`Geometry::new`], [`Camera`] and [`Geometry::check_view`] for views made with the
//! `View` builders.

use arbitrary::{Result, Unstructured};
use face_sort::{Camera, CullMode, DrawList, FrontFace, Geometry, Lens, SorterKind, View, oracle};

use crate::input::{number, point, soup_geometry, tame};

/// How the view is made.
fn view(u: &mut Unstructured, geometry: &Geometry) -> Result<Option<View>> {
    let (width, height) = (u.int_in_range(1u32..=96)?, u.int_in_range(1u32..=96)?);
    let view = if u.arbitrary()? {
        // A camera, as a user with an engine's numbers makes one.
        let lens = if u.arbitrary()? {
            Lens::perspective(number(u)? * 10.0, number(u)?)
        } else {
            Lens::orthographic(number(u)?)
        };
        let camera = Camera::look_at(point(u)?, point(u)?, point(u)?, lens);
        match camera.and_then(|c| c.view(geometry, width, height)) {
            Ok(view) => view,
            Err(_) => return Ok(None),
        }
    } else {
        // The View builders, which take any number; check_view is the gate.
        let mut view = View::fit(&geometry.bounds(), width, height).with_yaw_pitch_roll(
            number(u)? * 40.0,
            number(u)? * 40.0,
            number(u)? * 40.0,
        );
        if u.arbitrary()? {
            view = view.with_perspective(tame(u, 0.0, 4.0)? * f64::from(width) + number(u)?);
        }
        if u.arbitrary()? {
            view = view.with_scale(view.scale() * (1.0 + number(u)?));
        }
        if u.arbitrary()? {
            view = view.with_view_offset(point(u)?);
        }
        view = view
            .with_cull(*u.choose(&[CullMode::Back, CullMode::Front, CullMode::None])?)
            .with_front_face(*u.choose(&[FrontFace::CounterClockwise, FrontFace::Clockwise])?);
        if u.arbitrary()? {
            view = view.with_cull_margin(number(u)?);
        }
        view
    };
    Ok(geometry.check_view(&view).ok().map(|()| view))
}

/// The check. Panics when an exact sorter's list has a violation.
pub fn sorters(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let Some((mesh, geometry)) = soup_geometry(&mut u, number, 10, 6) else {
        return;
    };
    let Ok(Some(view)) = view(&mut u, &geometry) else {
        return;
    };
    let mut list = DrawList::new();
    for kind in SorterKind::EXACT {
        let mut sorter = kind.build(&geometry);
        sorter.sort(&view, &mut list);
        let violations = oracle::find_violations(&view, &list, 3);
        assert!(
            violations.is_empty(),
            "{}: {} violation(s), first {:?}; mesh {:?}; view {view:?}",
            kind.name(),
            violations.len(),
            violations.first(),
            mesh
        );
    }
}
