//! The seed system's sample book: its BSP left 48 (ortho) and 189 (perspective) order
//! violations over this grid; exact sorters here must leave none.

use crate::common::{asset, book_grid, read_obj, violations};
use face_sort::{DrawList, Geometry, SorterKind, View};

fn total_violations(kind: SorterKind, perspective: bool) -> usize {
    let mesh = read_obj(&asset("combobulate-samples/book.obj"));
    let geometry = Geometry::new(&mesh).unwrap();
    let mut sorter = kind.build(&geometry);
    let mut list = DrawList::new();
    let base = View::fit(&geometry.bounds(), 512, 512);
    let mut total = 0;
    for (yaw, pitch) in book_grid() {
        let mut view = base.with_yaw_pitch_roll(yaw, pitch, 0.0);
        if perspective {
            // Eye 4 model units from the centre: d/s = 4.
            view = view.with_perspective(4.0 * view.scale());
        }
        total += violations(sorter.as_mut(), &view, &mut list);
    }
    total
}

#[test]
fn bsp_has_no_violations_on_the_book_orthographic() {
    assert_eq!(total_violations(SorterKind::Bsp, false), 0);
}

#[test]
fn bsp_has_no_violations_on_the_book_perspective() {
    assert_eq!(total_violations(SorterKind::Bsp, true), 0);
}

#[test]
fn newell_has_no_violations_on_the_book_orthographic() {
    assert_eq!(total_violations(SorterKind::Newell, false), 0);
}

#[test]
fn newell_has_no_violations_on_the_book_perspective() {
    assert_eq!(total_violations(SorterKind::Newell, true), 0);
}

#[test]
fn centroid_is_wrong_on_the_book() {
    // The oracle must be able to fail: the baseline leaves violations on this grid.
    let ortho = total_violations(SorterKind::Centroid, false);
    let persp = total_violations(SorterKind::Centroid, true);
    eprintln!("centroid on the book: {ortho} orthographic, {persp} perspective violations");
    assert!(ortho + persp > 0);
}
