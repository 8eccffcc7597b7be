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
//! The error in every row is measured here ([`check::independent_error`]) and compared with the
//! solver's report; a disagreement is flagged in the CSV and on stderr, and makes the exit status 1.

mod check;
mod csv;
mod plot;
mod profile;
mod spec;

use std::collections::BTreeMap;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::Args;
use fc3d_core::{solve, FrictionProblem, SolveReport, SolveStatus};
use indicatif::{ProgressBar, ProgressStyle};

use self::csv::RunRecord;
use self::profile::PerformanceProfile;
use self::spec::SolverSpec;

/// The parsed `--solvers` list.
#[derive(Debug, Clone, PartialEq)]
pub struct SpecList(pub Vec<SolverSpec>);

fn parse_spec_list(s: &str) -> Result<SpecList, String> {
    spec::parse_spec_list(s).map(SpecList)
}

/// Measure the speed–accuracy trade of the solvers: performance profiles, work–precision curves,
/// or the error reached within time budgets.
#[derive(Args, Debug, Clone, PartialEq)]
pub struct BenchArgs {
    /// Siconos .dat problem files, or directories whose *.dat files are used. None: the built-in
    /// scenes.
    #[arg(value_name = "FILES")]
    pub paths: Vec<PathBuf>,
    /// Solvers, comma-separated (names and ids: `fc3d bench --help`).
    #[arg(long, value_name = "SPECS", default_value = "all", value_parser = parse_spec_list, long_help = spec::solvers_help())]
    pub solvers: SpecList,
    /// Tolerances on the relative natural-map error, comma-separated [default: 1e-4,1e-6,1e-8;
    /// with --budget: 1e-14, or the smallest given].
    #[arg(long, value_name = "X,...", value_delimiter = ',', value_parser = crate::parse_tolerance)]
    pub tol: Option<Vec<f64>>,
    /// Iteration (sweep) limit [default: 100000; with --budget: none].
    #[arg(long, value_name = "N")]
    pub max_iter: Option<usize>,
    /// Wall-clock cap of one run (e.g. 20s, 500ms): the solver's own time budget, after which
    /// it stops with status out-of-time.
    #[arg(long, value_name = "TIME", default_value = "20s", value_parser = parse_duration)]
    pub timeout: Duration,
    /// Repetitions of each run, each from r = 0; the time is their median.
    #[arg(long, value_name = "N", default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..))]
    pub reps: u32,
    /// Budget mode: wall-clock budgets, comma-separated (e.g. 1ms,10ms,100ms); records the error
    /// reached within each.
    #[arg(long, value_name = "TIME,...", value_delimiter = ',', value_parser = parse_duration)]
    pub budget: Option<Vec<Duration>>,
    /// Output directory (created if needed) for the CSV, the summary and the pictures.
    #[arg(long, value_name = "DIR", default_value = "target/bench-out")]
    pub out: PathBuf,
}

