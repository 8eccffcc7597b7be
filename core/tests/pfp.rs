//! PFP (Siconos 522): Panagiotopoulos' alternating normal (PGS) / tangent (FP-VI-UPK, projected
//! gradient, Gauss-Seidel) fixed point, on the analytic single-contact cases and on shared
//! problems in dense, sparse-block and CSR storage.

mod opt5_common;

use fc3d_core::{InnerTolerance, PfpOptions, SolveStatus, SolverConfig, TrescaInnerSolver};
use opt5_common::*;

fn pfp(tangent: TrescaInnerSolver, tol: f64) -> SolverConfig {
    SolverConfig::new(PfpOptions {
        tangent,
        ..Default::default()
    })
    .with_tolerance(tol)
}

#[test]
fn defaults() {
    let c = SolverConfig::new(PfpOptions::default());
    assert_eq!((c.max_iter, c.tolerance), (1000, 1e-4));
    let o = PfpOptions::default();
    assert_eq!(o.tangent, TrescaInnerSolver::FixedPointViUpk);
    assert_eq!(o.inner_tolerance, InnerTolerance::Adaptive { ratio: 10.0 });
}

#[test]
fn analytic_single_contact_cases() {
    for tangent in [
        TrescaInnerSolver::FixedPointViUpk,
        TrescaInnerSolver::ProjectedGradient,
        TrescaInnerSolver::GaussSeidel,
    ] {
        check_analytic(|tol| pfp(tangent, tol));
    }
}

#[test]
fn shared_problems_in_three_storages() {
    for (storage, p) in storages() {
        for tol in [1e-4, 1e-8] {
            let (rep, _, _) = run(&p, &pfp(TrescaInnerSolver::FixedPointViUpk, tol));
            assert!(rep.converged(), "{storage} at {tol}: {rep:?}");
        }
        for tangent in [
            TrescaInnerSolver::ProjectedGradient,
            TrescaInnerSolver::GaussSeidel,
        ] {
            let (rep, _, _) = run(&p, &pfp(tangent, 1e-6));
            assert!(rep.converged(), "{storage} {tangent:?}: {rep:?}");
        }
    }
}

#[test]
fn iteration_limit_gives_honest_failure() {
    let p = load("Confeti-ex03-Fc3D-SBM.dat");
    let c = SolverConfig::new(PfpOptions {
        inner_max_iter: 1,
        normal_max_iter: 1,
        ..Default::default()
    })
    .with_max_iter(1)
    .with_tolerance(1e-12);
    let (rep, _, _) = run(&p, &c);
    assert_eq!(rep.status, SolveStatus::MaxIterationsReached);
    assert!(rep.error > 1e-12);
}
