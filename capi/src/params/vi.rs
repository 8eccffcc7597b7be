//! DSFP 505, VI_FPP 506, VI_EG 507, HP 508, FPP 511, EG 512.
//!
//! 506/507 (Siconos' VI_cst.h slots): iparam[7] error evaluation (0 full, 1 light with full
//! final, 2 light), dparam[3] rho (> 0 fixed, < 0 self-adaptive from -rho), iparam[6] the ratio
//! (0 Khobotov, 1 Solodov-Tseng), dparam[4..7] nu, 1/nu, L, Lmin (0: Siconos' built-in value),
//! iparam[9] the trials per iteration (0: built-in), iparam[10] where the trials start (0 the
//! iterate, 1 the previous trial). iparam[8] (error evaluation frequency) is set but unused by
//! Siconos' VI solvers too.
//!
//! 505/511/512 read dparam[3] as Siconos does: DSFP's fixed rho (> 0); FPP's first rho of its
//! always self-adaptive step (Siconos 4.4 ignores the sign convention there: any non-zero value
//! starts the search from |dparam[3]|); EG's rho (> 0 fixed, with the correction from the
//! iterate as Siconos' fixed-rho EG does; < 0 self-adaptive from -rho, the correction from the
//! prediction). 511/512's self-adaptive constants default to Siconos' hard-coded ones (nu 0.6,
//! 1/0.7, L 0.9, Lmin 0.3, 10 trials, each trial from the previous one); fc3d also reads
//! dparam[4..7] and iparam[9] there when non-zero (Siconos leaves them 0 and ignores them).
//!
//! 508 (HP): Siconos' rho 1, iparam[12] the halvings of the search (default 50), dparam[4]
//! sigma (taken when in (0, 1), else 0.99, as Siconos does), the full error every iteration.

use std::os::raw::c_int;

use super::{invalid, unsupported_solver, Params, IPARAM_ERROR_EVALUATION};
use crate::CResult;
use fc3d_core::{
    ErrorEvaluation, ExtraGradientCorrection, SelfAdaptiveStep, StepRatio, StepSize, TrialStart,
    ViOptions, ViSolver,
};

const IPARAM_DECREASE_RHO: usize = 3;
const IPARAM_LINESEARCH_METHOD: usize = 6;
const IPARAM_LS_MAX_ITER: usize = 9;
const IPARAM_ACTIVATE_UPDATE: usize = 10;
pub(super) const DPARAM_RHO: usize = 3;
const DPARAM_LS_TAU: usize = 4;
const DPARAM_LS_TAUINV: usize = 5;
const DPARAM_LS_L: usize = 6;
const DPARAM_LS_LMIN: usize = 7;
const IPARAM_HP_MAX_HALVINGS: usize = 12;
const DPARAM_HP_SIGMA: usize = 4;

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
    if solver == ViSolver::HyperplaneProjection {
        // Siconos' HP hard-codes rho = 1 and the full error; dparam[3] and iparam[7] are not
        // read.
        v.hyperplane.max_halvings = p.count(IPARAM_HP_MAX_HALVINGS, "HP search halvings")?;
        let sigma = p.dparam[DPARAM_HP_SIGMA];
        if sigma > 0.0 && sigma < 1.0 {
            v.hyperplane.sigma = sigma;
        }
        return Ok(v);
    }
    v.error_evaluation = match p.iparam[IPARAM_ERROR_EVALUATION] {
        0 => ErrorEvaluation::Full,
        1 => ErrorEvaluation::LightWithFullFinal,
        2 => ErrorEvaluation::Light,
        other => return Err(invalid(format!("{what}: error evaluation (iparam[7]) = {other} is not implemented in fc3d (0 full, 1 light with full final, 2 light)"))),
    };
    let rho = p.dparam[DPARAM_RHO];
    if !rho.is_finite() || rho == 0.0 {
        return Err(invalid(format!("{what}: rho (dparam[3]) = {rho} must be finite and non-zero (> 0 fixed, < 0 self-adaptive from -rho)")));
    }
    let self_adaptive = match solver {
        ViSolver::DeSaxceFixedPoint if rho < 0.0 => {
            return Err(invalid(format!(
                "DSFP: rho (dparam[3]) = {rho} must be > 0 (DSFP has a fixed rho)"
            )));
        }
        ViSolver::FixedPointProjection => true,
        _ => rho < 0.0,
    };
    v.step = if !self_adaptive {
        if solver == ViSolver::ExtraGradient {
            v.correction = ExtraGradientCorrection::FromIterate;
        }
        StepSize::Fixed(rho)
    } else {
        let d = match v.step {
            StepSize::SelfAdaptive(s) => s,
            StepSize::Fixed(_) => SelfAdaptiveStep::default(),
        };
        let vi_lineage = matches!(
            solver,
            ViSolver::ViFixedPointProjection | ViSolver::ViExtraGradient
        );
        StepSize::SelfAdaptive(SelfAdaptiveStep {
            initial_rho: rho.abs(),
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
            trial_start: if vi_lineage {
                match p.iparam[IPARAM_ACTIVATE_UPDATE] {
                    0 => TrialStart::Iterate,
                    1 => TrialStart::PreviousTrial,
                    other => return Err(invalid(format!("{what}: update inside the line search (iparam[10]) = {other} must be 0 (each trial from the iterate) or 1 (from the previous trial)"))),
                }
            } else {
                d.trial_start
            },
        })
    };
    p.require(IPARAM_DECREASE_RHO, 0, "rho decrease rule")?;
    Ok(v)
}
