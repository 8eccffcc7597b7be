//! The only place that knows Siconos' iparam/dparam indices: each family's mapping between its
//! typed settings in the core and the slots of a `SolverOptions` (reading a host's options, and
//! writing the defaults `solver_options_create` returns), and the names of the settings' slots
//! for messages. Ranges are checked by the core (`SolverConfig::validate`); this layer decodes
//! integers into choices, rejects codes it does not know, and names the slot of a setting the
//! core rejects.

mod admm;
pub(crate) mod auto;
mod fixed_point;
pub(crate) mod global;
mod local;
mod nsgs;
mod nsn;
pub(crate) mod planar;
mod prox;
pub(crate) mod rolling;
mod siconos;
mod siconos_table;
mod tolerance;
mod vi;

pub(crate) use crate::names::{solver_name, solver_name_to_id};
pub(crate) use tolerance::{internal_solver_tolerance, set_tolerance};

use std::os::raw::{c_double, c_int};
use std::time::Duration;

use super::option_tree::check_tree;
use super::types::SolverOptions;
use super::{CError, CResult, FC3D_ERR_INVALID_OPTION, FC3D_ERR_UNSUPPORTED_SOLVER};
use fc3d_core::{Fc3dError, LocalSolverKind, Method, SolverConfig};

pub(crate) use super::OPTIONS_PARAM_SIZE;
const SIZE: usize = OPTIONS_PARAM_SIZE as usize;

// Option indices (Siconos' SICONOS_IPARAM / SICONOS_DPARAM and Friction_cst.h enums).
pub(crate) const IPARAM_MAX_ITER: usize = 0;
pub(crate) const IPARAM_ITER_DONE: usize = 1;
pub(crate) const IPARAM_INTERNAL_ERROR_STRATEGY: usize = 2;
pub(crate) const IPARAM_RESCALING: usize = 3;
pub(crate) const IPARAM_ERROR_EVALUATION: usize = 7;
pub(crate) const IPARAM_ERROR_EVALUATION_FREQUENCY: usize = 8;
pub(crate) const DPARAM_TOL: usize = 0;
pub(crate) const DPARAM_RESIDU: usize = 1;
pub(crate) const DPARAM_INTERNAL_ERROR_RATIO: usize = 2;
/// fc3d's wall-clock budget in seconds (0, the default: none), an index Siconos' fc3d solvers
/// leave unused (`FC3D_DPARAM_TIME_BUDGET`).
pub(crate) const DPARAM_TIME_BUDGET: usize = super::FC3D_DPARAM_TIME_BUDGET as usize;
/// Where NSGS writes Dumont's criterion (`FC3D_DPARAM_DUMONT_CRITERION`).
pub(crate) const DPARAM_DUMONT_CRITERION: usize = super::FC3D_DPARAM_DUMONT_CRITERION as usize;

use super::FC3D_RHO_STRATEGY_DUMONT;
use super::{FC3D_IPARAM_VARIANT, FC3D_VARIANT_FC3D, FC3D_VARIANT_SICONOS};
use fc3d_core::AlgorithmVariant;

/// Where Siconos' or fc3d's iteration is chosen (`FC3D_IPARAM_VARIANT`), for the ids that have
/// both.
pub(crate) const IPARAM_VARIANT: usize = FC3D_IPARAM_VARIANT as usize;

impl Params<'_> {
    /// The variant in `iparam[FC3D_IPARAM_VARIANT]`.
    pub fn variant(&self) -> CResult<AlgorithmVariant> {
        match self.iparam[IPARAM_VARIANT] {
            FC3D_VARIANT_SICONOS => Ok(AlgorithmVariant::Siconos),
            FC3D_VARIANT_FC3D => Ok(AlgorithmVariant::Fc3d),
            other => Err(invalid(format!("variant (iparam[{IPARAM_VARIANT}]) = {other} is not one of {FC3D_VARIANT_SICONOS} (Siconos) and {FC3D_VARIANT_FC3D} (fc3d)"))),
        }
    }
}

/// The code of `variant` in `iparam[FC3D_IPARAM_VARIANT]`.
pub(crate) fn variant_code(variant: AlgorithmVariant) -> c_int {
    match variant {
        AlgorithmVariant::Siconos => FC3D_VARIANT_SICONOS,
        AlgorithmVariant::Fc3d => FC3D_VARIANT_FC3D,
    }
}

