//! The VI / fixed-point family (DSFP 505, VI_FPP 506, VI_EG 507, FPP 511, EG 512): analytic
//! one-contact cases, shared Siconos problems in dense, sparse-block and CSR storage, option
//! checks and the behaviour on divergence.
//!
//! Reported errors are checked against an independent recomputation (entry-wise `u = W r + q`,
//! cone projection written here from its dot-product form).

mod common;
use common::honesty::{check_report, norm};

use std::path::PathBuf;

use approx::assert_relative_eq;
use fc3d_core::{
    solve, solve_with_observer, Delassus, DenseMatrix, ExtraGradientCorrection, FrictionProblem,
    SelfAdaptiveStep, SolveReport, SolverConfig, StepRatio, StepSize, TrialStart, ViOptions,
    ViSolver,
};

// ---------------------------------------------------------------------------------------------
// Helpers.

fn config(o: ViOptions, tol: f64, max_iter: usize) -> SolverConfig {
    SolverConfig::new(o)
        .with_tolerance(tol)
        .with_max_iter(max_iter)
}

fn options(solver: ViSolver, tol: f64, max_iter: usize) -> SolverConfig {
    config(ViOptions::new(solver), tol, max_iter)
}

/// Every member of the family, plus the UPTS variants of the self-adaptive ones.
fn all_variants(tol: f64, max_iter: usize) -> Vec<(String, SolverConfig)> {
    let mut v = Vec::new();
    for s in ViSolver::ALL {
        let o = ViOptions::new(s);
        v.push((s.short_name().to_string(), config(o, tol, max_iter)));
        match s {
            ViSolver::ExtraGradient | ViSolver::ViExtraGradient => {
                let korpelevich = ViOptions {
                    correction: ExtraGradientCorrection::FromIterate,
                    ..o
                };
                v.push((
                    format!("{}-96", s.short_name()),
                    config(korpelevich, tol, max_iter),
                ));
            }
            _ => {}
        }
        if let StepSize::SelfAdaptive(step) = o.step {
            let upts = ViOptions {
                step: StepSize::SelfAdaptive(SelfAdaptiveStep {
                    ratio: StepRatio::SolodovTseng,
                    ..step
                }),
                ..o
            };
            v.push((
                format!("{}-UPTS", s.short_name()),
                config(upts, tol, max_iter),
            ));
        }
    }
    v
}

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

// ---------------------------------------------------------------------------------------------
// Analytic cases.

/// Three decoupled contacts with `W_cc` = diag(1.25, 1, 1) blocks: take-off (q_N > 0: r = 0),
/// stick (|q_T| small: r = (-q_N/1.25, -q_T)), slide (r_N = -q_N/1.25, r_T = -mu r_N e with e the
/// direction of q_T, as u_T = q_T + r_T stays along q_T). (With W_NN = 2 the fixed rho = 1 of
/// DSFP/FPP would sit exactly on the stability limit `rho < 2 / W_NN` and oscillate.)
fn three_contacts() -> FrictionProblem<'static> {
    let n = 9;
    let mut w = vec![0.0; n * n];
    for c in 0..3 {
        let k = 3 * c;
        w[k + k * n] = 1.25;
        w[(k + 1) + (k + 1) * n] = 1.0;
        w[(k + 2) + (k + 2) * n] = 1.0;
    }
    let q = vec![1.0, 0.3, -0.2, -2.0, 0.1, 0.05, -2.0, 3.0, 4.0];
    FrictionProblem::new(
        Delassus::Dense(DenseMatrix::new(n, n, w).unwrap()),
        q,
        vec![0.5, 0.5, 0.5],
    )
    .unwrap()
}

