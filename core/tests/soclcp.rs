//! SOCLCP (Siconos 517), the convex relaxation solved on its own, and ACLMFP (516), the fixed
//! point that turns it into Coulomb's law: analytic single-contact cases and shared problems in
//! dense, sparse-block and CSR storage.

mod opt5_common;

use fc3d_core::{AclmOptions, SoclcpOptions, SolveStatus, SolverConfig};
use opt5_common::*;

fn aclm(tol: f64) -> SolverConfig {
    SolverConfig::new(AclmOptions::default()).with_tolerance(tol)
}

fn soclcp(tol: f64) -> SolverConfig {
    SolverConfig::new(SoclcpOptions::default()).with_tolerance(tol)
}

#[test]
fn aclm_analytic_single_contact_cases() {
    check_analytic(aclm);
}

#[test]
fn aclm_shared_problems_in_three_storages() {
    for (storage, p) in storages() {
        for tol in [1e-4, 1e-8] {
            let (rep, _, _) = run(&p, &aclm(tol));
            assert!(rep.converged(), "{storage} at {tol}: {rep:?}");
        }
    }
}

#[test]
fn soclcp_stick_is_coulomb() {
    // Sticking and separating contacts (q1 in K*): the relaxed solution is the Coulomb one.
    let p = two_contacts_with([-1.0, 0.2, -0.1], [1.0, 0.3, 0.0], 0.5);
    let (rep, r, u) = run(&p, &soclcp(1e-12));
    assert_eq!(rep.status, SolveStatus::Converged);
    for (a, b) in r.iter().zip([1.0, -0.2, 0.1, 0.0, 0.0, 0.0]) {
        approx::assert_abs_diff_eq!(*a, b, epsilon = 1e-12);
    }
    approx::assert_abs_diff_eq!(u[0], 0.0, epsilon = 1e-12);
}

#[test]
fn soclcp_slide_is_relaxed_not_coulomb() {
    // W = I, q0 = (-1, 2, 0), mu = 0.5: the SOCLCP solution slides with u on the boundary of K*
    // (u_N = mu ||u_T|| > 0: the contact lifts off), r on the boundary of K, u ⟂ r.
    let p = two_contacts_with([-1.0, 2.0, 0.0], [1.0, 0.3, 0.0], 0.5);
    let (rep, r, u) = run(&p, &soclcp(1e-12));
    assert_eq!(rep.status, SolveStatus::RelaxationNotCoulomb);
    assert_eq!(rep.status.info_code(), 3);
    assert!(rep.error > 1e-3);
    // Analytic relaxed solution: r = t (1, -mu, 0), u = r + q = lambda (mu, 1, 0):
    // t - 1 = mu lambda, 2 - mu t = lambda  =>  t = (1 + 2 mu) / (1 + mu^2) = 1.6.
    let t = (1.0 + 2.0 * 0.5) / (1.0 + 0.25);
    for (a, b) in r.iter().zip([t, -0.5 * t, 0.0, 0.0, 0.0, 0.0]) {
        approx::assert_abs_diff_eq!(*a, b, epsilon = 1e-12);
    }
    approx::assert_abs_diff_eq!(
        u[0] * r[0] + u[1] * r[1] + u[2] * r[2],
        0.0,
        epsilon = 1e-12
    );
}

#[test]
fn soclcp_on_shared_problems_in_three_storages() {
    // The relaxation converges; its solution is not a Coulomb solution on these sliding scenes.
    for (storage, p) in storages() {
        let (rep, _, _) = run(&p, &soclcp(1e-8));
        assert_eq!(
            rep.status,
            SolveStatus::RelaxationNotCoulomb,
            "{storage}: {rep:?}"
        );
        assert!(rep.error > 1e-8);
    }
}

#[test]
fn iteration_limit_and_bad_options() {
    let p = load("Confeti-ex03-Fc3D-SBM.dat");
    let c = SolverConfig::new(SoclcpOptions::default())
        .with_max_iter(1)
        .with_tolerance(1e-12);
    let (rep, _, _) = run(&p, &c);
    assert_eq!(rep.status, SolveStatus::MaxIterationsReached);
    let c = SolverConfig::new(AclmOptions {
        inner_max_iter: 1,
        ..Default::default()
    })
    .with_max_iter(1)
    .with_tolerance(1e-12);
    let (rep, _, _) = run(&p, &c);
    assert_eq!(rep.status, SolveStatus::MaxIterationsReached);

    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    for omega in [0.0, 2.0, f64::NAN] {
        let c = SolverConfig::new(SoclcpOptions { relaxation: omega });
        assert!(matches!(
            fc3d_core::solve(&p, &c, &mut r, &mut u),
            Err(e) if e.is_invalid_option()
        ));
    }
}
