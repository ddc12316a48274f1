//! Rounding to an integer without a library call: `f64::round` and `f64::floor` are calls into
//! libm on baseline x86-64, and the roundings here run for every point or every surface
//! evaluation (a lenslet's grid node, a constant-angle spiral's step).

/// The integer nearest to `x` (halves upwards): `floor(x + 0.5)`. Below 2⁵¹ the sum with
/// 1.5·2⁵² rounds y to an integer in the floating-point unit (its ulp is 1 there, the
/// subtraction exact), faster than a saturating conversion to i64 and back, which serves
/// beyond.
pub fn nearest(x: f64) -> f64 {
    const ROUNDER: f64 = 6_755_399_441_055_744.0; // 1.5·2⁵²
    let y = x + 0.5;
    let t = if y.abs() < ROUNDER / 3.0 {
        (y + ROUNDER) - ROUNDER
    } else {
        y as i64 as f64
    };
    if t > y { t - 1.0 } else { t }
}