#[test]
fn take_off_stick_and_slide() {
    let p = three_contacts();
    // Slide: r_N = 1.6, |r_T| = 0.8 opposite to q_T = (3, 4) (unit (0.6, 0.8)).
    let expected = [0.0, 0.0, 0.0, 1.6, -0.1, -0.05, 1.6, -0.48, -0.64];
    for (name, o) in all_variants(1e-12, 20000) {
        let (rep, r, u, calls) = run(&p, &o);
        check_report(&name, &p, 1e-12, &rep, &r, &u);
        if name == "HP" {
            // Siconos' HP searches along the velocity without the De Saxcé term: the sliding
            // contact stalls it (see hyperplane_projection_*).
            assert!(!rep.converged(), "{name}: {rep:?}");
            continue;
        }
        assert!(rep.converged(), "{name}: {rep:?}");
        assert_eq!(
            calls, rep.iterations,
            "{name}: one observer call per iteration"
        );
        for (a, b) in r.iter().zip(&expected) {
            assert_relative_eq!(*a, *b, epsilon = 1e-9);
        }
        // Sliding velocity: u_T = q_T + r_T = (2.52, 3.36), u_N = 0.
        assert_relative_eq!(u[6], 0.0, epsilon = 1e-9);
        assert_relative_eq!(u[7], 2.52, epsilon = 1e-9);
        assert_relative_eq!(u[8], 3.36, epsilon = 1e-9);
    }
}

#[test]
fn fixed_point_with_rho_1_on_identity_converges_in_two_steps() {
    // W = I, q = (-1, 0.2, 0), stick: from r_0 = 0, F(r_0) = q + (mu |q_T|, 0, 0) = (-0.9, 0.2, 0)
    // gives r_1 = (0.9, -0.2, 0); then u_1 = (-0.1, 0, 0) has no tangential part, F(r_1) = u_1 and
    // r_2 = r_1 - u_1 = (1, -0.2, 0), the exact solution.
    let w = DenseMatrix::new(3, 3, vec![1., 0., 0., 0., 1., 0., 0., 0., 1.]).unwrap();
    let p = FrictionProblem::new(Delassus::Dense(w), vec![-1.0, 0.2, 0.0], vec![0.5]).unwrap();
    let (rep, r, _, _) = run(&p, &options(ViSolver::DeSaxceFixedPoint, 1e-14, 10));
    assert!(rep.converged());
    assert_eq!(rep.iterations, 2);
    assert_relative_eq!(r[0], 1.0, epsilon = 1e-15);
    assert_eq!(&r[1..], &[-0.2, 0.0]);
}

// ---------------------------------------------------------------------------------------------
// Shared problems in every storage.

fn storages(p: &FrictionProblem<'static>) -> Vec<(&'static str, FrictionProblem<'static>)> {
    let mut v = vec![(p.w().storage_name(), p.clone())];
    if !matches!(p.w(), Delassus::SparseBlock(_)) {
        v.push((
            "sparse-block",
            p.with_w(Delassus::SparseBlock(p.w().to_block_sparse().unwrap()))
                .unwrap(),
        ));
    }
    v.push(("csr", p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap()));
    v
}

