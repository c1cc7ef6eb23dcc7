//! The one float formatter behind every CSV, every `wavy eval` row and every snapshot.
//!
//! Numbers are written with [`SIGNIFICANT_DIGITS`] significant digits, fixed-point for
//! magnitudes in [1e-4, 1e6) and scientific otherwise, trailing zeros trimmed, `-0` written
//! as `0`. Rounding here is what makes outputs byte-stable across machines: the last bits of
//! a float depend on the libm and the instruction set, six digits do not.

/// Significant digits of every number this project writes.
pub const SIGNIFICANT_DIGITS: usize = 6;

/// Formats `x` with [`SIGNIFICANT_DIGITS`] significant digits (see the module doc).
/// Non-finite values are written `nan`, `inf`, `-inf`.
pub fn sig(x: f64) -> String {
    sig_digits(x, SIGNIFICANT_DIGITS)
}

/// Formats `x` with `digits` significant digits (≥ 1).
pub fn sig_digits(x: f64, digits: usize) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let digits = digits.max(1);
    // Round once, in scientific form; then decide how to print the rounded value.
    let sci = format!("{:.*e}", digits - 1, x);
    let (mantissa, exponent) = sci
        .split_once('e')
        .expect("`{:e}` always writes an exponent");
    let exponent: i32 = exponent.parse().expect("exponent is an integer");
    let rounded: f64 = sci.parse().expect("formatted float parses");
    if rounded == 0.0 {
        return "0".into();
    }
    let out = if (-4..6).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        trim_zeros(&format!("{rounded:.decimals$}"))
    } else {
        format!("{}e{exponent}", trim_zeros(mantissa))
    };
    out
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn six_significant_digits() {
        assert_eq!(sig(0.0), "0");
        assert_eq!(sig(-0.0), "0");
        assert_eq!(sig(1.0), "1");
        assert_eq!(sig(std::f64::consts::PI), "3.14159");
        assert_eq!(sig(-0.000123456789), "-0.000123457");
        assert_eq!(sig(1.23456789e-5), "1.23457e-5");
        assert_eq!(sig(123456789.0), "1.23457e8");
        assert_eq!(sig(999999.6), "1e6");
        assert_eq!(sig(0.1 + 0.2), "0.3");
        assert_eq!(sig(f64::NAN), "nan");
    }
}
