//! Numbers as the command reads and prints them: the tolerance flags (`fc3d solve --tol`,
//! `fc3d bench --tol`), errors in C's `%.2e` style and times with a unit, in every table.

use std::time::Duration;

/// A tolerance flag: a finite number >= 0.
pub(crate) fn parse_tolerance(s: &str) -> Result<f64, String> {
    let x: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if x.is_finite() && x >= 0.0 {
        Ok(x)
    } else {
        Err(format!("the tolerance must be finite and >= 0, got {s}"))
    }
}

/// `x` as `d.dde±XX`, like C's `%.2e`.
pub(crate) fn scientific(x: f64) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    let s = format!("{x:.2e}");
    match s.split_once('e') {
        Some((mantissa, exp)) => {
            let (sign, digits) = match exp.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', exp),
            };
            format!("{mantissa}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

/// A duration with the unit that suits it: `12.3 µs`, `12.35 ms`, `12.345 s`.
pub(crate) fn format_time(t: Duration) -> String {
    let us = t.as_secs_f64() * 1e6;
    if us < 1e3 {
        format!("{us:.1} µs")
    } else if us < 1e6 {
        format!("{:.2} ms", us / 1e3)
    } else {
        format!("{:.3} s", us / 1e6)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scientific_format() {
        assert_eq!(scientific(2.5912e-9), "2.59e-09");
        assert_eq!(scientific(0.0), "0.00e+00");
        assert_eq!(scientific(1.27e-6), "1.27e-06");
        assert_eq!(scientific(3.0e120), "3.00e+120");
        assert_eq!(scientific(f64::NAN), "NaN");
    }

    #[test]
    fn time_format() {
        assert_eq!(format_time(Duration::from_nanos(12_345)), "12.3 µs");
        assert_eq!(format_time(Duration::from_micros(12_345)), "12.35 ms");
        assert_eq!(format_time(Duration::from_millis(12_345)), "12.345 s");
    }
}
