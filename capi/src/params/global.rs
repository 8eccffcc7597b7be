//! The global ids (Siconos' `gfc3d_driver`: 600-615; `g_rolling_fc3d_driver`: 5000), one arm
//! each in [`global_method`]. A `_WR` id reads its slots as its local solver does (600 as 500,
//! 602 as 502, 603 as 505, 604 as 503, 606 as 504, 614 as 523: Siconos' `_WR` solvers hand
//! their options to the local solver as they are) and runs that solver on the reduced problem;
//! 5000 reads them as the rolling NSGS 3000. The direct solvers read Siconos' slots of their id:
//! 605 (projected Jacobi) iparam[8] the error frequency; 607 (Newton on (v, u, r)) iparam[10]
//! formulation, dparam[3] rho, iparam[11] line search (0 Goldstein-Price, -1 none), iparam[12]
//! its trials, iparam[8] the error frequency; 610 / 611 the VI slots of 506 / 507; 612 (ACLMFP)
//! iparam[2] / dparam[2] the inner tolerance and its internal solver 1203 (ConvexQP ADMM:
//! iparam[0], iparam[9] rho strategy, iparam[10] acceleration, dparam[3..6]); 613 (ADMM) the
//! slots of 523 and iparam[15] (De Saxcé update: 0 yes, 1 no, the convex relaxation),
//! iparam[8] the error frequency; 615 (IPM) iparam[11] Nesterov-Todd, iparam[15] UPDATE_S,
//! dparam[7..11]. 607 and 613 read the rescaling of the problem in iparam[3] (Siconos' scalar and
//! balancing rescalings, exact reformulations in fc3d, the error measured on the host's
//! problem); the other direct ids refuse one. 601 and the GAMS ids are refused with
//! Siconos' own reason.

use std::os::raw::{c_double, c_int};

use super::fixed_point::inner_tolerance;
use super::{
    admm, annotate, check_tree, config_from_node_as, first_internal, invalid, rolling, solver_name,
    unsupported_solver, vi, Params, DPARAM_TOL, IPARAM_ERROR_EVALUATION_FREQUENCY, IPARAM_MAX_ITER,
    IPARAM_RESCALING,
};
use crate::types::SolverOptions;
use crate::{CError, CResult, FC3D_ERR_UNSUPPORTED_SOLVER};
use fc3d_core::global::{
    GlobalAclmOptions, GlobalAdmmOptions, GlobalConfig, GlobalMethod, GlobalNewtonOptions,
    GlobalReport, GlobalRescaling, GlobalRollingConfig, IpmOptions, JacobiOptions,
};
use fc3d_core::{AdmmAcceleration, AdmmRhoStrategy, NsnFormulation, Rescaling};

/// The configuration the options of a global id describe (`gfc3d_driver`), checked by the core.
/// The tree is checked as in `config_from_c`.
pub(crate) unsafe fn global_config_from_c(o: &SolverOptions) -> CResult<GlobalConfig> {
    check_tree(o)?;
    let id = o.solverId;
    let what = solver_name(id).to_string_lossy();
    let p = Params::of(o, &format!("{what} options"))?;
    let method = global_method(o, id)?;
    let mut config = GlobalConfig::new(method);
    config.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
    config.tolerance = p.dparam[DPARAM_TOL];
    config.time_budget = p.time_budget()?;
    config.validate().map_err(annotate)?;
    Ok(config)
}

