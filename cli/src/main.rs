//! The `fc3d` command.
//!
//! * `fc3d` solves every built-in scene ([`fc3d_core::scenes::default_scenes`]) with AUTO (or the
//!   solver of `--solver`) and prints a table: problem, contacts, storage, solver, iterations,
//!   error, status, time; for AUTO, the stages it took under each row.
//! * `fc3d FILE.dat [MORE FILES OR DIRECTORIES]` solves Siconos `.dat` problem files instead; a
//!   directory stands for the `*.dat` files directly in it (sorted by name; files that hold a problem
//!   fc3d does not handle, e.g. a 2D one, are skipped with a note on stderr).
//! * `fc3d solve ...` is the same as `fc3d ...`.
//! * `fc3d bench [FILES]` measures the speed–accuracy trade of the solvers: CSV, summary,
//!   performance profiles and work–precision pictures (see the `bench` module).
//! * `fc3d convert IN OUT` rewrites a problem file as `.dat` or FCLIB `.hdf5`, by OUT's
//!   extension, without changing a bit (see the `convert` module).
//!
//! Defaults: AUTO (fc3d's solver that chooses), tolerance 1e-8 on the natural-map error, at most
//! 100000 iterations. `--solver` takes any solver by name or Siconos id as `fc3d bench` does
//! (`NSGS`, `500/552`, `PROX`, `590`...), `--local` the local solver of NSGS, `--budget` a time
//! budget per problem, `--option NAME=VALUE` Siconos' option slots by name. The tolerance is tighter than Siconos'
//! 1e-4 default so that the table shows how accurate the solvers can be; the sweep limit leaves the
//! slow-converging problems of the Siconos collection room without letting one run for minutes.
//! The error column is the one measured on the returned `(r, u)`, not the solver's own test.
//!
//! Exit status: 0 when every problem was read and solved (converged or not: the status column
//! says), 1 when an input could not be read or solved (a message names it, the others are still
//! solved), 2 on a command-line error.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::{Args, Parser, Subcommand};

mod bench;
mod convert;
mod scene;
use bench::spec::{parse_spec, SolverSpec};
use fc3d_core::{
    solve, Fc3dError, FrictionProblem, LocalSolverKind, Method, NsgsOptions, Rescaling,
    SolveReport, SolverConfig,
};

/// Solves 3D frictional contact problems FC(W, q, mu) (Signorini + Coulomb, Delassus form).
///
/// Without FILES, solves the built-in scenes. A file name that is also a subcommand's name
/// (`solve`, `bench`, `convert`) must be written with a path, e.g. `./solve`.
#[derive(Parser, Debug)]
#[command(name = "fc3d", version, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    solve: SolveArgs,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Solve the built-in scenes or the given .dat files (what `fc3d` does without a subcommand).
    Solve(SolveArgs),
    /// Benchmark solvers: CSV, summary, performance profiles, work–precision curves.
    Bench(bench::BenchArgs),
    /// Convert a problem file between Siconos .dat and FCLIB .hdf5 (by OUT's extension),
    /// losslessly. FCLIB needs fc3d built with the `fclib` feature.
    Convert(convert::ConvertArgs),
    /// Generate a pile scene (seeded, deterministic) and write it as a Siconos .dat file.
    Scene(scene::SceneArgs),
}

