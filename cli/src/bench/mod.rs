//! `fc3d bench`: the speed–accuracy trade of the solvers on a problem set.
//!
//! * Tolerance mode (default): every (problem, solver, tolerance) is solved `--reps` times from
//!   r = 0 with the time cap `--timeout` (the solver's own time budget, so nothing can hang); the
//!   time is the median of the repetitions. Outputs: `runs.csv`, `summary.txt`, a performance
//!   profile per tolerance (`profile-<tol>.svg/.png`) and work–precision curves per problem
//!   family (`work-precision-<family>.svg/.png`).
//! * Budget mode (`--budget 1ms,10ms,100ms`): every (problem, solver, budget) runs until the
//!   budget is spent (tolerance: the smallest `--tol` given, else 1e-14; no iteration limit
//!   unless `--max-iter` is given) and the error reached is recorded: the paper's real-time
//!   criterion. Outputs: `budget.csv`, `summary.txt`, and error-versus-time pictures per family
//!   (`budget-<family>.svg/.png`).
//!
//! With AUTO among the solvers (tolerance mode), `auto-ratio.txt` compares its time with the
//! fastest other solver's per problem and tolerance; `--auto-max-ratio X` fails the run when
//! AUTO is more than X times behind.
//!
//! The error in every row is measured here ([`check::independent_error`]) and compared with the
//! solver's report; a disagreement is flagged in the CSV and on stderr, and makes the exit status 1.

pub(crate) mod args;
mod auto_ratio;
mod check;
mod csv;
mod format;
mod pictures;
mod plan;
pub(crate) mod plot;
mod problems;
mod profile;
mod runner;
pub(crate) mod spec;
mod stats;
mod summary;
#[cfg(test)]
mod tests;

pub use args::BenchArgs;
pub use runner::run;
