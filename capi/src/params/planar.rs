//! The 2D ids (Siconos' `fc2d`): 400 NSGS reads iparam[7] error evaluation (0 full, 1 light, 2
//! light with full final), iparam[5] shuffling (any positive value: a new order every sweep, as
//! Siconos' 2D NSGS does; seed iparam[6]), iparam[4] relaxation with omega dparam[8], iparam[8]
//! evaluation frequency, iparam[19] freezing; 402 CPG has no option; 404 Lemke requires
//! iparam[5] (pivoting rule) = 0, lexicographic; 405 enumeration reads its first case iparam[9]
//! and requires iparam[10] (least squares) and iparam[11] (all solutions) = 0; its iparam[0]
//! counts the cases to try (0, Siconos' default: every case, refused for more than 10 contacts
//! unless a time budget is set).

use std::os::raw::c_int;

use super::{annotate, invalid, Params, IPARAM_ERROR_EVALUATION};
use super::{IPARAM_ERROR_EVALUATION_FREQUENCY, IPARAM_MAX_ITER};
use crate::CResult;
use fc3d_core::{ContactOrder, ErrorEvaluation, PlanarConfig, PlanarMethod, PlanarNsgsOptions};

const IPARAM_RELAXATION: usize = 4;
const IPARAM_SHUFFLE: usize = 5;
const IPARAM_SHUFFLE_SEED: usize = 6;
const IPARAM_FREEZING_CONTACT: usize = 19;
const DPARAM_RELAXATION_VALUE: usize = 8;
const IPARAM_PIVOTING_METHOD: usize = 5;
const IPARAM_ENUM_SEED: usize = 9;
const IPARAM_ENUM_USE_DGELS: usize = 10;
const IPARAM_ENUM_MULTIPLE_SOLUTIONS: usize = 11;

/// Whether `id` is one of Siconos' 2D friction ids.
pub(crate) fn is_planar(id: c_int) -> bool {
    matches!(id, 400 | 402 | 404 | 405)
}

/// The configuration the options of a 2D id describe (the caller checked the id).
pub(crate) fn read(id: c_int, p: &Params<'_>) -> CResult<PlanarConfig> {
    let method = match id {
        400 => PlanarMethod::Nsgs(read_nsgs(p)?),
        402 => PlanarMethod::Cpg,
        404 => {
            p.require(IPARAM_PIVOTING_METHOD, 0, "Lemke pivoting rule")?;
            PlanarMethod::Lemke
        }
        405 => {
            p.require(IPARAM_ENUM_USE_DGELS, 0, "enumeration by least squares")?;
            p.require(
                IPARAM_ENUM_MULTIPLE_SOLUTIONS,
                0,
                "enumeration of every solution",
            )?;
            let seed = p.count(IPARAM_ENUM_SEED, "enumeration seed")? as u64;
            PlanarMethod::Enumeration { seed }
        }
        _ => return Err(super::unsupported_solver(id)),
    };
    let mut config = PlanarConfig::new(method);
    config.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
    config.tolerance = p.dparam[super::DPARAM_TOL];
    config.time_budget = p.time_budget()?;
    config.validate().map_err(annotate)?;
    Ok(config)
}

fn read_nsgs(p: &Params<'_>) -> CResult<PlanarNsgsOptions> {
    let error_evaluation = match p.iparam[IPARAM_ERROR_EVALUATION] {
        0 => ErrorEvaluation::Full,
        1 => ErrorEvaluation::Light,
        2 => ErrorEvaluation::LightWithFullFinal,
        other => {
            return Err(invalid(format!(
                "error evaluation (iparam[7]) = {other} is not one of 0 (full), 1 (light), 2 \
                 (light with full final) for the 2D NSGS"
            )))
        }
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
    let order = match p.iparam[IPARAM_SHUFFLE] {
        0 => ContactOrder::Natural,
        k if k > 0 => ContactOrder::ShuffledEachSweep {
            seed: p.iparam[IPARAM_SHUFFLE_SEED] as i64 as u64,
        },
        other => {
            return Err(invalid(format!(
                "shuffle (iparam[5]) = {other} is negative (0 off, positive: every sweep)"
            )))
        }
    };
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
    Ok(PlanarNsgsOptions {
        error_evaluation,
        evaluation_frequency,
        order,
        relaxation,
        freezing,
    })
}