#[derive(Args, Debug, Clone, PartialEq)]
struct SolveArgs {
    /// Siconos .dat problem files, or directories whose *.dat files are solved. None: the
    /// built-in scenes.
    #[arg(value_name = "FILES")]
    paths: Vec<PathBuf>,
    /// Tolerance on the relative natural-map error.
    #[arg(long, value_name = "X", default_value = "1e-8", value_parser = parse_tolerance)]
    tol: f64,
    /// Iteration limit (sweeps for NSGS, Newton steps for NSN, all stages together for AUTO).
    #[arg(long, value_name = "N", default_value_t = 100_000)]
    max_iter: usize,
    /// Solver, by name or Siconos id, with its defaults (as `fc3d bench --solvers`): AUTO (590,
    /// the default), NSGS or 500 (local solver 565), NSGS/552, VI-FPP, NSN-AC, PROX, TFP, ADMM...
    #[arg(long, value_name = "SOLVER", default_value = "AUTO", value_parser = parse_spec)]
    solver: SolverSpec,
    /// NSGS's local solver, by Siconos id (only with an NSGS solver): 550 (Alart-Curnier
    /// Newton), 551 (Newton with Goldstein-Price line search), 552 (one projection on the cone),
    /// 553 (projection on the cone with local iterations), 557 (one projection on the
    /// cylinder), 565 (hybrid Newton, NSGS's default), 554, 555, 558, 561, 562, 564, 570, 571,
    /// 572.
    #[arg(long, value_name = "ID", value_parser = parse_local)]
    local: Option<LocalSolverKind>,
    /// Wall-clock budget of each solve (`10ms`, `1s`...): the solver stops when it is spent and
    /// returns its best iterate (with tolerance 0: an anytime solve).
    #[arg(long, value_name = "TIME", value_parser = bench::args::parse_duration)]
    budget: Option<Duration>,
    /// A Siconos option slot by name, applied after the flags above (repeatable):
    /// SICONOS_IPARAM_MAX_ITER, SICONOS_DPARAM_TOL, FC3D_DPARAM_TIME_BUDGET (s, 0 = none),
    /// SICONOS_FRICTION_3D_IPARAM_RESCALING (0 none, 1 scalar),
    /// SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE (NSGS, 0 = none).
    #[arg(long = "option", value_name = "NAME=VALUE", value_parser = parse_option)]
    options: Vec<(SiconosOption, f64)>,
    /// After each problem, print per-contact diagnostics as `#` lines: how many contacts take
    /// off, stick, slide or sit at the cone apex, and the K contacts (default 5) with the
    /// largest share of the error, with their status and normal velocity u_N (< 0: penetrating).
    /// Written `--diagnostics` or `--diagnostics=K`.
    #[arg(long, value_name = "K", num_args = 0..=1, require_equals = true, default_missing_value = "5")]
    diagnostics: Option<usize>,
}

/// The Siconos option slots `--option` sets, by their Siconos names.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SiconosOption {
    MaxIter,
    Tolerance,
    TimeBudget,
    Rescaling,
    Relaxation,
}

const OPTION_NAMES: [(&str, SiconosOption); 5] = [
    ("SICONOS_IPARAM_MAX_ITER", SiconosOption::MaxIter),
    ("SICONOS_DPARAM_TOL", SiconosOption::Tolerance),
    ("FC3D_DPARAM_TIME_BUDGET", SiconosOption::TimeBudget),
    (
        "SICONOS_FRICTION_3D_IPARAM_RESCALING",
        SiconosOption::Rescaling,
    ),
    (
        "SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE",
        SiconosOption::Relaxation,
    ),
];

fn parse_option(s: &str) -> Result<(SiconosOption, f64), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("'{s}' is not NAME=VALUE"))?;
    let option = OPTION_NAMES
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(name.trim()))
        .map(|(_, o)| *o)
        .ok_or_else(|| {
            let names: Vec<&str> = OPTION_NAMES.iter().map(|(n, _)| *n).collect();
            format!("unknown option '{name}' (one of {})", names.join(", "))
        })?;
    let value: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("'{value}' is not a number (in '{s}')"))?;
    Ok((option, value))
}