/// The slot each setting the core may reject comes from, for messages.
const SETTING_SLOTS: &[(&str, &str)] = &[
    ("tolerance", "dparam[0]"),
    ("time_budget", "dparam[19]"),
    ("nsgs.relaxation", "dparam[8]"),
    ("nsgs.local_tolerance.ratio", "dparam[2]"),
    ("nsgs.decomposition", "iparam[15]"),
    ("local.tolerance", "internal solver's dparam[0]"),
    ("local.rho", "internal solver's dparam[3]"),
    ("local.regularization", "internal solver's dparam[3]"),
    ("vi.rho", "dparam[3]"),
    ("vi.nu", "dparam[4]"),
    ("vi.increase", "dparam[5]"),
    ("vi.l", "dparam[6]"),
    ("vi.l_min", "dparam[7]"),
    ("vi.max_trials", "iparam[9]"),
    ("admm.rho", "dparam[3]"),
    ("admm.restart_eta", "dparam[4]"),
    ("admm.balancing_tau", "dparam[5]"),
    ("admm.balancing_phi", "dparam[6]"),
    ("inner_tolerance.ratio", "dparam[2]"),
    ("inner_tolerance", "internal solver's dparam[0]"),
    ("soclcp.relaxation", "dparam[8]"),
    ("nsn.rho", "dparam[3]"),
    ("nsn.line_search_max_iter", "iparam[12]"),
    ("prox.alpha", "dparam[3]"),
    ("prox.sigma", "dparam[4]"),
    ("prox.nu", "dparam[5]"),
];

/// The C error of a core error, naming the iparam/dparam slot of a rejected setting.
pub(crate) fn annotate(e: Fc3dError) -> CError {
    if let Fc3dError::InvalidSetting {
        setting,
        value,
        requirement,
    } = &e
    {
        let slot = SETTING_SLOTS
            .iter()
            .find(|(s, _)| s == setting)
            .map_or("", |(_, slot)| slot);
        return CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("{setting} ({slot}) = {value} must be {requirement}"),
        );
    }
    e.into()
}

pub(crate) fn invalid(msg: impl Into<String>) -> CError {
    CError::new(FC3D_ERR_INVALID_OPTION, msg)
}

/// `FC3D_ERR_UNSUPPORTED_SOLVER` for an id fc3d does not run where it was given, naming the
/// solver and saying why.
pub(crate) fn unsupported_solver(id: c_int) -> CError {
    if let Some(reason) = unfinished_in_siconos(id) {
        return CError::new(
            FC3D_ERR_UNSUPPORTED_SOLVER,
            format!(
                "solver id {id} ({}) is rejected by fc3d: {reason}",
                solver_name(id).to_string_lossy()
            ),
        );
    }
    let why = match id {
        514 | 515 | 518 | 519 | 608 | 609 => {
            "is not provided by fc3d: it calls GAMS/PATH, a commercial solver fc3d does not link"
        }
        600..=615 => "is a solver of the global formulation: call gfc3d_driver",
        5000 => "is the global rolling-friction solver: call g_rolling_fc3d_driver",
        3000..=3003 => "is a rolling-friction solver: call rolling_fc3d_driver",
        4000..=4002 => "is a 2D rolling-friction solver: call rolling_fc2d_driver",
        400..=405 => "is a 2D solver: it runs through fc2d_driver, not fc3d_driver",
        1000..=1299 => {
            "is a VI, SOCLCP or ConvexQP solver: fc3d knows its options (the internal solvers of the friction solvers) but does not run it as a solver of its own"
        }
        _ => "is not implemented in fc3d",
    };
    CError::new(
        FC3D_ERR_UNSUPPORTED_SOLVER,
        format!(
            "solver id {id} ({}) {why}",
            solver_name(id).to_string_lossy()
        ),
    )
}

/// Why fc3d rejects an id that is an unfinished experiment in Siconos 4.4 itself (evidence from
/// Siconos' sources and runs of the installed library, README "Solver ids").
fn unfinished_in_siconos(id: c_int) -> Option<&'static str> {
    match id {
        501 => Some(
            "Siconos 4.4's NSGSV (fc3d_nsgs_velocity) is unfinished: it accepts only the local \
             solver 558 while solver_options_create(501) gives it 550 (Siconos exits), passes a \
             NULL local problem to 558 (Siconos crashes), handles dense matrices only, and \
             overwrites W with its pseudo-inverse",
        ),
        _ => None,
    }
}

