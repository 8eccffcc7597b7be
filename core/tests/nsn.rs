//! Nonsmooth Newton (504 AC / JM, 513 FB, 520 NM): single-contact analytic cases for every
//! formulation and line search, shared problems in dense, sparse-block and CSR storage, option
//! checks and honest failures. Errors are re-measured here from `u = W r + q` entry by entry.

use std::path::PathBuf;
use std::time::Duration;

use approx::assert_relative_eq;
use fc3d_core::{
    solve, Delassus, DenseMatrix, FrictionProblem, NsnFormulation, NsnLineSearch, NsnOptions,
    RhoRule, SolveStatus, SolverConfig,
};

const FORMULATIONS: [NsnFormulation; 4] = [
    NsnFormulation::AlartCurnier,
    NsnFormulation::JeanMoreau,
    NsnFormulation::FischerBurmeister,
    NsnFormulation::NaturalMap,
];

const LINE_SEARCHES: [NsnLineSearch; 4] = [
    NsnLineSearch::None,
    NsnLineSearch::GoldsteinPrice,
    NsnLineSearch::Armijo,
    NsnLineSearch::NonMonotone,
];

fn config(f: NsnFormulation, ls: NsnLineSearch, tol: f64, max_iter: usize) -> SolverConfig {
    let mut o = NsnOptions::new(f);
    o.line_search = ls;
    SolverConfig::new(o)
        .with_tolerance(tol)
        .with_max_iter(max_iter)
}

/// Relative natural-map error recomputed from scratch (entry-wise u, cone projection written
/// from the boundary-ray formula).
fn independent_error(p: &FrictionProblem<'_>, r: &[f64]) -> f64 {
    let mut u = p.q().to_vec();
    p.w().for_each_entry(|i, j, v| u[i] += v * r[j]);
    let mut s = 0.0;
    for (c, &mu) in p.mu().iter().enumerate() {
        let un = u[3 * c] + mu * (u[3 * c + 1].powi(2) + u[3 * c + 2].powi(2)).sqrt();
        let x = [
            r[3 * c] - un,
            r[3 * c + 1] - u[3 * c + 1],
            r[3 * c + 2] - u[3 * c + 2],
        ];
        let nt = (x[1] * x[1] + x[2] * x[2]).sqrt();
        let proj = if x[0] >= 0.0 && nt <= mu * x[0] {
            x
        } else if mu * nt <= -x[0] {
            [0.0; 3]
        } else {
            let k = 1.0 / (1.0 + mu * mu).sqrt();
            let d = [k, k * mu * x[1] / nt, k * mu * x[2] / nt];
            let t = x[0] * d[0] + x[1] * d[1] + x[2] * d[2];
            [t * d[0], t * d[1], t * d[2]]
        };
        for k in 0..3 {
            s += (r[3 * c + k] - proj[k]).powi(2);
        }
    }
    let n2 = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    s.sqrt() / n2(p.q()).max(n2(r)).max(n2(&u)).max(f64::MIN_POSITIVE)
}

fn dense(n: usize, w: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> FrictionProblem<'static> {
    FrictionProblem::new(Delassus::Dense(DenseMatrix::new(n, n, w).unwrap()), q, mu).unwrap()
}

/// Two decoupled contacts with W = diag(2, 1, 1, 1, 1, 1) (the second one is given).
fn two_contacts(second_q: [f64; 3], mu: f64) -> FrictionProblem<'static> {
    let mut w = vec![0.0; 36];
    for i in 0..6 {
        w[i + 6 * i] = 1.0;
    }
    w[0] = 2.0;
    let mut q = vec![-2.0, 0.0, 0.0];
    q.extend(second_q);
    dense(6, w, q, vec![0.5, mu])
}

fn run(p: &FrictionProblem<'_>, c: &SolverConfig) -> (fc3d_core::SolveReport, Vec<f64>, Vec<f64>) {
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let rep = solve(p, c, &mut r, &mut u).unwrap();
    (rep, r, u)
}

