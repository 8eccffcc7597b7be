//! The run loop: every (problem, solver, level) in tolerance or budget mode, repeated and timed,
//! then the CSV, the summary and the pictures written.

use std::io::{IsTerminal, Write};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use fc3d_core::global::solve_global;
use fc3d_core::{solve, SolveStatus};
use indicatif::{ProgressBar, ProgressStyle};

use super::args::BenchArgs;
use super::auto_ratio::{auto_ratio_table, auto_ratios, over_limit};
use super::check;
use super::csv::{self, RunRecord};
use super::format::{duration_name, tol_name};
use super::pictures::{family_pictures, profile_pictures};
use super::plan::Plan;
use super::problems::{load_problems, Problem};
use super::spec::{self, SolverSpec};
use super::stats::median;
use super::summary::{budget_summary, tolerance_summary};
use crate::inputs::AnyProblem;

/// One repetition: solve from r = 0, time the solve call alone, then measure the error here.
struct Rep {
    time: Duration,
    status: SolveStatus,
    iterations: usize,
    reported_error: f64,
    error: f64,
}

/// The limits of one run: tolerance, time budget, iteration limit.
type Level = (f64, Duration, usize);

/// One run of `spec` on a local problem, or on a global one (the global solver, or the
/// reduction with the local solver; set-up and factorization of M included in the time).
fn run_once(problem: &AnyProblem, spec: &SolverSpec, level: Level) -> Result<Rep, String> {
    let (tol, budget, max_iter) = level;
    match problem {
        AnyProblem::Local(problem) => {
            let config = spec::solver_config(spec, tol, max_iter, Some(budget))?;
            let n = problem.size();
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let start = Instant::now();
            let report = solve(problem, &config, &mut r, &mut u).map_err(|e| e.to_string())?;
            let time = start.elapsed();
            Ok(Rep {
                time,
                status: report.status,
                iterations: report.iterations,
                reported_error: report.error,
                error: check::independent_error(problem, &r),
            })
        }
        AnyProblem::Global(problem, _) => {
            let config = spec::global_solver_config(spec, tol, max_iter, Some(budget));
            let (n, ndof) = (problem.size(), problem.ndof());
            let (mut r, mut u, mut v) = (vec![0.0; n], vec![0.0; n], vec![0.0; ndof]);
            let start = Instant::now();
            let report = solve_global(problem, &config, &mut r, &mut u, &mut v)
                .map_err(|e| e.to_string())?;
            let time = start.elapsed();
            Ok(Rep {
                time,
                status: report.status,
                iterations: report.iterations,
                reported_error: report.error,
                error: check::independent_global_error(problem, &r, &v),
            })
        }
    }
}

fn status_name(s: SolveStatus) -> &'static str {
    s.name()
}

