//! The `fc3d bench` arguments (clap) and their value parsers.

use std::path::PathBuf;
use std::time::Duration;

use clap::Args;

use super::spec::{self, SolverSpec};

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
    #[arg(long, value_name = "X,...", value_delimiter = ',', value_parser = crate::units::parse_tolerance)]
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
    /// Tolerance mode with AUTO among the solvers: exit status 1 when AUTO is more than this many
    /// times slower than the fastest other solver on some problem and tolerance, or does not
    /// converge where another does (`auto-ratio.txt` lists every ratio).
    #[arg(long, value_name = "X")]
    pub auto_max_ratio: Option<f64>,
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
