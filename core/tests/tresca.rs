//! TFP (Siconos 503): the Tresca successive approximation with each sub-problem solver, on the
//! analytic single-contact cases and on shared problems in dense, sparse-block and CSR storage.

mod opt5_common;

use fc3d_core::{InnerTolerance, SolveStatus, SolverConfig, TrescaInnerSolver, TrescaOptions};
use opt5_common::*;

fn tfp(inner: TrescaInnerSolver, tol: f64) -> SolverConfig {
    SolverConfig::new(TrescaOptions {
        inner,
        ..Default::default()
    })
    .with_tolerance(tol)
}

#[test]
fn defaults_are_siconos() {
    let c = SolverConfig::new(TrescaOptions::default());
    assert_eq!(c.max_iter, 1000);
    assert_eq!(c.tolerance, 1e-4);
    let o = TrescaOptions::default();
    assert_eq!(o.inner, TrescaInnerSolver::GaussSeidel);
    assert_eq!(o.inner_tolerance, InnerTolerance::Adaptive { ratio: 10.0 });
}

#[test]
fn analytic_single_contact_cases() {
    for inner in [
        TrescaInnerSolver::GaussSeidel,
        TrescaInnerSolver::FixedPointViUpk,
        TrescaInnerSolver::ProjectedGradient,
    ] {
        check_analytic(|tol| tfp(inner, tol));
    }
}

#[test]
fn shared_problems_in_three_storages() {
    for (storage, p) in storages() {
        for tol in [1e-4, 1e-8] {
            let (rep, _, _) = run(&p, &tfp(TrescaInnerSolver::GaussSeidel, tol));
            assert!(rep.converged(), "{storage} at {tol}: {rep:?}");
            assert!(rep.error <= tol);
        }
    }
}

#[test]
fn projection_inner_solvers_on_shared_problems() {
    for (storage, p) in storages() {
        for inner in [
            TrescaInnerSolver::FixedPointViUpk,
            TrescaInnerSolver::ProjectedGradient,
        ] {
            let (rep, _, _) = run(&p, &tfp(inner, 1e-6));
            assert!(rep.converged(), "{storage} {inner:?}: {rep:?}");
        }
    }
}

#[test]
fn storages_agree() {
    let s = storages();
    let (_, r_sbm, _) = run(&s[1].1, &tfp(TrescaInnerSolver::GaussSeidel, 1e-8));
    let (_, r_csr, _) = run(&s[2].1, &tfp(TrescaInnerSolver::GaussSeidel, 1e-8));
    for (a, b) in r_sbm.iter().zip(&r_csr) {
        approx::assert_abs_diff_eq!(*a, *b, epsilon = 1e-12 * (1.0 + norm(&r_sbm)));
    }
}

#[test]
fn iteration_limit_gives_honest_failure() {
    let p = load("Confeti-ex03-Fc3D-SBM.dat");
    let c = SolverConfig::new(TrescaOptions {
        inner_max_iter: 1,
        ..Default::default()
    })
    .with_max_iter(1)
    .with_tolerance(1e-12);
    let (rep, _, _) = run(&p, &c);
    assert_eq!(rep.status, SolveStatus::MaxIterationsReached);
    assert_eq!(rep.iterations, 1);
    assert!(rep.error > 1e-12);
}

#[test]
fn bad_options_are_rejected() {
    let p = one_contact([-1.0, 0.0, 0.0], 0.5);
    let mut r = vec![0.0; 3];
    let mut u = vec![0.0; 3];
    for inner_tolerance in [
        InnerTolerance::Adaptive { ratio: 0.0 },
        InnerTolerance::Given(f64::NAN),
    ] {
        let c = SolverConfig::new(TrescaOptions {
            inner_tolerance,
            ..Default::default()
        });
        assert!(matches!(
            fc3d_core::solve(&p, &c, &mut r, &mut u),
            Err(e) if e.is_invalid_option()
        ));
    }
}

#[test]
fn every_family_stops_when_its_time_budget_is_spent() {
    // A 1 ns budget is spent after the first iteration: the run stops there, finite and honest.
    let p = load("Confeti-ex03-Fc3D-SBM.dat");
    let budget = Some(std::time::Duration::from_nanos(1));
    let configs = [
        SolverConfig::new(TrescaOptions::default()),
        SolverConfig::new(fc3d_core::PfpOptions::default()),
        SolverConfig::new(fc3d_core::AclmOptions::default()),
        SolverConfig::new(fc3d_core::SoclcpOptions::default()),
    ]
    .map(|c| c.with_tolerance(1e-14).with_time_budget(budget));
    for c in configs {
        let (rep, _, _) = run(&p, &c);
        assert_eq!(
            rep.status,
            SolveStatus::TimeBudgetExhausted,
            "{}",
            c.label()
        );
        assert_eq!(rep.iterations, 1, "{}", c.label());
    }
}
