//! Siconos' rule for the tolerance a fixed-point method hands to its internal solver
//! (`fc3d_set_internalsolver_tolerance`), read from the outer options' slots.

use std::os::raw::{c_double, c_int};

use super::IPARAM_INTERNAL_ERROR_STRATEGY;
use super::{invalid, Params, DPARAM_INTERNAL_ERROR_RATIO, DPARAM_TOL};
use crate::types::SolverOptions;
use crate::CResult;

/// Values of `iparam[IPARAM_INTERNAL_ERROR_STRATEGY]` (Siconos' Friction_cst.h).
const ADAPTIVE: c_int = 0;
const GIVEN_VALUE: c_int = 1;
const ADAPTIVE_N_CONTACT: c_int = 2;

/// The internal solver's tolerance for the outer error `error` on `nc` contacts, or `None` when
/// the strategy keeps the internal solver's own value. The adaptive rule is floored at
/// `dparam[0] / nc` for the local fixed points (`fc3d_set_internalsolver_tolerance`), not for the
/// global ones (`gfc3d_set_internalsolver_tolerance`: `floored` false), as in Siconos 4.4.
pub(crate) unsafe fn internal_solver_tolerance(
    o: &SolverOptions,
    nc: c_int,
    error: c_double,
    floored: bool,
) -> CResult<Option<c_double>> {
    let p = Params::of(o, "options")?;
    let ratio = p.dparam[DPARAM_INTERNAL_ERROR_RATIO];
    let nc = c_double::from(nc);
    let floor = if floored {
        p.dparam[DPARAM_TOL] / nc
    } else {
        f64::NEG_INFINITY
    };
    match p.iparam[IPARAM_INTERNAL_ERROR_STRATEGY] {
        ADAPTIVE => Ok(Some((error / ratio).max(floor))),
        ADAPTIVE_N_CONTACT => Ok(Some(error / (ratio * nc))),
        GIVEN_VALUE => Ok(None),
        other => Err(invalid(format!(
            "internal error strategy iparam[{IPARAM_INTERNAL_ERROR_STRATEGY}] = {other} is unknown (0 adaptive, 1 given value, 2 adaptive per contact)"
        ))),
    }
}

/// Writes `tol` to the tolerance slot of `o`.
pub(crate) unsafe fn set_tolerance(o: &mut SolverOptions, tol: c_double) -> CResult<()> {
    if o.dparam.is_null() || o.dSize <= DPARAM_TOL as c_int {
        return Err(invalid(format!(
            "internal solver options: dparam is NULL or dSize = {} has no slot {DPARAM_TOL}",
            o.dSize
        )));
    }
    *o.dparam.add(DPARAM_TOL) = tol;
    Ok(())
}
