//! ADMM (523, Friction_cst.h's SICONOS_FRICTION_3D_ADMM_* slots): iparam[9] rho strategy (0
//! constant, 2 residual balancing, 3 scaled residual balancing), iparam[10] initial rho (0 given
//! dparam[3], 1 norm inf, 2 eigenvalues), iparam[11] acceleration (0 none, 1 or 2 accelerated
//! with restart eta dparam[4]), dparam[5]/[6] balancing tau and phi. fc3d factors W + rho I with
//! a general sparse LU, exact for any W: the symmetry choices of iparam[12] that keep W as it is
//! (0 check, 1 forced symmetric, 2 forced asymmetric, 4 assume) all lead there; 3 would
//! symmetrize W, i.e. solve another problem. iparam[13] (forced sparse storage) is what fc3d
//! always does: any value is accepted. iparam[3] rescaling: 0 none, 1 scalar (||W||_inf).

use super::{invalid, Params, IPARAM_RESCALING};
use crate::CResult;
use fc3d_core::{AdmmAcceleration, AdmmInitialRho, AdmmOptions, AdmmRhoStrategy};

const IPARAM_RHO_STRATEGY: usize = 9;
const IPARAM_INITIAL_RHO: usize = 10;
const IPARAM_ACCELERATION: usize = 11;
const IPARAM_SYMMETRY: usize = 12;
const IPARAM_GET_PROBLEM_INFO: usize = 14;
const IPARAM_UPDATE_S: usize = 15;
const IPARAM_FULL_H: usize = 17;
const DPARAM_RHO: usize = 3;
const DPARAM_RESTART_ETA: usize = 4;
const DPARAM_BALANCING_TAU: usize = 5;
const DPARAM_BALANCING_PHI: usize = 6;

pub(super) fn read(p: &Params<'_>) -> CResult<AdmmOptions> {
    let mut a = read_iteration(p)?;
    a.scalar_rescaling = match p.iparam[IPARAM_RESCALING] {
        0 => false,
        1 => true,
        other => return Err(invalid(format!("ADMM: rescaling (iparam[3]) = {other} is not implemented in fc3d (0 none, 1 scalar; Siconos' ADMM ignores the balancing values)"))),
    };
    p.require(IPARAM_UPDATE_S, 0, "De Saxcé term update (0 = yes)")?;
    Ok(a)
}

/// Whether De Saxcé's term is updated at every iteration (`iparam[15]`: 0 yes, 1 no: the convex
/// relaxation), for the global ADMM (613).
pub(super) fn read_update_s(p: &Params<'_>) -> CResult<bool> {
    match p.iparam[IPARAM_UPDATE_S] {
        0 => Ok(true),
        1 => Ok(false),
        other => Err(invalid(format!(
            "ADMM: De Saxcé term update (iparam[15]) = {other} is not 0 (yes) or 1 (no)"
        ))),
    }
}

/// The slots of the iteration shared by the local (523) and global (613) ADMM: all but the
/// rescaling (of W for 523, of the global problem for 613) and the De Saxcé term update.
pub(super) fn read_iteration(p: &Params<'_>) -> CResult<AdmmOptions> {
    let mut a = AdmmOptions {
        rho: p.dparam[DPARAM_RHO],
        restart_eta: p.dparam[DPARAM_RESTART_ETA],
        balancing_tau: p.dparam[DPARAM_BALANCING_TAU],
        balancing_phi: p.dparam[DPARAM_BALANCING_PHI],
        ..AdmmOptions::default()
    };
    a.rho_strategy = match p.iparam[IPARAM_RHO_STRATEGY] {
        0 => AdmmRhoStrategy::Constant,
        2 => AdmmRhoStrategy::ResidualBalancing,
        3 => AdmmRhoStrategy::ScaledResidualBalancing,
        other => return Err(invalid(format!("ADMM: rho strategy (iparam[9]) = {other} is not implemented in fc3d (0 constant, 2 residual balancing, 3 scaled residual balancing)"))),
    };
    a.initial_rho = match p.iparam[IPARAM_INITIAL_RHO] {
        0 => AdmmInitialRho::Given,
        1 => AdmmInitialRho::NormInf,
        2 => AdmmInitialRho::Eigenvalues,
        other => return Err(invalid(format!("ADMM: initial rho (iparam[10]) = {other} is not implemented in fc3d (0 given, 1 norm inf, 2 eigenvalues)"))),
    };
    a.acceleration = match p.iparam[IPARAM_ACCELERATION] {
        0 => AdmmAcceleration::None,
        1 | 2 => AdmmAcceleration::Accelerated,
        other => return Err(invalid(format!("ADMM: acceleration (iparam[11]) = {other} is not implemented in fc3d (0 none, 1 or 2 accelerated with restart)"))),
    };
    match p.iparam[IPARAM_SYMMETRY] {
        0 | 1 | 2 | 4 => {}
        other => return Err(invalid(format!("ADMM: symmetry (iparam[12]) = {other} is not implemented in fc3d (W is never symmetrized; 0, 1, 2, 4 accepted)"))),
    }
    p.require(IPARAM_GET_PROBLEM_INFO, 0, "problem info printing")?;
    p.require(IPARAM_FULL_H, 0, "full H")?;
    Ok(a)
}