/// Ids of Friction_cst.h that Siconos 4.4 itself does not run as top-level solvers: its
/// `fc3d_driver` has no case for them and stops with "Unknown solver". fc3d rejects them with
/// the reason (the evidence is in Siconos 4.4.0's sources, cited in README.md).
fn not_a_top_level_solver(id: c_int) -> Option<CError> {
    let why = match id {
        510 => {
            "in Siconos 4.4 an NSGS local solver only, and an unfinished one: its fixed point \
             (NCP_FixedP.c, compute_Z_GlockerFixedP) never recomputes the Glocker map inside the \
             loop, fc3d_FixedP_solve never maps the result back to the contact's reaction (the call \
             to its post-solver is commented out) and exits the process when it does not converge"
        }
        566 | 567 => {
            "in Siconos 4.4 a Tresca (cylinder) sub-problem solver of TFP (503) only: set it as \
             TFP's internal solver (internalSolvers[0]->solverId)"
        }
        _ => return None,
    };
    Some(CError::new(
        FC3D_ERR_UNSUPPORTED_SOLVER,
        format!(
            "solver id {id} ({}) is not a top-level friction solver: {why}; Siconos' fc3d_driver \
             rejects it too (\"Unknown solver\")",
            solver_name(id).to_string_lossy()
        ),
    ))
}

// ---------------------------------------------------------------------------------------------
// Reading.

/// Typed view of a host's parameter arrays.
pub(crate) struct Params<'a> {
    pub iparam: &'a [c_int],
    pub dparam: &'a [c_double],
}

impl<'a> Params<'a> {
    pub unsafe fn of(o: &'a SolverOptions, what: &str) -> CResult<Self> {
        if o.iparam.is_null() || o.dparam.is_null() {
            return Err(invalid(format!("{what}: iparam or dparam is NULL")));
        }
        if o.iSize < OPTIONS_PARAM_SIZE || o.dSize < OPTIONS_PARAM_SIZE {
            return Err(invalid(format!(
                "{what}: iSize = {} and dSize = {} must be at least {OPTIONS_PARAM_SIZE}",
                o.iSize, o.dSize
            )));
        }
        // Only the first OPTIONS_PARAM_SIZE slots carry settings: nothing beyond them is read,
        // whatever iSize and dSize say.
        Ok(Params {
            iparam: std::slice::from_raw_parts(o.iparam, SIZE),
            dparam: std::slice::from_raw_parts(o.dparam, SIZE),
        })
    }

    /// `iparam[k]` as a count (>= 0).
    pub fn count(&self, k: usize, what: &str) -> CResult<usize> {
        usize::try_from(self.iparam[k]).map_err(|_| {
            invalid(format!(
                "{what} (iparam[{k}]) = {} is negative",
                self.iparam[k]
            ))
        })
    }

    /// fc3d's wall-clock budget (`dparam[FC3D_DPARAM_TIME_BUDGET]`, seconds, 0 = none). Huge
    /// means unlimited: a budget too large for the clock (above about 1.8e19 s, +inf included)
    /// is no budget. A positive budget below the clock's resolution is 1 ns (spent at once), not
    /// a zero budget.
    pub fn time_budget(&self) -> CResult<Option<Duration>> {
        let b = self.dparam[DPARAM_TIME_BUDGET];
        if b == 0.0 {
            Ok(None)
        } else if b > 0.0 && !b.is_nan() {
            Ok(Duration::try_from_secs_f64(b)
                .ok()
                .map(|d| d.max(Duration::from_nanos(1))))
        } else {
            Err(invalid(format!(
                "time budget (dparam[{DPARAM_TIME_BUDGET}]) = {b} must be 0 (none) or a positive number of seconds"
            )))
        }
    }

    /// Rejects a non-default value of an option fc3d does not implement (never ignore it
    /// silently: the host asked for a behaviour).
    pub fn require(&self, k: usize, expected: c_int, name: &str) -> CResult<()> {
        if self.iparam[k] == expected {
            Ok(())
        } else {
            Err(invalid(format!(
                "{name} (iparam[{k}]) = {} is not implemented in fc3d (only {expected})",
                self.iparam[k]
            )))
        }
    }
}

