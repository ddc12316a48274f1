//! Closed intervals of reals with outward rounding, for bounding a patch's derivatives over a
//! knot cell (`bounds.rs`): every operation widens its result by two units in the last place
//! of its larger end (an IEEE operation errs by at most half of one), so the interval computed
//! holds every value the exact operation takes on the operands' intervals.

/// `[lo, hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// The least value.
    pub lo: f64,
    /// The largest value.
    pub hi: f64,
}

impl Interval {
    /// The single value `v`.
    pub const fn point(v: f64) -> Self {
        Self { lo: v, hi: v }
    }

    /// The smallest interval holding `a` and `b`.
    pub fn hull(self, b: Interval) -> Self {
        Self {
            lo: self.lo.min(b.lo),
            hi: self.hi.max(b.hi),
        }
    }

    /// `[lo, hi]` widened outwards for the rounding of the operation that made it.
    fn rounded(lo: f64, hi: f64) -> Self {
        let ulps = |v: f64| v.abs() * (2.0 * f64::EPSILON) + f64::MIN_POSITIVE;
        Self {
            lo: lo - ulps(lo),
            hi: hi + ulps(hi),
        }
    }

    /// Every `a + b`.
    pub fn add(self, b: Interval) -> Self {
        Self::rounded(self.lo + b.lo, self.hi + b.hi)
    }

    /// Every `a − b`.
    pub fn sub(self, b: Interval) -> Self {
        Self::rounded(self.lo - b.hi, self.hi - b.lo)
    }

    /// Every `a·b`.
    pub fn mul(self, b: Interval) -> Self {
        let p = [
            self.lo * b.lo,
            self.lo * b.hi,
            self.hi * b.lo,
            self.hi * b.hi,
        ];
        let (lo, hi) = p
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                (l.min(v), h.max(v))
            });
        Self::rounded(lo, hi)
    }

    /// Every `k·a`.
    pub fn scale(self, k: f64) -> Self {
        self.mul(Self::point(k))
    }

    /// Every `a²` (not below zero, unlike `a·a`).
    pub fn square(self) -> Self {
        if self.lo <= 0.0 && self.hi >= 0.0 {
            let m = self.magnitude();
            Self {
                lo: 0.0,
                ..Self::rounded(0.0, m * m)
            }
        } else {
            let (a, b) = (self.lo * self.lo, self.hi * self.hi);
            Self::rounded(a.min(b), a.max(b))
        }
    }

    /// Every `a / b`, or `None` where `b` may be zero.
    pub fn div(self, b: Interval) -> Option<Self> {
        (b.lo > 0.0 || b.hi < 0.0).then(|| self.mul(Self::rounded(1.0 / b.hi, 1.0 / b.lo)))
    }

    /// The largest |a|.
    pub fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operations_hold_every_sampled_result() {
        // Each operation against the exact operation on a grid of operand values (in f64, whose
        // single rounding the widening covers).
        let (a, b) = (
            Interval { lo: -1.5, hi: 0.75 },
            Interval { lo: 0.2, hi: 3.0 },
        );
        let holds = |i: Interval, v: f64| i.lo <= v && v <= i.hi;
        for k in 0..=40 {
            let x = a.lo + (a.hi - a.lo) * k as f64 / 40.0;
            for l in 0..=40 {
                let y = b.lo + (b.hi - b.lo) * l as f64 / 40.0;
                assert!(holds(a.add(b), x + y));
                assert!(holds(a.sub(b), x - y));
                assert!(holds(a.mul(b), x * y));
                assert!(holds(a.div(b).unwrap(), x / y));
                assert!(holds(a.square(), x * x));
                assert!(holds(b.scale(-2.5), -2.5 * y));
            }
        }
        assert!(a.square().lo == 0.0 && a.square().hi >= 2.25);
        assert!(b.div(a).is_none());
        assert_eq!(a.magnitude(), 1.5);
    }
}
