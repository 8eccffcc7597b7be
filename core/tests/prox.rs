//! Proximal point method (502) with NSN-AC (PPA-NSN-AC) and NSGS (PPA-NSGS-AC) internal
//! solvers: analytic single contacts, shared problems in dense, sparse-block and CSR storage,
//! option checks and honest failures.

use std::path::PathBuf;

use approx::assert_relative_eq;
use fc3d_core::{
    natural_map_error, solve, Delassus, DenseMatrix, FrictionProblem, NsgsOptions, NsnFormulation,
    NsnOptions, ProxInternal, ProxOptions, SolveStatus, SolverConfig,
};

fn internals() -> [ProxInternal; 2] {
    [
        ProxInternal::NsnAc(NsnOptions::new(NsnFormulation::AlartCurnier)),
        ProxInternal::Nsgs(NsgsOptions::default()),
    ]
}

fn config(internal: ProxInternal, tol: f64, max_iter: usize) -> SolverConfig {
    SolverConfig::new(ProxOptions {
        internal,
        ..ProxOptions::default()
    })
    .with_tolerance(tol)
    .with_max_iter(max_iter)
}

fn run(p: &FrictionProblem<'_>, c: &SolverConfig) -> (fc3d_core::SolveReport, Vec<f64>, Vec<f64>) {
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let rep = solve(p, c, &mut r, &mut u).unwrap();
    (rep, r, u)
}

/// Two decoupled contacts, W = I; the first is pushed in (r = (1, 0, 0)).
fn two_contacts(second_q: [f64; 3], mu: f64) -> FrictionProblem<'static> {
    let mut w = vec![0.0; 36];
    for i in 0..6 {
        w[i + 6 * i] = 1.0;
    }
    let mut q = vec![-1.0, 0.0, 0.0];
    q.extend(second_q);
    FrictionProblem::new(
        Delassus::Dense(DenseMatrix::new(6, 6, w).unwrap()),
        q,
        vec![0.5, mu],
    )
    .unwrap()
}

#[test]
fn single_contact_analytic_cases() {
    for internal in internals() {
        let c = config(internal, 1e-12, 200);
        // take-off, stick, slide (r_T = -mu r_N u_T / |u_T|)
        let cases = [
            ([0.5, 0.3, -0.2], 0.5, [0.0, 0.0, 0.0]),
            ([-1.0, 0.1, 0.0], 0.5, [1.0, -0.1, 0.0]),
            ([-1.0, 2.0, 0.0], 0.5, [1.0, -0.5, 0.0]),
        ];
        for (q2, mu, expected) in cases {
            let p = two_contacts(q2, mu);
            let (rep, r, u) = run(&p, &c);
            assert_eq!(rep.status, SolveStatus::Converged, "{internal:?} {q2:?}");
            assert_relative_eq!(r[0], 1.0, epsilon = 1e-10);
            for k in 0..3 {
                assert_relative_eq!(r[3 + k], expected[k], epsilon = 1e-9);
            }
            if expected[1] != 0.0 && u[4] != 0.0 {
                assert!(r[4] * u[4] < 0.0, "friction opposes sliding");
            }
        }
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

#[test]
fn shared_problems_in_every_storage() {
    for (name, storage) in [
        ("FC3D_Example1.dat", "dense"),
        ("NESpheres_10_1.dat", "dense"),
        ("Confeti-ex13-Fc3D-SBM.dat", "sparse-block"),
    ] {
        let p = shared(name);
        assert_eq!(p.w().storage_name(), storage);
        let csr = p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap();
        for internal in internals() {
            for problem in [&p, &csr] {
                let (rep, r, _) = run(problem, &config(internal, 1e-8, 1000));
                assert_eq!(
                    rep.status,
                    SolveStatus::Converged,
                    "{name} {} {internal:?}: {rep:?}",
                    problem.w().storage_name()
                );
                let mut u = vec![0.0; p.size()];
                let e = natural_map_error(&p, &r, &mut u);
                assert!(e <= 1e-8, "{name}: {e}");
            }
        }
    }
}

#[test]
fn shift_grows_tenfold_when_the_internal_solve_fails() {
    // Siconos' proximal strategy: the internal Newton fails on BoxesStack1 at the small first
    // shifts, and the shift grows by 10 until it succeeds. Siconos 4.4 (test_prox_1, case 1:
    // tol 1e-8, alpha 1e4): 7 proximal iterations, error 1.2e-9; without the growth fc3d ran
    // past 120 s. fc3d takes 7 with its own internal Newton and 6 with Siconos' (the default
    // since the NSN fidelity work): the internal solves end at slightly different points.
    let p = shared("BoxesStack1-i100000-32.hdf5.dat");
    let c = SolverConfig::new(ProxOptions::default())
        .with_tolerance(1e-8)
        .with_max_iter(1000);
    let (rep, r, _) = run(&p, &c);
    assert_eq!(rep.status, SolveStatus::Converged, "{rep:?}");
    assert!(rep.iterations <= 7, "{rep:?}");
    let mut u = vec![0.0; p.size()];
    assert!(natural_map_error(&p, &r, &mut u) <= 1e-8);
}

#[test]
fn negative_alpha_is_a_fixed_shift() {
    // Siconos' dparam[3] < 0: the shift stays at -alpha.
    let p = shared("NESpheres_10_1.dat");
    let c = SolverConfig::new(ProxOptions {
        alpha: -1.0,
        ..ProxOptions::default()
    })
    .with_tolerance(1e-8)
    .with_max_iter(1000);
    let (rep, r, _) = run(&p, &c);
    assert_eq!(rep.status, SolveStatus::Converged, "{rep:?}");
    let mut u = vec![0.0; p.size()];
    assert!(natural_map_error(&p, &r, &mut u) <= 1e-8);
}

#[test]
fn failures_are_honest_and_finite() {
    let p = shared("Confeti-ex13-Fc3D-SBM.dat");
    for internal in internals() {
        let (rep, r, u) = run(&p, &config(internal, 1e-14, 1));
        assert_eq!(rep.status, SolveStatus::MaxIterationsReached);
        assert_eq!(rep.iterations, 1);
        assert!(r.iter().chain(&u).all(|v| v.is_finite()));
        let mut u2 = vec![0.0; p.size()];
        assert_eq!(rep.error, natural_map_error(&p, &r, &mut u2));
    }
}

#[test]
fn bad_options_are_rejected() {
    let p = two_contacts([-1.0, 0.0, 0.0], 0.5);
    let mut r = vec![0.0; 6];
    let mut u = vec![0.0; 6];
    for bad in [
        ProxOptions {
            sigma: 0.0,
            ..ProxOptions::default()
        },
        ProxOptions {
            nu: f64::NAN,
            ..ProxOptions::default()
        },
        ProxOptions {
            internal: ProxInternal::NsnAc(NsnOptions::new(NsnFormulation::NaturalMap)),
            ..ProxOptions::default()
        },
        ProxOptions {
            alpha: 0.0,
            ..ProxOptions::default()
        },
        ProxOptions {
            alpha: f64::NAN,
            ..ProxOptions::default()
        },
    ] {
        assert!(matches!(
            solve(&p, &SolverConfig::new(bad), &mut r, &mut u),
            Err(e) if e.is_invalid_option()
        ));
    }
}
