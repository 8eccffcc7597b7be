//! The global ids (Siconos' `gfc3d_driver`: 600-615; `g_rolling_fc3d_driver`: 5000), one arm
//! each in [`global_method`]. A `_WR` id reads its slots as its local solver does (600 as 500,
//! 602 as 502, 603 as 505, 604 as 503, 606 as 504, 614 as 523: Siconos' `_WR` solvers hand
//! their options to the local solver as they are) and runs that solver on the reduced problem;
//! 5000 reads them as the rolling NSGS 3000. 601 and the GAMS ids are refused with Siconos'
//! own reason; the direct global solvers are refused until the core has them.

use std::os::raw::{c_double, c_int};

use super::{
    annotate, check_tree, config_from_node_as, first_internal, invalid, rolling, solver_name,
    unsupported_solver, Params, DPARAM_INTERNAL_ERROR_RATIO, DPARAM_TOL,
    IPARAM_INTERNAL_ERROR_STRATEGY, IPARAM_MAX_ITER,
};
use crate::types::SolverOptions;
use crate::{CError, CResult, FC3D_ERR_UNSUPPORTED_SOLVER};
use fc3d_core::global::{GlobalConfig, GlobalMethod, GlobalReport, GlobalRollingConfig};
use fc3d_core::Rescaling;

/// The configuration the options of a global id describe (`gfc3d_driver`), checked by the core.
/// The tree is checked as in `config_from_c`.
pub(crate) unsafe fn global_config_from_c(o: &SolverOptions) -> CResult<GlobalConfig> {
    check_tree(o)?;
    let id = o.solverId;
    let what = solver_name(id).to_string_lossy();
    let p = Params::of(o, &format!("{what} options"))?;
    let method = global_method(o, id)?;
    let mut config = GlobalConfig::new(method);
    config.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
    config.tolerance = p.dparam[DPARAM_TOL];
    config.time_budget = p.time_budget()?;
    config.validate().map_err(annotate)?;
    Ok(config)
}

/// The method of global id `id`: one arm per id.
unsafe fn global_method(o: &SolverOptions, id: c_int) -> CResult<GlobalMethod> {
    Ok(match id {
        600 | 602 | 603 | 604 | 606 | 614 => GlobalMethod::Reduced(reduced(o, id)?),
        601 => {
            return Err(refused(
                id,
                "Siconos 4.4's NSGSV_WR runs fc3d_nsgs_velocity on the reduced problem, which \
                 exits the process with its default internal solver (550) and on any W that is \
                 not dense (\"Not yet implemented\"): there is no result to reproduce",
            ))
        }
        605 | 607 | 610 | 611 | 612 | 613 | 615 => {
            return Err(refused(
                id,
                "not implemented yet in fc3d (the _WR ids 600, 602, 603, 604, 606 and 614 run \
                 through the reduced problem)",
            ))
        }
        608 | 609 => return Err(unsupported_solver(id)),
        5000 => {
            return Err(refused(
                id,
                "the global rolling-friction solver: call g_rolling_fc3d_driver",
            ))
        }
        _ => {
            return Err(refused(
                id,
                "not a global friction solver: gfc3d_driver runs the ids 600-615",
            ))
        }
    })
}

/// `FC3D_ERR_UNSUPPORTED_SOLVER` naming the id and the reason.
fn refused(id: c_int, why: &str) -> CError {
    CError::new(
        FC3D_ERR_UNSUPPORTED_SOLVER,
        format!(
            "solver id {id} ({}): {why}",
            solver_name(id).to_string_lossy()
        ),
    )
}

/// The local method a `_WR` id runs, its options read as those of the local id.
unsafe fn reduced(o: &SolverOptions, id: c_int) -> CResult<fc3d_core::Method> {
    let local_id = GlobalMethod::reduced_local_id(id)
        .ok_or_else(|| refused(id, "not a reduction (_WR) id"))?;
    let local = config_from_node_as(o, local_id)?;
    if local.rescaling != Rescaling::None {
        // Siconos' _WR solvers call the local solver directly, not through fc3d_driver, which
        // is where the local rescaling is applied: it would be silently ignored.
        return Err(invalid(format!(
            "rescaling (iparam[3]) = {:?} is not applied by the global _WR solvers (Siconos \
             calls the local solver without it): set iparam[3] to 0",
            local.rescaling
        )));
    }
    Ok(local.method)
}

/// The rolling configuration of the global rolling id 5000 (`g_rolling_fc3d_driver`): the
/// slots of the rolling NSGS 3000 and its internal solver. Any other id is refused.
pub(crate) unsafe fn global_rolling_config_from_c(
    o: &SolverOptions,
) -> CResult<GlobalRollingConfig> {
    check_tree(o)?;
    let id = o.solverId;
    if id != 5000 {
        return Err(refused(
            id,
            "not run by g_rolling_fc3d_driver, which solves 5000 (GFC3D_NSGS_WR for rolling \
             friction)",
        ));
    }
    let what = solver_name(id).to_string_lossy();
    let p = Params::of(o, &format!("{what} options"))?;
    rolling::read(3000, 5, &p, first_internal(o))
}

/// Siconos' `gfc3d_set_internalsolver_tolerance` rule by `iparam[2]`: adaptive (0):
/// `error / dparam[2]`; adaptive per contact (2): `error / (dparam[2] nc)`; given value (1):
/// None (the internal solver's tolerance stays). An unknown strategy is an error.
pub(crate) unsafe fn global_internal_tolerance(
    o: &SolverOptions,
    nc: c_int,
    error: c_double,
) -> CResult<Option<c_double>> {
    let p = Params::of(o, "options")?;
    let ratio = p.dparam[DPARAM_INTERNAL_ERROR_RATIO];
    match p.iparam[IPARAM_INTERNAL_ERROR_STRATEGY] {
        0 => Ok(Some(error / ratio)),
        1 => Ok(None),
        2 => Ok(Some(error / (ratio * f64::from(nc)))),
        other => Err(invalid(format!(
            "internal error strategy (iparam[2]) = {other} is not 0 (adaptive), 1 (given \
             value) or 2 (adaptive per contact)"
        ))),
    }
}

/// Writes the outputs of a global solve: `iparam[1]` the iterations, `dparam[1]` the global
/// error of the returned `(r, u, v)`.
pub(crate) unsafe fn write_global_outputs(o: &mut SolverOptions, report: &GlobalReport) {
    *o.iparam.add(super::IPARAM_ITER_DONE) =
        c_int::try_from(report.iterations).unwrap_or(c_int::MAX);
    *o.dparam.add(super::DPARAM_RESIDU) = report.error;
}

/// LMGC90's options (`gfc3d_LmgcDriver`): Siconos' defaults of `id` with every non-zero entry of
/// the host's `iparam` (first `isize`, at most the defaults' size) and `dparam` put over them,
/// as Siconos does.
pub(crate) fn lmgc_overrides(defaults: &mut SolverOptions, iparam: &[c_int], dparam: &[c_double]) {
    // SAFETY: the defaults come from `create_options`: OPTIONS_PARAM_SIZE slots each.
    let size = super::SIZE;
    for (k, &v) in iparam.iter().enumerate().take(size) {
        if v != 0 {
            unsafe { *defaults.iparam.add(k) = v };
        }
    }
    for (k, &v) in dparam.iter().enumerate().take(size) {
        // As Siconos' `fabs(dparam[i]) > 0`: a NaN is not taken.
        if v.abs() > 0.0 {
            unsafe { *defaults.dparam.add(k) = v };
        }
    }
}