/// Solves `name` with every variant at 1e-8 in every storage; `expect_converged` lists which
/// variants must converge (the others must fail honestly). Storages agree on the result.
fn shared_problem(name: &str, max_iter: usize, converging: &[&str]) {
    let base = siconos(name);
    let tol = 1e-8;
    for (label, o) in all_variants(tol, max_iter) {
        let mut first: Option<Vec<f64>> = None;
        for (storage, p) in storages(&base) {
            let what = format!("{name} {label} {storage}");
            let (rep, r, u, _) = run(&p, &o);
            check_report(&what, &p, tol, &rep, &r, &u);
            if std::env::var_os("FC3D_VI_PRINT").is_some() {
                eprintln!("RESULT {what}: {rep:?}");
                continue;
            }
            assert_eq!(
                rep.converged(),
                converging.contains(&label.as_str()),
                "{what}: {rep:?}"
            );
            match &first {
                None => first = Some(r),
                Some(r0) if rep.converged() => {
                    let d: f64 = r
                        .iter()
                        .zip(r0)
                        .map(|(a, b)| (a - b).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    assert!(
                        d <= 1e-6 * norm(r0).max(1e-300),
                        "{what}: r differs by {d:e}"
                    );
                }
                Some(_) => {}
            }
        }
    }
}

#[test]
fn nespheres_dense() {
    // Siconos 4.4 at 1e-8: DSFP 214 iterations, VI_FPP 112, VI_EG 52.
    shared_problem(
        "NESpheres_10_1.dat",
        20000,
        &[
            "DSFP",
            "VI-FPP",
            "VI-FPP-UPTS",
            "VI-EG",
            "VI-EG-96",
            "VI-EG-UPTS",
            "FPP",
            "FPP-UPTS",
            "EG",
            "EG-96",
            "EG-UPTS",
        ],
    );
}

#[test]
fn fc3d_example1_sparse_block() {
    shared_problem(
        "FC3D_Example1_SBM.dat",
        20000,
        &[
            "DSFP",
            "VI-FPP",
            "VI-FPP-UPTS",
            "VI-EG",
            "VI-EG-96",
            "VI-EG-UPTS",
            "HP",
            "FPP",
            "FPP-UPTS",
            "EG",
            "EG-96",
            "EG-UPTS",
        ],
    );
}

#[test]
fn confeti_ex03_sparse_block() {
    // Fixed rho = 1 stalls here (Siconos' DSFP too: 1.8e-6 after 10^5 iterations), and so does
    // Siconos' HP.
    shared_problem(
        "Confeti-ex03-Fc3D-SBM.dat",
        3000,
        &[
            "VI-FPP",
            "VI-FPP-UPTS",
            "VI-EG",
            "VI-EG-96",
            "VI-EG-UPTS",
            "FPP",
            "FPP-UPTS",
            "EG",
            "EG-96",
            "EG-UPTS",
        ],
    );
}

#[test]
fn siconos_iteration_counts_match_on_nespheres() {
    // The fixed point and the UPK rule are Siconos' to the iteration (reference CSV in
    // shared/data): DSFP 214 iterations, error 9.908e-9; VI_FPP 112, 2.293e-9.
    let p = siconos("NESpheres_10_1.dat");
    let (rep, ..) = run(&p, &options(ViSolver::DeSaxceFixedPoint, 1e-8, 20000));
    assert_eq!(rep.iterations, 214);
    assert_relative_eq!(rep.error, 9.908e-9, max_relative = 1e-3);
    let (rep, ..) = run(&p, &options(ViSolver::ViFixedPointProjection, 1e-8, 20000));
    assert_eq!(rep.iterations, 112);
    assert_relative_eq!(rep.error, 2.293e-9, max_relative = 1e-3);
}

#[test]
fn vi_solvers_hand_back_their_adapted_rho() {
    // Siconos' generic VI solvers (506/507) return the rho they ended with (the C layer writes
    // it to dparam[3]); restarted from the solution with that rho, one iteration confirms it.
    let p = siconos("NESpheres_10_1.dat");
    for s in ViSolver::ALL {
        let (rep, r, _, _) = run(&p, &options(s, 1e-8, 20000));
        let lineage_vi = matches!(
            s,
            ViSolver::ViFixedPointProjection | ViSolver::ViExtraGradient
        );
        assert_eq!(rep.final_rho.is_some(), lineage_vi, "{}", s.short_name());
        if let Some(rho) = rep.final_rho {
            assert!(rho > 0.0 && rho.is_finite(), "{}: {rho}", s.short_name());
            let mut o = ViOptions::new(s);
            if let StepSize::SelfAdaptive(step) = &mut o.step {
                step.initial_rho = rho;
            }
            let mut r2 = r.clone();
            let mut u2 = vec![0.0; p.size()];
            let rep2 = solve(&p, &config(o, 1e-8, 20000), &mut r2, &mut u2).unwrap();
            assert!(rep2.converged(), "{}: {rep2:?}", s.short_name());
        }
    }
}

/// Each id against the installed Siconos 4.4 at 1e-8 (scripts/compare-siconos.sh, Siconos'
/// defaults): (problem, options, Siconos' iterations).
#[test]
fn siconos_iteration_counts_per_id() {
    let with_trials_from_previous = |s: ViSolver| {
        let mut o = ViOptions::new(s);
        if let StepSize::SelfAdaptive(step) = &mut o.step {
            step.trial_start = TrialStart::PreviousTrial;
        }
        o
    };
    let fixed_rho_eg = ViOptions {
        step: StepSize::Fixed(1.0),
        correction: ExtraGradientCorrection::FromIterate,
        ..ViOptions::new(ViSolver::ExtraGradient)
    };
    let cases = [
        (
            "NESpheres_10_1.dat",
            ViOptions::new(ViSolver::ViExtraGradient),
            52,
        ),
        (
            "NESpheres_10_1.dat",
            ViOptions::new(ViSolver::FixedPointProjection),
            99,
        ),
        (
            "NESpheres_10_1.dat",
            ViOptions::new(ViSolver::ExtraGradient),
            50,
        ),
        ("NESpheres_10_1.dat", fixed_rho_eg, 287),
        (
            "NESpheres_10_1.dat",
            with_trials_from_previous(ViSolver::ViFixedPointProjection),
            110,
        ),
        (
            "NESpheres_10_1.dat",
            with_trials_from_previous(ViSolver::ViExtraGradient),
            60,
        ),
        (
            "Confeti-ex03-Fc3D-SBM.dat",
            ViOptions::new(ViSolver::ViFixedPointProjection),
            523,
        ),
        (
            "Confeti-ex03-Fc3D-SBM.dat",
            ViOptions::new(ViSolver::ViExtraGradient),
            261,
        ),
        (
            "Confeti-ex03-Fc3D-SBM.dat",
            ViOptions::new(ViSolver::FixedPointProjection),
            181,
        ),
        (
            "Confeti-ex03-Fc3D-SBM.dat",
            ViOptions::new(ViSolver::ExtraGradient),
            100,
        ),
        (
            "Rover1040.dat",
            ViOptions::new(ViSolver::ViFixedPointProjection),
            414,
        ),
        (
            "Rover1040.dat",
            ViOptions::new(ViSolver::ViExtraGradient),
            188,
        ),
        (
            "Rover1040.dat",
            ViOptions::new(ViSolver::FixedPointProjection),
            188,
        ),
        ("Rover1040.dat", ViOptions::new(ViSolver::ExtraGradient), 97),
        (
            "FC3D_Example1_SBM.dat",
            ViOptions::new(ViSolver::HyperplaneProjection),
            1656,
        ),
    ];
    for (name, o, iterations) in cases {
        let p = siconos(name);
        let (rep, r, u, _) = run(&p, &config(o, 1e-8, 20000));
        let what = format!("{name} {}", o.solver.short_name());
        check_report(&what, &p, 1e-8, &rep, &r, &u);
        assert!(rep.converged(), "{what}: {rep:?}");
        assert_eq!(rep.iterations, iterations, "{what}");
    }
}

// ---------------------------------------------------------------------------------------------
// Failures, options.

#[test]
fn divergence_stops_with_finite_r_and_honest_error() {
    // rho = 1 is far above 2 / lambda_max(W) on OneObject: DSFP's fixed point diverges; FPP's
    // search does not find a step that passes in its 10 trials and fails too.
    let p = siconos("OneObject-i1028-138.hdf5.dat");
    for s in [ViSolver::DeSaxceFixedPoint, ViSolver::FixedPointProjection] {
        let o = options(s, 1e-8, 20000);
        let (rep, r, u, _) = run(&p, &o);
        assert!(!rep.converged());
        check_report(s.short_name(), &p, 1e-8, &rep, &r, &u);
        assert!(rep.error.is_finite());
    }
}

#[test]
fn max_iter_is_respected_and_reported() {
    let p = siconos("Confeti-ex03-Fc3D-SBM.dat");
    for (label, o) in all_variants(1e-14, 7) {
        let (rep, r, u, calls) = run(&p, &o);
        assert_eq!(rep.iterations, 7, "{label}");
        assert_eq!(calls, 7, "{label}");
        check_report(&label, &p, 1e-14, &rep, &r, &u);
    }
}

#[test]
fn starts_from_the_given_reaction() {
    // From the solution, the first iteration confirms it.
    let p = three_contacts();
    let mut r = vec![0.0, 0.0, 0.0, 1.6, -0.1, -0.05, 1.6, -0.48, -0.64];
    let mut u = vec![0.0; 9];
    for s in ViSolver::ALL {
        let rep = solve(&p, &options(s, 1e-12, 100), &mut r, &mut u).unwrap();
        assert!(rep.converged());
        assert_eq!(rep.iterations, 1, "{}", s.short_name());
    }
}

#[test]
fn bad_options_are_rejected_and_leave_r_untouched() {
    let p = three_contacts();
    let adaptive = SelfAdaptiveStep::default();
    let bad = [
        SolverConfig::new(ViOptions {
            step: StepSize::Fixed(0.0),
            ..ViOptions::new(ViSolver::DeSaxceFixedPoint)
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::Fixed(f64::NAN),
            ..ViOptions::new(ViSolver::FixedPointProjection)
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::SelfAdaptive(adaptive),
            ..ViOptions::new(ViSolver::DeSaxceFixedPoint)
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::SelfAdaptive(SelfAdaptiveStep {
                nu: 1.0,
                ..adaptive
            }),
            ..ViOptions::default()
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::SelfAdaptive(SelfAdaptiveStep { l: 1.5, ..adaptive }),
            ..ViOptions::default()
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::SelfAdaptive(SelfAdaptiveStep {
                l_min: 0.95,
                ..adaptive
            }),
            ..ViOptions::default()
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::SelfAdaptive(SelfAdaptiveStep {
                initial_rho: -1.0,
                ..adaptive
            }),
            ..ViOptions::default()
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::SelfAdaptive(SelfAdaptiveStep {
                increase: 0.5,
                ..adaptive
            }),
            ..ViOptions::default()
        }),
        SolverConfig::new(ViOptions {
            step: StepSize::SelfAdaptive(SelfAdaptiveStep {
                max_trials: 0,
                ..adaptive
            }),
            ..ViOptions::default()
        }),
        SolverConfig::new(ViOptions::default()).with_tolerance(-1.0),
    ];
    for c in bad {
        let mut r = vec![0.25; 9];
        let mut u = vec![0.5; 9];
        let e = solve(&p, &c, &mut r, &mut u);
        assert!(
            matches!(&e, Err(e) if e.is_invalid_option()),
            "{c:?}: {e:?}"
        );
        assert_eq!(r, vec![0.25; 9]);
        assert_eq!(u, vec![0.5; 9]);
    }
}

#[test]
fn defaults_are_siconos() {
    for s in ViSolver::ALL {
        let o = ViOptions::new(s);
        let c = SolverConfig::new(o);
        let max_iter = if s == ViSolver::HyperplaneProjection {
            2_000_000
        } else {
            20000
        };
        assert_eq!(c.max_iter, max_iter);
        assert_eq!(c.tolerance, 1e-3);
        assert_eq!(c.siconos_id(), s.siconos_id());
        assert_eq!(ViSolver::from_siconos_id(s.siconos_id()), Some(s));
        assert_eq!(o.correction, ExtraGradientCorrection::FromPrediction);
    }
    let a = SelfAdaptiveStep::default();
    assert_eq!(
        (a.initial_rho, a.nu, a.increase, a.l, a.l_min, a.max_trials),
        (1.0, 2.0 / 3.0, 1.5, 0.9, 0.3, 10)
    );
    assert_eq!(a.trial_start, TrialStart::Iterate);
    // FPP 511 and EG 512 hard-code their own constants and update the trial in place.
    let f = SelfAdaptiveStep::friction_defaults();
    assert_eq!(
        (f.initial_rho, f.nu, f.increase, f.l, f.l_min, f.max_trials),
        (1.0, 0.6, 1.0 / 0.7, 0.9, 0.3, 10)
    );
    assert_eq!(f.trial_start, TrialStart::PreviousTrial);
    for s in [ViSolver::DeSaxceFixedPoint, ViSolver::HyperplaneProjection] {
        assert_eq!(ViOptions::new(s).step, StepSize::Fixed(1.0));
    }
    for s in [ViSolver::FixedPointProjection, ViSolver::ExtraGradient] {
        assert_eq!(ViOptions::new(s).step, StepSize::SelfAdaptive(f));
    }
    for s in [ViSolver::ViFixedPointProjection, ViSolver::ViExtraGradient] {
        assert_eq!(ViOptions::new(s).step, StepSize::SelfAdaptive(a));
    }
    let hp = ViOptions::new(ViSolver::HyperplaneProjection).hyperplane;
    assert_eq!((hp.sigma, hp.max_halvings), (0.99, 50));
    assert_eq!(ViSolver::from_siconos_id(500), None);
}

#[test]
fn time_budget_stops_the_run() {
    let p = siconos("OneObject-i1028-138.hdf5.dat");
    for s in [ViSolver::ViFixedPointProjection, ViSolver::ExtraGradient] {
        let c = SolverConfig::new(ViOptions::new(s))
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
        check_report(s.short_name(), &p, 0.0, &rep, &r, &u);
    }
}
