//! AUTO against the best fixed solver of the run (`auto-ratio.txt`): per problem and tolerance,
//! AUTO's time, the fastest other solver and its time, and their ratio. With
//! `--auto-max-ratio X` a problem where AUTO is more than X times behind (or unsolved where some
//! other solver converged) makes the exit status 1: issue 27's rule that AUTO is never an order
//! of magnitude behind the library's best fixed solver, checked by the bench (wall-clock times
//! on a shared machine are not a unit test's business).

use super::csv::RunRecord;
use super::format::{format_time, tol_name};

/// The label AUTO's rows carry.
pub(super) const AUTO_LABEL: &str = "AUTO";

/// One (problem, tolerance): AUTO's time (None: not converged) against the best other solver's.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct AutoRatio {
    pub problem: String,
    pub contacts: usize,
    pub tolerance: f64,
    pub auto_time: Option<f64>,
    /// The fastest converged solver other than AUTO, with its time.
    pub best: Option<(String, f64)>,
}

impl AutoRatio {
    /// AUTO's time over the best fixed solver's: infinite when AUTO did not converge and some
    /// fixed solver did; None when no fixed solver converged.
    pub fn ratio(&self) -> Option<f64> {
        let (_, best) = self.best.as_ref()?;
        Some(match self.auto_time {
            Some(t) => t / best.max(1e-9),
            None => f64::INFINITY,
        })
    }
}

/// The ratios of every (problem, tolerance) where AUTO ran, in the records' order.
pub(super) fn auto_ratios(records: &[RunRecord]) -> Vec<AutoRatio> {
    records
        .iter()
        .filter(|r| r.solver == AUTO_LABEL)
        .map(|a| {
            let best = records
                .iter()
                .filter(|r| {
                    r.problem == a.problem
                        && r.tolerance == a.tolerance
                        && r.solver != AUTO_LABEL
                        && r.converged()
                })
                .min_by(|x, y| x.time_s.total_cmp(&y.time_s))
                .map(|r| (r.solver.clone(), r.time_s));
            AutoRatio {
                problem: a.problem.clone(),
                contacts: a.contacts,
                tolerance: a.tolerance,
                auto_time: a.converged().then_some(a.time_s),
                best,
            }
        })
        .collect()
}

/// The table of `auto-ratio.txt`, with the worst ratio per tolerance and the rows above
/// `max_ratio` marked.
pub(super) fn auto_ratio_table(ratios: &[AutoRatio], max_ratio: Option<f64>) -> String {
    let mut out = format!(
        "# AUTO against the fastest other solver of this run (ratio = AUTO's time / its time)\n\
         {:<44} {:>8} {:>9} {:>10} {:>16} {:>10} {:>8}\n",
        "problem", "contacts", "tolerance", "AUTO", "best other", "its time", "ratio"
    );
    for r in ratios {
        let ratio = r.ratio();
        let flag = match (ratio, max_ratio) {
            (Some(x), Some(m)) if x > m => "  <-- over the limit",
            _ => "",
        };
        out.push_str(&format!(
            "{:<44} {:>8} {:>9} {:>10} {:>16} {:>10} {:>8}{flag}\n",
            r.problem,
            r.contacts,
            tol_name(r.tolerance),
            r.auto_time.map_or("-".into(), format_time),
            r.best.as_ref().map_or("-", |(s, _)| s.as_str()),
            r.best.as_ref().map_or("-".into(), |&(_, t)| format_time(t)),
            ratio.map_or("-".into(), |x| format!("{x:.2}")),
        ));
    }
    let mut tols: Vec<f64> = ratios.iter().map(|r| r.tolerance).collect();
    tols.sort_by(|a, b| b.total_cmp(a));
    tols.dedup();
    for t in tols {
        let at: Vec<f64> = ratios
            .iter()
            .filter(|r| r.tolerance == t)
            .filter_map(AutoRatio::ratio)
            .collect();
        let worst = at.iter().copied().fold(f64::NAN, f64::max);
        let finite: Vec<f64> = at.iter().copied().filter(|x| x.is_finite()).collect();
        let geo = (finite.iter().map(|x| x.ln()).sum::<f64>() / finite.len().max(1) as f64).exp();
        out.push_str(&format!(
            "# tolerance {}: {} problems some other solver solves, worst ratio {worst:.2}, \
             geometric mean {geo:.2}, within 2x: {}, within 10x: {}\n",
            tol_name(t),
            at.len(),
            at.iter().filter(|&&x| x <= 2.0).count(),
            at.iter().filter(|&&x| x <= 10.0).count(),
        ));
    }
    out
}

/// The rows over `max_ratio`.
pub(super) fn over_limit(ratios: &[AutoRatio], max_ratio: f64) -> Vec<&AutoRatio> {
    ratios
        .iter()
        .filter(|r| r.ratio().is_some_and(|x| x > max_ratio))
        .collect()
}