/// The method of global id `id`: one arm per id.
unsafe fn global_method(o: &SolverOptions, id: c_int) -> CResult<GlobalMethod> {
    Ok(match id {
        600 | 602 | 603 | 604 | 606 | 614 => GlobalMethod::Reduced(reduced(o, id)?),
        601 => {
            return Err(refused(
                id,
                "Siconos 4.4's NSGSV_WR runs fc3d_nsgs_velocity on the reduced problem, which \
                 exits the process with its default internal solver (550) and on any W that is \
                 not dense (\"Not yet implemented\"): there is no result to reproduce",
            ))
        }
        605 => GlobalMethod::ProjectedJacobi(jacobi(o)?),
        607 => GlobalMethod::Newton(newton(o)?),
        610 => GlobalMethod::Vi(vi::read(506, &global_params(o)?)?),
        611 => GlobalMethod::Vi(vi::read(507, &global_params(o)?)?),
        612 => GlobalMethod::Aclm(aclm(o)?),
        613 => GlobalMethod::Admm(global_admm(o)?),
        615 => GlobalMethod::Ipm(ipm(o)?),
        608 | 609 => return Err(unsupported_solver(id)),
        5000 => {
            return Err(refused(
                id,
                "the global rolling-friction solver: call g_rolling_fc3d_driver",
            ))
        }
        _ => {
            return Err(refused(
                id,
                "not a global friction solver: gfc3d_driver runs the ids 600-615",
            ))
        }
    })
}

/// The options of a direct global solver. Its rescaling (iparam[3]) is read by
/// [`rescaling`] for 607 and 613, the ids Siconos rescales; for the others it must be 0.
unsafe fn global_params(o: &SolverOptions) -> CResult<Params<'_>> {
    let what = solver_name(o.solverId).to_string_lossy();
    let p = Params::of(o, &format!("{what} options"))?;
    if !matches!(o.solverId, 607 | 613) && p.iparam[IPARAM_RESCALING] != 0 {
        return Err(invalid(format!(
            "{what}: rescaling (iparam[3]) = {} is not read by Siconos for this id; fc3d \
             rescales 607 and 613 only (0 none)",
            p.iparam[IPARAM_RESCALING]
        )));
    }
    Ok(p)
}

/// 607's and 613's rescaling (iparam[3]): 0 none, 1 scalar, 2 balancing of M, 3 (Siconos'
/// balancing of M and H, which Siconos 4.4 does not implement: no rescaling, as there), 4
/// balancing of `[[M, H], [H^T, 0]]`.
fn rescaling(p: &Params<'_>, what: &str) -> CResult<GlobalRescaling> {
    Ok(match p.iparam[IPARAM_RESCALING] {
        0 | 3 => GlobalRescaling::None,
        1 => GlobalRescaling::Scalar,
        2 => GlobalRescaling::BalancingM,
        4 => GlobalRescaling::BalancingMhht,
        other => {
            return Err(invalid(format!(
                "{what}: rescaling (iparam[3]) = {other} is not 0 (none), 1 (scalar), 2 \
                 (balancing M), 3 (balancing M and H: none in Siconos 4.4) or 4 (balancing \
                 [[M, H], [H^T, 0]])"
            )))
        }
    })
}

/// Every `iparam[8]` iterations (0: every one, as Siconos reads it).
fn error_frequency(p: &Params<'_>) -> CResult<usize> {
    Ok(p.count(
        IPARAM_ERROR_EVALUATION_FREQUENCY,
        "error evaluation frequency",
    )?
    .max(1))
}

/// 605: Siconos' projected Jacobi (step 1). Siconos exits unless iparam[4] is 0.
unsafe fn jacobi(o: &SolverOptions) -> CResult<JacobiOptions> {
    let p = global_params(o)?;
    p.require(4, 0, "GFC3D_NSGS: iparam[4] (Siconos exits unless 0)")?;
    Ok(JacobiOptions {
        error_frequency: error_frequency(&p)?,
        ..JacobiOptions::default()
    })
}

