//! The report's running figures of a path ([`Stats`]), gathered one point at a time as the path
//! streams by, and joined exactly when the path was planned in slices ([`Stats::merge`]: the page's
//! workers each plan a stretch). A figure of two or three consecutive points (the Z slope, the
//! second difference of X, an X reversal, a run of loop points) that straddles a seam is computed
//! at the join from the points either side, which each slice keeps (its first two and last two),
//! in the order the whole walk would meet it, so the merged figures equal the walk's to the bit,
//! ties included (the first largest value wins in both).

use crate::path::PathPoint;
use serde::{Deserialize, Serialize};

/// Running figures of a path, or of a slice of it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Points seen.
    pub points: u64,
    pub(super) first_theta: f64,
    /// The first two points, for a join with the slice before.
    first: Option<Seen>,
    second: Option<Seen>,
    last: Option<Seen>,
    before_last: Option<Seen>,
    pub(super) z_min: f64,
    pub(super) z_max: f64,
    pub(super) sag_min: f64,
    pub(super) sag_max: f64,
    #[serde(with = "unbounded")]
    pub(super) max_slope: f64,
    pub(super) max_slope_at: (f64, f64),
    pub(super) arc_end: u64,
    pub(super) first_arc_end: Option<(f64, f64)>,
    /// Sign of the first and of the last non-zero X step.
    first_dx_sign: f64,
    last_dx_sign: f64,
    pub(super) x_reversals: u64,
    /// Largest |d²X/dC²|, mm/rad².
    #[serde(with = "unbounded")]
    pub(super) max_x_curv: f64,
    pub(super) max_x_curv_at: (f64, f64),
    pub(super) loops: u64,
    pub(super) loop_points: u64,
    pub(super) first_loop: Option<(f64, f64)>,
    /// Index of the first and of the last loop point, to tell runs apart.
    first_loop_index: Option<u64>,
    last_loop_index: Option<u64>,
}

/// What the figures of consecutive points need of a point: a third of its size, copied twice a
/// point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct Seen {
    rho: f64,
    theta: f64,
    z: f64,
}

impl Stats {
    /// Adds one point.
    pub fn add(&mut self, point: &PathPoint) {
        let p = &Seen {
            rho: point.rho,
            theta: point.theta,
            z: point.z,
        };
        match self.last {
            None => {
                self.first_theta = p.theta;
                (self.z_min, self.z_max) = (p.z, p.z);
                (self.sag_min, self.sag_max) = (point.contact[2], point.contact[2]);
                self.first = Some(*p);
            }
            Some(q) => {
                self.second.get_or_insert(*p);
                let sag = point.contact[2];
                self.extremes(p.z, p.z, sag, sag);
                self.step(&q, p);
                if let Some(o) = self.before_last {
                    self.x_curvature(&o, &q, p);
                }
            }
        }
        self.before_last = self.last;
        if point.at_arc_end {
            self.arc_end += 1;
            self.first_arc_end.get_or_insert((p.rho, p.theta));
        }
        self.points += 1;
        self.last = Some(*p);
    }

    /// Records that the two-way offset folds at `p`, which was just [added](Stats::add).
    pub fn add_loop_point(&mut self, p: &PathPoint) {
        if self.last_loop_index.is_none_or(|i| i + 1 != p.index) {
            self.loops += 1;
        }
        self.first_loop_index.get_or_insert(p.index);
        self.last_loop_index = Some(p.index);
        self.loop_points += 1;
        self.first_loop.get_or_insert((p.rho, p.theta));
    }

