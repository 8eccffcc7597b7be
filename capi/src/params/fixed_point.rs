//! The optimization-based fixed points: TFP 503, PFP 522, ACLMFP 516 and the SOCLCP relaxation
//! 517. iparam[2] inner tolerance strategy (0 adaptive with ratio dparam[2], 1 the internal
//! solver's dparam[0]); internal solver 0 of TFP/PFP picks the Tresca sub-problem solver (500
//! NSGS on the cylinder with an exact one-contact solve, 566 FP-VI-UPK, 567 projected gradient)
//! and its iparam[0] bounds each inner solve; dparam[8] the SOCLCP relaxation. They implement no
//! rescaling, error evaluation option or evaluation frequency: those slots must stay 0.

use std::os::raw::c_int;

use super::{
    invalid, solver_name, write_config, Encoded, Params, DPARAM_INTERNAL_ERROR_RATIO, DPARAM_TOL,
    IPARAM_ERROR_EVALUATION, IPARAM_ERROR_EVALUATION_FREQUENCY, IPARAM_INTERNAL_ERROR_STRATEGY,
    IPARAM_MAX_ITER, IPARAM_RESCALING,
};
use crate::types::SolverOptions;
use crate::CResult;
use fc3d_core::{
    AclmOptions, InnerTolerance, NsgsOptions, PfpOptions, SoclcpOptions, SolverConfig,
    TrescaInnerSolver, TrescaOptions,
};

const DPARAM_SOCLCP_RELAXATION: usize = 8;

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

unsafe fn inner_tolerance(
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

pub(super) unsafe fn read_pfp(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<PfpOptions> {
    require_no_extras(p)?;
    let mut t = PfpOptions::default();
    if let Some(i) = internal {
        (t.tangent, t.inner_max_iter) = tresca_inner(i)?;
    }
    t.inner_tolerance = inner_tolerance(p, internal)?;
    Ok(t)
}

pub(super) unsafe fn read_aclm(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<AclmOptions> {
    require_no_extras(p)?;
    if internal.is_some() {
        return Err(invalid("ACLMFP (516) takes no internal solver in fc3d (its SOCLCP is solved by its own Gauss-Seidel)"));
    }
    Ok(AclmOptions {
        inner_tolerance: inner_tolerance(p, None)?,
        ..AclmOptions::default()
    })
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
    if internal.is_some() {
        return Err(invalid("SOCLCP (517) takes no internal solver in fc3d"));
    }
    Ok(SoclcpOptions {
        relaxation: p.dparam[DPARAM_SOCLCP_RELAXATION],
    })
}

/// The strategy slots of an inner tolerance; `Given` writes its tolerance into `internal`.
fn write_inner_tolerance(t: InnerTolerance, e: &mut Encoded) {
    match t {
        InnerTolerance::Adaptive { ratio } => {
            e.iparam[IPARAM_INTERNAL_ERROR_STRATEGY] = 0;
            e.dparam[DPARAM_INTERNAL_ERROR_RATIO] = ratio;
        }
        InnerTolerance::Given(tolerance) => {
            e.iparam[IPARAM_INTERNAL_ERROR_STRATEGY] = 1;
            if let Some(i) = e.internal.first_mut() {
                i.dparam[DPARAM_TOL] = tolerance;
            }
        }
    }
}

/// Internal solver 0 of TFP/PFP: NSGS with its defaults (as Siconos creates it) or the named
/// sub-problem solver, with the inner iteration limit.
fn write_tresca_inner(solver: TrescaInnerSolver, max_iter: usize) -> CResult<Encoded> {
    let mut i = match solver {
        TrescaInnerSolver::GaussSeidel => write_config(&SolverConfig::new(NsgsOptions::default()))?,
        other => Encoded::new(other.siconos_id()),
    };
    i.iparam[IPARAM_MAX_ITER] = c_int::try_from(max_iter).unwrap_or(c_int::MAX);
    Ok(i)
}

pub(super) fn write_tfp(t: &TrescaOptions) -> CResult<Encoded> {
    let mut e = Encoded::new(503);
    e.internal
        .push(write_tresca_inner(t.inner, t.inner_max_iter)?);
    write_inner_tolerance(t.inner_tolerance, &mut e);
    Ok(e)
}

/// PFP's Siconos defaults have no internal solver: one is written only when the tangent solver
/// or its limit differ from the defaults.
pub(super) fn write_pfp(t: &PfpOptions) -> CResult<Encoded> {
    let mut e = Encoded::new(522);
    let d = PfpOptions::default();
    if (t.tangent, t.inner_max_iter) != (d.tangent, d.inner_max_iter) {
        e.internal
            .push(write_tresca_inner(t.tangent, t.inner_max_iter)?);
    }
    write_inner_tolerance(t.inner_tolerance, &mut e);
    Ok(e)
}

pub(super) fn write_aclm(t: &AclmOptions) -> Encoded {
    let mut e = Encoded::new(516);
    write_inner_tolerance(t.inner_tolerance, &mut e);
    e
}

pub(super) fn write_soclcp(t: &SoclcpOptions) -> Encoded {
    let mut e = Encoded::new(517);
    e.dparam[DPARAM_SOCLCP_RELAXATION] = t.relaxation;
    e
}
