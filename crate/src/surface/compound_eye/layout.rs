//! Where the elements and lenslets of a compound eye sit in XY: element centres on a hexagonal
//! grid of rings about the axis, lenslet centres in hexagonally packed rows about each element
//! centre (paper 000, section "Experimental validation": "seven single-compound eye elements
//! arranged in a hexagonal layout", "17 lenses arranged in a hexagonal layout").

/// Spacing of hexagonally packed rows, in pitches: √3/2.
const ROW_SPACING: f64 = 0.866_025_403_784_438_6;

/// Number of centres within `rings` rings of a hexagonal grid: 1 + 3·n·(n + 1).
pub fn hexagon_count(rings: u32) -> u64 {
    let n = u64::from(rings);
    1 + 3 * n * (n + 1)
}

/// The centres of a hexagonal grid of pitch `pitch` within `rings` rings of the origin: the nodes
/// `pitch·(i + j/2, j·√3/2)` whose hexagonal distance `max(|i|, |j|, |i + j|)` is at most
/// `rings`, rows along X, ordered by row (j) then along the row (i).
pub fn element_centres(rings: u32, pitch: f64) -> Vec<(f64, f64)> {
    let n = i64::from(rings);
    let mut out = Vec::new();
    for j in -n..=n {
        for i in -n..=n {
            if (i + j).abs() <= n {
                let (fi, fj) = (i as f64, j as f64);
                out.push(((fi + 0.5 * fj) * pitch, fj * ROW_SPACING * pitch));
            }
        }
    }
    out
}

/// Lenslet centres relative to their element's centre: row k of `rows.len()` rows lies at
/// `y = (k − (m − 1)/2)·pitch·√3/2` and holds `rows[k]` lenslets at
/// `x = (i − (rows[k] − 1)/2)·pitch`, so every row is centred on the element; rows whose counts
/// differ by one interleave in a hexagonal packing (paper 000's 17 = 3 + 4 + 3 + 4 + 3).
pub fn lenslet_offsets(rows: &[u32], pitch: f64) -> Vec<(f64, f64)> {
    let m = rows.len() as f64;
    let mut out = Vec::new();
    for (k, &count) in rows.iter().enumerate() {
        let y = (k as f64 - (m - 1.0) / 2.0) * ROW_SPACING * pitch;
        for i in 0..count {
            let x = (f64::from(i) - (f64::from(count) - 1.0) / 2.0) * pitch;
            out.push((x, y));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rings_hold_one_seven_nineteen_centres_a_pitch_apart() {
        for (rings, count) in [(0, 1), (1, 7), (2, 19), (3, 37)] {
            let c = element_centres(rings, 2.0);
            assert_eq!(c.len(), count);
            assert_eq!(hexagon_count(rings), count as u64);
        }
        // Ring 1: six neighbours at exactly one pitch, 60° apart.
        let c = element_centres(1, 2.0);
        let mut angles: Vec<f64> = c
            .iter()
            .filter(|(x, y)| x.hypot(*y) > 1.0)
            .map(|(x, y)| {
                assert!((x.hypot(*y) - 2.0).abs() < 1e-15);
                y.atan2(*x).to_degrees().rem_euclid(360.0)
            })
            .collect();
        angles.sort_by(f64::total_cmp);
        for (k, a) in angles.iter().enumerate() {
            assert!((a - 60.0 * k as f64).abs() < 1e-12, "{angles:?}");
        }
        assert!((ROW_SPACING - 3f64.sqrt() / 2.0).abs() < 1e-16);
    }

    #[test]
    fn paper_rows_pack_seventeen_lenslets_hexagonally() {
        let o = lenslet_offsets(&[3, 4, 3, 4, 3], 1.0);
        assert_eq!(o.len(), 17);
        // One lenslet at the element centre, and every lenslet's nearest neighbours a pitch away.
        assert!(o.iter().any(|&(x, y)| x == 0.0 && y == 0.0));
        for &(x, y) in &o {
            let nearest = o
                .iter()
                .map(|&(u, v)| (u - x).hypot(v - y))
                .filter(|&d| d > 0.0)
                .fold(f64::INFINITY, f64::min);
            assert!((nearest - 1.0).abs() < 1e-15, "({x}, {y}): {nearest}");
        }
        // Centred: the offsets sum to zero.
        let (sx, sy) = o.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
        assert!(sx.abs() < 1e-15 && sy.abs() < 1e-15);
    }
}