    /// The figures of this slice followed by those of `later`, the slice right after it: what
    /// one walk over both would have gathered.
    pub fn merge(mut self, later: Stats) -> Stats {
        let (Some(q), Some(p)) = (self.last, later.first) else {
            return if self.points == 0 { later } else { self };
        };
        // The figures across the seam, in the walk's order.
        self.step(&q, &p);
        if let Some(o) = self.before_last {
            self.x_curvature(&o, &q, &p);
        }
        if let Some(s) = later.second {
            self.x_curvature(&q, &p, &s);
        }
        // Then the later slice's own.
        if later.max_slope > self.max_slope {
            (self.max_slope, self.max_slope_at) = (later.max_slope, later.max_slope_at);
        }
        if later.max_x_curv > self.max_x_curv {
            (self.max_x_curv, self.max_x_curv_at) = (later.max_x_curv, later.max_x_curv_at);
        }
        self.dx_sign(later.first_dx_sign);
        self.x_reversals += later.x_reversals;
        if later.last_dx_sign != 0.0 {
            self.last_dx_sign = later.last_dx_sign;
        }
        self.extremes(later.z_min, later.z_max, later.sag_min, later.sag_max);
        self.arc_end += later.arc_end;
        self.first_arc_end = self.first_arc_end.or(later.first_arc_end);
        let joined = matches!(
            (self.last_loop_index, later.first_loop_index),
            (Some(i), Some(j)) if i + 1 == j
        );
        self.loops = self.loops + later.loops - u64::from(joined);
        self.loop_points += later.loop_points;
        self.first_loop = self.first_loop.or(later.first_loop);
        self.first_loop_index = self.first_loop_index.or(later.first_loop_index);
        self.last_loop_index = later.last_loop_index.or(self.last_loop_index);
        self.second = self.second.or(later.first);
        self.before_last = later.before_last.or(self.last);
        self.last = later.last;
        self.points += later.points;
        self
    }

    /// Total spindle angle, radians.
    pub fn total_angle(&self) -> f64 {
        self.last
            .map_or(0.0, |l| (l.theta - self.first_theta).abs())
    }

    fn extremes(&mut self, z_min: f64, z_max: f64, sag_min: f64, sag_max: f64) {
        self.z_min = self.z_min.min(z_min);
        self.z_max = self.z_max.max(z_max);
        self.sag_min = self.sag_min.min(sag_min);
        self.sag_max = self.sag_max.max(sag_max);
    }

    /// The step from `q` to `p`: its Z slope per degree of C and its X direction.
    fn step(&mut self, q: &Seen, p: &Seen) {
        let slope = ((p.z - q.z) / (p.theta - q.theta).to_degrees()).abs();
        if slope > self.max_slope {
            self.max_slope = slope;
            self.max_slope_at = (p.rho, p.theta);
        }
        let dx = p.rho - q.rho;
        if dx != 0.0 {
            self.dx_sign(dx.signum());
        }
    }

    /// The next non-zero X step goes the way of `sign` (0: no step): a reversal if the last
    /// went the other way.
    fn dx_sign(&mut self, sign: f64) {
        if sign == 0.0 {
            return;
        }
        if self.last_dx_sign != 0.0 && sign != self.last_dx_sign {
            self.x_reversals += 1;
        }
        if self.first_dx_sign == 0.0 {
            self.first_dx_sign = sign;
        }
        self.last_dx_sign = sign;
    }

    /// |d²X/dC²| at `q` from its neighbours `o` and `p`, on their (possibly unequal) C steps.
    fn x_curvature(&mut self, o: &Seen, q: &Seen, p: &Seen) {
        let (h1, h2) = ((q.theta - o.theta).abs(), (p.theta - q.theta).abs());
        if h1 > 0.0 && h2 > 0.0 {
            let d2 = (2.0 * ((p.rho - q.rho) / h2 - (q.rho - o.rho) / h1) / (h1 + h2)).abs();
            if d2 > self.max_x_curv {
                self.max_x_curv = d2;
                self.max_x_curv_at = (q.rho, q.theta);
            }
        }
    }
}

/// A largest ratio as JSON: a number, or `"inf"` where a step of C was zero (JSON has no
/// infinity, and the slices travel between the page's workers as JSON).
mod unbounded {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        match *v {
            f64::INFINITY => s.serialize_str("inf"),
            v => s.serialize_f64(v),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Value {
            Number(f64),
            Text(String),
        }
        match Value::deserialize(d)? {
            Value::Number(v) => Ok(v),
            Value::Text(t) if t == "inf" => Ok(f64::INFINITY),
            Value::Text(t) => Err(serde::de::Error::custom(format!("{t:?} is not a number"))),
        }
    }
}
