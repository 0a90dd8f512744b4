//! Counts computed in floating point (steps, batch sizes, grid points) turned into integers
//! with their range checked: the one place a float becomes a count.

/// 2⁶⁴, the first float beyond `u64::MAX`.
const TWO_TO_64: f64 = 18_446_744_073_709_551_616.0;

/// `x` rounded up, as a count: `None` if `x` is not finite, below zero or at least 2⁶⁴.
pub fn ceil_count(x: f64) -> Option<u64> {
    to_count(x.ceil())
}

/// `x` rounded to the nearest integer, as a count: `None` if it is not finite, below zero
/// or at least 2⁶⁴.
pub fn round_count(x: f64) -> Option<u64> {
    to_count(x.round())
}

// The range is checked before the cast, which is then exact (`whole` is an integer).
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn to_count(whole: f64) -> Option<u64> {
    (whole.is_finite() && (0.0..TWO_TO_64).contains(&whole)).then_some(whole as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_in_range_and_refusals_outside() {
        assert_eq!(ceil_count(2.1), Some(3));
        assert_eq!(round_count(2.5), Some(3));
        assert_eq!(round_count(-0.4), Some(0));
        assert_eq!(
            ceil_count(9_007_199_254_740_993.0),
            Some(9_007_199_254_740_992)
        );
        assert_eq!(ceil_count(-1.0), None);
        assert_eq!(ceil_count(f64::NAN), None);
        assert_eq!(ceil_count(f64::INFINITY), None);
        assert_eq!(ceil_count(TWO_TO_64), None);
        assert_eq!(ceil_count(1e300), None);
        assert_eq!(ceil_count(TWO_TO_64 / 2.0), Some(1 << 63));
    }
}