/// `20s`, `1.5s`, `100ms`, `250us` (or `µs`), `500ns`, `2min`; a bare number is seconds.
/// Must be positive and finite.
pub fn parse_duration(s: &str) -> Result<Duration, String> {
    let t = s.trim();
    let split = t
        .find(|c: char| {
            !(c.is_ascii_digit() || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-')
        })
        .unwrap_or(t.len());
    // `1e-3s` is a number then a unit; but `e` may not start a unit anyway.
    let (number, unit) = t.split_at(split);
    let x: f64 = number
        .parse()
        .map_err(|_| format!("'{s}' is not a duration (e.g. 20s, 100ms, 250us)"))?;
    let scale = match unit.trim() {
        "" | "s" => 1.0,
        "ms" => 1e-3,
        "us" | "µs" => 1e-6,
        "ns" => 1e-9,
        "min" | "m" => 60.0,
        u => {
            return Err(format!(
                "unknown time unit '{u}' in '{s}' (ns, us, ms, s, min)"
            ))
        }
    };
    let secs = x * scale;
    if !(secs.is_finite() && secs > 0.0) || secs > 1e9 {
        return Err(format!("a duration must be positive and finite, got '{s}'"));
    }
    Ok(Duration::from_secs_f64(secs))
}

/// Problem family: the file name's prefix before the first digit or dash, without trailing
/// `_`/`.` (`Rover1039.dat` → `Rover`, `Capsules-i100-889.dat` → `Capsules`,
/// `NESpheres_10_1.dat` → `NESpheres`); the whole stem when that prefix is empty.
pub fn family_of(file_name: &str) -> String {
    let stem = file_name.strip_suffix(".dat").unwrap_or(file_name);
    let cut = stem
        .find(|c: char| c.is_ascii_digit() || c == '-')
        .unwrap_or(stem.len());
    let prefix = stem[..cut].trim_end_matches(['_', '.', ' ']);
    if prefix.is_empty() {
        stem.to_string()
    } else {
        prefix.to_string()
    }
}

/// A loaded problem.
struct Problem {
    name: String,
    family: String,
    problem: FrictionProblem<'static>,
}

/// Tolerance mode or budget mode, with the levels each (problem, solver) is run at.
#[derive(Debug, Clone, PartialEq)]
enum Plan {
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
    fn from_args(args: &BenchArgs) -> Plan {
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
    fn levels(&self) -> Vec<(f64, Duration, usize)> {
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

    fn mode(&self) -> &'static str {
        match self {
            Plan::Tolerances { .. } => "tolerance",
            Plan::Budgets { .. } => "budget",
        }
    }
}

/// Loads the inputs with the CLI's rules (folder scan, skips); errors go to stderr.
fn load_problems(paths: &[PathBuf], failed: &mut bool) -> Vec<Problem> {
    if paths.is_empty() {
        return fc3d_core::scenes::default_scenes()
            .into_iter()
            .map(|s| Problem {
                name: s.name.to_string(),
                family: s.name.to_string(),
                problem: s.problem,
            })
            .collect();
    }
    let (inputs, errors) = crate::expand_paths(paths);
    for message in &errors {
        eprintln!("fc3d: {message}");
    }
    *failed |= !errors.is_empty();
    let mut problems = Vec::new();
    for input in inputs {
        match crate::load_input(input) {
            crate::Loaded::Problem(name, problem) => problems.push(Problem {
                family: family_of(&name),
                name,
                problem,
            }),
            crate::Loaded::Skipped => {}
            crate::Loaded::Failed => *failed = true,
        }
    }
    problems
}

/// One repetition: solve from r = 0, time the solve call alone, then measure the error here.
struct Rep {
    time: Duration,
    report: SolveReport,
    error: f64,
}

fn run_once(
    problem: &FrictionProblem<'_>,
    config: &fc3d_core::SolverConfig,
) -> Result<Rep, fc3d_core::Fc3dError> {
    let n = problem.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let start = Instant::now();
    let report = solve(problem, config, &mut r, &mut u)?;
    let time = start.elapsed();
    Ok(Rep {
        time,
        report,
        error: check::independent_error(problem, &r),
    })
}

fn status_name(s: SolveStatus) -> &'static str {
    match s {
        SolveStatus::Converged => "converged",
        SolveStatus::MaxIterationsReached => "max-iter",
        SolveStatus::TimeBudgetExhausted => "out-of-time",
        SolveStatus::RelaxationNotCoulomb => "relaxed-not-coulomb",
    }
}

/// Median of sorted values (mean of the two middle ones for an even count).
fn median_sorted(v: &[f64]) -> f64 {
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    median_sorted(&v)
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
            for &(tol, budget, max_iter) in &levels {
                let config = spec::solver_config(spec, tol, max_iter, Some(budget));
                match run_reps(p, spec, &config, &plan, args.reps as usize) {
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
    config: &fc3d_core::SolverConfig,
    plan: &Plan,
    reps: usize,
) -> Result<RunRecord, fc3d_core::Fc3dError> {
    let mut runs: Vec<Rep> = Vec::with_capacity(reps);
    for _ in 0..reps {
        let rep = run_once(&p.problem, config)?;
        let out_of_time = rep.report.status == SolveStatus::TimeBudgetExhausted;
        runs.push(rep);
        if out_of_time && matches!(plan, Plan::Tolerances { .. }) {
            break;
        }
    }
    let error_ok = runs
        .iter()
        .all(|r| check::errors_agree(r.error, r.report.error));
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
        tolerance: config.tolerance,
        time_budget_s: config
            .time_budget
            .map_or(f64::INFINITY, |b| b.as_secs_f64()),
        max_iter: config.max_iter,
        status: status_name(rep.report.status),
        info: rep.report.status.info_code(),
        iterations: rep.report.iterations,
        error: rep.error,
        reported_error: rep.report.error,
        error_ok,
        time_s,
        reps: runs.len(),
    })
}

/// `tolerance` formatted for file names and tables: `1e-8`.
fn tol_name(t: f64) -> String {
    format!("{t:e}")
}

fn duration_name(d: Duration) -> String {
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

fn format_time(secs: f64) -> String {
    if !secs.is_finite() {
        return "-".to_string();
    }
    crate::format_time(Duration::from_secs_f64(secs))
}

/// Per solver and tolerance: problems solved, fastest (rho_s(1)), total time of all runs,
/// median time over the solved problems.
fn tolerance_summary(
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
                crate::scientific(tol),
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
fn tolerance_profile(at_tol: &[&RunRecord], labels: &[String]) -> PerformanceProfile {
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
fn budget_summary(
    records: &[RunRecord],
    labels: &[String],
    budgets: &[Duration],
    tol: f64,
    n_problems: usize,
) -> String {
    let mut out = format!(
        "# error reached within each wall-clock budget (tolerance {}, so the budget stops the run)\n",
        crate::scientific(tol)
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
                crate::scientific(median(errors.clone())),
                crate::scientific(worst),
                under(1e-4),
                under(1e-6),
                under(1e-8),
            ));
        }
    }
    out
}

fn profile_pictures(
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
fn family_pictures(
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
            curves,
        };
        out.push(plot::save(&picture, dir, &stem));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn families() {
        assert_eq!(family_of("Rover1039.dat"), "Rover");
        assert_eq!(family_of("Capsules-i100-889.dat"), "Capsules");
        assert_eq!(family_of("Confeti-ex03-Fc3D-SBM.dat"), "Confeti");
        assert_eq!(family_of("NESpheres_10_1.dat"), "NESpheres");
        assert_eq!(family_of("BoxesStack1-i100000-32.hdf5.dat"), "BoxesStack");
        assert_eq!(
            family_of("FrictionContactProblem00031.dat"),
            "FrictionContactProblem"
        );
        assert_eq!(family_of("ACinputs.dat"), "ACinputs");
        assert_eq!(family_of("123.dat"), "123");
        assert_eq!(family_of("box_stack"), "box_stack");
    }

    #[test]
    fn durations() {
        assert_eq!(parse_duration("20s"), Ok(Duration::from_secs(20)));
        assert_eq!(parse_duration("1ms"), Ok(Duration::from_millis(1)));
        assert_eq!(parse_duration(" 100ms "), Ok(Duration::from_millis(100)));
        assert_eq!(parse_duration("250us"), Ok(Duration::from_micros(250)));
        assert_eq!(parse_duration("250µs"), Ok(Duration::from_micros(250)));
        assert_eq!(parse_duration("1.5"), Ok(Duration::from_millis(1500)));
        assert_eq!(parse_duration("2min"), Ok(Duration::from_secs(120)));
        assert_eq!(parse_duration("1e-3s"), Ok(Duration::from_millis(1)));
        for bad in ["", "0", "0s", "-1s", "x", "10 parsecs", "nan", "inf"] {
            assert!(parse_duration(bad).is_err(), "{bad:?}");
        }
        assert_eq!(duration_name(Duration::from_millis(1)), "1ms");
        assert_eq!(duration_name(Duration::from_micros(2500)), "2.5ms");
        assert_eq!(duration_name(Duration::from_secs(20)), "20s");
        assert_eq!(duration_name(Duration::from_micros(20)), "20us");
    }

    #[test]
    fn plans() {
        use clap::Parser;
        let cli = crate::Cli::try_parse_from(["fc3d", "bench"]).unwrap();
        let Some(crate::Command::Bench(args)) = cli.command else {
            panic!("expected bench")
        };
        assert_eq!(
            Plan::from_args(&args),
            Plan::Tolerances {
                tols: vec![1e-4, 1e-6, 1e-8],
                max_iter: 100_000,
                timeout: Duration::from_secs(20)
            }
        );
        assert_eq!(args.reps, 3);
        assert_eq!(args.out, PathBuf::from("target/bench-out"));
        assert_eq!(args.solvers.0, spec::all_specs());

        let cli = crate::Cli::try_parse_from([
            "fc3d",
            "bench",
            "--budget",
            "1ms,10ms",
            "--tol",
            "1e-6,1e-10",
            "--solvers",
            "500/552",
        ])
        .unwrap();
        let Some(crate::Command::Bench(args)) = cli.command else {
            panic!("expected bench")
        };
        assert_eq!(
            Plan::from_args(&args),
            Plan::Budgets {
                budgets: vec![Duration::from_millis(1), Duration::from_millis(10)],
                tol: 1e-10,
                max_iter: usize::MAX
            }
        );
        assert_eq!(args.solvers.0.len(), 1);

        let cli = crate::Cli::try_parse_from(["fc3d", "bench", "--budget", "5ms"]).unwrap();
        let Some(crate::Command::Bench(args)) = cli.command else {
            panic!("expected bench")
        };
        assert!(matches!(Plan::from_args(&args), Plan::Budgets { tol, .. } if tol == 1e-14));

        for bad in [
            vec!["fc3d", "bench", "--reps", "0"],
            vec!["fc3d", "bench", "--solvers", "PSOR"],
            vec!["fc3d", "bench", "--tol", "1e-4,-1"],
            vec!["fc3d", "bench", "--timeout", "0s"],
            vec!["fc3d", "bench", "--budget", "1ms,soon"],
        ] {
            assert!(crate::Cli::try_parse_from(&bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn medians() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(vec![]).is_nan());
    }

    fn rec(problem: &str, solver: &str, tol: f64, info: i32, time_s: f64, error: f64) -> RunRecord {
        RunRecord {
            mode: "tolerance",
            problem: problem.into(),
            family: family_of(problem),
            contacts: 1,
            solver: solver.into(),
            tolerance: tol,
            time_budget_s: 20.0,
            max_iter: 10,
            status: if info == 0 {
                "converged"
            } else {
                "out-of-time"
            },
            info,
            iterations: 1,
            error,
            reported_error: error,
            error_ok: true,
            time_s,
            reps: 1,
        }
    }

    #[test]
    fn summaries_from_records() {
        let labels = vec!["A".to_string(), "B".to_string()];
        let records = vec![
            rec("p1.dat", "A", 1e-6, 0, 1.0, 1e-7),
            rec("p1.dat", "B", 1e-6, 0, 2.0, 1e-7),
            rec("p2.dat", "A", 1e-6, 2, 20.0, 1e-3),
            rec("p2.dat", "B", 1e-6, 0, 4.0, 1e-7),
        ];
        let at: Vec<&RunRecord> = records.iter().collect();
        let p = tolerance_profile(&at, &labels);
        assert_eq!(p.rho(0, 1.0), 0.5);
        assert_eq!(p.rho(1, 1.0), 0.5);
        assert_eq!(p.rho(1, 2.0), 1.0);
        assert_eq!(p.robustness(0), 0.5);
        let s = tolerance_summary(&records, &labels, &[1e-6], 2);
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines.len(), 3, "{s}");
        assert!(lines[1].starts_with("A") && lines[1].contains("1/2"), "{s}");
        assert!(lines[1].contains("21.000 s"), "{s}");
        assert!(
            lines[2].contains("2/2") && lines[2].contains("3.000 s"),
            "{s}"
        );
    }
}