/// 607: Siconos' Newton on (v, u, r).
unsafe fn newton(o: &SolverOptions) -> CResult<GlobalNewtonOptions> {
    let p = global_params(o)?;
    let formulation = match p.iparam[10] {
        0 | 2 => NsnFormulation::AlartCurnier,
        1 | 3 => NsnFormulation::JeanMoreau,
        other => return Err(invalid(format!("GFC3D_NSN_AC: formulation (iparam[10]) = {other} is not implemented in fc3d (0/2 Alart-Curnier, 1/3 Jean-Moreau)"))),
    };
    let line_search = match p.iparam[11] {
        0 => true,
        -1 => false,
        other => return Err(invalid(format!("GFC3D_NSN_AC: line search (iparam[11]) = {other} is not implemented (0 Goldstein-Price, -1 none; Siconos refuses Armijo, 1, too)"))),
    };
    Ok(GlobalNewtonOptions {
        formulation,
        rho: p.dparam[3],
        line_search,
        line_search_max_iter: p.count(12, "GFC3D_NSN_AC: line-search trials (iparam[12])")?,
        error_frequency: error_frequency(&p)?,
        rescaling: rescaling(&p, "GFC3D_NSN_AC")?,
    })
}

/// 612: the outer fixed point's inner tolerance and its ConvexQP ADMM (1203, required as
/// Siconos requires it).
unsafe fn aclm(o: &SolverOptions) -> CResult<GlobalAclmOptions> {
    let p = global_params(o)?;
    let internal = first_internal(o);
    let mut a = GlobalAclmOptions::default();
    if let Some(i) = internal {
        if i.solverId != 1203 {
            return Err(invalid(format!(
                "GFC3D_ACLMFP: internal solver {} ({}): Siconos' ACLMFP runs the ConvexQP ADMM \
                 (1203) only",
                i.solverId,
                solver_name(i.solverId).to_string_lossy()
            )));
        }
        let ip = Params::of(i, "GFC3D_ACLMFP internal solver options")?;
        a.inner_max_iter = ip.count(IPARAM_MAX_ITER, "GFC3D_ACLMFP internal max iterations")?;
        a.inner.rho = ip.dparam[3];
        a.inner.restart_eta = ip.dparam[4];
        a.inner.balancing_tau = ip.dparam[5];
        a.inner.balancing_phi = ip.dparam[6];
        a.inner.rho_strategy = match ip.iparam[9] {
            0 => AdmmRhoStrategy::Constant,
            2 => AdmmRhoStrategy::ResidualBalancing,
            3 => AdmmRhoStrategy::ScaledResidualBalancing,
            other => return Err(invalid(format!("GFC3D_ACLMFP: the ConvexQP ADMM's rho strategy (iparam[9]) = {other} is not implemented in fc3d (0 constant, 2 residual balancing, 3 scaled)"))),
        };
        a.inner.acceleration = match ip.iparam[10] {
            0 => AdmmAcceleration::None,
            1 | 2 => AdmmAcceleration::Accelerated,
            other => return Err(invalid(format!("GFC3D_ACLMFP: the ConvexQP ADMM's acceleration (iparam[10]) = {other} is not 0, 1 or 2"))),
        };
    }
    a.inner_tolerance = inner_tolerance(&p, internal)?;
    Ok(a)
}

/// 615: Siconos' IPM slots: iparam[11] Nesterov-Todd scaling (1 yes, 0 no), iparam[15] the
/// De Saxcé update (0 yes, 1 no: the convex relaxation, Siconos' default), dparam[7..11] the
/// centering and step constants; iparam[12] (sparse storage) is what fc3d always does.
unsafe fn ipm(o: &SolverOptions) -> CResult<IpmOptions> {
    let p = global_params(o)?;
    let flag = |k: usize, what: &str| match p.iparam[k] {
        0 => Ok(false),
        1 => Ok(true),
        other => Err(invalid(format!(
            "GFC3D IPM: {what} (iparam[{k}]) = {other} is not 0 or 1"
        ))),
    };
    p.require(13, 0, "GFC3D IPM: problem info printing")?;
    Ok(IpmOptions {
        nesterov_todd: flag(11, "Nesterov-Todd scaling")?,
        update_s: !flag(15, "no De Saxcé update")?,
        centering_threshold: p.dparam[7],
        centering_exponent_factor: p.dparam[8],
        final_centering_exponent: p.dparam[9],
        step_safety: p.dparam[10],
        step_safety_slope: p.dparam[11],
    })
}

