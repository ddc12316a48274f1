//! Linear least squares over many points through the normal equations `AᵀA·x = Aᵀb`, the
//! shared tool of the registration and the Zernike fit: millions of measured points, a few to
//! 37 unknowns, so the k × k sums are accumulated in one pass (in parallel, each worker over a
//! fixed run of points, summed in order, so the result does not depend on timing) and solved by
//! nalgebra: Cholesky when the system is well conditioned, else the singular value
//! decomposition's least-norm solution with singular values below [`SINGULAR`] of the largest
//! treated as zero. The columns are scaled to unit length before either (Jacobi scaling), so
//! unknowns of different units (µm of piston, µrad of tilt) do not spoil the conditioning.

use crate::parallel::fill_chunks;
use nalgebra::{DMatrix, DVector};

/// The least work (rows × k²) summed on several threads.
const MIN_PARALLEL_WORK: usize = 1 << 16;

/// The parts a larger sum is split into (spread over the threads).
const PARTS: usize = 16;

/// Relative threshold of the singular values kept by the fallback solve.
pub const SINGULAR: f64 = 1e-12;

/// The sums `AᵀA` (full, symmetric) and `Aᵀb` of k unknowns.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalEquations {
    /// AᵀA, k × k.
    pub ata: DMatrix<f64>,
    /// Aᵀb, k.
    pub atb: DVector<f64>,
}

impl NormalEquations {
    /// The sums over rows `0 … count`, row i given by `row(i, a_row, &mut b)` (it fills the k
    /// values of the row and its right-hand side). The first error in row order stops it.
    pub fn accumulate<E: Send>(
        count: usize,
        k: usize,
        row: impl Fn(usize, &mut [f64], &mut f64) -> Result<(), E> + Sync,
    ) -> Result<Self, E> {
        // Small sums (a local fit of a few points, called per grid node from threads already)
        // are one part, summed here: a thread costs more than they do. Larger ones are summed
        // in a fixed number of parts, whatever the number of threads, so that the result is the
        // same on every machine and in the page.
        let parts = if count * k * k < MIN_PARALLEL_WORK {
            1
        } else {
            PARTS
        };
        let mut parts = vec![(vec![0.0; k * k], vec![0.0; k]); parts];
        let per = count.div_ceil(parts.len()).max(1);
        fill_chunks(&mut parts, |first, out| {
            let mut a = vec![0.0; k];
            for (j, (ata, atb)) in out.iter_mut().enumerate() {
                let start = ((first + j) * per).min(count);
                let end = (start + per).min(count);
                for i in start..end {
                    let mut b = 0.0;
                    row(i, &mut a, &mut b)?;
                    for p in 0..k {
                        atb[p] += a[p] * b;
                        let line = &mut ata[p * k..(p + 1) * k];
                        for q in p..k {
                            line[q] += a[p] * a[q];
                        }
                    }
                }
            }
            Ok(())
        })?;
        let mut ata = DMatrix::<f64>::zeros(k, k);
        let mut atb = DVector::<f64>::zeros(k);
        for (sums, rhs) in &parts {
            for p in 0..k {
                atb[p] += rhs[p];
                for q in p..k {
                    ata[(p, q)] += sums[p * k + q];
                }
            }
        }
        for p in 0..k {
            for q in 0..p {
                ata[(p, q)] = ata[(q, p)];
            }
        }
        Ok(Self { ata, atb })
    }

    /// The least-squares solution, and whether the system was singular (the least-norm
    /// solution taken).
    pub fn solve(&self) -> (DVector<f64>, bool) {
        solve_symmetric(&self.ata, &self.atb)
    }

    /// The sums restricted to the unknowns `keep` (in that order).
    pub fn select(&self, keep: &[usize]) -> Self {
        let k = keep.len();
        Self {
            ata: DMatrix::from_fn(k, k, |i, j| self.ata[(keep[i], keep[j])]),
            atb: DVector::from_fn(k, |i, _| self.atb[keep[i]]),
        }
    }

