//! ADMM (Siconos id 523): analytic one-contact cases, shared Siconos problems in dense,
//! sparse-block and CSR storage with every rho strategy, option checks, divergence handling.
//!
//! Reported errors are checked against an independent recomputation (entry-wise `u = W r + q`,
//! cone projection written here from its dot-product form).

mod common;
use common::honesty::check_report;

use std::path::PathBuf;

use approx::assert_relative_eq;
use fc3d_core::{
    solve, solve_with_observer, AdmmAcceleration, AdmmInitialRho, AdmmOptions, AdmmRhoStrategy,
    Delassus, DenseMatrix, FrictionProblem, SolveReport, SolverConfig,
};

fn run(p: &FrictionProblem<'_>, c: &SolverConfig) -> (SolveReport, Vec<f64>, Vec<f64>, usize) {
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let mut calls = 0;
    let rep = solve_with_observer(p, c, &mut r, &mut u, &mut |_| calls += 1)
        .expect("valid problem and options");
    (rep, r, u, calls)
}

fn siconos(name: &str) -> FrictionProblem<'static> {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/siconos"
    ))
    .join(name);
    fc3d_core::io::read_problem_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The default (Siconos') configuration and the two automatic penalty updates.
fn variants(tol: f64, max_iter: usize) -> Vec<(&'static str, SolverConfig)> {
    let base = AdmmOptions::default();
    let options = vec![
        ("default", base),
        (
            "residual-balancing",
            AdmmOptions {
                rho_strategy: AdmmRhoStrategy::ResidualBalancing,
                ..base
            },
        ),
        (
            "scaled-residual-balancing",
            AdmmOptions {
                rho_strategy: AdmmRhoStrategy::ScaledResidualBalancing,
                ..base
            },
        ),
        (
            "plain-given-rho",
            AdmmOptions {
                acceleration: AdmmAcceleration::None,
                initial_rho: AdmmInitialRho::Given,
                ..base
            },
        ),
        (
            "norm-inf",
            AdmmOptions {
                initial_rho: AdmmInitialRho::NormInf,
                ..base
            },
        ),
        (
            "eigenvalues",
            AdmmOptions {
                initial_rho: AdmmInitialRho::Eigenvalues,
                ..base
            },
        ),
        (
            // Siconos' test_admm_1 third block: residual balancing on (W, q) / ||W||_inf.
            "rescaled-residual-balancing",
            AdmmOptions {
                rho_strategy: AdmmRhoStrategy::ResidualBalancing,
                scalar_rescaling: true,
                ..base
            },
        ),
    ];
    options
        .into_iter()
        .map(|(name, o)| {
            (
                name,
                SolverConfig::new(o)
                    .with_tolerance(tol)
                    .with_max_iter(max_iter),
            )
        })
        .collect()
}

/// Take-off, stick and slide on decoupled `diag(1.25, 1, 1)` blocks (see tests/vi.rs).
#[test]
fn take_off_stick_and_slide() {
    let n = 9;
    let mut w = vec![0.0; n * n];
    for c in 0..3 {
        let k = 3 * c;
        w[k + k * n] = 1.25;
        w[(k + 1) + (k + 1) * n] = 1.0;
        w[(k + 2) + (k + 2) * n] = 1.0;
    }
    let p = FrictionProblem::new(
        Delassus::Dense(DenseMatrix::new(n, n, w).unwrap()),
        vec![1.0, 0.3, -0.2, -2.0, 0.1, 0.05, -2.0, 3.0, 4.0],
        vec![0.5; 3],
    )
    .unwrap();
    let expected = [0.0, 0.0, 0.0, 1.6, -0.1, -0.05, 1.6, -0.48, -0.64];
    for (name, o) in variants(1e-12, 20000) {
        let (rep, r, u, calls) = run(&p, &o);
        check_report(name, &p, 1e-12, &rep, &r, &u);
        assert!(rep.converged(), "{name}: {rep:?}");
        assert_eq!(calls, rep.iterations, "{name}");
        for (a, b) in r.iter().zip(&expected) {
            assert_relative_eq!(*a, *b, epsilon = 1e-9);
        }
        assert_relative_eq!(u[7], 2.52, epsilon = 1e-9);
        assert_relative_eq!(u[8], 3.36, epsilon = 1e-9);
    }
}

/// Every variant in every storage; `converging` names the variants that must reach 1e-8.
fn shared_problem(name: &str, max_iter: usize, converging: &[&str]) {
    let base = siconos(name);
    let tol = 1e-8;
    let mut storages = vec![base.clone()];
    if !matches!(base.w(), Delassus::SparseBlock(_)) {
        storages.push(
            base.with_w(Delassus::SparseBlock(base.w().to_block_sparse().unwrap()))
                .unwrap(),
        );
    }
    if !matches!(base.w(), Delassus::Dense(_)) {
        storages.push(base.with_w(Delassus::Dense(base.w().to_dense())).unwrap());
    }
    storages.push(base.with_w(Delassus::Sparse(base.w().to_csr())).unwrap());
    for (label, o) in variants(tol, max_iter) {
        for p in &storages {
            let what = format!("{name} {label} {}", p.w().storage_name());
            let (rep, r, u, _) = run(p, &o);
            check_report(&what, p, tol, &rep, &r, &u);
            if std::env::var_os("FC3D_ADMM_PRINT").is_some() {
                eprintln!("RESULT {what}: {rep:?}");
                continue;
            }
            assert_eq!(
                rep.converged(),
                converging.contains(&label),
                "{what}: {rep:?}"
            );
        }
    }
}

#[test]
fn nespheres_dense() {
    shared_problem(
        "NESpheres_10_1.dat",
        2000,
        &[
            "default",
            "residual-balancing",
            "scaled-residual-balancing",
            "plain-given-rho",
            "norm-inf",
            "eigenvalues",
            "rescaled-residual-balancing",
        ],
    );
}

#[test]
fn confeti_ex03_sparse_block() {
    // rho = 1 (Siconos' default, far from W's scale here) stalls, accelerated or not; residual
    // balancing without scaling is at 4e-7 after 2000 iterations.
    shared_problem(
        "Confeti-ex03-Fc3D-SBM.dat",
        2000,
        &[
            "scaled-residual-balancing",
            "norm-inf",
            "eigenvalues",
            "rescaled-residual-balancing",
        ],
    );
}

#[test]
fn rover_dense_singular_w() {
    // W is singular (more contact unknowns than degrees of freedom): the eigenvalue rule's floor
    // keeps rho usable. Plain ADMM with rho = 1 (about 10 lambda_max here) is still at 7e-6
    // after 2000 iterations; accelerated (the default) it converges.
    shared_problem(
        "Rover1040.dat",
        2000,
        &[
            "default",
            "residual-balancing",
            "scaled-residual-balancing",
            "norm-inf",
            "eigenvalues",
            "rescaled-residual-balancing",
        ],
    );
}

/// Against the installed Siconos 4.4 (scripts/compare-siconos.sh, tol 1e-5, Siconos' test_admm
/// collections' settings): where Siconos' residual test and fc3d's error test stop at the same
/// iteration, the counts are equal (same iterates).
#[test]
fn siconos_iteration_counts() {
    let p = siconos("Capsules-i100-1090.dat");
    let base = AdmmOptions::default();
    for (label, o, iterations) in [
        ("default", base, 63),
        (
            "scaled-residual-balancing",
            AdmmOptions {
                rho_strategy: AdmmRhoStrategy::ScaledResidualBalancing,
                ..base
            },
            218,
        ),
        (
            "rescaled-residual-balancing",
            AdmmOptions {
                rho_strategy: AdmmRhoStrategy::ResidualBalancing,
                scalar_rescaling: true,
                ..base
            },
            160,
        ),
    ] {
        let c = SolverConfig::new(o)
            .with_tolerance(1e-5)
            .with_max_iter(10000);
        let (rep, r, u, _) = run(&p, &c);
        check_report(label, &p, 1e-5, &rep, &r, &u);
        assert!(rep.converged(), "{label}: {rep:?}");
        assert_eq!(rep.iterations, iterations, "{label}");
    }
}

#[test]
fn stalling_problem_fails_honestly() {
    // OneObject-i1028-138: 2000 iterations are not enough for any variant; the result is finite
    // and its error honest.
    let p = siconos("OneObject-i1028-138.hdf5.dat");
    for (label, o) in variants(1e-8, 200) {
        let (rep, r, u, calls) = run(&p, &o);
        assert!(!rep.converged(), "{label}");
        assert_eq!(rep.iterations, calls, "{label}");
        check_report(label, &p, 1e-8, &rep, &r, &u);
    }
}

#[test]
fn bad_options_are_rejected_and_leave_r_untouched() {
    let p = siconos("FC3D_Example1.dat");
    let n = p.size();
    let bad = [
        SolverConfig::new(AdmmOptions {
            initial_rho: AdmmInitialRho::Given,
            rho: 0.0,
            ..AdmmOptions::default()
        }),
        SolverConfig::new(AdmmOptions {
            restart_eta: 1.5,
            ..AdmmOptions::default()
        }),
        SolverConfig::new(AdmmOptions {
            rho_strategy: AdmmRhoStrategy::ResidualBalancing,
            balancing_tau: 1.0,
            ..AdmmOptions::default()
        }),
        SolverConfig::new(AdmmOptions {
            rho_strategy: AdmmRhoStrategy::ScaledResidualBalancing,
            balancing_phi: f64::NAN,
            ..AdmmOptions::default()
        }),
        SolverConfig::new(AdmmOptions::default()).with_tolerance(f64::INFINITY),
    ];
    for c in bad {
        let mut r = vec![0.25; n];
        let mut u = vec![0.5; n];
        let e = solve(&p, &c, &mut r, &mut u);
        assert!(
            matches!(&e, Err(e) if e.is_invalid_option()),
            "{c:?}: {e:?}"
        );
        assert_eq!(r, vec![0.25; n]);
        assert_eq!(u, vec![0.5; n]);
    }
}

#[test]
fn defaults_are_siconos() {
    let o = AdmmOptions::default();
    let c = SolverConfig::new(o);
    assert_eq!((c.max_iter, c.tolerance, o.rho), (20000, 1e-6, 1.0));
    assert_eq!(o.initial_rho, AdmmInitialRho::Given);
    assert_eq!(o.rho_strategy, AdmmRhoStrategy::Constant);
    assert_eq!(o.acceleration, AdmmAcceleration::Accelerated);
    assert_eq!(
        (o.restart_eta, o.balancing_tau, o.balancing_phi),
        (0.999, 2.0, 2.0)
    );
    assert_eq!(c.siconos_id(), 523);
}

#[test]
fn time_budget_stops_the_run() {
    let p = siconos("OneObject-i1028-138.hdf5.dat");
    let c = SolverConfig::new(AdmmOptions::default())
        .with_tolerance(0.0)
        .with_max_iter(usize::MAX)
        .with_time_budget(Some(std::time::Duration::from_millis(20)));
    let (rep, r, u, calls) = run(&p, &c);
    assert_eq!(
        rep.status,
        fc3d_core::SolveStatus::TimeBudgetExhausted,
        "{rep:?}"
    );
    assert_eq!(calls, rep.iterations);
    check_report("ADMM", &p, 0.0, &rep, &r, &u);
}
