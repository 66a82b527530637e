//! How the writers print numbers: as few digits as the output needs.
//!
//! - **Pixel coordinates** (SVG points and paths, overlays, plots): three decimals, a
//!   thousandth of a pixel. Zoomed 4×, a corner is off by at most 0.002 px, far inside the
//!   0.75 px margin that makes a pixel unambiguous in the error metric (CONVENTIONS.md), so
//!   ID pictures stay exact.
//! - **Matrix entries** (CSS `matrix3d`, SVG image placements): seven significant digits,
//!   the precision of the f32 matrices browsers composite with.

/// A pixel coordinate: at most three decimals, no trailing zeros, no `-0`.
pub(crate) fn pixel(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// A number with about `significant` significant digits, no trailing zeros, no exponent
/// (CSS and SVG accept it); 0 for non-finite input.
pub(crate) fn significant(v: f64, significant: i32) -> String {
    if v == 0.0 || !v.is_finite() {
        return "0".to_owned();
    }
    let digits = (significant - 1 - v.abs().log10().floor() as i32).clamp(0, 15) as usize;
    let s = format!("{v:.digits$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    };
    if s == "-0" {
        return "0".to_owned();
    }
    // Tiny and huge values are shorter with an exponent (`4.0796e-9`).
    let e = format!("{v:.*e}", (significant - 1).max(0) as usize);
    let e = match e.split_once('e') {
        Some((mantissa, exponent)) if mantissa.contains('.') => {
            format!(
                "{}e{exponent}",
                mantissa.trim_end_matches('0').trim_end_matches('.')
            )
        }
        _ => e,
    };
    if e.len() < s.len() { e } else { s }
}

/// Matrix entries: [`significant`] to seven digits.
pub(crate) fn matrix_entry(v: f64) -> String {
    significant(v, 7)
}

/// `#rrggbb` of a colour.
pub(crate) fn hex(c: [u8; 4]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_round_trip_within_their_precision() {
        assert_eq!(pixel(402.34625), "402.346");
        assert_eq!(pixel(-0.0001), "0");
        assert_eq!(pixel(12.0), "12");
        assert_eq!(matrix_entry(5.246594833384398), "5.246595");
        assert_eq!(matrix_entry(1.5625022164028158e-2), "0.01562502");
        assert_eq!(matrix_entry(-1044.0076034098547), "-1044.008");
        assert_eq!(matrix_entry(-4.079599e-9), "-4.079599e-9");
        for v in [1e-9, 3.3e-5, 0.7, 123.456789, 98765.4321, -2.5e7, 7.25e12] {
            let back: f64 = matrix_entry(v).parse().unwrap();
            assert!((back - v).abs() <= 5e-7 * v.abs(), "{v} -> {back}");
        }
    }
}
