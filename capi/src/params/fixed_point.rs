//! The optimization-based fixed points: TFP 503, PFP 522, ACLMFP 516 and the SOCLCP relaxation
//! 517. iparam[2] inner tolerance strategy (0 adaptive with ratio dparam[2], 1 the internal
//! solver's dparam[0]); internal solver 0 of TFP picks the Tresca sub-problem solver (500 NSGS on
//! the cylinder with an exact one-contact solve, 566 FP-VI-UPK, 567 projected gradient) and its
//! iparam[0] bounds each inner solve; dparam[8] the SOCLCP relaxation. They implement no
//! rescaling, error evaluation option or evaluation frequency: those slots must stay 0.
//!
//! The internal solvers Siconos' `solver_options_create` puts in are accepted as they are:
//! PFP's pair (202 LCP PGS for the normal part, 1201 ConvexQP VI FPP or 1200 ConvexQP PG for the
//! tangent part), ACLMFP's 1100 SOCLCP NSGS (its iparam[0] bounds each inner SOCLCP solve) with
//! its one-cone solver 1151 (or the SOCLCP VI solvers 1106/1107 Siconos' tests put there), and
//! 517's one-cone solver 1151. fc3d solves each cone exactly, so
//! the one-cone solver's own limits are not read; any other internal solver is refused.

use super::{
    invalid, solver_name, Params, DPARAM_INTERNAL_ERROR_RATIO, DPARAM_TOL, IPARAM_ERROR_EVALUATION,
    IPARAM_ERROR_EVALUATION_FREQUENCY, IPARAM_INTERNAL_ERROR_STRATEGY, IPARAM_MAX_ITER,
    IPARAM_RESCALING,
};
use crate::types::SolverOptions;
use crate::CResult;
use std::os::raw::c_int;

use fc3d_core::{
    AclmOptions, InnerTolerance, PfpOptions, SoclcpOptions, TrescaInnerSolver, TrescaOptions,
};

const DPARAM_SOCLCP_RELAXATION: usize = 8;

/// Siconos' solver ids of the internal solvers of its PFP, ACLMFP and SOCLCP defaults.
const LCP_PGS: c_int = 202;
const SOCLCP_NSGS: c_int = 1100;
const SOCLCP_VI_FPP: c_int = 1106;
const SOCLCP_VI_EG: c_int = 1107;
const SOCLCP_ONE_CONE_PROJECTION_WITH_LOCAL_ITERATION: c_int = 1151;
const CONVEXQP_PG: c_int = 1200;
const CONVEXQP_VI_FPP: c_int = 1201;

/// Refuses an internal solver other than the ones listed, naming it.
fn require_internal(i: &SolverOptions, owner: &str, accepted: &[c_int]) -> CResult<()> {
    if accepted.contains(&i.solverId) {
        return Ok(());
    }
    let list: Vec<String> = accepted
        .iter()
        .map(|&id| format!("{id} {}", solver_name(id).to_string_lossy()))
        .collect();
    Err(invalid(format!(
        "{owner}: internal solver {} ({}) is not implemented in fc3d (accepted: {})",
        i.solverId,
        solver_name(i.solverId).to_string_lossy(),
        list.join(", ")
    )))
}

/// Internal solver `k` of `o` (the caller checked the count; the tree was checked).
unsafe fn internal_at(o: &SolverOptions, k: usize) -> CResult<&SolverOptions> {
    (*o.internalSolvers.add(k))
        .as_ref()
        .ok_or_else(|| invalid(format!("internalSolvers[{k}] is NULL")))
}

/// The options these solvers do not implement must keep their default (0).
fn require_no_extras(p: &Params<'_>) -> CResult<()> {
    p.require(IPARAM_RESCALING, 0, "rescaling")?;
    p.require(IPARAM_ERROR_EVALUATION, 0, "error evaluation")?;
    p.require(
        IPARAM_ERROR_EVALUATION_FREQUENCY,
        0,
        "error evaluation frequency",
    )
}

/// The Tresca sub-problem solver and its iteration limit, from internal solver 0.
unsafe fn tresca_inner(i: &SolverOptions) -> CResult<(TrescaInnerSolver, usize)> {
    let solver = TrescaInnerSolver::from_siconos_id(i.solverId).ok_or_else(|| {
        invalid(format!(
            "internal solver {} ({}) is not implemented for Tresca sub-problems in fc3d (500, 566 or 567)",
            i.solverId,
            solver_name(i.solverId).to_string_lossy()
        ))
    })?;
    let ip = Params::of(i, "internal solver options")?;
    Ok((
        solver,
        ip.count(IPARAM_MAX_ITER, "internal max iterations")?,
    ))
}

