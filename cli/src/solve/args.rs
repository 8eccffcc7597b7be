//! The flags of `fc3d solve` (and of `fc3d` without a subcommand) and the solver configuration
//! they describe.

use std::path::PathBuf;
use std::time::Duration;

use clap::Args;

use crate::bench;
use crate::bench::spec::{parse_spec, SolverSpec};
use crate::units::parse_tolerance;
use fc3d_core::global::{GlobalConfig, GlobalMethod};
use fc3d_core::{F32Sweeps, LocalSolverKind, Method, NsgsOptions, Rescaling, SolverConfig};

#[derive(Args, Debug, Clone, PartialEq)]
pub(crate) struct SolveArgs {
    /// Siconos .dat problem files (local or global: a global file, M and H, is recognised by its
    /// content), FCLIB files, or directories whose *.dat files are solved. None: the built-in
    /// scenes.
    #[arg(value_name = "FILES")]
    pub paths: Vec<PathBuf>,
    /// Tolerance on the relative natural-map error.
    #[arg(long, value_name = "X", default_value = "1e-8", value_parser = parse_tolerance)]
    pub tol: f64,
    /// Iteration limit (sweeps for NSGS, Newton steps for NSN, all stages together for AUTO).
    #[arg(long, value_name = "N", default_value_t = 100_000)]
    pub max_iter: usize,
    /// Solver, by name or Siconos id, with its defaults (as `fc3d bench --solvers`): AUTO (590,
    /// the default), NSGS or 500 (local solver 565), NSGS/552, VI-FPP, NSN-AC, PROX, TFP, ADMM...;
    /// for global problems also a global id or name (600 NSGS_WR, 605 GFC3D_NSGS, 607, 613, 615,
    /// ...): a local solver solves a global problem's reduction (AUTO's by default).
    #[arg(long, value_name = "SOLVER", default_value = "AUTO", value_parser = parse_spec)]
    pub solver: SolverSpec,
    /// NSGS's local solver, by Siconos id (only with an NSGS solver): 550 (Alart-Curnier
    /// Newton), 551 (Newton with Goldstein-Price line search), 552 (one projection on the cone),
    /// 553 (projection on the cone with local iterations), 557 (one projection on the
    /// cylinder), 565 (hybrid Newton, NSGS's default), 554, 555, 558, 561, 562, 564, 570, 571,
    /// 572.
    #[arg(long, value_name = "ID", value_parser = parse_local)]
    pub local: Option<LocalSolverKind>,
    /// Wall-clock budget of each solve (`10ms`, `1s`...): the solver stops when it is spent and
    /// returns its best iterate (with tolerance 0: an anytime solve).
    #[arg(long, value_name = "TIME", value_parser = bench::args::parse_duration)]
    pub budget: Option<Duration>,
    /// A Siconos option slot by name, applied after the flags above (repeatable):
    /// SICONOS_IPARAM_MAX_ITER, SICONOS_DPARAM_TOL, FC3D_DPARAM_TIME_BUDGET (s, 0 = none),
    /// SICONOS_FRICTION_3D_IPARAM_RESCALING (0 none, 1 scalar),
    /// SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE (NSGS, 0 = none).
    #[arg(long = "option", value_name = "NAME=VALUE", value_parser = parse_option)]
    pub options: Vec<(SiconosOption, f64)>,
    /// After each problem, print per-contact diagnostics as `#` lines: how many contacts take
    /// off, stick, slide or sit at the cone apex, and the K contacts (default 5) with the
    /// largest share of the error, with their status and normal velocity u_N (< 0: penetrating).
    /// Written `--diagnostics` or `--diagnostics=K`.
    #[arg(long, value_name = "K", num_args = 0..=1, require_equals = true, default_missing_value = "5")]
    pub diagnostics: Option<usize>,
    /// NSGS only: early sweeps on an f32 copy of W's coupling blocks (f64 accumulation, f64
    /// diagonal blocks and local solves), then f64 sweeps from the first test whose error is at
    /// most E (default 1e-5), or when the f32 sweeps reach their rounding floor or stall. Every
    /// full error, the final one included, is measured in f64 on the problem's W. Written
    /// `--f32-sweeps` or `--f32-sweeps=E`.
    #[arg(long, value_name = "E", num_args = 0..=1, require_equals = true, default_missing_value = "1e-5")]
    pub f32_sweeps: Option<f64>,
}

