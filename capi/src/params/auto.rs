//! AUTO (`FC3D_AUTO`, fc3d's id 590): iparam[0] the iteration limit over all stages (default
//! 10000), dparam[0] the tolerance (default 1e-4; 0 with a time budget is an anytime solve),
//! dparam[19] the time budget (`FC3D_DPARAM_TIME_BUDGET`). AUTO has no other setting: its rules
//! are data in the core (`fc3d_core::solvers::auto::RULES`). Output beside iparam[1] and
//! dparam[1]: `iparam[FC3D_IPARAM_AUTO_STAGES]` packs the stages taken, one decimal digit each,
//! first stage most significant (1 NSGS, 2 NSN-AC, 3 PROX, 4 ADMM, 5 TFP, 6 EG, 7 TFP-APGD: 12 is
//! NSGS then NSN-AC).

use std::os::raw::c_int;

use super::{Encoded, Params, DPARAM_TOL, IPARAM_MAX_ITER};
use crate::{CResult, FC3D_AUTO, FC3D_IPARAM_AUTO_STAGES};
#[cfg(test)]
use fc3d_core::StageKind;
use fc3d_core::{AutoOptions, Method, SolverConfig, StageLog};

pub(crate) const IPARAM_STAGES: usize = FC3D_IPARAM_AUTO_STAGES as usize;

pub(super) fn read(_p: &Params<'_>) -> CResult<AutoOptions> {
    Ok(AutoOptions::default())
}

/// `solver_options_create(FC3D_AUTO)`: the core's default limits.
pub(super) fn defaults() -> Encoded {
    let config = SolverConfig::new(Method::Auto(AutoOptions::default()));
    let mut e = Encoded::new(FC3D_AUTO);
    e.iparam[IPARAM_MAX_ITER] = c_int::try_from(config.max_iter).unwrap_or(c_int::MAX);
    e.dparam[DPARAM_TOL] = config.tolerance;
    e
}

/// The packed stage code written to `iparam[FC3D_IPARAM_AUTO_STAGES]`.
pub(super) fn encode_stages(log: &StageLog) -> c_int {
    c_int::try_from(log.packed_codes()).unwrap_or(c_int::MAX)
}

/// The stages a packed code stands for (`None`: not a code AUTO writes): the inverse of
/// [`encode_stages`], which the tests check.
#[cfg(test)]
pub(crate) fn decode_stages(code: c_int) -> Option<Vec<StageKind>> {
    u32::try_from(code).ok().and_then(StageLog::unpack_codes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stage_codes_round_trip() {
        assert_eq!(
            decode_stages(12),
            Some(vec![StageKind::Nsgs, StageKind::Newton])
        );
        assert_eq!(decode_stages(0), Some(vec![]));
        assert_eq!(decode_stages(-3), None);
        assert_eq!(decode_stages(19), None);
    }
}
