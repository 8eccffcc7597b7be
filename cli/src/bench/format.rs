//! How tolerances, budgets and times are written in file names and tables.

use std::time::Duration;

/// `tolerance` formatted for file names and tables: `1e-8`.
pub(super) fn tol_name(t: f64) -> String {
    format!("{t:e}")
}

pub(super) fn duration_name(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s >= 1.0 {
        format!("{}s", trim_float(s))
    } else if s >= 1e-3 {
        format!("{}ms", trim_float(s * 1e3))
    } else if s >= 1e-6 {
        format!("{}us", trim_float(s * 1e6))
    } else {
        format!("{}ns", trim_float(s * 1e9))
    }
}

fn trim_float(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

pub(super) fn format_time(secs: f64) -> String {
    if !secs.is_finite() {
        return "-".to_string();
    }
    crate::units::format_time(Duration::from_secs_f64(secs))
}
