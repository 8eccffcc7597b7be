//! DSFP 505, VI_FPP 506, VI_EG 507, FPP 511, EG 512 (Siconos' VI_cst.h slots): iparam[7] error
//! evaluation (0 full, 1 light with full final, 2 light), dparam[3] rho (> 0 fixed, < 0
//! self-adaptive from -rho), iparam[6] the ratio (0 Khobotov, 1 Solodov-Tseng), dparam[4..7] nu,
//! 1/nu, L, Lmin (0: Siconos' built-in value), iparam[9] the trials per iteration (0: built-in).
//! iparam[8] (error evaluation frequency) is set but unused by Siconos' VI solvers too.

use std::os::raw::c_int;

use super::{invalid, unsupported_solver, Params, IPARAM_ERROR_EVALUATION};
use crate::CResult;
use fc3d_core::{ErrorEvaluation, SelfAdaptiveStep, StepRatio, StepSize, ViOptions, ViSolver};

const IPARAM_DECREASE_RHO: usize = 3;
const IPARAM_LINESEARCH_METHOD: usize = 6;
const IPARAM_LS_MAX_ITER: usize = 9;
const IPARAM_ACTIVATE_UPDATE: usize = 10;
const DPARAM_RHO: usize = 3;
const DPARAM_LS_TAU: usize = 4;
const DPARAM_LS_TAUINV: usize = 5;
const DPARAM_LS_L: usize = 6;
const DPARAM_LS_LMIN: usize = 7;

/// A line-search constant: 0 (unset, as in the defaults of 511/512) means Siconos' built-in
/// value; anything else is taken as given (and checked by the core).
fn constant(p: &Params<'_>, k: usize, default: f64) -> f64 {
    if p.dparam[k] == 0.0 {
        default
    } else {
        p.dparam[k]
    }
}

pub(super) fn read(id: c_int, p: &Params<'_>) -> CResult<ViOptions> {
    let solver = ViSolver::from_siconos_id(id).ok_or_else(|| unsupported_solver(id))?;
    let what = solver.short_name();
    let mut v = ViOptions::new(solver);
    v.error_evaluation = match p.iparam[IPARAM_ERROR_EVALUATION] {
        0 => ErrorEvaluation::Full,
        1 => ErrorEvaluation::LightWithFullFinal,
        2 => ErrorEvaluation::Light,
        other => return Err(invalid(format!("{what}: error evaluation (iparam[7]) = {other} is not implemented in fc3d (0 full, 1 light with full final, 2 light)"))),
    };
    let rho = p.dparam[DPARAM_RHO];
    if rho.is_nan() || rho == 0.0 {
        return Err(invalid(format!("{what}: rho (dparam[3]) = {rho} must be finite and non-zero (> 0 fixed, < 0 self-adaptive from -rho)")));
    }
    v.step = if rho > 0.0 {
        StepSize::Fixed(rho)
    } else if solver == ViSolver::DeSaxceFixedPoint {
        return Err(invalid(format!(
            "DSFP: rho (dparam[3]) = {rho} must be > 0 (DSFP has a fixed rho)"
        )));
    } else {
        let d = SelfAdaptiveStep::default();
        StepSize::SelfAdaptive(SelfAdaptiveStep {
            initial_rho: -rho,
            ratio: match p.iparam[IPARAM_LINESEARCH_METHOD] {
                0 => StepRatio::Khobotov,
                1 => StepRatio::SolodovTseng,
                other => return Err(invalid(format!("{what}: line search (iparam[6]) = {other} is not implemented in fc3d (0 Armijo with Khobotov's ratio, 1 Solodov-Tseng's)"))),
            },
            nu: constant(p, DPARAM_LS_TAU, d.nu),
            increase: constant(p, DPARAM_LS_TAUINV, d.increase),
            l: constant(p, DPARAM_LS_L, d.l),
            l_min: constant(p, DPARAM_LS_LMIN, d.l_min),
            max_trials: match p.count(IPARAM_LS_MAX_ITER, "line-search max iterations")? {
                0 => d.max_trials,
                m => m,
            },
        })
    };
    p.require(IPARAM_DECREASE_RHO, 0, "rho decrease rule")?;
    p.require(IPARAM_ACTIVATE_UPDATE, 0, "update inside the line search")?;
    Ok(v)
}
