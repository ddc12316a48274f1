//! The four-point mean (paper 004 section 3, after Hu et al., "An accurate interpolator for FTS
//! diamond turning of optical freeform surface", Int. J. Adv. Manuf. Technol. 73 (2014)):
//! the height at a query is the mean of the heights of its four nearest data points. The
//! surface is piecewise constant: flat (zero gradient and Hessian) between switches of the
//! four-point set, where it steps — the "obvious steps" of paper 004's Figure 3.

use crate::surface::Local;

/// The mean of `z` (the heights of the four neighbours), flat.
pub fn local(z: &[f64]) -> Local {
    Local {
        z: z.iter().sum::<f64>() / z.len().max(1) as f64,
        ..Local::default()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn mean_and_flat() {
        let l = super::local(&[1.0, 2.0, 4.0, 5.0]);
        assert_eq!(l.z, 3.0);
        assert_eq!((l.zx, l.zy, l.zxx, l.zxy, l.zyy), (0.0, 0.0, 0.0, 0.0, 0.0));
    }
}