/// The configuration the flags describe, checked by the core.
fn config_of(args: &SolveArgs) -> Result<SolverConfig, String> {
    let method = match (args.solver.method, args.local) {
        (Method::Nsgs(_), Some(local)) => Method::Nsgs(NsgsOptions::with_local(local)),
        (m, Some(_)) => {
            return Err(format!(
                "--local applies to NSGS only, not to {}",
                m.label()
            ))
        }
        (m, None) => m,
    };
    let mut config = SolverConfig::new(method)
        .with_tolerance(args.tol)
        .with_max_iter(args.max_iter)
        .with_time_budget(args.budget);
    for &(option, v) in &args.options {
        let whole = |what: &str| {
            (v.fract() == 0.0 && v >= 0.0 && v <= usize::MAX as f64)
                .then_some(v as usize)
                .ok_or_else(|| format!("{what} must be a whole number >= 0, got {v}"))
        };
        match option {
            SiconosOption::MaxIter => config.max_iter = whole("SICONOS_IPARAM_MAX_ITER")?,
            SiconosOption::Tolerance => config.tolerance = v,
            SiconosOption::TimeBudget if v == 0.0 => config.time_budget = None,
            SiconosOption::TimeBudget => {
                config.time_budget = Some(Duration::try_from_secs_f64(v).map_err(|_| {
                    format!("FC3D_DPARAM_TIME_BUDGET must be 0 or a positive number of seconds, got {v}")
                })?)
            }
            SiconosOption::Rescaling => {
                config.rescaling = match whole("SICONOS_FRICTION_3D_IPARAM_RESCALING")? {
                    0 => Rescaling::None,
                    1 => Rescaling::Scalar,
                    other => {
                        return Err(format!(
                            "SICONOS_FRICTION_3D_IPARAM_RESCALING = {other} is not 0 (none) or 1 (scalar)"
                        ))
                    }
                }
            }
            SiconosOption::Relaxation => match &mut config.method {
                Method::Nsgs(o) => o.relaxation = (v != 0.0).then_some(v),
                m => {
                    return Err(format!(
                        "SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE applies to NSGS only, not to {}",
                        m.label()
                    ))
                }
            },
        }
    }
    config.validate().map_err(|e| e.to_string())?;
    Ok(config)
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
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

fn parse_local(s: &str) -> Result<LocalSolverKind, String> {
    let ids: Vec<String> = LocalSolverKind::ALL
        .iter()
        .map(|k| k.siconos_id().to_string())
        .collect();
    s.trim()
        .parse::<i32>()
        .ok()
        .and_then(LocalSolverKind::from_siconos_id)
        .ok_or_else(|| format!("unknown local solver '{s}' (one of {})", ids.join(", ")))
}

/// One problem to solve: a built-in scene, a generated one
/// (`gen:contacts=N,piles=P,seed=S[,shape=boxes]`) or a file.
enum Input {
    Scene(fc3d_core::scenes::Scene),
    Generated(fc3d_core::scenes::GeneratedScene),
    File { path: PathBuf, from_directory: bool },
}

/// A row of the result table.
struct Row {
    problem: String,
    contacts: usize,
    storage: &'static str,
    solver: String,
    report: SolveReport,
    time: Duration,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Prints help/version (exit 0) or the usage error (exit 2).
        Err(e) => e.exit(),
    };
    let args = match cli.command {
        Some(Command::Solve(args)) => args,
        Some(Command::Bench(args)) => return bench::run(&args),
        Some(Command::Convert(args)) => return convert::run(&args),
        Some(Command::Scene(args)) => return scene::run(&args),
        None => cli.solve,
    };
    run_solve(&args)
}

