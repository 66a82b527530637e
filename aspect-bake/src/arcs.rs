//! Sets of arcs on the circle of angles: where a sign condition `a·cos θ + b·sin θ + c`
//! holds, and their intersections and differences.

use std::f64::consts::TAU;

use smallvec::{SmallVec, smallvec};

use crate::event::{EventFn, Roots};
use crate::tolerance::ROOT_NOISE;

/// Relative rounding of an event function's value (its [`ROOT_NOISE`]), with room.
const ROUNDING: f64 = 16.0 * ROOT_NOISE;

/// A finite union of arcs of `[0, 2π)`, as sorted, disjoint, non-touching intervals
/// `[lo, hi]` with `0 ≤ lo < hi ≤ 2π`. Endpoints do not matter to its users (every set is
/// widened or shrunk by a margin on purpose), so open and closed arcs are not told apart.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct ArcSet {
    arcs: Arcs,
}

/// Inline room for the few arcs a set usually has.
pub(crate) type Arcs = SmallVec<[(f64, f64); 2]>;

impl ArcSet {
    /// No angle.
    pub(crate) fn empty() -> Self {
        ArcSet { arcs: Arcs::new() }
    }

    /// Every angle.
    pub(crate) fn full() -> Self {
        ArcSet {
            arcs: smallvec![(0.0, TAU)],
        }
    }

    /// Whether no angle is in the set.
    pub(crate) fn is_empty(&self) -> bool {
        self.arcs.is_empty()
    }

    /// The arc from `start` running `length` radians (`0 < length`), any `start`.
    pub(crate) fn arc(start: f64, length: f64) -> Self {
        if length >= TAU {
            return Self::full();
        }
        let lo = start.rem_euclid(TAU);
        let hi = lo + length;
        if hi <= TAU {
            ArcSet {
                arcs: smallvec![(lo, hi)],
            }
        } else {
            ArcSet {
                arcs: smallvec![(0.0, hi - TAU), (lo, TAU)],
            }
        }
    }

    /// Where `f > 0` (`positive`) or `f < 0`, each arc widened by `grow` radians at both ends
    /// (`grow < 0` shrinks; an arc shrunk to nothing is dropped). A function that is
    /// identically zero, or only touches zero, is positive or negative nowhere.
    pub(crate) fn where_sign(f: &EventFn, positive: bool, grow: f64) -> Self {
        let sign = if positive { 1.0 } else { -1.0 };
        match f.roots() {
            Roots::Identically => Self::empty(),
            // Constant sign (away from a tangency's touch point): that of `c`, since
            // `|c| ≥ hypot(a, b)` there.
            Roots::None | Roots::Tangent(_) => {
                if f.c * sign > 0.0 {
                    Self::full()
                } else {
                    Self::empty()
                }
            }
            Roots::Two { down, up } => {
                // Positive from `up` to `down`, negative from `down` to `up`.
                let (start, end) = if positive { (up, down) } else { (down, up) };
                let length = (end - start).rem_euclid(TAU) + 2.0 * grow;
                if length <= 0.0 {
                    Self::empty()
                } else {
                    Self::arc(start - grow, length)
                }
            }
        }
    }

    /// The set less the angles where `f ≥ 0`, that is, its part where `f < 0`, shrunk by
    /// `margin` at the ends that roots of `f` make. Arcs over which `f` keeps one sign are
    /// kept or dropped whole without solving for roots: `|f(t) − f(m)| ≤ hypot(a, b)·|t − m|`.
    pub(crate) fn where_negative(&self, f: &EventFn, margin: f64) -> ArcSet {
        let amplitude = (f.a * f.a + f.b * f.b).sqrt() * (1.0 + 1e-12);
        let slack = ROUNDING * f.scale;
        let mut out = Arcs::new();
        let mut solved: Option<ArcSet> = None;
        for &(lo, hi) in &self.arcs {
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            let value = f.value(mid);
            let bound = amplitude * half + slack;
            if value + bound < 0.0 {
                out.push((lo, hi));
            } else if value - bound > 0.0 {
                continue;
            } else {
                let negative = solved.get_or_insert_with(|| ArcSet::where_sign(f, false, -margin));
                let piece = ArcSet {
                    arcs: smallvec![(lo, hi)],
                };
                out.extend(piece.intersect(negative).arcs);
            }
        }
        ArcSet { arcs: out }
    }

    /// The arcs as probes for quick sign tests ([`Probes`]).
    pub(crate) fn probes(&self) -> Probes {
        Probes(
            self.arcs
                .iter()
                .map(|&(lo, hi)| {
                    let mid = 0.5 * (lo + hi);
                    (mid.cos(), mid.sin(), 0.5 * (hi - lo))
                })
                .collect(),
        )
    }

    /// The set's arcs whose index `keep` accepts.
    pub(crate) fn arcs_where(&self, mut keep: impl FnMut(usize) -> bool) -> ArcSet {
        ArcSet {
            arcs: (0..self.arcs.len())
                .filter(|&k| keep(k))
                .map(|k| self.arcs[k])
                .collect(),
        }
    }

    /// Whether the set meets `[lo, hi]` (`0 ≤ lo ≤ hi ≤ 2π`).
    pub(crate) fn meets(&self, lo: f64, hi: f64) -> bool {
        self.arcs.iter().any(|&(a, b)| a <= hi && b >= lo)
    }

    /// The total length of the arcs (radians).
    pub(crate) fn total_length(&self) -> f64 {
        self.arcs.iter().map(|&(lo, hi)| hi - lo).sum()
    }