/// The first internal solver's options, if any.
pub(crate) unsafe fn first_internal(o: &SolverOptions) -> Option<&SolverOptions> {
    if o.numberOfInternalSolvers >= 1 && !o.internalSolvers.is_null() {
        (*o.internalSolvers).as_ref()
    } else {
        None
    }
}

/// The typed solver configuration described by Siconos options, checked by the core. Rejects
/// unimplemented solver ids and options with a message naming them, and option trees that are
/// not finite or not readable (`check_tree`: cycles, chains deeper than
/// `FC3D_OPTIONS_MAX_DEPTH`, counts and sizes outside the limits).
pub(crate) unsafe fn config_from_c(o: &SolverOptions) -> CResult<SolverConfig> {
    check_tree(o)?;
    config_from_node(o)
}

/// The 2D configuration (`fc2d_driver`) the options describe: ids 400, 402, 404, 405; any other
/// id is refused with `FC3D_ERR_UNSUPPORTED_SOLVER`. The tree is checked as in
/// [`config_from_c`].
pub(crate) unsafe fn planar_config_from_c(o: &SolverOptions) -> CResult<fc3d_core::PlanarConfig> {
    check_tree(o)?;
    let id = o.solverId;
    let what = solver_name(id).to_string_lossy();
    if !planar::is_planar(id) {
        return Err(CError::new(
            FC3D_ERR_UNSUPPORTED_SOLVER,
            format!(
                "solver id {id} ({what}) is not a 2D friction solver: fc2d_driver solves 400 \
                 (F2D_NSGS), 402 (F2D_CPG), 404 (F2D_LEMKE) and 405 (F2D_ENUM)"
            ),
        ));
    }
    let p = Params::of(o, &format!("{what} options"))?;
    planar::read(id, &p)
}

/// The rolling configuration (`rolling_fc3d_driver` for `dimension` 5, `rolling_fc2d_driver`
/// for 3) the options describe; any other id is refused with `FC3D_ERR_UNSUPPORTED_SOLVER`. The
/// tree is checked as in [`config_from_c`].
pub(crate) unsafe fn rolling_config_from_c(
    o: &SolverOptions,
    dimension: usize,
) -> CResult<fc3d_core::RollingConfig> {
    check_tree(o)?;
    let id = o.solverId;
    if !rolling::is_rolling(id, dimension) {
        let (driver, ids) = if dimension == 5 {
            (
                "rolling_fc3d_driver",
                "3000 (RFC3D_NSGS) and 3003 (RFC3D ADMM)",
            )
        } else {
            ("rolling_fc2d_driver", "4000 (RFC2D_NSGS)")
        };
        return Err(CError::new(
            FC3D_ERR_UNSUPPORTED_SOLVER,
            format!(
                "solver id {id} ({}) is not run by {driver}: fc3d's {driver} solves {ids}",
                solver_name(id).to_string_lossy()
            ),
        ));
    }
    let what = solver_name(id).to_string_lossy();
    let p = Params::of(o, &format!("{what} options"))?;
    rolling::read(id, dimension, &p, first_internal(o))
}

/// `config_from_c` of a node of a checked tree.
pub(crate) unsafe fn config_from_node(o: &SolverOptions) -> CResult<SolverConfig> {
    config_from_node_as(o, o.solverId)
}