#[test]
fn single_contact_analytic_cases_every_formulation_and_line_search() {
    for f in FORMULATIONS {
        for ls in LINE_SEARCHES {
            let c = config(f, ls, 1e-12, 100);
            let what = format!("{f:?}/{ls:?}");
            // Take-off of the second contact: q_N > 0 gives r = 0 there (the first contact,
            // pushed in, keeps the trivial shortcut away: r_1 = (1, 0, 0)).
            let p = two_contacts([0.5, 0.3, -0.2], 0.5);
            let (rep, r, u) = run(&p, &c);
            assert_eq!(rep.status, SolveStatus::Converged, "{what}: {rep:?}");
            assert_relative_eq!(r[0], 1.0, epsilon = 1e-10);
            for k in 3..6 {
                assert!(r[k].abs() < 1e-10, "{what}: take-off r = {r:?}");
            }
            assert_relative_eq!(u[3], 0.5, epsilon = 1e-10);
            // Stick: q = (-1, 0.1, 0), W_cc = I, mu = 0.5: r = (1, -0.1, 0), u = 0.
            let p = two_contacts([-1.0, 0.1, 0.0], 0.5);
            let (rep, r, u) = run(&p, &c);
            assert_eq!(rep.status, SolveStatus::Converged, "{what}: {rep:?}");
            for (k, v) in [1.0, -0.1, 0.0].iter().enumerate() {
                assert_relative_eq!(r[3 + k], v, epsilon = 1e-10);
                assert!(u[3 + k].abs() < 1e-10, "{what}: stick u = {u:?}");
            }
            // Slide: q = (-1, 1, 0.5), mu = 0.3: r_N = 1, r_T = -mu r_N u_T/|u_T| with
            // u_T = q_T + r_T parallel to q_T.
            let p = two_contacts([-1.0, 1.0, 0.5], 0.3);
            let (rep, r, u) = run(&p, &c);
            assert_eq!(rep.status, SolveStatus::Converged, "{what}: {rep:?}");
            let nq = (1.0f64 + 0.25).sqrt();
            assert_relative_eq!(r[3], 1.0, epsilon = 1e-9);
            assert_relative_eq!(r[4], -0.3 / nq, epsilon = 1e-9);
            assert_relative_eq!(r[5], -0.3 * 0.5 / nq, epsilon = 1e-9);
            let ut = (u[4] * u[4] + u[5] * u[5]).sqrt();
            assert_relative_eq!(r[4], -0.3 * r[3] * u[4] / ut, epsilon = 1e-9);
            assert_relative_eq!(r[5], -0.3 * r[3] * u[5] / ut, epsilon = 1e-9);
            assert!(independent_error(&p, &r) <= 1e-12);
        }
    }
}

#[test]
fn frictionless_contacts_are_solved() {
    for f in FORMULATIONS {
        let p = two_contacts([-1.0, 1.0, 0.5], 0.0);
        let (rep, r, _) = run(&p, &config(f, NsnLineSearch::GoldsteinPrice, 1e-12, 50));
        assert_eq!(rep.status, SolveStatus::Converged, "{f:?}");
        assert_relative_eq!(r[3], 1.0, epsilon = 1e-10);
        assert!(r[4].abs() < 1e-10 && r[5].abs() < 1e-10, "{f:?}: {r:?}");
    }
}

fn shared(name: &str) -> FrictionProblem<'static> {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/siconos"
    ))
    .join(name);
    fc3d_core::io::read_problem_file(&path).unwrap()
}

