//! The rolling-friction ids (Siconos' `rolling_fc3d` and `rolling_fc2d`): 3000 / 4000 NSGS read
//! the sweep slots of the 3D NSGS (iparam[7] error evaluation, iparam[2] local tolerance
//! strategy with its ratio dparam[2], iparam[4] relaxation with omega dparam[8], iparam[5]/[6]
//! shuffling, iparam[8] evaluation frequency, iparam[19] freezing) and iparam[14], the filter
//! of local solutions; internal solver 0 is the local solver: 3001 / 4001 one projected step,
//! 3002 / 4002 the projection iteration (its iparam[0] steps, dparam[0] tolerance, iparam[10]
//! the closed-form stick branch). Siconos' 2D NSGS takes the 3D local ids 3001 / 3002 (its
//! `solver_options_create(4000)` gives 3002); fc3d accepts those and 4001 / 4002 alike. 3003
//! ADMM reads the slots of the 3D ADMM (523, `params/admm.rs`); Siconos' rolling ADMM has no
//! rescaling, so iparam[3] must be 0.

use std::os::raw::c_int;

use super::{annotate, invalid, nsgs, Params, DPARAM_TOL, IPARAM_MAX_ITER};
use crate::types::SolverOptions;
use crate::CResult;
use fc3d_core::{
    RollingConfig, RollingLocalSolver, RollingMethod, RollingNsgsOptions,
    RollingProjectionIteration,
};

const IPARAM_FILTER_LOCAL_SOLUTION: usize = 14;
const IPARAM_USE_TRIVIAL_SOLUTION: usize = 10;

/// Whether `id` is a top-level rolling solver of the dimension (5: 3D, 3: 2D).
pub(crate) fn is_rolling(id: c_int, dimension: usize) -> bool {
    match dimension {
        5 => matches!(id, 3000 | 3003),
        _ => matches!(id, 4000),
    }
}

/// The configuration the options of rolling id `id` describe for contacts of dimension
/// `dimension` (5 or 3); the caller checked the id.
pub(crate) unsafe fn read(
    id: c_int,
    dimension: usize,
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<RollingConfig> {
    if id == 3003 {
        let mut config = RollingConfig::new(RollingMethod::Admm(super::admm::read(p)?));
        config.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
        config.tolerance = p.dparam[DPARAM_TOL];
        config.time_budget = p.time_budget()?;
        config.validate().map_err(annotate)?;
        return Ok(config);
    }
    let sweep = nsgs::read(p, None)?;
    let filter_local_solution = match p.iparam[IPARAM_FILTER_LOCAL_SOLUTION] {
        0 => false,
        1 => true,
        other => {
            return Err(invalid(format!(
                "filter local solution (iparam[14]) = {other} is not 0 (off) or 1 (on)"
            )))
        }
    };
    let local = match internal {
        None => RollingLocalSolver::default(),
        Some(i) => read_local(i, dimension)?,
    };
    let method = RollingMethod::Nsgs(RollingNsgsOptions {
        error_evaluation: sweep.error_evaluation,
        evaluation_frequency: sweep.evaluation_frequency,
        local_tolerance: sweep.local_tolerance,
        relaxation: sweep.relaxation,
        order: sweep.order,
        freezing: sweep.freezing,
        filter_local_solution,
        local,
    });
    debug_assert!(is_rolling(id, dimension));
    let mut config = RollingConfig::new(method);
    config.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
    config.tolerance = p.dparam[DPARAM_TOL];
    config.time_budget = p.time_budget()?;
    config.validate().map_err(annotate)?;
    Ok(config)
}

unsafe fn read_local(o: &SolverOptions, dimension: usize) -> CResult<RollingLocalSolver> {
    let p = Params::of(o, "rolling local solver options")?;
    match o.solverId {
        3001 | 4001 => Ok(RollingLocalSolver::Projection {
            unit_step: dimension == 3,
        }),
        3002 | 4002 => {
            let use_trivial_solution = match p.iparam[IPARAM_USE_TRIVIAL_SOLUTION] {
                0 => false,
                1 => true,
                other => {
                    return Err(invalid(format!(
                        "use trivial solution (internal iparam[10]) = {other} is not 0 or 1"
                    )))
                }
            };
            Ok(RollingLocalSolver::ProjectionWithLocalIteration(
                RollingProjectionIteration {
                    tolerance: p.dparam[DPARAM_TOL],
                    max_iter: p.count(IPARAM_MAX_ITER, "local max iterations")?,
                    use_trivial_solution,
                },
            ))
        }
        other => Err(invalid(format!(
            "internal solver {other} ({}) is not a rolling local solver (3001 / 4001 \
             projection on the rolling cone, 3002 / 4002 with local iterations)",
            super::solver_name(other).to_string_lossy()
        ))),
    }
}
