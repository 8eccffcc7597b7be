//! PROX (502): dparam[3] alpha (> 0 variable shift, < 0 fixed shift -alpha, as Siconos),
//! dparam[4] sigma, dparam[5] nu; internal solver 0 is NSN_AC (504, Siconos' default) or NSGS
//! (500), whose iteration limit bounds each internal solve (its tolerance is replaced by the
//! proximal rule). Rejected: iparam[2] (internal error strategy other than Siconos' adaptive
//! max(error / 10, tol / contacts)), iparam[8] (relaxation), iparam[9] (other proximal
//! strategies).

use super::{config_from_node, Params};
use crate::types::SolverOptions;
use crate::{CError, CResult, FC3D_ERR_UNSUPPORTED_SOLVER};
use fc3d_core::{Method, NsnFormulation, ProxInternal, ProxOptions};

const IPARAM_ERROR_STRATEGY: usize = 2;
const IPARAM_RELAXATION: usize = 8;
const IPARAM_STRATEGY: usize = 9;
const DPARAM_ALPHA: usize = 3;
const DPARAM_SIGMA: usize = 4;
const DPARAM_NU: usize = 5;

pub(super) unsafe fn read(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<ProxOptions> {
    let mut x = ProxOptions {
        alpha: p.dparam[DPARAM_ALPHA],
        sigma: p.dparam[DPARAM_SIGMA],
        nu: p.dparam[DPARAM_NU],
        ..ProxOptions::default()
    };
    p.require(
        IPARAM_ERROR_STRATEGY,
        0,
        "proximal internal error strategy (0 = adaptive)",
    )?;
    p.require(IPARAM_RELAXATION, 0, "proximal relaxation")?;
    p.require(IPARAM_STRATEGY, 0, "proximal strategy (0 = proximal point)")?;
    if let Some(i) = internal {
        // Named as the internal solver's: its slots are not PROX's.
        let inner = config_from_node(i).map_err(|e| CError {
            message: format!("PROX's internal solver {}: {}", i.solverId, e.message),
            ..e
        })?;
        x.internal = match inner.method {
            Method::Nsn(n)
                if matches!(
                    n.formulation,
                    NsnFormulation::AlartCurnier | NsnFormulation::JeanMoreau
                ) =>
            {
                ProxInternal::NsnAc(n)
            }
            Method::Nsgs(g) => ProxInternal::Nsgs(g),
            other => {
                return Err(CError::new(
                    FC3D_ERR_UNSUPPORTED_SOLVER,
                    format!(
                    "PROX's internal solver {} is not supported in fc3d (504 NSN_AC or 500 NSGS)",
                    other.siconos_id()
                ),
                ))
            }
        };
        // The internal solver's own default is what `None` stands for.
        x.internal_max_iter =
            (inner.max_iter != inner.method.default_limits().1).then_some(inner.max_iter);
    }
    Ok(x)
}