/// (problem, expected storage) solved by every formulation at 1e-8 in its own storage and as CSR.
#[test]
fn shared_problems_in_every_storage() {
    let cases = [
        ("FC3D_Example1.dat", "dense"),
        ("NESpheres_10_1.dat", "dense"),
        ("Confeti-ex13-Fc3D-SBM.dat", "sparse-block"),
        ("Rover4144.dat", "dense"),
    ];
    for (name, storage) in cases {
        let p = shared(name);
        assert_eq!(p.w().storage_name(), storage, "{name}");
        let csr = p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap();
        for f in FORMULATIONS {
            let c = config(f, NsnLineSearch::GoldsteinPrice, 1e-8, 1000);
            let (rep, r, u) = run(&p, &c);
            assert_eq!(rep.status, SolveStatus::Converged, "{name} {f:?}: {rep:?}");
            let e = independent_error(&p, &r);
            assert!(e <= 1e-8, "{name} {f:?}: {e}");
            assert_relative_eq!(rep.error, e, max_relative = 1e-6, epsilon = 1e-14);
            assert!(u.iter().all(|v| v.is_finite()));
            let (rep_csr, r_csr, _) = run(&csr, &c);
            assert_eq!(rep_csr.status, SolveStatus::Converged, "{name} {f:?} csr");
            assert!(independent_error(&csr, &r_csr) <= 1e-8);
        }
    }
}

#[test]
fn sparse_block_copy_of_a_dense_problem_gives_the_same_iterates() {
    let p = shared("NESpheres_10_1.dat");
    let sbm = p
        .with_w(Delassus::SparseBlock(p.w().to_block_sparse().unwrap()))
        .unwrap();
    let c = config(
        NsnFormulation::AlartCurnier,
        NsnLineSearch::GoldsteinPrice,
        1e-10,
        100,
    );
    let (a, ra, _) = run(&p, &c);
    let (b, rb, _) = run(&sbm, &c);
    // The Newton loop works on the same block copy whatever the storage: same iterates.
    assert_eq!(a.iterations, b.iterations);
    assert_eq!(ra, rb);
}

#[test]
fn failures_are_honest_and_finite() {
    let p = shared("Confeti-ex13-Fc3D-SBM.dat");
    for f in FORMULATIONS {
        let (rep, r, u) = run(&p, &config(f, NsnLineSearch::None, 1e-14, 1));
        assert_eq!(rep.status, SolveStatus::MaxIterationsReached, "{f:?}");
        assert!(r.iter().chain(&u).all(|v| v.is_finite()));
        assert_relative_eq!(rep.error, independent_error(&p, &r), max_relative = 1e-9);
        assert!(rep.iterations <= 1);
    }
    // A time budget stops the run with the best iterate.
    let o = NsnOptions::new(NsnFormulation::NaturalMap);
    let c = SolverConfig::new(o)
        .with_tolerance(0.0)
        .with_max_iter(usize::MAX)
        .with_time_budget(Some(Duration::from_millis(30)));
    let (rep, r, _) = run(&p, &c);
    assert_eq!(rep.status, SolveStatus::TimeBudgetExhausted);
    assert!(r.iter().all(|v| v.is_finite()));
}

#[test]
fn bad_options_are_rejected() {
    let p = two_contacts([-1.0, 0.0, 0.0], 0.5);
    let o = NsnOptions {
        rho_rule: RhoRule::Constant(0.0),
        ..NsnOptions::default()
    };
    let mut r = vec![0.0; 6];
    let mut u = vec![0.0; 6];
    assert!(matches!(
        solve(&p, &SolverConfig::new(o), &mut r, &mut u),
        Err(e) if e.is_invalid_option()
    ));
    let o = NsnOptions {
        line_search_max_iter: 0,
        ..NsnOptions::default()
    };
    assert!(matches!(
        solve(&p, &SolverConfig::new(o), &mut r, &mut u),
        Err(e) if e.is_invalid_option()
    ));
    assert_eq!(r, vec![0.0; 6]);
}

#[test]
fn every_rho_rule_solves_a_shared_problem() {
    let p = shared("NESpheres_10_1.dat");
    for rule in [
        RhoRule::Constant(1.0),
        RhoRule::SpectralNorm,
        RhoRule::SplitSpectralNorm,
        RhoRule::SplitSpectralNormCond,
    ] {
        let o = NsnOptions {
            rho_rule: rule,
            ..NsnOptions::default()
        };
        let (rep, r, _) = run(&p, &SolverConfig::new(o).with_tolerance(1e-8));
        assert_eq!(rep.status, SolveStatus::Converged, "{rule:?}");
        assert!(independent_error(&p, &r) <= 1e-8);
    }
}
