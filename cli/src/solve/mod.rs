//! `fc3d solve` (and `fc3d` without a subcommand): reads the inputs, solves each from r = 0 with
//! the configuration of the flags and prints the table, AUTO's stages, the fill of a factorizing
//! solver and, with `--diagnostics`, the contacts' status. A global problem (M, H) is solved with
//! the global solver given (`--solver 605`), or by its reduction with the local one (AUTO by
//! default); its error column is Siconos' global error of the returned `(r, u, v)`.

mod args;
mod table;

pub(crate) use args::{config_of, global_config_of, SolveArgs};

use std::io::Write;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use crate::bench::spec::SolverSpec;
use crate::inputs::{expand_paths, load_input, AnyProblem, Input, Loaded};
use crate::units::scientific;
use fc3d_core::global::{solve_global, GlobalConfig, GlobalProblem, GlobalReport};
use fc3d_core::{solve, Fc3dError, FrictionProblem, Method, SolveReport, SolverConfig};
use table::{Row, Table};

pub(crate) fn run_solve(args: &SolveArgs) -> ExitCode {
    let mut failed = false;
    let inputs = if args.paths.is_empty() {
        fc3d_core::scenes::default_scenes()
            .into_iter()
            .map(Input::Scene)
            .collect()
    } else {
        let (inputs, errors) = expand_paths(&args.paths);
        for message in &errors {
            eprintln!("fc3d: {message}");
        }
        failed |= !errors.is_empty();
        inputs
    };

    // A local solver runs on local problems and on the reduction of global ones; a global
    // solver on global problems only. Flags the solver given cannot take are a command-line
    // error.
    let local_config = config_of(args);
    let global_config = global_config_of(args);
    let given = match args.solver {
        SolverSpec::Local(_) => local_config.as_ref().map(drop),
        SolverSpec::Global(_) => global_config.as_ref().map(drop),
    };
    if let Err(e) = given {
        eprintln!("fc3d: {e}");
        return ExitCode::from(2);
    }

    let mut stdout = std::io::stdout().lock();
    // A closed stdout (e.g. `fc3d | head`) ends the program quietly, never with a panic.
    let mut out = |line: String| writeln!(stdout, "{line}").is_ok();
    let header = match (&local_config, &global_config) {
        (Ok(config), _) => local_header(config),
        (Err(_), Ok(config)) => global_header(config),
        (Err(e), Err(_)) => unreachable!("refused above: {e}"),
    };
    if !out(header) {
        return ExitCode::SUCCESS;
    }

    let mut table = Table::new();
    let mut global_header_done = local_config.is_err();
    for input in inputs {
        let (name, problem) = match load_input(input) {
            Loaded::Problem(name, problem) => (name, problem),
            Loaded::Skipped => continue,
            Loaded::Failed => {
                failed = true;
                continue;
            }
        };
        let problem = match problem {
            AnyProblem::Local(problem) => problem,
            AnyProblem::Global(problem, storage) => {
                let config = match &global_config {
                    Ok(c) => c,
                    Err(e) => {
                        eprintln!("fc3d: {name}: a global problem: {e}");
                        failed = true;
                        continue;
                    }
                };
                if !global_header_done {
                    global_header_done = true;
                    if !out(global_header(config)) {
                        return ExitCode::SUCCESS;
                    }
                }
                match solve_global_one(&problem, config) {
                    Ok((report, time)) => {
                        let row = Row {
                            problem: name.clone(),
                            contacts: problem.n_contacts(),
                            storage: format!("global (M {})", storage.m.name()),
                            solver: config.method.label(),
                            status: report.status,
                            iterations: report.iterations,
                            error: report.error,
                            time,
                        };
                        let stages = report
                            .local
                            .and_then(|l| l.stages)
                            .map(|log| stage_line(&name, &log));
                        for line in table.push(row).into_iter().chain(stages) {
                            if !out(line) {
                                return ExitCode::SUCCESS;
                            }
                        }
                        if args.diagnostics.is_some()
                            && !out(format!(
                                "#   diagnostics: not available for the global problem {name}"
                            ))
                        {
                            return ExitCode::SUCCESS;
                        }
                    }
                    Err(e) => {
                        eprintln!("fc3d: {name}: {e}");
                        failed = true;
                    }
                }
                continue;
            }
        };
        let config = match &local_config {
            Ok(c) => c,
            Err(e) => {
                eprintln!("fc3d: {name}: {e}");
                failed = true;
                continue;
            }
        };
        match solve_one(&problem, config) {
            Ok((report, time, r)) => {
                let row = Row {
                    problem: name,
                    contacts: problem.n_contacts(),
                    storage: problem.w().storage_name().to_string(),
                    solver: config.label(),
                    status: report.status,
                    iterations: report.iterations,
                    error: report.error,
                    time,
                };
                // Rows are printed as they come (a long run shows progress) with the widths
                // the table has settled on; the header comes first.
                let stages = report.stages.map(|log| stage_line(&row.problem, &log));
                let fill = report.fill.map(|f| fill_line(&row.problem, &f));
                let f32_sweeps = report.f32_sweeps.map(|k| {
                    format!(
                        "#   f32 sweeps on {}: {k} of {} on the f32 copy of W's coupling blocks",
                        row.problem, report.iterations
                    )
                });
                let lines = table.push(row).into_iter().chain(stages).chain(fill);
                for line in lines.chain(f32_sweeps) {
                    if !out(line) {
                        return ExitCode::SUCCESS;
                    }
                }
                if let Some(k) = args.diagnostics {
                    for line in diagnostic_lines(&problem, &r, &report, k) {
                        if !out(line) {
                            return ExitCode::SUCCESS;
                        }
                    }
                }
            }
            Err(e) => {
                eprintln!("fc3d: {name}: {e}");
                failed = true;
            }
        }
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// The header line of a global solver.
fn global_header(config: &GlobalConfig) -> String {
    let budget = config
        .time_budget
        .map_or(String::new(), |b| format!(", budget {b:?}"));
    format!(
        "# global problems: {} (id {}), tolerance {:e}, at most {} iterations{budget}; error = \
         Siconos' global error (gfc3d_compute_error) of the returned (r, u, v)",
        config.method.label(),
        config.method.siconos_id(),
        config.tolerance,
        config.max_iter
    )
}

/// The header line of a local solver.
fn local_header(config: &SolverConfig) -> String {
    let budget = config
        .time_budget
        .map_or(String::new(), |b| format!(", budget {b:?}"));
    match config.method {
        Method::Nsgs(o) => format!(
            "# NSGS, local solver {} ({:?}), tolerance {:e}, at most {} sweeps{budget}; error = \
             relative natural-map error of the returned (r, u)",
            o.local.kind.siconos_id(),
            o.local.kind,
            config.tolerance,
            config.max_iter
        ),
        m => format!(
            "# {} (id {}), tolerance {:e}, at most {} iterations{budget}; error = relative \
             natural-map error of the returned (r, u)",
            m.label(),
            m.siconos_id(),
            config.tolerance,
            config.max_iter
        ),
    }
}

/// AUTO's stages as a comment line: `#   AUTO on NAME: TFP 3 it. -> 1.2e-3 (stalled) > ...`.
fn stage_line(problem: &str, log: &fc3d_core::StageLog) -> String {
    let stages: Vec<String> = log
        .stages()
        .map(|s| {
            format!(
                "{} {} it. -> {} ({})",
                s.kind.name(),
                s.iterations,
                scientific(s.error),
                s.end.name()
            )
        })
        .collect();
    format!(
        "#   AUTO on {problem} (rule {}): {}",
        log.rule,
        stages.join(" > ")
    )
}

/// The fill of a factorizing solver as a comment line:
/// `#   fill on NAME: nnz(A) 15840, nnz(L)+nnz(U) 29784 (1.88x)`.
fn fill_line(problem: &str, fill: &fc3d_core::Fill) -> String {
    format!(
        "#   fill on {problem}: nnz(A) {}, nnz(L)+nnz(U) {} ({:.2}x)",
        fill.matrix_nnz,
        fill.factor_nnz,
        fill.ratio()
    )
}

/// Solves a global problem from r = 0 and times the solve call (M's factorization included).
fn solve_global_one(
    problem: &GlobalProblem<'_>,
    config: &GlobalConfig,
) -> Result<(GlobalReport, Duration), Fc3dError> {
    let (n, ndof) = (problem.size(), problem.ndof());
    let (mut r, mut u, mut v) = (vec![0.0; n], vec![0.0; n], vec![0.0; ndof]);
    let start = Instant::now();
    let report = solve_global(problem, config, &mut r, &mut u, &mut v)?;
    Ok((report, start.elapsed()))
}

/// Solves from r = 0 and times the solve call alone; returns the reaction too.
fn solve_one(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
) -> Result<(SolveReport, Duration, Vec<f64>), Fc3dError> {
    let n = problem.size();
    let mut r = vec![0.0; n];
    let mut u = vec![0.0; n];
    let start = Instant::now();
    let report = solve(problem, config, &mut r, &mut u)?;
    Ok((report, start.elapsed(), r))
}

/// `--diagnostics`: the status counts and the `k` worst contacts of the solution `r`, as `#`
/// lines. The status tolerance follows the error reached (10 times it, at least the default),
/// so that a contact is not called sliding for a velocity the solve left unresolved.
fn diagnostic_lines(
    problem: &FrictionProblem<'_>,
    r: &[f64],
    report: &SolveReport,
    k: usize,
) -> Vec<String> {
    let tolerance = (10.0 * report.error).max(fc3d_core::DiagnosticOptions::default().tolerance);
    let d = match fc3d_core::diagnose(problem, r, &fc3d_core::DiagnosticOptions { tolerance }) {
        Ok(d) => d,
        Err(e) => return vec![format!("#   diagnostics: {e}")],
    };
    let (take_off, stick, slide, apex) = d.counts();
    let mut lines = vec![format!(
        "#   contacts: {take_off} take-off, {stick} stick, {slide} slide, {apex} apex (status tolerance {tolerance:.1e})"
    )];
    for c in d.worst(k) {
        let cd = &d.contacts[c];
        lines.push(format!(
            "#   contact {c:>6}: {:<8} error share {:.2e}  u_N {:+.3e}  r_N {:+.3e}  |u_T| {:.3e}",
            cd.status.name(),
            cd.error_contribution,
            cd.normal_velocity,
            cd.normal_reaction,
            cd.tangential_velocity
        ));
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fill_lines_name_both_sizes_and_the_ratio() {
        let fill = fc3d_core::Fill {
            matrix_nnz: 15840,
            factor_nnz: 29784,
        };
        assert_eq!(
            fill_line("boxes-c120-p1-s3", &fill),
            "#   fill on boxes-c120-p1-s3: nnz(A) 15840, nnz(L)+nnz(U) 29784 (1.88x)"
        );
    }
}
