//! The convex hull of the data points, the region where a scattered surface is defined:
//! Andrew's monotone chain (A. M. Andrew, "Another efficient algorithm for convex hulls in two
//! dimensions", Information Processing Letters 9 (1979) 216–219), O(N log N) once, and an
//! O(log H) point-in-convex-polygon test per query (the wedge of the fan from the first vertex
//! by binary search, then one edge).
//!
//! A query counts as inside when it lies within `tolerance` of the hull (outward), so that
//! points on its edges, such as the border of a grid, are inside despite rounding.

/// A convex polygon, counter-clockwise, without collinear vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexHull {
    vertices: Vec<[f64; 2]>,
    tolerance: f64,
}

/// Twice the signed area of the triangle (o, a, b): > 0 when b lies left of o→a.
fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

impl ConvexHull {
    /// The hull of `points`; `None` when they span no area (fewer than three points not on
    /// one line). `tolerance` (mm) is how far outside a query may lie and count as inside.
    pub fn new(points: &[[f64; 2]], tolerance: f64) -> Option<Self> {
        let mut p = points.to_vec();
        p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        p.dedup();
        if p.len() < 3 {
            return None;
        }
        let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
        for pass in 0..2 {
            let start = hull.len();
            let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
                Box::new(p.iter())
            } else {
                Box::new(p.iter().rev())
            };
            for &q in iter {
                while hull.len() >= start + 2
                    && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
                {
                    hull.pop();
                }
                hull.push(q);
            }
            hull.pop();
        }
        (hull.len() >= 3).then_some(Self {
            vertices: hull,
            tolerance,
        })
    }

    /// The vertices, counter-clockwise.
    pub fn vertices(&self) -> &[[f64; 2]] {
        &self.vertices
    }

    /// Signed distance from the edge a→b to q, positive inside (left of the edge).
    fn edge_distance(a: [f64; 2], b: [f64; 2], q: [f64; 2]) -> f64 {
        cross(a, b, q) / ((b[0] - a[0]).hypot(b[1] - a[1]))
    }

    /// Whether (x, y) lies in the hull or within the tolerance of it.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        self.inside_fan([x, y]) || self.near_edges([x, y])
    }

    /// The exact test: q lies in the wedge (v[k], v[k+1]) of the fan from v[0] found by
    /// binary search, on the inner side of its edge.
    fn inside_fan(&self, q: [f64; 2]) -> bool {
        let v = &self.vertices;
        let (o, n) = (v[0], v.len());
        if cross(o, v[1], q) < 0.0 || cross(o, v[n - 1], q) > 0.0 {
            return false;
        }
        let (mut lo, mut hi) = (1, n - 1);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if cross(o, v[mid], q) >= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        cross(v[lo], v[hi], q) >= 0.0
    }

    /// Whether q lies on the inner side of every edge or within the tolerance of it: the
    /// O(H) test, run only for queries the exact test puts outside.
    fn near_edges(&self, q: [f64; 2]) -> bool {
        let v = &self.vertices;
        (0..v.len()).all(|k| Self::edge_distance(v[k], v[(k + 1) % v.len()], q) >= -self.tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed};

    #[test]
    fn square_grid_and_degenerate_sets() {
        let pts: Vec<[f64; 2]> = (0..5)
            .flat_map(|i| (0..4).map(move |j| [i as f64 * 0.5, j as f64]))
            .collect();
        let h = ConvexHull::new(&pts, 1e-9).unwrap();
        assert_eq!(
            h.vertices(),
            &[[0.0, 0.0], [2.0, 0.0], [2.0, 3.0], [0.0, 3.0]]
        );
        assert!(h.contains(0.0, 0.0) && h.contains(2.0, 1.5) && h.contains(1.0, 3.0));
        assert!(h.contains(2.0 + 1e-10, 1.0));
        assert!(!h.contains(2.0 + 1e-8, 1.0) && !h.contains(-0.1, -0.1));
        assert!(ConvexHull::new(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]], 0.0).is_none());
        assert!(ConvexHull::new(&[[0.0, 0.0], [0.0, 0.0], [1.0, 0.0]], 0.0).is_none());
    }

    proptest! {
        #![proptest_config(Config {
            cases: 64, rng_seed: RngSeed::Fixed(4004), failure_persistence: None,
            ..Config::default()
        })]

        /// The hull contains every point, its vertices are points and turn left, and a query
        /// is inside exactly when adding it to the set leaves the hull's area unchanged (an
        /// independent test), away from the boundary.
        #[test]
        fn hull_matches_brute_force(
            pts in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 3..60),
            queries in prop::collection::vec((-1.2..1.2f64, -1.2..1.2f64), 20),
        ) {
            let pts: Vec<[f64; 2]> = pts.into_iter().map(|(x, y)| [x, y]).collect();
            let Some(h) = ConvexHull::new(&pts, 1e-12) else { return Ok(()); };
            let v = h.vertices();
            for k in 0..v.len() {
                prop_assert!(pts.contains(&v[k]));
                prop_assert!(cross(v[k], v[(k + 1) % v.len()], v[(k + 2) % v.len()]) > 0.0);
            }
            for p in &pts {
                prop_assert!(h.contains(p[0], p[1]));
            }
            let area = |v: &[[f64; 2]]| {
                (0..v.len()).map(|k| cross([0.0, 0.0], v[k], v[(k + 1) % v.len()])).sum::<f64>()
            };
            let a0 = area(v);
            for (x, y) in queries {
                let mut more = pts.clone();
                more.push([x, y]);
                let a1 = area(ConvexHull::new(&more, 0.0).unwrap().vertices());
                // Inside: the same vertices, the same area. Clearly outside: a larger one.
                if a1 == a0 {
                    prop_assert!(h.contains(x, y), "({}, {})", x, y);
                } else if a1 > a0 * (1.0 + 1e-9) {
                    prop_assert!(!h.contains(x, y), "({}, {})", x, y);
                }
            }
        }
    }
}
