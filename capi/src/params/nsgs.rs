//! NSGS (500): iparam[7] error evaluation (0 full, 1 light, 2 light with full final,
//! `FC3D_ERROR_EVALUATION_DUMONT`), iparam[2] local tolerance strategy with its ratio dparam[2],
//! iparam[3] rescaling, iparam[4] relaxation with omega dparam[8], iparam[5]/[6] shuffling and
//! its seed, iparam[8] evaluation frequency, iparam[19] freezing, fc3d's iparam[15]
//! decomposition (sequential, coloured, islands) and iparam[16] threads; internal solver 0 is
//! the local solver.

use super::{
    invalid, local, Params, DPARAM_INTERNAL_ERROR_RATIO, IPARAM_ERROR_EVALUATION,
    IPARAM_ERROR_EVALUATION_FREQUENCY, IPARAM_INTERNAL_ERROR_STRATEGY, IPARAM_RESCALING,
};
use crate::types::SolverOptions;
use crate::{CResult, FC3D_ERROR_EVALUATION_DUMONT};
use fc3d_core::{
    ContactOrder, Decomposition, ErrorEvaluation, LocalTolerance, NsgsOptions, Rescaling,
};

const IPARAM_RELAXATION: usize = 4;
const IPARAM_SHUFFLE: usize = 5;
const IPARAM_SHUFFLE_SEED: usize = 6;
const IPARAM_FREEZING_CONTACT: usize = 19;
const DPARAM_RELAXATION_VALUE: usize = 8;
/// fc3d's decomposition slot (`FC3D_IPARAM_NSGS_DECOMPOSITION`), unused by Siconos' NSGS.
const IPARAM_DECOMPOSITION: usize = crate::FC3D_IPARAM_NSGS_DECOMPOSITION as usize;
/// fc3d's thread-count slot (`FC3D_IPARAM_NSGS_THREADS`), unused by Siconos' NSGS.
const IPARAM_THREADS: usize = crate::FC3D_IPARAM_NSGS_THREADS as usize;

pub(super) unsafe fn read(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<NsgsOptions> {
    let error_evaluation = match p.iparam[IPARAM_ERROR_EVALUATION] {
        0 => ErrorEvaluation::Full,
        1 => ErrorEvaluation::Light,
        2 => ErrorEvaluation::LightWithFullFinal,
        FC3D_ERROR_EVALUATION_DUMONT => ErrorEvaluation::DumontCriterion,
        other => return Err(invalid(format!("error evaluation (iparam[7]) = {other} is not implemented in fc3d (0 full, 1 light, 2 light with full final, {FC3D_ERROR_EVALUATION_DUMONT} Dumont's criterion)"))),
    };
    let ratio = p.dparam[DPARAM_INTERNAL_ERROR_RATIO];
    let local_tolerance = match p.iparam[IPARAM_INTERNAL_ERROR_STRATEGY] {
        0 => LocalTolerance::Adaptive { ratio },
        1 => LocalTolerance::Given,
        2 => LocalTolerance::AdaptivePerContact { ratio },
        other => return Err(invalid(format!("local tolerance strategy (iparam[2]) = {other} is not one of 0 (adaptive), 1 (given value), 2 (adaptive per contact)"))),
    };
    let relaxation = match p.iparam[IPARAM_RELAXATION] {
        0 => None,
        1 => Some(p.dparam[DPARAM_RELAXATION_VALUE]),
        other => {
            return Err(invalid(format!(
                "relaxation (iparam[4]) = {other} is not 0 (off) or 1 (on, omega in dparam[8])"
            )))
        }
    };
    // The seed is an int in C; every value, negative included, is a valid seed.
    let seed = p.iparam[IPARAM_SHUFFLE_SEED] as i64 as u64;
    let order = match p.iparam[IPARAM_SHUFFLE] {
        0 => ContactOrder::Natural,
        1 => ContactOrder::ShuffledOnce { seed },
        2 => ContactOrder::ShuffledEachSweep { seed },
        other => {
            return Err(invalid(format!(
                "shuffle (iparam[5]) = {other} is not 0 (off), 1 (once) or 2 (each sweep)"
            )))
        }
    };
    // 0 and 1 both mean every sweep.
    let evaluation_frequency = p
        .count(
            IPARAM_ERROR_EVALUATION_FREQUENCY,
            "error evaluation frequency",
        )?
        .max(1);
    let freezing = match p.count(IPARAM_FREEZING_CONTACT, "contact freezing sweeps")? {
        0 => None,
        k => Some(k),
    };
    let decomposition = match p.iparam[IPARAM_DECOMPOSITION] {
        crate::FC3D_NSGS_SEQUENTIAL => Decomposition::Sequential,
        crate::FC3D_NSGS_COLOURED => Decomposition::Coloured,
        crate::FC3D_NSGS_ISLANDS => Decomposition::Islands,
        other => {
            return Err(invalid(format!(
                "decomposition (iparam[{IPARAM_DECOMPOSITION}]) = {other} is not 0 (sequential), 1 (coloured) or 2 (islands)"
            )))
        }
    };
    let threads = p.count(IPARAM_THREADS, "threads")?;
    let local = match internal {
        Some(i) => local::read(i)?,
        None => NsgsOptions::default().local,
    };
    Ok(NsgsOptions {
        error_evaluation,
        evaluation_frequency,
        local,
        local_tolerance,
        relaxation,
        order,
        freezing,
        decomposition,
        threads,
        ..Default::default()
    })
}

/// Only NSGS gives `iparam[3]` this meaning (other families use index 3 for their own options):
/// 0 none, 1 scalar; Siconos' balancing values 2-4 scale the global formulation (M, H) and are
/// rejected for the reduced problem.
pub(super) fn read_rescaling(p: &Params<'_>) -> CResult<Rescaling> {
    match p.iparam[IPARAM_RESCALING] {
        0 => Ok(Rescaling::None),
        1 => Ok(Rescaling::Scalar),
        other => Err(invalid(format!("rescaling (iparam[3]) = {other} is not 0 (none) or 1 (scalar); balancing (2-4) applies to the global formulation only"))),
    }
}
