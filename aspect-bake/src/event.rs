//! Event functions `a·cos θ + b·sin θ + c` and their roots in closed form.

use std::f64::consts::TAU;

use crate::tolerance::{IDENTICALLY_ZERO, ROOT_NOISE, TANGENT};

/// A quantity `a·cos θ + b·sin θ + c` whose sign decides part of a draw list (see the crate
/// docs for why every such quantity has this form).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EventFn {
    /// Coefficient of `cos θ`.
    pub a: f64,
    /// Coefficient of `sin θ`.
    pub b: f64,
    /// Constant.
    pub c: f64,
    /// The magnitude of the terms that formed the coefficients (e.g. `|n| · |eye| + |offset|`),
    /// against which "zero" is judged ([`IDENTICALLY_ZERO`]).
    pub scale: f64,
}

/// The zeros of an [`EventFn`] over one period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Roots {
    /// Never zero: the sign is constant.
    None,
    /// Zero at one angle without a sign change (a double root).
    Tangent(f64),
    /// Two sign changes: `down` where the value goes from positive to negative, `up` where it
    /// goes from negative to positive (radians in `(−2π, 2π)`, not reduced).
    Two {
        /// Positive to negative.
        down: f64,
        /// Negative to positive.
        up: f64,
    },
    /// Zero for every angle (e.g. a face edge-on all the way round): never a sign change.
    Identically,
}

impl EventFn {
    /// The function's value at `theta` (radians).
    #[must_use]
    pub fn value(&self, theta: f64) -> f64 {
        self.a * theta.cos() + self.b * theta.sin() + self.c
    }

    /// The function minus another (both describe the same `θ`).
    #[must_use]
    pub fn minus(&self, other: &EventFn) -> EventFn {
        EventFn {
            a: self.a - other.a,
            b: self.b - other.b,
            c: self.c - other.c,
            scale: self.scale + other.scale,
        }
    }

    /// The roots in closed form: with `r = hypot(a, b)` and `φ = atan2(b, a)`,
    /// `f(θ) = r·cos(θ − φ) + c`, zero where `cos(θ − φ) = −c / r`, i.e. `θ = φ ± acos(−c / r)`.
    /// At `φ + α` the derivative `−r·sin α` is negative (a down-crossing), at `φ − α` positive.
    #[must_use]
    pub fn roots(&self) -> Roots {
        let r = magnitude(self.a, self.b);
        let zero = self.zero();
        if r <= zero {
            return if self.c.abs() <= zero {
                Roots::Identically
            } else {
                Roots::None
            };
        }
        let q = -self.c / r;
        let phi = self.b.atan2(self.a);
        if q.abs() > 1.0 + TANGENT {
            Roots::None
        } else if q.abs() >= 1.0 - TANGENT {
            Roots::Tangent(if q > 0.0 { phi } else { phi + TAU / 2.0 })
        } else {
            // α = acos(−c/r), through atan2 of the sine `sqrt((r − c)(r + c))`: well
            // conditioned also near tangency, where acos loses half the digits.
            let alpha = ((r - self.c) * (r + self.c)).sqrt().atan2(-self.c);
            Roots::Two {
                down: phi + alpha,
                up: phi - alpha,
            }
        }
    }

    /// What counts as zero against the function's scale.
    fn zero(&self) -> f64 {
        IDENTICALLY_ZERO * self.scale.max(f64::MIN_POSITIVE)
    }

    /// Whether the function is zero at every angle ([`Roots::Identically`]), without
    /// solving for roots.
    #[must_use]
    pub fn is_identically_zero(&self) -> bool {
        let zero = self.zero();
        self.c.abs() <= zero && magnitude(self.a, self.b) <= zero
    }

    /// Whether the function is zero within rounding at `theta`: its value there within the
    /// bound of [`is_identically_zero`](Self::is_identically_zero), or the function zero at
    /// every angle.
    pub(crate) fn is_zero_at(&self, theta: f64) -> bool {
        self.is_identically_zero() || self.value(theta).abs() <= self.zero()
    }

