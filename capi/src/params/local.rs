//! One-contact solvers (NSGS's internal solver 0): iparam[0] iterations, dparam[0] tolerance,
//! iparam[9] rho rule with dparam[3] (Newton solvers, 570-572), dparam[3] the regularization of
//! 554, iparam[10] formulation and iparam[11] line search (Newton solvers; they select 550, 551
//! or 565), iparam[12] line-search trials, iparam[15]/[16] the hybrid rounds of 565,
//! iparam[19] (`FC3D_IPARAM_VARIANT`) Siconos' or fc3d's iteration of 550/551/565/553.

use std::os::raw::c_int;

use super::{
    invalid, unsupported_solver, variant_code, Encoded, Params, FC3D_RHO_STRATEGY_DUMONT,
    IPARAM_MAX_ITER, IPARAM_VARIANT,
};
use crate::types::SolverOptions;
use crate::CResult;
use fc3d_core::{LocalSolverKind, LocalSolverOptions, NewtonFormulation, RhoRule};

const IPARAM_RHO_STRATEGY: usize = 9;
const IPARAM_FORMULATION: usize = 10;
const IPARAM_LINE_SEARCH: usize = 11;
const IPARAM_LINE_SEARCH_MAX_ITER: usize = 12;
const IPARAM_HYBRID_MAX_LOOP: usize = 15;
const IPARAM_HYBRID_MAX_ITER: usize = 16;
const DPARAM_RHO: usize = 3;

/// Kinds with a Siconos and an fc3d variant (iparam[19]).
fn has_variant(kind: LocalSolverKind) -> bool {
    use LocalSolverKind::*;
    matches!(
        kind,
        NewtonAlartCurnier
            | NewtonAlartCurnierGp
            | NewtonHybrid
            | ProjectionOnConeWithLocalIteration
    )
}

/// Kinds whose rho comes from a rule (iparam[9]); the projection solvers use `1 / W_NN`.
fn has_rho_rule(kind: LocalSolverKind) -> bool {
    use LocalSolverKind::*;
    matches!(
        kind,
        NewtonAlartCurnier
            | NewtonAlartCurnierGp
            | NewtonHybrid
            | EnhancedAugmentedLagrangian
            | EnhancedBipotential
            | FpViUpk
    )
}

fn is_alart_curnier_newton(kind: LocalSolverKind) -> bool {
    use LocalSolverKind::*;
    matches!(
        kind,
        NewtonAlartCurnier | NewtonAlartCurnierGp | NewtonHybrid
    )
}

/// The local solver described by internal solver options.
pub(super) unsafe fn read(o: &SolverOptions) -> CResult<LocalSolverOptions> {
    let kind = LocalSolverKind::from_siconos_id(o.solverId)
        .ok_or_else(|| unsupported_solver(o.solverId))?;
    let p = Params::of(o, "local solver options")?;
    let mut l = LocalSolverOptions::new(kind);
    l.max_iter = p.count(IPARAM_MAX_ITER, "local max iterations")?;
    l.tolerance = p.dparam[super::DPARAM_TOL];
    if has_rho_rule(kind) {
        l.rho_rule = match p.iparam[IPARAM_RHO_STRATEGY] {
            0 => RhoRule::Constant(p.dparam[DPARAM_RHO]),
            1 => RhoRule::SpectralNorm,
            2 => RhoRule::SplitSpectralNormCond,
            3 => RhoRule::SplitSpectralNorm,
            FC3D_RHO_STRATEGY_DUMONT => RhoRule::Dumont(p.dparam[DPARAM_RHO]),
            other => return Err(invalid(format!("rho strategy (iparam[9]) = {other} is not implemented in fc3d (0-3, {FC3D_RHO_STRATEGY_DUMONT} = Dumont)"))),
        };
    }
    if kind == LocalSolverKind::ProjectionOnConeWithRegularization {
        l.regularization = p.dparam[DPARAM_RHO];
    }
    if kind == LocalSolverKind::EnhancedAugmentedLagrangian {
        p.require(IPARAM_FORMULATION, 0, "EAL formulation (Alart-Curnier, 0)")?;
        l.kind = match p.iparam[IPARAM_LINE_SEARCH] {
            -1 => LocalSolverKind::EnhancedAugmentedLagrangian,
            // EAL with the Goldstein-Price search is 551 with Dumont's rho.
            0 => LocalSolverKind::NewtonAlartCurnierGp,
            other => return Err(invalid(format!("line search (iparam[11]) = {other} is not implemented in fc3d (-1 none, 0 Goldstein-Price)"))),
        };
    }
    if is_alart_curnier_newton(kind) {
        l.formulation = match p.iparam[IPARAM_FORMULATION] {
            0 | 2 => NewtonFormulation::AlartCurnier,
            1 | 3 => NewtonFormulation::JeanMoreau,
            other => return Err(invalid(format!("Newton formulation (iparam[10]) = {other} is not implemented in fc3d (0/2 Alart-Curnier, 1/3 Jean-Moreau)"))),
        };
        l.kind = match (kind, p.iparam[IPARAM_LINE_SEARCH]) {
            (LocalSolverKind::NewtonHybrid, 0) => LocalSolverKind::NewtonHybrid,
            (LocalSolverKind::NewtonHybrid, -1) => {
                return Err(invalid("the hybrid Newton solver (565) needs the Goldstein-Price line search (iparam[11] = 0)"))
            }
            (_, 0) => LocalSolverKind::NewtonAlartCurnierGp,
            (_, -1) => LocalSolverKind::NewtonAlartCurnier,
            (_, other) => return Err(invalid(format!("line search (iparam[11]) = {other} is not implemented in fc3d (-1 none, 0 Goldstein-Price)"))),
        };
    }
    // Trials and hybrid rounds matter only to the solvers that have them.
    if matches!(
        l.kind,
        LocalSolverKind::NewtonAlartCurnierGp | LocalSolverKind::NewtonHybrid
    ) {
        l.line_search_max_iter =
            p.count(IPARAM_LINE_SEARCH_MAX_ITER, "line-search max iterations")?;
    }
    if l.kind == LocalSolverKind::NewtonHybrid {
        l.hybrid_max_loop = p.count(IPARAM_HYBRID_MAX_LOOP, "hybrid max loops")?;
        l.hybrid_max_iter = p.count(IPARAM_HYBRID_MAX_ITER, "hybrid max iterations")?;
    }
    if has_variant(l.kind) && has_variant(kind) {
        l.variant = p.variant()?;
    }
    Ok(l)
}