fn run_solve(args: &SolveArgs) -> ExitCode {
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

    let config = match config_of(args) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("fc3d: {e}");
            return ExitCode::from(2);
        }
    };

    let mut stdout = std::io::stdout().lock();
    // A closed stdout (e.g. `fc3d | head`) ends the program quietly, never with a panic.
    let mut out = |line: String| writeln!(stdout, "{line}").is_ok();
    let budget = config
        .time_budget
        .map_or(String::new(), |b| format!(", budget {b:?}"));
    let header = match config.method {
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
    };
    if !out(header) {
        return ExitCode::SUCCESS;
    }

    let mut table = Table::new();
    for input in inputs {
        let (name, problem) = match load_input(input) {
            Loaded::Problem(name, problem) => (name, problem),
            Loaded::Skipped => continue,
            Loaded::Failed => {
                failed = true;
                continue;
            }
        };
        match solve_one(&problem, &config) {
            Ok((report, time, r)) => {
                let row = Row {
                    problem: name,
                    contacts: problem.n_contacts(),
                    storage: problem.w().storage_name(),
                    solver: config.label(),
                    report,
                    time,
                };
                // Rows are printed as they come (a long run shows progress) with the widths
                // the table has settled on; the header comes first.
                let stages = row.report.stages.map(|log| stage_line(&row.problem, &log));
                let fill = row.report.fill.map(|f| fill_line(&row.problem, &f));
                for line in table.push(row).into_iter().chain(stages).chain(fill) {
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

/// What reading one input gave.
enum Loaded {
    Problem(String, FrictionProblem<'static>),
    /// Found by a folder scan but not a problem fc3d handles (a note was printed).
    Skipped,
    /// Could not be read (a message naming it was printed).
    Failed,
}

/// Reads one input; messages go to stderr.
fn load_input(input: Input) -> Loaded {
    match input {
        Input::Scene(s) => Loaded::Problem(s.name.to_string(), s.problem),
        Input::Generated(spec) => match spec.generate() {
            Ok(p) => Loaded::Problem(spec.name(), p),
            Err(e) => {
                eprintln!("fc3d: {e}");
                Loaded::Failed
            }
        },
        Input::File {
            path,
            from_directory,
        } => match read_problem(&path) {
            Ok(p) => Loaded::Problem(display_name(&path), p),
            // The reader's messages name the file.
            Err(Fc3dError::Unsupported(why)) if from_directory => {
                eprintln!("fc3d: skipping {why}");
                Loaded::Skipped
            }
            // A folder of Siconos test data holds other inputs too (global problems,
            // unit-test tables): they are not counted as failures when found by a scan.
            Err(e) if from_directory => {
                eprintln!("fc3d: skipping (not a local fc3d problem) {e}");
                Loaded::Skipped
            }
            Err(e) => {
                eprintln!("fc3d: {e}");
                Loaded::Failed
            }
        },
    }
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

fn display_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// An input named `gen:contacts=N,piles=P,seed=S` is a generated pile scene
/// ([`fc3d_core::scenes::sphere_piles`], or [`fc3d_core::scenes::box_piles`] with
/// `,shape=boxes`), not a file.
const GENERATED_PREFIX: &str = "gen:";

/// Files as given, directories replaced by their `*.dat` files sorted by name; paths that cannot
/// be used are returned as messages (the others are still solved).
fn expand_paths(paths: &[PathBuf]) -> (Vec<Input>, Vec<String>) {
    let mut inputs = Vec::new();
    let mut errors = Vec::new();
    for path in paths {
        if let Some(spec) = path.to_str().and_then(|p| p.strip_prefix(GENERATED_PREFIX)) {
            match fc3d_core::scenes::GeneratedScene::parse(spec) {
                Ok(spec) => inputs.push(Input::Generated(spec)),
                Err(e) => errors.push(e.to_string()),
            }
            continue;
        }
        match std::fs::metadata(path) {
            Err(e) => errors.push(format!("{}: {e}", path.display())),
            Ok(meta) if meta.is_dir() => match dat_files_in(path) {
                Ok(files) if files.is_empty() => errors.push(format!(
                    "{}: no .dat file in this directory",
                    path.display()
                )),
                Ok(files) => inputs.extend(files.into_iter().map(|path| Input::File {
                    path,
                    from_directory: true,
                })),
                Err(e) => errors.push(format!("{}: {e}", path.display())),
            },
            Ok(_) => inputs.push(Input::File {
                path: path.clone(),
                from_directory: false,
            }),
        }
    }
    (inputs, errors)
}

/// `.hdf5`/`.h5` files are FCLIB problems (read when built with the `fclib` feature, refused
/// with a clear message otherwise); any other path is read as a Siconos `.dat` file.
fn read_problem(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    if is_fclib(path) {
        fc3d_core::io::read_problem_file(path)
    } else {
        fc3d_core::io::dat::read_dat_file(path)
    }
}

fn is_fclib(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("hdf5") || e.eq_ignore_ascii_case("h5"))
}

fn dat_files_in(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if !path.is_file() || !(path.extension().is_some_and(|e| e == "dat") || is_fclib(&path)) {
            continue;
        }
        // Siconos names global problems (M, H, q, b, mu) GFC3D_/gfc3d_/gfc2d_: their text
        // happens to parse as a (wrong) local problem, so a folder scan leaves them out.
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        if name.starts_with("gfc3d_") || name.starts_with("gfc2d_") {
            eprintln!(
                "fc3d: skipping {}: a global (M, H) problem, not an fc3d input",
                path.display()
            );
            continue;
        }
        files.push(path);
    }
    files.sort();
    Ok(files)
}

/// Fixed-width table printed row by row.
struct Table {
    header_done: bool,
}

const HEADERS: [&str; 8] = [
    "problem",
    "contacts",
    "storage",
    "solver",
    "iterations",
    "error",
    "status",
    "time",
];
const WIDTHS: [usize; 8] = [36, 8, 12, 9, 10, 9, 9, 10];

impl Table {
    fn new() -> Self {
        Table { header_done: false }
    }

    fn push(&mut self, row: Row) -> Vec<String> {
        let mut lines = Vec::new();
        if !self.header_done {
            self.header_done = true;
            lines.push(format_cells(&HEADERS.map(String::from)));
            lines.push(format_cells(&WIDTHS.map(|w| "-".repeat(w))));
        }
        let status = row.report.status.name();
        lines.push(format_cells(&[
            row.problem,
            row.contacts.to_string(),
            row.storage.to_string(),
            row.solver,
            row.report.iterations.to_string(),
            scientific(row.report.error),
            status.to_string(),
            format_time(row.time),
        ]));
        lines
    }
}

/// Text columns left-aligned, the others right-aligned; a cell wider than its column widens it.
fn format_cells(cells: &[String; 8]) -> String {
    let mut s = String::new();
    for (k, (cell, &w)) in cells.iter().zip(WIDTHS.iter()).enumerate() {
        if k > 0 {
            s.push_str("  ");
        }
        let left = matches!(k, 0 | 2 | 3 | 6);
        if left {
            s.push_str(&format!("{cell:<w$}"));
        } else {
            s.push_str(&format!("{cell:>w$}"));
        }
    }
    s.trim_end().to_string()
}

/// `x` as `d.dde±XX`, like C's `%.2e`.
fn scientific(x: f64) -> String {
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

fn format_time(t: Duration) -> String {
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
    use clap::CommandFactory;

    #[test]
    fn generated_inputs_are_scenes_not_files() {
        let (inputs, errors) = expand_paths(&[
            PathBuf::from("gen:contacts=10,piles=2"),
            PathBuf::from("gen:piles=2"),
            PathBuf::from("gen:contacts=30,shape=boxes"),
            PathBuf::from("gen:contacts=30,shape=cones"),
        ]);
        assert_eq!((inputs.len(), errors.len()), (2, 2), "{errors:?}");
        let mut loaded = inputs.into_iter().map(load_input);
        match loaded.next().unwrap() {
            Loaded::Problem(name, p) => {
                assert_eq!(name, "piles-c10-p2-s1");
                assert_eq!(p.n_contacts(), 10);
            }
            _ => panic!("a generated scene loads"),
        }
        match loaded.next().unwrap() {
            Loaded::Problem(name, p) => {
                assert_eq!(name, "boxes-c30-p1-s1");
                assert_eq!(p.n_contacts(), 30);
            }
            _ => panic!("a generated box scene loads"),
        }
    }

    #[test]
    fn scene_writes_the_generated_problem_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("fc3d-scene-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("p.dat");
        let spec = fc3d_core::scenes::PileSpec {
            contacts: 50,
            piles: 2,
            seed: 3,
        };
        for (shape, made) in [
            (None, fc3d_core::scenes::sphere_piles(&spec).unwrap()),
            (Some("boxes"), fc3d_core::scenes::box_piles(&spec).unwrap()),
        ] {
            let cli = Cli::try_parse_from(
                [
                    "fc3d",
                    "scene",
                    "--contacts",
                    "50",
                    "--piles",
                    "2",
                    "--seed",
                    "3",
                ]
                .into_iter()
                .chain(shape.map(|s| ["--shape", s]).into_iter().flatten())
                .map(String::from)
                .chain(["-o".to_string(), out.display().to_string()]),
            )
            .unwrap();
            let Some(Command::Scene(args)) = cli.command else {
                panic!("expected the scene subcommand");
            };
            assert_eq!(scene::run(&args), ExitCode::SUCCESS);
            let read = read_problem(&out).unwrap();
            assert_eq!(read.w(), made.w(), "{shape:?}");
            assert_eq!(read.q(), made.q());
            assert_eq!(read.mu(), made.mu());
        }
        std::fs::remove_dir_all(&dir).ok();
    }

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

    #[test]
    fn cli_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn defaults_and_flags() {
        let cli = Cli::try_parse_from(["fc3d"]).unwrap();
        assert!(cli.command.is_none());
        assert!(cli.solve.paths.is_empty());
        assert_eq!(cli.solve.tol, 1e-8);
        assert_eq!(cli.solve.max_iter, 100_000);
        assert_eq!(cli.solve.local, None);
        assert_eq!(cli.solve.solver, parse_spec("AUTO").unwrap());
        assert_eq!(cli.solve.budget, None);

        let cli = Cli::try_parse_from([
            "fc3d",
            "a.dat",
            "dir",
            "--tol",
            "1e-6",
            "--max-iter",
            "50",
            "--local",
            "552",
        ])
        .unwrap();
        assert_eq!(
            cli.solve.paths,
            vec![PathBuf::from("a.dat"), PathBuf::from("dir")]
        );
        assert_eq!(cli.solve.tol, 1e-6);
        assert_eq!(cli.solve.max_iter, 50);
        assert_eq!(cli.solve.local, Some(LocalSolverKind::ProjectionOnCone));

        let cli = Cli::try_parse_from(["fc3d", "solve", "x.dat", "--local", "557"]).unwrap();
        match cli.command {
            Some(Command::Solve(a)) => {
                assert_eq!(a.paths, vec![PathBuf::from("x.dat")]);
                assert_eq!(a.local, Some(LocalSolverKind::ProjectionOnCylinder));
            }
            _ => panic!("expected the solve subcommand"),
        }

        // `bench` is a subcommand; its flags do not leak into `fc3d` / `fc3d solve`.
        let cli = Cli::try_parse_from(["fc3d", "bench", "x.dat", "--reps", "1"]).unwrap();
        match cli.command {
            Some(Command::Bench(a)) => {
                assert_eq!(a.paths, vec![PathBuf::from("x.dat")]);
                assert_eq!(a.reps, 1);
            }
            _ => panic!("expected the bench subcommand"),
        }
        assert!(Cli::try_parse_from(["fc3d", "--reps", "1"]).is_err());
        assert!(Cli::try_parse_from(["fc3d", "solve", "--timeout", "1s"]).is_err());
        // `--budget` is both a solve flag (one budget) and a bench flag (a list).
        assert!(Cli::try_parse_from(["fc3d", "solve", "--budget", "1ms"]).is_ok());
        // A file named like the subcommand, written with a path, is still a file.
        let cli = Cli::try_parse_from(["fc3d", "./bench"]).unwrap();
        assert!(cli.command.is_none());
        assert_eq!(cli.solve.paths, vec![PathBuf::from("./bench")]);
    }

    #[test]
    fn convert_takes_two_files_and_the_info_flags() {
        let cli = Cli::try_parse_from(["fc3d", "convert", "a.dat", "b.hdf5"]).unwrap();
        match cli.command {
            Some(Command::Convert(a)) => {
                assert_eq!(a.input, PathBuf::from("a.dat"));
                assert_eq!(a.output, PathBuf::from("b.hdf5"));
                assert_eq!((a.title, a.description, a.math_info), (None, None, None));
            }
            _ => panic!("expected the convert subcommand"),
        }
        let cli = Cli::try_parse_from([
            "fc3d",
            "convert",
            "a.hdf5",
            "b.h5",
            "--title",
            "T",
            "--description",
            "D",
            "--math-info",
            "M",
        ])
        .unwrap();
        match cli.command {
            Some(Command::Convert(a)) => {
                assert_eq!(a.title.as_deref(), Some("T"));
                assert_eq!(a.description.as_deref(), Some("D"));
                assert_eq!(a.math_info.as_deref(), Some("M"));
            }
            _ => panic!("expected the convert subcommand"),
        }
        for bad in [
            vec!["fc3d", "convert"],
            vec!["fc3d", "convert", "a.dat"],
            vec!["fc3d", "convert", "a.dat", "b.dat", "c.dat"],
            vec!["fc3d", "convert", "a.dat", "b.dat", "--tol", "1e-3"],
        ] {
            assert!(Cli::try_parse_from(&bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn bad_flags_are_errors() {
        for bad in [
            vec!["fc3d", "--local", "500"],
            vec!["fc3d", "--local", "x"],
            vec!["fc3d", "--tol", "-1"],
            vec!["fc3d", "--tol", "nan"],
            vec!["fc3d", "--tol", "inf"],
            vec!["fc3d", "--max-iter", "-3"],
            vec!["fc3d", "--frobnicate"],
            vec!["fc3d", "--solver", "PSOR"],
            vec!["fc3d", "--budget", "soon"],
            vec!["fc3d", "--option", "SICONOS_IPARAM_MAX_ITER"],
            vec!["fc3d", "--option", "NO_SUCH_SLOT=1"],
            vec!["fc3d", "--option", "SICONOS_DPARAM_TOL=x"],
        ] {
            assert!(Cli::try_parse_from(&bad).is_err(), "{bad:?}");
        }
        // Parsed, but refused when the configuration is built.
        for bad in [
            vec!["fc3d", "--solver", "PROX", "--local", "552"],
            vec!["fc3d", "--option", "SICONOS_IPARAM_MAX_ITER=2.5"],
            vec!["fc3d", "--option", "SICONOS_FRICTION_3D_IPARAM_RESCALING=3"],
            vec!["fc3d", "--option", "SICONOS_DPARAM_TOL=-1"],
            vec![
                "fc3d",
                "--solver",
                "AUTO",
                "--option",
                "SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE=0.5",
            ],
        ] {
            let cli = Cli::try_parse_from(&bad).unwrap();
            assert!(config_of(&cli.solve).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn solver_budget_and_options_build_the_config() {
        let cli = Cli::try_parse_from(["fc3d"]).unwrap();
        let c = config_of(&cli.solve).unwrap();
        assert_eq!(c.siconos_id(), 590);
        assert_eq!(
            (c.tolerance, c.max_iter, c.time_budget),
            (1e-8, 100_000, None)
        );
        let cli = Cli::try_parse_from([
            "fc3d",
            "--solver",
            "nsgs",
            "--local",
            "552",
            "--budget",
            "10ms",
            "--option",
            "SICONOS_IPARAM_MAX_ITER=77",
            "--option",
            "siconos_dparam_tol=1e-5",
            "--option",
            "SICONOS_FRICTION_3D_IPARAM_RESCALING=1",
            "--option",
            "SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE=0.9",
        ])
        .unwrap();
        let c = config_of(&cli.solve).unwrap();
        assert_eq!(c.label(), "NSGS/552");
        assert_eq!((c.tolerance, c.max_iter), (1e-5, 77));
        assert_eq!(c.time_budget, Some(Duration::from_millis(10)));
        assert_eq!(c.rescaling, Rescaling::Scalar);
        let Method::Nsgs(o) = c.method else { panic!() };
        assert_eq!(o.relaxation, Some(0.9));
        let cli = Cli::try_parse_from([
            "fc3d",
            "--solver",
            "504",
            "--option",
            "FC3D_DPARAM_TIME_BUDGET=0.5",
        ])
        .unwrap();
        let c = config_of(&cli.solve).unwrap();
        assert_eq!(c.label(), "NSN-AC/GP");
        assert_eq!(c.time_budget, Some(Duration::from_millis(500)));
    }

    #[test]
    fn scientific_format() {
        assert_eq!(scientific(2.5912e-9), "2.59e-09");
        assert_eq!(scientific(0.0), "0.00e+00");
        assert_eq!(scientific(1.27e-6), "1.27e-06");
        assert_eq!(scientific(3.0e120), "3.00e+120");
        assert_eq!(scientific(f64::NAN), "NaN");
    }

    #[test]
    fn paths_that_cannot_be_used_are_reported() {
        let (inputs, errors) = expand_paths(&[
            PathBuf::from("/nonexistent/fc3d/a.dat"),
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src"),
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml"),
        ]);
        assert_eq!(inputs.len(), 1);
        assert_eq!(errors.len(), 2, "{errors:?}");
        assert!(errors[1].contains("no .dat file"));
    }

    #[test]
    fn time_format() {
        assert_eq!(format_time(Duration::from_nanos(12_345)), "12.3 µs");
        assert_eq!(format_time(Duration::from_micros(12_345)), "12.35 ms");
        assert_eq!(format_time(Duration::from_millis(12_345)), "12.345 s");
    }
}