/// Runs `fc3d bench`.
pub fn run(args: &BenchArgs) -> ExitCode {
    let mut failed = false;
    let plan = Plan::from_args(args);
    let specs = &args.solvers.0;
    let problems = load_problems(&args.paths, &mut failed);
    if problems.is_empty() {
        eprintln!("fc3d bench: no problem to run");
        return ExitCode::from(1);
    }
    if let Err(e) = std::fs::create_dir_all(&args.out) {
        eprintln!("fc3d bench: {}: {e}", args.out.display());
        return ExitCode::from(1);
    }
    let levels = plan.levels();
    let total = (problems.len() * specs.len() * levels.len()) as u64;
    let progress = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(total);
        bar.set_style(
            ProgressStyle::with_template(
                "{elapsed_precise} [{wide_bar}] {pos}/{len} runs, ETA {eta}  {msg}",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let started = Instant::now();
    let mut records = Vec::new();
    let mut mismatches = 0usize;
    for (k, p) in problems.iter().enumerate() {
        progress.set_message(format!("{} ({} contacts)", p.name, p.problem.n_contacts()));
        for spec in specs {
            for &level in &levels {
                let tol = level.0;
                match run_reps(p, spec, level, &plan, args.reps as usize) {
                    Ok(record) => {
                        if !record.error_ok {
                            mismatches += 1;
                            progress.suspend(|| {
                                eprintln!(
                                    "fc3d bench: ERROR MISMATCH on {} with {} (tol {:e}): measured \
                                     {:e}, reported {:e}",
                                    record.problem,
                                    record.solver,
                                    tol,
                                    record.error,
                                    record.reported_error
                                )
                            });
                        }
                        records.push(record);
                    }
                    Err(e) => {
                        failed = true;
                        progress.suspend(|| {
                            eprintln!("fc3d bench: {} with {}: {e}", p.name, spec.label())
                        });
                    }
                }
                progress.inc(1);
            }
        }
        if progress.is_hidden() && total > 0 {
            eprintln!(
                "fc3d bench: [{}/{}] {} done ({:.1} s elapsed)",
                k + 1,
                problems.len(),
                p.name,
                started.elapsed().as_secs_f64()
            );
        }
    }
    progress.finish_and_clear();

    // Outputs.
    let csv_name = match plan {
        Plan::Tolerances { .. } => "runs.csv",
        Plan::Budgets { .. } => "budget.csv",
    };
    let mut written = Vec::new();
    let csv_path = args.out.join(csv_name);
    match std::fs::File::create(&csv_path).and_then(|f| {
        let mut w = std::io::BufWriter::new(f);
        csv::write_csv(&records, &mut w)?;
        w.flush()
    }) {
        Ok(()) => written.push(csv_path),
        Err(e) => {
            eprintln!("fc3d bench: {}: {e}", csv_path.display());
            failed = true;
        }
    }

    let labels: Vec<String> = specs.iter().map(SolverSpec::label).collect();
    let summary = match &plan {
        Plan::Tolerances { tols, .. } => tolerance_summary(&records, &labels, tols, problems.len()),
        Plan::Budgets { budgets, tol, .. } => {
            budget_summary(&records, &labels, budgets, *tol, problems.len())
        }
    };
    let level_list = match &plan {
        Plan::Tolerances { tols, timeout, .. } => format!(
            "tolerances {}, timeout {}",
            tols.iter()
                .map(|&t| tol_name(t))
                .collect::<Vec<_>>()
                .join(","),
            duration_name(*timeout)
        ),
        Plan::Budgets { budgets, .. } => format!(
            "budgets {}",
            budgets
                .iter()
                .map(|&b| duration_name(b))
                .collect::<Vec<_>>()
                .join(",")
        ),
    };
    let header = format!(
        "# fc3d bench: {} problems, {} solvers, {level_list}, {} repetitions; {:.1} s in all",
        problems.len(),
        specs.len(),
        args.reps,
        started.elapsed().as_secs_f64()
    );
    let text = format!("{header}\n{summary}");
    let summary_path = args.out.join("summary.txt");
    match std::fs::write(&summary_path, &text) {
        Ok(()) => written.push(summary_path),
        Err(e) => {
            eprintln!("fc3d bench: {}: {e}", summary_path.display());
            failed = true;
        }
    }

    if let Err(e) = write_auto_ratios(&records, &plan, args, &mut written) {
        eprintln!("fc3d bench: {e}");
        failed = true;
    }

    let legends: Vec<String> = specs.iter().map(SolverSpec::legend).collect();
    let pictures = match &plan {
        Plan::Tolerances { tols, .. } => {
            let mut r = profile_pictures(&records, &problems, &labels, &legends, tols, &args.out);
            r.extend(family_pictures(
                &records, &problems, &labels, &legends, &levels, &plan, &args.out,
            ));
            r
        }
        Plan::Budgets { .. } => family_pictures(
            &records, &problems, &labels, &legends, &levels, &plan, &args.out,
        ),
    };
    for p in pictures {
        match p {
            Ok(paths) => written.extend(paths),
            Err(e) => {
                eprintln!("fc3d bench: picture: {e}");
                failed = true;
            }
        }
    }

    let mut stdout = std::io::stdout().lock();
    let _ = write!(stdout, "{text}");
    let _ = writeln!(stdout, "# written to {}:", args.out.display());
    for w in &written {
        let _ = writeln!(stdout, "#   {}", w.display());
    }
    if mismatches > 0 {
        eprintln!(
            "fc3d bench: {mismatches} run(s) where the measured error differs from the reported one \
             (error_check = MISMATCH in the CSV)"
        );
        failed = true;
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// Runs the repetitions of one (problem, solver, level) and summarises them in a record.
///
/// Tolerance mode: the record's status, iterations and errors are those of the repetition with
/// the median time; a repetition that runs out of time ends the series (the others would too).
/// Budget mode: those of the repetition with the median error.
fn run_reps(
    p: &Problem,
    spec: &SolverSpec,
    level: Level,
    plan: &Plan,
    reps: usize,
) -> Result<RunRecord, String> {
    let (tolerance, budget, max_iter) = level;
    let mut runs: Vec<Rep> = Vec::with_capacity(reps);
    for _ in 0..reps {
        let rep = run_once(&p.problem, spec, level)?;
        let out_of_time = rep.status == SolveStatus::TimeBudgetExhausted;
        runs.push(rep);
        if out_of_time && matches!(plan, Plan::Tolerances { .. }) {
            break;
        }
    }
    let error_ok = runs
        .iter()
        .all(|r| check::errors_agree(r.error, r.reported_error));
    // Rounded to the nanosecond the clock resolves, so that the CSV shows no float noise.
    let time_s = (median(runs.iter().map(|r| r.time.as_secs_f64()).collect()) * 1e9).round() / 1e9;
    match plan {
        Plan::Tolerances { .. } => runs.sort_by_key(|r| r.time),
        Plan::Budgets { .. } => runs.sort_by(|a, b| a.error.total_cmp(&b.error)),
    }
    let rep = &runs[(runs.len() - 1) / 2];
    Ok(RunRecord {
        mode: plan.mode(),
        problem: p.name.clone(),
        family: p.family.clone(),
        contacts: p.problem.n_contacts(),
        solver: spec.label(),
        tolerance,
        time_budget_s: budget.as_secs_f64(),
        max_iter,
        status: status_name(rep.status),
        info: rep.status.info_code(),
        iterations: rep.iterations,
        error: rep.error,
        reported_error: rep.reported_error,
        error_ok,
        time_s,
        reps: runs.len(),
    })
}

/// `auto-ratio.txt` when AUTO ran in tolerance mode; an error when `--auto-max-ratio` is
/// exceeded (or the file cannot be written).
fn write_auto_ratios(
    records: &[RunRecord],
    plan: &Plan,
    args: &BenchArgs,
    written: &mut Vec<std::path::PathBuf>,
) -> Result<(), String> {
    let ratios = auto_ratios(records);
    if ratios.is_empty() || !matches!(plan, Plan::Tolerances { .. }) {
        return Ok(());
    }
    let table = auto_ratio_table(&ratios, args.auto_max_ratio);
    let path = args.out.join("auto-ratio.txt");
    std::fs::write(&path, &table).map_err(|e| format!("{}: {e}", path.display()))?;
    written.push(path);
    eprint!("{table}");
    let Some(limit) = args.auto_max_ratio else {
        return Ok(());
    };
    let over = over_limit(&ratios, limit);
    if over.is_empty() {
        return Ok(());
    }
    let names: Vec<String> = over
        .iter()
        .map(|r| format!("{} at {:e}", r.problem, r.tolerance))
        .collect();
    Err(format!(
        "AUTO more than {limit}x behind the fastest other solver on {}",
        names.join(", ")
    ))
}