/// The slots of a local solver's options.
pub(super) fn write(l: &LocalSolverOptions) -> Encoded {
    let kind = l.kind;
    let mut e = Encoded::new(kind.siconos_id());
    e.iparam[IPARAM_MAX_ITER] = c_int::try_from(l.max_iter).unwrap_or(c_int::MAX);
    e.dparam[super::DPARAM_TOL] = l.tolerance;
    if has_rho_rule(kind) {
        e.iparam[IPARAM_RHO_STRATEGY] = match l.rho_rule {
            RhoRule::Constant(rho) => {
                e.dparam[DPARAM_RHO] = rho;
                0
            }
            RhoRule::SpectralNorm => 1,
            RhoRule::SplitSpectralNormCond => 2,
            RhoRule::SplitSpectralNorm => 3,
            RhoRule::Dumont(alpha) => {
                e.dparam[DPARAM_RHO] = alpha;
                FC3D_RHO_STRATEGY_DUMONT
            }
        };
    }
    if kind == LocalSolverKind::ProjectionOnConeWithRegularization {
        e.dparam[DPARAM_RHO] = l.regularization;
    }
    if is_alart_curnier_newton(kind) {
        e.iparam[IPARAM_FORMULATION] = match l.formulation {
            NewtonFormulation::AlartCurnier => 0,
            NewtonFormulation::JeanMoreau => 1,
        };
    }
    if is_alart_curnier_newton(kind) || kind == LocalSolverKind::EnhancedAugmentedLagrangian {
        e.iparam[IPARAM_LINE_SEARCH] = match kind {
            LocalSolverKind::NewtonAlartCurnierGp | LocalSolverKind::NewtonHybrid => 0,
            _ => -1,
        };
    }
    // The trials of the solvers that search (EAL's: when the host switches its search on).
    if matches!(
        kind,
        LocalSolverKind::NewtonAlartCurnierGp
            | LocalSolverKind::NewtonHybrid
            | LocalSolverKind::EnhancedAugmentedLagrangian
    ) {
        e.iparam[IPARAM_LINE_SEARCH_MAX_ITER] =
            c_int::try_from(l.line_search_max_iter).unwrap_or(c_int::MAX);
    }
    if is_alart_curnier_newton(kind) {
        e.iparam[IPARAM_HYBRID_MAX_LOOP] = c_int::try_from(l.hybrid_max_loop).unwrap_or(c_int::MAX);
        e.iparam[IPARAM_HYBRID_MAX_ITER] = c_int::try_from(l.hybrid_max_iter).unwrap_or(c_int::MAX);
    }
    if has_variant(kind) {
        e.iparam[IPARAM_VARIANT] = variant_code(l.variant);
    }
    e
}
