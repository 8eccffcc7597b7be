//! Nonsmooth Newton (504, 513, 520). Honoured: iparam[9] rho strategy (0 constant dparam[3],
//! 1 spectral norm, 2 split with conditioning, 3 split), iparam[10] formulation (504 only: 0/2
//! Alart-Curnier, 1/3 Jean-Moreau; Siconos' "generated" variants compute the same function),
//! iparam[11] line search (-1 none, 0 Goldstein-Price, 1 Armijo), iparam[12] line-search trials,
//! iparam[13] linear solver (0 or 1: both mean a sparse LU, faer's here). Rejected: the adaptive
//! rho (iparam[9] = 4), hybrid strategies (iparam[14] != 0). iparam[3], [5], [8], [17], [18] are
//! Siconos' internal bookkeeping (work-space sizes, MPI) and carry no behaviour. iparam[19]
//! (`FC3D_IPARAM_VARIANT`): Siconos' iteration (0, default) or fc3d's (1).
//!
//! 521 (NSN_AC_TEST): Siconos 4.4 runs its generic Newton line-search solver on the same
//! Alart-Curnier function with rho = 1 on every contact; fc3d runs 504's Newton with rho = 1.
//! Honoured: iparam[0], dparam[0], iparam[10] (formulation), iparam[19]; Siconos' line-search
//! settings of that generic solver (iparam[3..6], dparam[2..4]) are not used.

use std::os::raw::c_int;

use super::{invalid, Params};
use crate::CResult;
use fc3d_core::{NsnFormulation, NsnLineSearch, NsnOptions, RhoRule};

const IPARAM_RHO_STRATEGY: usize = 9;
const IPARAM_FORMULATION: usize = 10;
const IPARAM_LINESEARCH: usize = 11;
const IPARAM_LINESEARCH_MAX_ITER: usize = 12;
const IPARAM_LINEAR_SOLVER: usize = 13;
const IPARAM_HYBRID_STRATEGY: usize = 14;
const DPARAM_RHO: usize = 3;

pub(super) fn read(id: c_int, p: &Params<'_>) -> CResult<NsnOptions> {
    let formulation = match id {
        504 => match p.iparam[IPARAM_FORMULATION] {
            0 | 2 => NsnFormulation::AlartCurnier,
            1 | 3 => NsnFormulation::JeanMoreau,
            other => return Err(invalid(format!("NSN formulation (iparam[10]) = {other} is not implemented in fc3d (0/2 Alart-Curnier, 1/3 Jean-Moreau)"))),
        },
        513 => NsnFormulation::FischerBurmeister,
        _ => NsnFormulation::NaturalMap,
    };
    if id != 504 {
        p.require(
            IPARAM_FORMULATION,
            0,
            "NSN formulation (fixed by the solver id)",
        )?;
    }
    let mut n = NsnOptions::new(formulation);
    n.rho_rule = match p.iparam[IPARAM_RHO_STRATEGY] {
        0 => RhoRule::Constant(p.dparam[DPARAM_RHO]),
        1 => RhoRule::SpectralNorm,
        2 => RhoRule::SplitSpectralNormCond,
        3 => RhoRule::SplitSpectralNorm,
        other => return Err(invalid(format!("rho strategy (iparam[9]) = {other} is not implemented in fc3d (0-3; the adaptive rule 4 is not)"))),
    };
    n.line_search = match p.iparam[IPARAM_LINESEARCH] {
        -1 => NsnLineSearch::None,
        0 => NsnLineSearch::GoldsteinPrice,
        1 => NsnLineSearch::Armijo,
        other => return Err(invalid(format!("line search (iparam[11]) = {other} is not implemented in fc3d (-1 none, 0 Goldstein-Price, 1 Armijo)"))),
    };
    n.line_search_max_iter = p.count(IPARAM_LINESEARCH_MAX_ITER, "line-search max iterations")?;
    match p.iparam[IPARAM_LINEAR_SOLVER] {
        0 | 1 => {}
        other => {
            return Err(invalid(format!(
            "linear solver (iparam[13]) = {other} is not implemented in fc3d (0 or 1: a sparse LU)"
        )))
        }
    }
    p.require(IPARAM_HYBRID_STRATEGY, 0, "NSN hybrid strategy")?;
    n.variant = p.variant()?;
    Ok(n)
}

/// NSN_AC_TEST (521): the Alart-Curnier Newton of 504 with rho = 1 on every contact.
pub(super) fn read_ac_test(p: &Params<'_>) -> CResult<NsnOptions> {
    let formulation = match p.iparam[IPARAM_FORMULATION] {
        0 | 2 => NsnFormulation::AlartCurnier,
        1 | 3 => NsnFormulation::JeanMoreau,
        other => return Err(invalid(format!("NSN formulation (iparam[10]) = {other} is not implemented in fc3d (0/2 Alart-Curnier, 1/3 Jean-Moreau)"))),
    };
    let mut n = NsnOptions::new(formulation);
    n.rho_rule = RhoRule::Constant(1.0);
    n.variant = p.variant()?;
    Ok(n)
}