    /// How far a root may move for a rounding error of `ROOT_NOISE · scale` in the value:
    /// `ROOT_NOISE · scale / |f′|`, with `|f′| = sqrt(r² − c²)` at either root.
    #[must_use]
    pub fn root_uncertainty(&self) -> f64 {
        let r = magnitude(self.a, self.b);
        let slope = ((r - self.c).abs() * (r + self.c).abs()).sqrt();
        ROOT_NOISE * self.scale / slope.max(f64::MIN_POSITIVE)
    }
}

/// `√(a² + b²)`: the plain formula where the sum of squares is a normal float (so neither
/// overflowed nor lost to underflow; then within two ulps of `hypot`, far inside
/// [`ROOT_NOISE`]), else `hypot`, which costs several times as much.
#[inline]
#[must_use]
pub(crate) fn magnitude(a: f64, b: f64) -> f64 {
    let sum = a * a + b * b;
    if sum.is_normal() && sum < f64::MAX {
        sum.sqrt()
    } else {
        a.hypot(b)
    }
}

/// `theta` moved by whole periods into `[start, start + 2π)`.
#[must_use]
pub fn reduce(theta: f64, start: f64) -> f64 {
    let t = start + (theta - start).rem_euclid(TAU);
    // rem_euclid may round up to exactly 2π.
    if t >= start + TAU { start } else { t }
}

/// `a·cos θ + b·sin θ + c` with the sum of the magnitudes as its scale (tests).
#[cfg(test)]
pub(crate) fn test_fn(a: f64, b: f64, c: f64) -> EventFn {
    EventFn {
        a,
        b,
        c,
        scale: a.abs() + b.abs() + c.abs(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use super::test_fn as f;

    #[test]
    fn magnitude_matches_hypot_at_every_scale() {
        let scales = [
            0.0, 1e-310, 1e-200, 1e-160, 1e-5, 1.0, 3e7, 1e150, 1e160, 1e200, 1e308,
        ];
        for &x in &scales {
            for &y in &scales {
                for (a, b) in [(x, y), (-x, y), (x * 0.3, -y * 0.7)] {
                    let (fast, exact) = (magnitude(a, b), a.hypot(b));
                    assert!(
                        (fast - exact).abs() <= 4.0 * f64::EPSILON * exact,
                        "magnitude({a}, {b}) = {fast}, hypot {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn two_roots_have_the_stated_crossing_directions() {
        let e = f(0.3, -0.7, 0.2);
        let Roots::Two { down, up } = e.roots() else {
            panic!("two roots expected, got {:?}", e.roots());
        };
        for (root, sign) in [(down, -1.0), (up, 1.0)] {
            assert!(e.value(root).abs() < 1e-15);
            assert!(e.value(root + 1e-6) * sign > 0.0);
            assert!(e.value(root - 1e-6) * sign < 0.0);
        }
    }

    #[test]
    fn sine_roots_are_exact_multiples_of_pi() {
        let Roots::Two { down, up } = f(0.0, -1.0, 0.0).roots() else {
            panic!("two roots expected");
        };
        assert_eq!(reduce(down, 0.0), 0.0);
        assert!((reduce(up, 0.0) - TAU / 2.0).abs() < 1e-15);
    }

    #[test]
    fn tangency_none_and_identically_zero() {
        assert!(matches!(f(1.0, 0.0, -1.0).roots(), Roots::Tangent(t) if t.abs() < 1e-15));
        assert_eq!(f(1.0, 1.0, 3.0).roots(), Roots::None);
        let edge_on = EventFn {
            a: 1e-20,
            b: 0.0,
            c: 0.0,
            scale: 1.0,
        };
        assert_eq!(edge_on.roots(), Roots::Identically);
        let offset = EventFn {
            a: 0.0,
            b: 0.0,
            c: 0.5,
            scale: 1.0,
        };
        assert_eq!(offset.roots(), Roots::None);
    }

    #[test]
    fn reduce_stays_in_the_window() {
        for t in [-7.0, -TAU, 0.0, 1e-300, TAU - 1e-16, TAU, 13.0] {
            let r = reduce(t, 0.5);
            assert!((0.5..0.5 + TAU).contains(&r), "{t} -> {r}");
        }
    }
}