    /// The multiple correlation of column `i` with the others: √(1 − s²/t²), s² the squared
    /// length of what of column i the others cannot express, t² its squared length about its
    /// mean (the column `ones` holds 1 in every row). 1 for a column that does not vary.
    pub fn correlation(&self, i: usize, ones: usize) -> f64 {
        let k = self.ata.nrows();
        let others: Vec<usize> = (0..k).filter(|&j| j != i).collect();
        let sub = self.select(&others);
        let cross = DVector::from_fn(others.len(), |p, _| self.ata[(others[p], i)]);
        let (x, _) = solve_symmetric(&sub.ata, &cross);
        let aii = self.ata[(i, i)];
        let unexplained = aii - cross.dot(&x);
        let n = self.ata[(ones, ones)];
        let centred = aii - self.ata[(ones, i)].powi(2) / n;
        if centred.is_nan() || centred <= 1e-24 * aii.max(f64::MIN_POSITIVE) {
            return 1.0;
        }
        (1.0 - (unexplained / centred).clamp(0.0, 1.0)).sqrt()
    }
}

/// Solves the symmetric positive semi-definite system `a·x = b` with Jacobi scaling: Cholesky
/// when well conditioned, else the SVD's least-norm solution. Returns the solution and whether
/// the fallback was taken.
pub fn solve_symmetric(a: &DMatrix<f64>, b: &DVector<f64>) -> (DVector<f64>, bool) {
    let k = a.nrows();
    let scale: Vec<f64> = (0..k)
        .map(|i| {
            let d = a[(i, i)];
            if d > 0.0 { 1.0 / d.sqrt() } else { 0.0 }
        })
        .collect();
    let scaled = DMatrix::from_fn(k, k, |i, j| a[(i, j)] * scale[i] * scale[j]);
    let rhs = DVector::from_fn(k, |i, _| b[i] * scale[i]);
    let unscale = |y: DVector<f64>| DVector::from_fn(k, |i, _| y[i] * scale[i]);
    if let Some(chol) = scaled.clone().cholesky() {
        let smallest = chol
            .l_dirty()
            .diagonal()
            .iter()
            .fold(f64::INFINITY, |m, v| m.min(v.abs()));
        if smallest * smallest > SINGULAR {
            return (unscale(chol.solve(&rhs)), false);
        }
    }
    let svd = scaled.svd(true, true);
    let eps = SINGULAR * svd.singular_values.max();
    match svd.solve(&rhs, eps) {
        Ok(y) => (unscale(y), true),
        Err(_) => (DVector::zeros(k), true),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_is_fitted_and_correlations_are_those_of_the_columns() {
        // z = 2 + 3x − y on a grid; columns 1, x, y, and x + 1e-3·x² (nearly x).
        let pts: Vec<(f64, f64)> = (0..400)
            .map(|i| ((i % 20) as f64 - 9.5, (i / 20) as f64 - 9.5))
            .collect();
        let ne = NormalEquations::accumulate(pts.len(), 3, |i, a, b| {
            let (x, y) = pts[i];
            a.copy_from_slice(&[1.0, x, y]);
            *b = 2.0 + 3.0 * x - y;
            Ok::<(), ()>(())
        })
        .unwrap();
        let (x, singular) = ne.solve();
        assert!(!singular);
        assert!(
            (x[0] - 2.0).abs() < 1e-12 && (x[1] - 3.0).abs() < 1e-12 && (x[2] + 1.0).abs() < 1e-12
        );
        // x and y are uncorrelated on a square grid.
        assert!(ne.correlation(1, 0) < 1e-12);
        let ne = NormalEquations::accumulate(pts.len(), 4, |i, a, b| {
            let (x, y) = pts[i];
            a.copy_from_slice(&[1.0, x, y, x + 1e-3 * x * x]);
            *b = 0.0;
            Ok::<(), ()>(())
        })
        .unwrap();
        let c = ne.correlation(3, 0);
        assert!(c > 0.99 && c < 1.0, "{c}");
        // A column equal to another is fully correlated, and the solve falls back.
        let ne = NormalEquations::accumulate(pts.len(), 3, |i, a, b| {
            let (x, _) = pts[i];
            a.copy_from_slice(&[1.0, x, 2.0 * x]);
            *b = x;
            Ok::<(), ()>(())
        })
        .unwrap();
        assert!((ne.correlation(2, 0) - 1.0).abs() < 1e-9);
        let (x, singular) = ne.solve();
        assert!(singular && (x[1] + 2.0 * x[2] - 1.0).abs() < 1e-9, "{x}");
    }
}
