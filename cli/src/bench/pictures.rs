//! The pictures: a performance profile per tolerance, and per problem family the work–precision
//! (tolerance mode) or error-within-budget (budget mode) curves.

use std::path::PathBuf;
use std::time::Duration;

use super::csv::RunRecord;
use super::format::tol_name;
use super::plan::Plan;
use super::plot;
use super::problems::Problem;
use super::stats::median;
use super::summary::tolerance_profile;

pub(super) fn profile_pictures(
    records: &[RunRecord],
    problems: &[Problem],
    labels: &[String],
    legends: &[String],
    tols: &[f64],
    dir: &std::path::Path,
) -> Vec<Result<Vec<PathBuf>, String>> {
    tols.iter()
        .map(|&tol| {
            let at_tol: Vec<&RunRecord> = records.iter().filter(|r| r.tolerance == tol).collect();
            let profile = tolerance_profile(&at_tol, labels);
            let picture = plot::ProfilePicture {
                title: format!(
                    "Performance profile, tolerance {}, {} problems",
                    tol_name(tol),
                    problems.len()
                ),
                profile: &profile,
                solver_names: legends,
            };
            plot::save(&picture, dir, &format!("profile-{}", tol_name(tol)))
        })
        .collect()
}

/// A family name usable in a file name.
fn file_safe(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Work–precision (tolerance mode) or error-within-budget (budget mode) pictures, one per
/// problem family: per solver, the median time (budget mode: the budget) and the median error
/// over the family's problems at each level, with every run as a faint dot.
pub(super) fn family_pictures(
    records: &[RunRecord],
    problems: &[Problem],
    labels: &[String],
    legends: &[String],
    levels: &[(f64, Duration, usize)],
    plan: &Plan,
    dir: &std::path::Path,
) -> Vec<Result<Vec<PathBuf>, String>> {
    let mut families: Vec<&str> = problems.iter().map(|p| p.family.as_str()).collect();
    families.sort();
    families.dedup();
    // Tolerance mode: x = the time the run took; budget mode: x = the budget given (runs that
    // converge early would otherwise pile up at their own time).
    let x_of = |r: &RunRecord| match plan {
        Plan::Tolerances { .. } => r.time_s,
        Plan::Budgets { .. } => r.time_budget_s,
    };
    let mut out = Vec::new();
    for family in families {
        let n = problems.iter().filter(|p| p.family == family).count();
        let mut curves = Vec::new();
        for (label, legend) in labels.iter().zip(legends) {
            let mine: Vec<&RunRecord> = records
                .iter()
                .filter(|r| r.family == family && &r.solver == label)
                .collect();
            let mut points = Vec::new();
            for &(tol, budget, _) in levels {
                let at: Vec<&&RunRecord> = mine
                    .iter()
                    .filter(|r| r.tolerance == tol && r.time_budget_s == budget.as_secs_f64())
                    .collect();
                if !at.is_empty() {
                    points.push((
                        median(at.iter().map(|r| x_of(r)).collect()),
                        median(at.iter().map(|r| r.error).collect()),
                    ));
                }
            }
            curves.push(plot::Curve {
                name: legend.clone(),
                points,
                runs: mine.iter().map(|r| (x_of(r), r.error)).collect(),
            });
        }
        let what = if n == 1 {
            "1 problem".to_string()
        } else {
            format!("{n} problems, medians")
        };
        let (title, x_desc, stem) = match plan {
            Plan::Tolerances { .. } => (
                format!("Work–precision: {family} ({what})"),
                "time to reach the tolerance (s); one point per tolerance".to_string(),
                format!("work-precision-{}", file_safe(family)),
            ),
            Plan::Budgets { .. } => (
                format!("Error within a time budget: {family} ({what})"),
                "wall-clock budget (s); the error reached within it".to_string(),
                format!("budget-{}", file_safe(family)),
            ),
        };
        let picture = plot::WorkPrecisionPicture {
            title,
            x_desc,
            y_desc: plot::ERROR_DESC.to_string(),
            curves,
        };
        out.push(plot::save(&picture, dir, &stem));
    }
    out
}