/// 613: the ADMM iteration's slots (as 523's), the De Saxcé update and the error frequency.
unsafe fn global_admm(o: &SolverOptions) -> CResult<GlobalAdmmOptions> {
    let p = global_params(o)?;
    Ok(GlobalAdmmOptions {
        admm: admm::read_iteration(&p)?,
        update_s: admm::read_update_s(&p)?,
        error_frequency: error_frequency(&p)?,
        rescaling: rescaling(&p, "GFC3D ADMM")?,
    })
}

/// `FC3D_ERR_UNSUPPORTED_SOLVER` naming the id and the reason.
fn refused(id: c_int, why: &str) -> CError {
    CError::new(
        FC3D_ERR_UNSUPPORTED_SOLVER,
        format!(
            "solver id {id} ({}): {why}",
            solver_name(id).to_string_lossy()
        ),
    )
}

/// The local method a `_WR` id runs, its options read as those of the local id.
unsafe fn reduced(o: &SolverOptions, id: c_int) -> CResult<fc3d_core::Method> {
    let local_id = GlobalMethod::reduced_local_id(id)
        .ok_or_else(|| refused(id, "not a reduction (_WR) id"))?;
    let local = config_from_node_as(o, local_id)?;
    if local.rescaling != Rescaling::None {
        // Siconos' _WR solvers call the local solver directly, not through fc3d_driver, which
        // is where the local rescaling is applied: it would be silently ignored.
        return Err(invalid(format!(
            "rescaling (iparam[3]) = {:?} is not applied by the global _WR solvers (Siconos \
             calls the local solver without it): set iparam[3] to 0",
            local.rescaling
        )));
    }
    Ok(local.method)
}

/// The rolling configuration of the global rolling id 5000 (`g_rolling_fc3d_driver`): the
/// slots of the rolling NSGS 3000 and its internal solver. Any other id is refused.
pub(crate) unsafe fn global_rolling_config_from_c(
    o: &SolverOptions,
) -> CResult<GlobalRollingConfig> {
    check_tree(o)?;
    let id = o.solverId;
    if id != 5000 {
        return Err(refused(
            id,
            "not run by g_rolling_fc3d_driver, which solves 5000 (GFC3D_NSGS_WR for rolling \
             friction)",
        ));
    }
    let what = solver_name(id).to_string_lossy();
    let p = Params::of(o, &format!("{what} options"))?;
    rolling::read(3000, 5, &p, first_internal(o))
}

/// Writes the outputs of a global solve: `iparam[1]` the iterations, `dparam[1]` the global
/// error of the returned `(r, u, v)`.
pub(crate) unsafe fn write_global_outputs(o: &mut SolverOptions, report: &GlobalReport) {
    *o.iparam.add(super::IPARAM_ITER_DONE) =
        c_int::try_from(report.iterations).unwrap_or(c_int::MAX);
    *o.dparam.add(super::DPARAM_RESIDU) = report.error;
}

/// LMGC90's options (`gfc3d_LmgcDriver`): Siconos' defaults of `id` with every non-zero entry of
/// the host's `iparam` (first `isize`, at most the defaults' size) and `dparam` put over them,
/// as Siconos does.
pub(crate) fn lmgc_overrides(defaults: &mut SolverOptions, iparam: &[c_int], dparam: &[c_double]) {
    // SAFETY: the defaults come from `create_options`: OPTIONS_PARAM_SIZE slots each.
    let size = super::SIZE;
    for (k, &v) in iparam.iter().enumerate().take(size) {
        if v != 0 {
            unsafe { *defaults.iparam.add(k) = v };
        }
    }
    for (k, &v) in dparam.iter().enumerate().take(size) {
        // As Siconos' `fabs(dparam[i]) > 0`: a NaN is not taken.
        if v.abs() > 0.0 {
            unsafe { *defaults.dparam.add(k) = v };
        }
    }
}