/// [`config_from_node`] reading the options as those of solver `id` (a global `_WR` id reads
/// its slots as its local solver does: 600 as 500, ...).
pub(crate) unsafe fn config_from_node_as(o: &SolverOptions, id: c_int) -> CResult<SolverConfig> {
    let what = solver_name(id).to_string_lossy();
    let p = Params::of(o, &format!("{what} options"))?;
    let internal = first_internal(o);
    let method = match id {
        500 => Method::Nsgs(nsgs::read(&p, internal)?),
        505 | 506 | 507 | 508 | 511 | 512 => Method::Vi(vi::read(id, &p)?),
        504 | 513 | 520 => Method::Nsn(nsn::read(id, &p)?),
        521 => Method::Nsn(nsn::read_ac_test(&p)?),
        502 => Method::Prox(prox::read(&p, internal)?),
        503 => Method::Tresca(fixed_point::read_tfp(&p, internal)?),
        522 => Method::Pfp(fixed_point::read_pfp(&p, o)?),
        516 => Method::Aclm(fixed_point::read_aclm(&p, internal)?),
        517 => Method::Soclcp(fixed_point::read_soclcp(&p, internal)?),
        523 => Method::Admm(admm::read(&p)?),
        super::FC3D_AUTO => Method::Auto(auto::read(&p)?),
        id if planar::is_planar(id) => {
            return Err(CError::new(
                FC3D_ERR_UNSUPPORTED_SOLVER,
                format!("solver id {id} ({what}) solves 2D problems: call fc2d_driver"),
            ))
        }
        // QUARTIC as a top-level solver (Siconos 4.4 solves a one-contact problem with it):
        // NSGS sweeps with the exact one-contact solution, which solve one contact in a sweep
        // and extend it to any number of contacts.
        562 | 563 => Method::Nsgs(fc3d_core::NsgsOptions {
            local: local::read(o)?,
            ..Default::default()
        }),
        _ => return Err(not_a_top_level_solver(id).unwrap_or_else(|| unsupported_solver(id))),
    };
    let mut config = SolverConfig::new(method);
    config.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
    config.tolerance = p.dparam[DPARAM_TOL];
    config.time_budget = p.time_budget()?;
    if id == 500 {
        config.rescaling = nsgs::read_rescaling(&p)?;
    }
    config.validate().map_err(annotate)?;
    Ok(config)
}

/// Writes the outputs Siconos hosts read: iterations done and final error (and Dumont's
/// criterion where it was measured).
pub(crate) unsafe fn write_outputs(o: &mut SolverOptions, report: &fc3d_core::SolveReport) {
    *o.iparam.add(IPARAM_ITER_DONE) = c_int::try_from(report.iterations).unwrap_or(c_int::MAX);
    *o.dparam.add(DPARAM_RESIDU) = report.error;
    if let Some(d) = report.dumont_criterion {
        *o.dparam.add(DPARAM_DUMONT_CRITERION) = d;
    }
    // Siconos' VI solvers (506/507) leave their adapted rho in dparam[3] as -rho, the encoding
    // of "self-adaptive from rho", for the host's next call.
    if let Some(rho) = report.final_rho {
        *o.dparam.add(vi::DPARAM_RHO) = -rho;
    }
    if let Some(log) = &report.stages {
        *o.iparam.add(auto::IPARAM_STAGES) = auto::encode_stages(log);
    }
}

// ---------------------------------------------------------------------------------------------
// Writing the defaults.

/// The content of a `SolverOptions` before it is allocated for C: id, parameters, internal
/// solvers.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Encoded {
    pub id: c_int,
    pub iparam: [c_int; SIZE],
    pub dparam: [c_double; SIZE],
    pub internal: Vec<Encoded>,
}

impl Encoded {
    fn new(id: c_int) -> Self {
        let mut dparam = [0.0; SIZE];
        // The residual is +inf until a solve writes it, as in Siconos.
        dparam[DPARAM_RESIDU] = f64::INFINITY;
        Encoded {
            id,
            iparam: [0; SIZE],
            dparam,
            internal: Vec::new(),
        }
    }
}

/// The options `solver_options_create(id)` returns: Siconos 4.4's defaults for every solver id
/// of the friction headers (implemented or not: `fc3d_driver` rejects the others), and for
/// fc3d's own one-contact ids the local solver's `LocalSolverOptions::new` written into the slots.
pub(crate) fn defaults(id: c_int) -> CResult<Encoded> {
    if let Some(e) = siconos::defaults(id) {
        return Ok(e);
    }
    if let Some(kind) = LocalSolverKind::from_siconos_id(id) {
        return Ok(local::write(&fc3d_core::LocalSolverOptions::new(kind)));
    }
    if id == super::FC3D_AUTO {
        return Ok(auto::defaults());
    }
    Err(CError::new(
        FC3D_ERR_UNSUPPORTED_SOLVER,
        format!(
            "unknown solver id {id} ({}): not a solver of Siconos 4.4's friction headers nor of fc3d",
            solver_name(id).to_string_lossy()
        ),
    ))
}

/// The slots of a configuration (and its internal solvers').
#[cfg(test)]
#[cfg(test)]
mod tests;
