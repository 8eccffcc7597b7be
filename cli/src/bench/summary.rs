//! The `summary.txt` tables: per solver and tolerance, or per solver and budget.

use std::collections::BTreeMap;
use std::time::Duration;

use super::csv::RunRecord;
use super::format::{duration_name, format_time};
use super::profile::PerformanceProfile;
use super::stats::median;

/// Per solver and tolerance: problems solved, fastest (rho_s(1)), total time of all runs,
/// median time over the solved problems.
pub(super) fn tolerance_summary(
    records: &[RunRecord],
    labels: &[String],
    tols: &[f64],
    n_problems: usize,
) -> String {
    let mut out = String::new();
    out.push_str(&format!(
        "{:<16} {:>9} {:>10} {:>8} {:>12} {:>14}\n",
        "solver", "tolerance", "solved", "fastest", "total time", "median solved"
    ));
    for &tol in tols {
        let at_tol: Vec<&RunRecord> = records.iter().filter(|r| r.tolerance == tol).collect();
        let profile = tolerance_profile(&at_tol, labels);
        for (s, label) in labels.iter().enumerate() {
            let mine: Vec<&&RunRecord> = at_tol.iter().filter(|r| &r.solver == label).collect();
            let solved: Vec<f64> = mine
                .iter()
                .filter(|r| r.converged())
                .map(|r| r.time_s)
                .collect();
            let total: f64 = mine.iter().map(|r| r.time_s).sum();
            let fastest = (profile.rho(s, 1.0) * profile.n_problems() as f64).round() as usize;
            out.push_str(&format!(
                "{:<16} {:>9} {:>10} {:>8} {:>12} {:>14}\n",
                label,
                crate::units::scientific(tol),
                format!("{}/{}", solved.len(), n_problems),
                fastest,
                format_time(total),
                format_time(if solved.is_empty() {
                    f64::NAN
                } else {
                    median(solved)
                }),
            ));
        }
    }
    out
}

/// The performance profile of the records of one tolerance (times of unsolved runs: None).
pub(super) fn tolerance_profile(at_tol: &[&RunRecord], labels: &[String]) -> PerformanceProfile {
    let mut by_problem: BTreeMap<&str, Vec<Option<f64>>> = BTreeMap::new();
    for r in at_tol {
        let row = by_problem
            .entry(r.problem.as_str())
            .or_insert_with(|| vec![None; labels.len()]);
        if let Some(s) = labels.iter().position(|l| *l == r.solver) {
            if r.converged() {
                row[s] = Some(r.time_s);
            }
        }
    }
    let times: Vec<Vec<Option<f64>>> = by_problem.into_values().collect();
    PerformanceProfile::new(&times, labels.len())
}

/// Per solver and budget: median and worst error over the problems, problems under 1e-4, 1e-6,
/// 1e-8.
pub(super) fn budget_summary(
    records: &[RunRecord],
    labels: &[String],
    budgets: &[Duration],
    tol: f64,
    n_problems: usize,
) -> String {
    let mut out = format!(
        "# error reached within each wall-clock budget (tolerance {}, so the budget stops the run)\n",
        crate::units::scientific(tol)
    );
    out.push_str(&format!(
        "{:<16} {:>8} {:>12} {:>12} {:>9} {:>9} {:>9}\n",
        "solver", "budget", "median error", "worst error", "<= 1e-4", "<= 1e-6", "<= 1e-8"
    ));
    for &b in budgets {
        for label in labels {
            let errors: Vec<f64> = records
                .iter()
                .filter(|r| &r.solver == label && r.time_budget_s == b.as_secs_f64())
                .map(|r| r.error)
                .collect();
            let under = |x: f64| {
                format!(
                    "{}/{}",
                    errors.iter().filter(|&&e| e <= x).count(),
                    n_problems
                )
            };
            let worst = errors.iter().copied().fold(f64::NAN, f64::max);
            out.push_str(&format!(
                "{:<16} {:>8} {:>12} {:>12} {:>9} {:>9} {:>9}\n",
                label,
                duration_name(b),
                crate::units::scientific(median(errors.clone())),
                crate::units::scientific(worst),
                under(1e-4),
                under(1e-6),
                under(1e-8),
            ));
        }
    }
    out
}