    /// Whether `theta` (in `[0, 2π)`) lies in the set.
    #[cfg(test)]
    pub(crate) fn contains(&self, theta: f64) -> bool {
        self.arcs.iter().any(|&(a, b)| a <= theta && theta <= b)
    }

    /// The intersection.
    pub(crate) fn intersect(&self, other: &ArcSet) -> ArcSet {
        let mut out = Arcs::new();
        let (mut i, mut j) = (0, 0);
        while i < self.arcs.len() && j < other.arcs.len() {
            let (a0, a1) = self.arcs[i];
            let (b0, b1) = other.arcs[j];
            let (lo, hi) = (a0.max(b0), a1.min(b1));
            if lo < hi {
                out.push((lo, hi));
            }
            if a1 < b1 { i += 1 } else { j += 1 }
        }
        ArcSet { arcs: out }
    }

    /// The set less `other`.
    pub(crate) fn minus(&self, other: &ArcSet) -> ArcSet {
        let mut out = Arcs::new();
        let mut j = 0;
        for &(a0, a1) in &self.arcs {
            let mut lo = a0;
            while j < other.arcs.len() && other.arcs[j].1 <= lo {
                j += 1;
            }
            let mut k = j;
            while k < other.arcs.len() && other.arcs[k].0 < a1 {
                let (b0, b1) = other.arcs[k];
                if b0 > lo {
                    out.push((lo, b0));
                }
                lo = lo.max(b1);
                k += 1;
            }
            if lo < a1 {
                out.push((lo, a1));
            }
        }
        ArcSet { arcs: out }
    }

    /// The arcs as `(lo, hi)`, sorted, disjoint and not touching (one through angle 0 is two:
    /// `(0, hi)` first and `(lo, 2π)` last).
    pub(crate) fn as_slice(&self) -> &[(f64, f64)] {
        &self.arcs
    }

    /// The arcs as `(start, length)` with those through angle 0 joined into one.
    pub(crate) fn joined(&self) -> Arcs {
        let mut out: Arcs = self.arcs.iter().map(|&(lo, hi)| (lo, hi - lo)).collect();
        if out.len() > 1 && self.arcs[0].0 <= 0.0 && self.arcs[self.arcs.len() - 1].1 >= TAU {
            let first = out.remove(0);
            let last = out.last_mut().expect("more than one arc");
            last.1 += first.1;
        }
        out
    }
}

/// Per arc of a set, the cosine and sine of its middle and its half-length: sign tests of
/// event functions over the arcs without evaluating trigonometry per function.
pub(crate) struct Probes(SmallVec<[(f64, f64, f64); 2]>);

impl Probes {
    /// Whether `f > 0` certainly holds all over arc `k`: its value at the middle exceeds
    /// the most it can change over half the arc (`(|a| + |b|)·half`, above
    /// `hypot(a, b)·half`) plus its rounding, as in [`ArcSet::where_negative`].
    pub(crate) fn positive_over(&self, k: usize, f: &EventFn) -> bool {
        let (value, reach) = self.middle_and_reach(k, f);
        value - reach > 0.0
    }

    /// Whether `f` certainly keeps one sign all over arc `k` (so has no root there).
    pub(crate) fn one_sign_over(&self, k: usize, f: &EventFn) -> bool {
        let (value, reach) = self.middle_and_reach(k, f);
        value.abs() - reach > 0.0
    }

    /// `f` at the middle of arc `k`, and the most it can differ from that over the arc
    /// (with its rounding).
    fn middle_and_reach(&self, k: usize, f: &EventFn) -> (f64, f64) {
        let (cos, sin, half) = self.0[k];
        let value = f.a * cos + f.b * sin + f.c;
        let reach = (f.a.abs() + f.b.abs()) * half * (1.0 + 1e-12) + ROUNDING * f.scale;
        (value, reach)
    }

    /// How many arcs.
    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::event::test_fn as f;

    #[test]
    fn sign_sets_match_the_function() {
        for (a, b, c) in [
            (1.0, 0.0, 0.5),
            (0.3, -0.7, -0.2),
            (0.0, 1.0, 0.0),
            (1.0, 1.0, 3.0),
        ] {
            let g = f(a, b, c);
            let pos = ArcSet::where_sign(&g, true, 0.0);
            let neg = ArcSet::where_sign(&g, false, 0.0);
            for k in 0..997 {
                let t = TAU * (k as f64 + 0.5) / 997.0;
                let v = g.value(t);
                if v.abs() > 1e-9 {
                    assert_eq!(pos.contains(t), v > 0.0, "{a} {b} {c} at {t}");
                    assert_eq!(neg.contains(t), v < 0.0, "{a} {b} {c} at {t}");
                }
            }
        }
    }

    #[test]
    fn set_algebra() {
        let a = ArcSet::arc(6.0, 1.0); // through 0
        assert_eq!(a.arcs.len(), 2);
        let b = ArcSet::arc(0.5, 1.0);
        let i = a.intersect(&b);
        assert!(i.contains(0.6) && !i.contains(0.2) && !i.contains(6.1));
        let m = a.minus(&b);
        assert!(m.contains(0.2) && m.contains(6.1) && !m.contains(0.6));
        assert_eq!(
            a.as_slice(),
            &[
                (0.0, 1.0 - (std::f64::consts::TAU - 6.0)),
                (6.0, std::f64::consts::TAU)
            ]
        );
        assert_eq!(a.joined().len(), 1);
        assert!((a.joined()[0].1 - 1.0).abs() < 1e-12);
        assert!(ArcSet::full().minus(&ArcSet::full()).is_empty());
    }
}