/// The Siconos option slots `--option` sets, by their Siconos names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SiconosOption {
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

/// The configuration of a global problem the flags describe, checked by the core: the global
/// solver given, or the reduction with the local configuration of [`config_of`] (which must not
/// rescale: the reduced problem is solved as it is, as Siconos' `_WR` ids do).
pub(crate) fn global_config_of(args: &SolveArgs) -> Result<GlobalConfig, String> {
    let SolverSpec::Global(method) = args.solver else {
        let local = config_of(args)?;
        if local.rescaling != Rescaling::None {
            return Err(
                "SICONOS_FRICTION_3D_IPARAM_RESCALING: the reduction of a global problem is \
                 solved without rescaling"
                    .to_string(),
            );
        }
        let mut config = GlobalConfig::new(GlobalMethod::Reduced(local.method));
        config.tolerance = local.tolerance;
        config.max_iter = local.max_iter;
        config.time_budget = local.time_budget;
        return Ok(config);
    };
    if args.f32_sweeps.is_some() {
        return Err(format!(
            "--f32-sweeps applies to NSGS on W only, not to the global solver {}",
            method.label()
        ));
    }
    let method = match (method, args.local) {
        // The H-form sweep is NSGS: its local solver is chosen the same way.
        (GlobalMethod::HForm(o), Some(local)) => GlobalMethod::HForm(NsgsOptions {
            local: NsgsOptions::with_local(local).local,
            ..o
        }),
        (method, Some(_)) => {
            return Err(format!(
                "--local applies to NSGS only, not to the global solver {}",
                method.label()
            ))
        }
        (method, None) => method,
    };
    let mut config = GlobalConfig::new(method);
    config.tolerance = args.tol;
    config.max_iter = args.max_iter;
    config.time_budget = args.budget;
    for &(option, v) in &args.options {
        match option {
            SiconosOption::MaxIter => config.max_iter = whole(v, "SICONOS_IPARAM_MAX_ITER")?,
            SiconosOption::Tolerance => config.tolerance = v,
            SiconosOption::TimeBudget => config.time_budget = budget_of(v)?,
            SiconosOption::Rescaling | SiconosOption::Relaxation => {
                return Err(format!(
                    "{} applies to the local solvers, not to the global solver {}",
                    OPTION_NAMES
                        .iter()
                        .find(|(_, o)| *o == option)
                        .map_or("", |(n, _)| *n),
                    method.label()
                ))
            }
        }
    }
    config.validate().map_err(|e| e.to_string())?;
    Ok(config)
}

/// A whole number >= 0 from an option's value.
fn whole(v: f64, what: &str) -> Result<usize, String> {
    (v.fract() == 0.0 && v >= 0.0 && v <= usize::MAX as f64)
        .then_some(v as usize)
        .ok_or_else(|| format!("{what} must be a whole number >= 0, got {v}"))
}

/// `FC3D_DPARAM_TIME_BUDGET`: 0 none, else seconds.
fn budget_of(v: f64) -> Result<Option<Duration>, String> {
    if v == 0.0 {
        return Ok(None);
    }
    Duration::try_from_secs_f64(v).map(Some).map_err(|_| {
        format!("FC3D_DPARAM_TIME_BUDGET must be 0 or a positive number of seconds, got {v}")
    })
}

/// The configuration the flags describe, checked by the core.
pub(crate) fn config_of(args: &SolveArgs) -> Result<SolverConfig, String> {
    let method = match (args.solver.local_method()?, args.local) {
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
        match option {
            SiconosOption::MaxIter => config.max_iter = whole(v, "SICONOS_IPARAM_MAX_ITER")?,
            SiconosOption::Tolerance => config.tolerance = v,
            SiconosOption::TimeBudget => config.time_budget = budget_of(v)?,
            SiconosOption::Rescaling => {
                config.rescaling = match whole(v, "SICONOS_FRICTION_3D_IPARAM_RESCALING")? {
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
    if let Some(switch_error) = args.f32_sweeps {
        match &mut config.method {
            Method::Nsgs(o) => o.f32_sweeps = Some(F32Sweeps { switch_error }),
            m => {
                return Err(format!(
                    "--f32-sweeps applies to NSGS only, not to {}",
                    m.label()
                ))
            }
        }
    }
    config.validate().map_err(|e| e.to_string())?;
    Ok(config)
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
