//! The bake target: a small mesh and a spin (yaw, pitch, roll or a free axis; orthographic
//! or perspective) give a typed error, or bakes that their `verify` passes: the picture bake
//! ([`aspect_bake::bake_picture`], checked by [`aspect_bake::verify_picture`]) and the exact
//! BSP-signature bake ([`aspect_bake::bake`], checked by [`aspect_bake::verify`]). A picture
//! bake's spinning page ([`vector_sink::write_culled_spin_html`]) parses as HTML (the
//! writers target's check), and every number in its elements' rules is finite.
//!
//! Coordinates have a modest dynamic range (the `input` module's `modest`): the bakes'
//! guarantee, like the error metric's, holds for features above `1e-6 · L`, and any bits
//! make slivers a billionth of the model wide (docs/ROBUSTNESS.md). The spin's free axis
//! still takes any numbers.
//!
//! Budgets keep every execution small: at most 256 pieces, 10,000 candidate pairs, 100,000
//! events and 1 MiB of lists; a bake over them is a typed error.

use aspect_bake::{Axis, BakeOptions, BspSource, PictureOptions, Spin};
use face_sort::{Geometry, View};
use sprite_compose::Materials;

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
    if let Ok((baked, _)) = aspect_bake::bake_picture(&geometry, &spin, &PICTURE) {
        if let Err(e) = aspect_bake::verify_picture(&baked, &spin, 2, 1) {
            panic!("picture bake: {e}; mesh {mesh:?}; spin {spin:?}");
        }
        if let Ok(lists) = aspect_bake::drawn_lists(&baked, &spin) {
            let page = vector_sink::write_culled_spin_html(
                &baked,
                &lists,
                &spin,
                &geometry,
                &vector_sink::SpinOptions::DEFAULT.with_materials(&Materials::solid(
                    (0..geometry.face_count()).map(|face| [face as u8, 0, 0, 255]),
                )),
            );
            crate::writers::check_html(&page);
            check_numbers(&page);
        }
    }
    let source = BspSource::of(&geometry);
    if let Ok(baked) = aspect_bake::bake(&source, &spin, &EXACT)
        && let Err(e) = aspect_bake::verify(&baked, &source, &spin, 2, 1)
    {
        panic!("BSP bake: {e}; mesh {mesh:?}; spin {spin:?}");
    }
}

/// Every number in the page's element rules (`.p…{…}`: border widths and `matrix3d`) is
/// finite.
fn check_numbers(page: &str) {
    for rule in page.lines().filter(|l| l.starts_with(".p")) {
        let body = rule
            .split_once('{')
            .map_or("", |(_, b)| b)
            .trim_end_matches('}');
        for declaration in body.split(';') {
            let (name, value) = declaration.split_once(':').unwrap_or((declaration, ""));
            let numbers: Vec<&str> = match name {
                "border-width" | "width" | "height" => value
                    .split_whitespace()
                    .map(|t| t.trim_end_matches("px"))
                    .collect(),
                "transform" => value
                    .trim_start_matches("matrix3d(")
                    .trim_end_matches(')')
                    .split(',')
                    .collect(),
                _ => continue,
            };
            for t in numbers {
                let x: f64 = t
                    .parse()
                    .unwrap_or_else(|_| panic!("not a number: {t:?} in {rule}"));
                assert!(x.is_finite(), "{t} in {rule}");
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn page() -> String {
        let mesh = test_support::models::uv_sphere(8, 4);
        let geometry = Geometry::new(&mesh).expect("a sphere");
        let view = View::fit(&geometry.bounds(), 64, 64).with_perspective(128.0);
        let spin = Spin::new(
            view,
            Axis::Yaw {
                pitch: 20.0,
                roll: 0.0,
            },
        )
        .expect("a spin");
        let (baked, _) = aspect_bake::bake_picture(&geometry, &spin, &PICTURE).expect("a bake");
        let lists = aspect_bake::drawn_lists(&baked, &spin).expect("lists");
        vector_sink::write_culled_spin_html(
            &baked,
            &lists,
            &spin,
            &geometry,
            &vector_sink::SpinOptions::DEFAULT.with_materials(&Materials::solid(
                (0..geometry.face_count()).map(|_| [200, 100, 50, 255]),
            )),
        )
    }

    #[test]
    fn a_spinning_page_passes_the_checks() {
        let page = page();
        assert!(page.lines().filter(|l| l.starts_with(".p")).count() > 10);
        crate::writers::check_html(&page);
        check_numbers(&page);
    }

    #[test]
    #[should_panic(expected = "NaN")]
    fn a_rule_with_a_nan_fails_the_number_check() {
        let page = page().replacen("matrix3d(", "matrix3d(NaN,", 1);
        check_numbers(&page);
    }
}
