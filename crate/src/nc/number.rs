//! Fixed-point decimal formatting for NC words, without allocation: the value is rounded once to
//! an integer count of the last digit (`round(v·10^d)`, ties away from zero), then written left
//! to right, integer part and decimals each eight digits at once (SWAR on a 64-bit word) where
//! they fit, else digit pair by digit pair. Negative zero prints as zero, so `-0.000000` never
//! appears; NaN, infinities and values beyond ±9·10¹⁸ units of the last digit are refused.

pub use crate::job::output::MAX_DECIMALS;

/// 10^d for d = 0…9.
const POW10: [i64; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// `v` in units of the last of `decimals` digits, or `None` if it cannot be written.
///
/// The product `v·10^d` is rounded once in floating point; where that lands within 10⁻⁶ of a
/// half-way point the exact remainder `v·10^d − s` (one fused multiply-add) decides, so the
/// result is the correctly rounded decimal of the binary value `v`. The rounding is done on
/// the integer part (a truncating conversion) and the exact fraction beside it, as
/// `f64::round` does, without its library call: this runs for every word of a program.
pub fn scaled(v: f64, decimals: u32) -> Option<i64> {
    /// 2⁵²: every double at least this large is an integer.
    const INTEGRAL: f64 = 4_503_599_627_370_496.0;
    let p = POW10[decimals as usize] as f64;
    let product = v * p;
    if !product.is_finite() {
        return None;
    }
    if product.abs() >= INTEGRAL {
        // Already an integer.
        return (product.abs() < 9.0e18).then_some(product as i64);
    }
    let whole = product as i64;
    let fraction = product - whole as f64;
    let mut s = whole + i64::from(fraction >= 0.5) - i64::from(fraction <= -0.5);
    if (fraction.abs() - 0.5).abs() < 1e-6 {
        let rest = v.mul_add(p, -(s as f64));
        if rest > 0.5 || (rest == 0.5 && v > 0.0) {
            s += 1;
        } else if rest < -0.5 || (rest == -0.5 && v < 0.0) {
            s -= 1;
        }
    }
    Some(s)
}

/// The room [`put_scaled`] needs from where it writes: a sign, 19 digits, the point and a
/// leading zero, with room for its fixed-size stores past the text.
pub const MAX_SCALED_LEN: usize = 24;

/// Appends `units · 10^−decimals` with exactly `decimals` digits after the point
/// ([`put_scaled`] in a window of fixed size appended to `buf` and cut to the text's length: a
/// copy of a length known only at run time would be a library call for every word of a
/// program).
pub fn push_scaled(buf: &mut Vec<u8>, units: i64, decimals: u32) {
    let start = buf.len();
    buf.extend_from_slice(&[0; MAX_SCALED_LEN]);
    let end = put_scaled(&mut buf[start..], 0, units, decimals);
    buf.truncate(start + end);
}

/// Writes `units · 10^−decimals` with exactly `decimals` digits after the point at
/// `text[at..]`, which has room for [`MAX_SCALED_LEN`] bytes (bytes past the text may be
/// overwritten); returns where the text ends.
#[inline(always)]
pub fn put_scaled(text: &mut [u8], at: usize, units: i64, decimals: u32) -> usize {
    // The programs' usual decimals as constants: their divisions become multiplications.
    match decimals {
        3 => put_decimals(text, at, units, 3),
        5 => put_decimals(text, at, units, 5),
        6 => put_decimals(text, at, units, 6),
        d => put_decimals(text, at, units, d),
    }
}

/// [`put_scaled`]'s body, inlined into each of its cases: up to 8 decimals and 8 digits
/// before the point (every word of a usual program) left to right, a one-digit integer part as
/// its byte, a longer one and the decimals each as eight digits at once ([`eight_digits`]);
/// else digit pair by digit pair ([`put_by_pairs`]).
#[inline(always)]
fn put_decimals(text: &mut [u8], at: usize, units: i64, decimals: u32) -> usize {
    let mag = units.unsigned_abs();
    let scale = POW10[decimals as usize] as u64;
    let whole = mag / scale;
    if decimals > 8 || whole >= 100_000_000 {
        return put_by_pairs(text, at, units, decimals, whole);
    }
    let text = &mut text[at..at + MAX_SCALED_LEN];
    let fraction = mag - whole * scale;
    let mut i = usize::from(units < 0);
    text[0] = b'-';
    if whole < 10 {
        // The usual X and Z of a part: one digit.
        text[i] = b'0' + whole as u8;
        i += 1;
    } else {
        // Eight digits with their leading zeros, the first in the lowest byte: shifted down
        // by the zeros not written.
        let digits = whole.ilog10() as usize + 1;
        let w = eight_digits(whole as u32) >> (8 * (8 - digits));
        text[i..i + 8].copy_from_slice(&w.to_le_bytes());
        i += digits;
    }
    if decimals > 0 {
        text[i] = b'.';
        let f = eight_digits(fraction as u32) >> (8 * (8 - decimals));
        text[i + 1..i + 9].copy_from_slice(&f.to_le_bytes());
        i += 1 + decimals as usize;
    }
    at + i
}

/// The eight decimal digits of `n` < 10⁸ (leading zeros included) as ASCII bytes of a
/// little-endian word, the first digit in the lowest byte, by arithmetic on its lanes ("SWAR"):
/// `n` splits into two halves of four digits in 32-bit lanes, each into two pairs in 16-bit
/// lanes (x/100 as ⌊x·10486/2²⁰⌋, exact below 43 699), each pair into two digits in bytes (x/10
/// as ⌊x·103/2¹⁰⌋, exact below 179): a few multiplications, no chain of divisions a digit
/// pair, no table.
#[inline(always)]
fn eight_digits(n: u32) -> u64 {
    debug_assert!(n < 100_000_000);
    let v = u64::from(n / 10_000) | (u64::from(n % 10_000) << 32);
    let hundreds = ((v * 10_486) >> 20) & 0x0000_007f_0000_007f;
    let v = hundreds | ((v - hundreds * 100) << 16);
    let tens = ((v * 103) >> 10) & 0x000f_000f_000f_000f;
    let v = tens | ((v - tens * 10) << 8);
    v + 0x3030_3030_3030_3030
}

/// [`put_decimals`] for any decimals and magnitude, right to left digit pair by digit pair,
/// its length counted first; `whole` is the magnitude's integer part.
fn put_by_pairs(text: &mut [u8], at: usize, units: i64, decimals: u32, whole: u64) -> usize {
    let mut mag = units.unsigned_abs();
    let digits = whole.checked_ilog10().map_or(1, |l| l as usize + 1);
    let len = usize::from(units < 0) + digits + usize::from(decimals > 0) + decimals as usize;
    let text = &mut text[at..at + len];
    let mut i = len;
    let mut fraction = decimals as usize;
    while fraction >= 2 {
        i -= 2;
        put_pair(text, i, mag % 100);
        mag /= 100;
        fraction -= 2;
    }
    if fraction == 1 {
        i -= 1;
        text[i] = b'0' + (mag % 10) as u8;
        mag /= 10;
    }
    if decimals > 0 {
        i -= 1;
        text[i] = b'.';
    }
    i = put_digits(text, i, mag);
    if units < 0 {
        i -= 1;
        text[i] = b'-';
    }
    debug_assert_eq!(i, 0, "the length counted is the text's");
    at + len
}

/// 10^`decimals` (at most [`MAX_DECIMALS`]).
pub fn pow10(decimals: u32) -> i64 {
    POW10[decimals as usize]
}

/// Writes the two digits of `n` (< 100) at `tmp[i..i + 2]`.
fn put_pair(tmp: &mut [u8], i: usize, n: u64) {
    let k = n as usize * 2;
    tmp[i..i + 2].copy_from_slice(&PAIRS[k..k + 2]);
}

/// Writes the decimal digits of `n` (at least one) ending just before `tmp[end]`; returns
/// where they start.
fn put_digits(tmp: &mut [u8], end: usize, mut n: u64) -> usize {
    let mut i = end;
    while n >= 100 {
        i -= 2;
        put_pair(tmp, i, n % 100);
        n /= 100;
    }
    if n >= 10 {
        i -= 2;
        put_pair(tmp, i, n);
    } else {
        i -= 1;
        tmp[i] = b'0' + n as u8;
    }
    i
}

/// Appends `v` rounded to `decimals` digits; `false` (and nothing appended) if it cannot be.
pub fn push_fixed(buf: &mut Vec<u8>, v: f64, decimals: u32) -> bool {
    match scaled(v, decimals) {
        Some(u) => {
            push_scaled(buf, u, decimals);
            true
        }
        None => false,
    }
}

/// "00" … "99": two digits a division.
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

#[cfg(test)]
mod tests {
    use super::*;

    fn fixed(v: f64, d: u32) -> String {
        let mut b = Vec::new();
        assert!(push_fixed(&mut b, v, d));
        String::from_utf8(b).unwrap()
    }

    #[test]
    fn matches_std_formatting() {
        for &v in &[
            0.0,
            1.5,
            -2.25,
            123.456789,
            -0.0004,
            5.0,
            1e-9,
            -7.1234565,
            359.999_996,
            1e6 + 0.25,
            0.1 + 0.2,
            2.675,
        ] {
            for d in [0, 3, 5, 6, 9] {
                let std = format!("{:.*}", d as usize, v);
                let std = if std
                    .trim_start_matches('-')
                    .chars()
                    .all(|c| c == '0' || c == '.')
                {
                    std.trim_start_matches('-').to_string()
                } else {
                    std
                };
                // Both round the exact binary value; they differ only on exact binary ties
                // (std: to even, ours: away from zero), which these values avoid.
                assert_eq!(fixed(v, d), std, "{v} with {d} decimals");
            }
        }
    }

    #[test]
    fn digits_match_std_for_every_length() {
        let mut n = 0u64;
        let mut b = Vec::new();
        for k in 0..2000u64 {
            for v in [k, n, n.wrapping_sub(1), u64::MAX - k] {
                b.clear();
                let mut tmp = [0u8; 24];
                let i = put_digits(&mut tmp, 24, v);
                b.extend_from_slice(&tmp[i..]);
                assert_eq!(b, v.to_string().as_bytes());
            }
            n = n.wrapping_mul(10).wrapping_add(k % 10 + 1);
        }
    }

    #[test]
    fn scaled_text_is_the_integer_with_its_point_placed() {
        // Against std's integer formatting with the point inserted: every digit count of the
        // magnitude, both signs, every number of decimals.
        let mut buf = b"G1 X".to_vec();
        for decimals in 0..=MAX_DECIMALS {
            let mut mag = 0i64;
            for k in 0..19 {
                for units in [mag, -mag, mag + 7, -(mag + 7)] {
                    let digits = units.unsigned_abs().to_string();
                    let digits = format!("{digits:0>width$}", width = decimals as usize + 1);
                    let (int, frac) = digits.split_at(digits.len() - decimals as usize);
                    let sign = if units < 0 { "-" } else { "" };
                    let point = if decimals > 0 { "." } else { "" };
                    buf.truncate(4);
                    push_scaled(&mut buf, units, decimals);
                    assert_eq!(
                        String::from_utf8(buf[4..].to_vec()).unwrap(),
                        format!("{sign}{int}{point}{frac}"),
                        "{units} with {decimals} decimals"
                    );
                }
                mag = mag * 10 + (k % 9 + 1);
            }
        }
        for (units, text) in [
            (i64::MAX, "9223372036.854775807"),
            (i64::MIN, "-9223372036.854775808"),
        ] {
            buf.truncate(4);
            push_scaled(&mut buf, units, 9);
            assert_eq!(String::from_utf8(buf[4..].to_vec()).unwrap(), text);
        }
    }

    #[test]
    fn scaled_text_matches_std_on_random_magnitudes() {
        // Both ways of writing (eight digits at once, digit pairs) against std's integer text
        // with the point placed, on magnitudes spread over every digit count.
        let mut x = 0x9e37_79b9_7f4a_7c15_u64;
        let mut buf = Vec::new();
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let units = (x as i64) >> (x % 64);
            for decimals in 0..=MAX_DECIMALS {
                let digits = units.unsigned_abs().to_string();
                let digits = format!("{digits:0>width$}", width = decimals as usize + 1);
                let (int, frac) = digits.split_at(digits.len() - decimals as usize);
                let sign = if units < 0 { "-" } else { "" };
                let point = if decimals > 0 { "." } else { "" };
                buf.clear();
                push_scaled(&mut buf, units, decimals);
                assert_eq!(buf, format!("{sign}{int}{point}{frac}").as_bytes());
            }
        }
    }

    #[test]
    fn the_rounding_is_f64_round_of_the_product_away_from_ties() {
        // Against the library's round over products spread across every magnitude written,
        // away from the near-ties the exact remainder decides (those: the test below).
        let mut x = 0.123_456_789_f64;
        for k in 0..200_000 {
            x = (x * 7.3 + 0.37).fract();
            let v = (x - 0.5) * 10f64.powi(k % 14 - 4);
            for d in [0, 3, 4, 6, 7] {
                let product = v * 10f64.powi(d as i32);
                if ((product - product.trunc()).abs() - 0.5).abs() >= 1e-6 {
                    assert_eq!(scaled(v, d), Some(product.round() as i64), "{v} {d}");
                }
            }
        }
        assert_eq!(scaled(4.6e15, 0), Some(4_600_000_000_000_000));
        assert_eq!(scaled(-8.9e12, 6), Some((-8.9e12f64 * 1e6) as i64));
        assert_eq!(scaled(9.1e12, 6), None);
    }

    #[test]
    fn exact_ties_round_away_from_zero() {
        assert_eq!(fixed(2.5, 0), "3");
        assert_eq!(fixed(-2.5, 0), "-3");
        assert_eq!(fixed(0.125, 2), "0.13");
    }

    #[test]
    fn negative_zero_and_small_negatives_print_as_zero() {
        assert_eq!(fixed(-0.0, 6), "0.000000");
        assert_eq!(fixed(-4e-7, 6), "0.000000");
        assert_eq!(fixed(-6e-7, 6), "-0.000001");
    }

    #[test]
    fn non_finite_and_huge_values_are_refused() {
        let mut b = Vec::new();
        assert!(!push_fixed(&mut b, f64::NAN, 6));
        assert!(!push_fixed(&mut b, f64::INFINITY, 6));
        assert!(!push_fixed(&mut b, 1e13, 6));
        assert!(b.is_empty());
    }
}
