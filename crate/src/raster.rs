//! A square raster of values over the part disc: the form in which analyses (linearization
//! error, predicted form error) hand a map to the page and the command line. Row `j` lies at
//! `y = y0 + j·step`, column `i` at `x = x0 + i·step`; samples outside the part, or where no
//! value fell, are NaN.

/// A square map of values over the part, NaN where there is none.
#[derive(Debug, Clone, PartialEq)]
pub struct Raster {
    /// Samples per side.
    pub size: usize,
    /// x of column 0, mm.
    pub x0_mm: f64,
    /// y of row 0, mm.
    pub y0_mm: f64,
    /// Grid spacing, mm.
    pub step_mm: f64,
    /// Values row by row (`j·size + i`).
    pub values: Vec<f64>,
}

impl Raster {
    /// An empty (all NaN) `size` × `size` raster covering the disc of `radius_mm` about the
    /// origin; `size` is clamped to [2, 4096].
    pub fn over_part(radius_mm: f64, size: usize) -> Self {
        let size = size.clamp(2, 4096);
        Self {
            size,
            x0_mm: -radius_mm,
            y0_mm: -radius_mm,
            step_mm: 2.0 * radius_mm / (size - 1) as f64,
            values: vec![f64::NAN; size * size],
        }
    }

    /// The sample nearest to (x, y), if inside the raster.
    pub fn index_of(&self, x: f64, y: f64) -> Option<usize> {
        let i = ((x - self.x0_mm) / self.step_mm).round();
        let j = ((y - self.y0_mm) / self.step_mm).round();
        let n = self.size as f64;
        ((0.0..n).contains(&i) && (0.0..n).contains(&j))
            .then(|| j as usize * self.size + i as usize)
    }

    /// Keeps at the sample nearest to (x, y) the value of largest magnitude seen there.
    pub fn keep_largest(&mut self, x: f64, y: f64, value: f64) {
        if let Some(k) = self.index_of(x, y) {
            let v = &mut self.values[k];
            if v.is_nan() || value.abs() > v.abs() {
                *v = value;
            }
        }
    }

    /// The position of sample (i, j), mm.
    pub fn position(&self, i: usize, j: usize) -> (f64, f64) {
        (
            self.x0_mm + i as f64 * self.step_mm,
            self.y0_mm + j as f64 * self.step_mm,
        )
    }

    /// The smallest and largest value, ignoring NaN; None when every sample is NaN.
    pub fn range(&self) -> Option<(f64, f64)> {
        self.values
            .iter()
            .filter(|v| !v.is_nan())
            .fold(None, |acc, &v| match acc {
                None => Some((v, v)),
                Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_sit_on_the_grid_and_keep_the_largest_magnitude() {
        let mut r = Raster::over_part(2.0, 5);
        assert_eq!(r.step_mm, 1.0);
        assert_eq!(r.position(4, 0), (2.0, -2.0));
        assert_eq!(r.index_of(0.4, -0.4), Some(2 * 5 + 2));
        assert_eq!(r.index_of(2.6, 0.0), None);
        r.keep_largest(0.1, 0.1, 0.5);
        r.keep_largest(-0.2, 0.2, -0.7);
        r.keep_largest(0.0, 0.0, 0.6);
        assert_eq!(r.values[12], -0.7);
        assert_eq!(r.range(), Some((-0.7, -0.7)));
        assert_eq!(Raster::over_part(1.0, 3).range(), None);
    }
}