pub(super) unsafe fn inner_tolerance(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<InnerTolerance> {
    match (p.iparam[IPARAM_INTERNAL_ERROR_STRATEGY], internal) {
        (0, _) => Ok(InnerTolerance::Adaptive {
            ratio: p.dparam[DPARAM_INTERNAL_ERROR_RATIO],
        }),
        (1, Some(i)) => Ok(InnerTolerance::Given(
            Params::of(i, "internal solver options")?.dparam[DPARAM_TOL],
        )),
        (other, _) => Err(invalid(format!("internal error strategy (iparam[{IPARAM_INTERNAL_ERROR_STRATEGY}]) = {other} is not implemented here (0 adaptive, 1 the internal solver's tolerance when there is one)"))),
    }
}

pub(super) unsafe fn read_tfp(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<TrescaOptions> {
    require_no_extras(p)?;
    let mut t = TrescaOptions::default();
    if let Some(i) = internal {
        (t.inner, t.inner_max_iter) = tresca_inner(i)?;
    }
    t.inner_tolerance = inner_tolerance(p, internal)?;
    Ok(t)
}

/// PFP with no internal solver (fc3d's defaults), one (fc3d's layout: the tangent solver 500, 566
/// or 567, whose iparam[0] bounds both inner solves) or two (Siconos' layout: 202 PGS for the
/// normal part, then 1201 ConvexQP VI FPP, read as FP-VI-UPK, or 1200 ConvexQP PG, read as the
/// projected gradient, for the tangent part, each bounded by its own iparam[0]).
pub(super) unsafe fn read_pfp(p: &Params<'_>, o: &SolverOptions) -> CResult<PfpOptions> {
    require_no_extras(p)?;
    let mut t = PfpOptions::default();
    let first = match o.numberOfInternalSolvers {
        0 => None,
        1 => {
            let i = internal_at(o, 0)?;
            (t.tangent, t.inner_max_iter) = tresca_inner(i)?;
            t.normal_max_iter = t.inner_max_iter;
            Some(i)
        }
        2 => {
            let normal = internal_at(o, 0)?;
            let tangent = internal_at(o, 1)?;
            require_internal(normal, "PFP (522) normal part", &[LCP_PGS])?;
            require_internal(
                tangent,
                "PFP (522) tangent part",
                &[CONVEXQP_VI_FPP, CONVEXQP_PG],
            )?;
            t.tangent = if tangent.solverId == CONVEXQP_PG {
                TrescaInnerSolver::ProjectedGradient
            } else {
                TrescaInnerSolver::FixedPointViUpk
            };
            t.normal_max_iter = Params::of(normal, "PFP normal solver options")?
                .count(IPARAM_MAX_ITER, "PFP normal solver max iterations")?;
            t.inner_max_iter = Params::of(tangent, "PFP tangent solver options")?
                .count(IPARAM_MAX_ITER, "PFP tangent solver max iterations")?;
            Some(normal)
        }
        n => {
            return Err(invalid(format!(
                "PFP (522) takes at most 2 internal solvers, not {n}"
            )))
        }
    };
    t.inner_tolerance = inner_tolerance(p, first)?;
    Ok(t)
}

/// ACLMFP with no internal solver or one of Siconos' SOCLCP solvers: 1100 NSGS (the default; its
/// own internal solver may be the one-cone solver 1151), 1106 VI FPP or 1107 VI EG. fc3d solves
/// each inner SOCLCP by its Gauss-Seidel with an exact one-cone solve whichever of the three is
/// named: the inner problem and its stopping rule (tolerance, the internal solver's iparam[0])
/// are the same, so is the fixed point ACLMFP converges to.
pub(super) unsafe fn read_aclm(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<AclmOptions> {
    require_no_extras(p)?;
    let mut a = AclmOptions::default();
    if let Some(i) = internal {
        require_internal(
            i,
            "ACLMFP (516)",
            &[SOCLCP_NSGS, SOCLCP_VI_FPP, SOCLCP_VI_EG],
        )?;
        let ip = Params::of(i, "ACLMFP internal solver options")?;
        a.inner_max_iter = ip.count(IPARAM_MAX_ITER, "ACLMFP internal max iterations")?;
        let relaxation = ip.dparam[DPARAM_SOCLCP_RELAXATION];
        if i.solverId == SOCLCP_NSGS && relaxation != 1.0 && relaxation != 0.0 {
            return Err(invalid(format!("ACLMFP (516): relaxation of the inner SOCLCP sweep (internal solver's dparam[{DPARAM_SOCLCP_RELAXATION}]) = {relaxation} is not implemented in fc3d (only 1)")));
        }
        if let Some(local) = super::first_internal(i) {
            require_internal(
                local,
                "ACLMFP's SOCLCP NSGS",
                &[SOCLCP_ONE_CONE_PROJECTION_WITH_LOCAL_ITERATION],
            )?;
        }
    }
    a.inner_tolerance = inner_tolerance(p, internal)?;
    Ok(a)
}

pub(super) fn read_soclcp(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<SoclcpOptions> {
    require_no_extras(p)?;
    p.require(
        IPARAM_INTERNAL_ERROR_STRATEGY,
        0,
        "internal error strategy (SOCLCP has no internal solver)",
    )?;
    if let Some(i) = internal {
        require_internal(
            i,
            "SOCLCP (517)",
            &[SOCLCP_ONE_CONE_PROJECTION_WITH_LOCAL_ITERATION],
        )?;
    }
    Ok(SoclcpOptions {
        relaxation: p.dparam[DPARAM_SOCLCP_RELAXATION],
    })
}
