//! Rounding to an integer without a library call: `f64::round` and `f64::floor` are calls into
//! libm on baseline x86-64, and the roundings here run for every point or every surface
//! evaluation (a lenslet's grid node, a constant-angle spiral's step).

/// The integer nearest to `x` (halves upwards): `floor(x + 0.5)`, for |x| < 2⁶³. Below 2⁵¹
/// the sum with 1.5·2⁵² rounds y to an integer in the floating-point unit (its ulp is 1 there,
/// the subtraction exact), faster than the conversion to i64 and back that serves beyond (it
/// saturates past 2⁶³).
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_is_the_floor_of_the_value_and_a_half() {
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            1e15 + 0.5,
            -1e15 - 0.5,
        ];
        for e in [0, 10, 30, 50, 51, 52, 53, 60, 62] {
            let big = 2f64.powi(e);
            for x in [big, -big] {
                values.extend([x, x.next_up(), x.next_down(), x + 0.5, x - 0.5, x * 0.75]);
            }
        }
        // A pseudo-random sweep, halves and their neighbours included.
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..100_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let x = (seed >> 11) as f64 / 2f64.powi(30) - 4096.0;
            let half = x.floor() + 0.5;
            values.extend([x, half, half.next_up(), half.next_down()]);
        }
        for x in values {
            assert_eq!(nearest(x), (x + 0.5).floor(), "{x:e}");
        }
    }
}
