//! What the arguments ask for: tolerance mode or budget mode, and the levels of each.

use std::time::Duration;

use super::args::BenchArgs;

/// Tolerance mode or budget mode, with the levels each (problem, solver) is run at.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Plan {
    Tolerances {
        tols: Vec<f64>,
        max_iter: usize,
        timeout: Duration,
    },
    Budgets {
        budgets: Vec<Duration>,
        tol: f64,
        max_iter: usize,
    },
}

impl Plan {
    pub(super) fn from_args(args: &BenchArgs) -> Plan {
        match &args.budget {
            None => Plan::Tolerances {
                tols: args.tol.clone().unwrap_or_else(|| vec![1e-4, 1e-6, 1e-8]),
                max_iter: args.max_iter.unwrap_or(100_000),
                timeout: args.timeout,
            },
            Some(budgets) => Plan::Budgets {
                budgets: budgets.clone(),
                tol: args
                    .tol
                    .as_ref()
                    .and_then(|t| t.iter().copied().reduce(f64::min))
                    .unwrap_or(1e-14),
                max_iter: args.max_iter.unwrap_or(usize::MAX),
            },
        }
    }

    /// (tolerance, time budget, max_iter) of every level.
    pub(super) fn levels(&self) -> Vec<(f64, Duration, usize)> {
        match self {
            Plan::Tolerances {
                tols,
                max_iter,
                timeout,
            } => tols.iter().map(|&t| (t, *timeout, *max_iter)).collect(),
            Plan::Budgets {
                budgets,
                tol,
                max_iter,
            } => budgets.iter().map(|&b| (*tol, b, *max_iter)).collect(),
        }
    }

    pub(super) fn mode(&self) -> &'static str {
        match self {
            Plan::Tolerances { .. } => "tolerance",
            Plan::Budgets { .. } => "budget",
        }
    }
}
