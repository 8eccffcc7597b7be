//! Siconos' `GFC3D IPM` (615) on generated scenes (sphere and box piles in the global form):
//! every run returns a consistent triple whose reported error is the independent recomputation
//! of Siconos' global error; the default solves the convex relaxation to the tolerance and says
//! whether that is Coulomb's solution; the De Saxcé update solves Coulomb's law where the fixed
//! point inside the iteration converges (box piles) and says so where it does not (sphere
//! piles); limits hold; contacts without friction are well defined.

mod common;

use std::time::{Duration, Instant};

use common::global::{check_triple, independent_error_of, scene, solve_checked};
use fc3d_core::global::{
    solve_global, solve_global_with_observer, GlobalConfig, GlobalMethod, GlobalProblem,
    GlobalReport, IpmOptions,
};
use fc3d_core::scenes::PileShape;
use fc3d_core::SolveStatus;

/// The same problem with the friction coefficients `mu(c, old)`.
fn with_mu(p: &GlobalProblem, mu: impl Fn(usize, f64) -> f64) -> GlobalProblem<'static> {
    let mu: Vec<f64> = p.mu().iter().enumerate().map(|(c, &m)| mu(c, m)).collect();
    GlobalProblem::new(
        p.m().clone(),
        p.h().clone(),
        p.q().to_vec(),
        p.b().to_vec(),
        mu,
    )
    .unwrap()
}

fn ipm(options: IpmOptions, tolerance: f64) -> GlobalConfig {
    GlobalConfig {
        tolerance,
        ..GlobalConfig::new(GlobalMethod::Ipm(options))
    }
}

/// Solves, checks the triple against the independent recomputation, and returns the report
/// and the recomputed convex error of the result.
fn run(p: &GlobalProblem, config: &GlobalConfig) -> (GlobalReport, f64) {
    let (report, r, u, v) = solve_checked(p, config);
    assert!(r.iter().chain(&u).chain(&v).all(|x| x.is_finite()));
    (report, independent_error_of(p, &r, &v, false))
}

#[test]
fn siconos_defaults_and_checked_settings() {
    let config = GlobalConfig::new(GlobalMethod::Ipm(IpmOptions::default()));
    assert_eq!((config.tolerance, config.max_iter), (1e-8, 200));
    assert_eq!(config.method.siconos_id(), 615);
    let o = IpmOptions::default();
    assert!(o.nesterov_todd && !o.update_s);
    assert_eq!(
        (
            o.centering_threshold,
            o.centering_exponent_factor,
            o.final_centering_exponent,
            o.step_safety,
            o.step_safety_slope
        ),
        (1e-5, 3.0, 1.0, 0.8, 0.09)
    );
    for bad in [
        IpmOptions {
            step_safety: 1.0,
            ..o
        },
        IpmOptions {
            step_safety_slope: 0.2,
            ..o
        },
        IpmOptions {
            centering_exponent_factor: 0.0,
            ..o
        },
        IpmOptions {
            centering_threshold: f64::NAN,
            ..o
        },
    ] {
        assert!(GlobalConfig::new(GlobalMethod::Ipm(bad))
            .validate()
            .is_err());
    }
}

/// The default (Siconos' UPDATE_S = NO) solves the convex relaxation to 1e-8 on piles of 10 to
/// 300 contacts in 15 to 30 iterations; sliding contacts make its solution not Coulomb's, which
/// the status says.
#[test]
fn the_default_solves_the_convex_relaxation_and_says_what_it_is() {
    for (shape, contacts) in [
        (PileShape::Spheres, 10),
        (PileShape::Spheres, 100),
        (PileShape::Spheres, 300),
        (PileShape::Boxes, 100),
        (PileShape::Boxes, 300),
    ] {
        let p = scene(contacts, shape);
        for nesterov_todd in [true, false] {
            let options = IpmOptions {
                nesterov_todd,
                ..Default::default()
            };
            let (report, convex) = run(&p, &ipm(options, 1e-8));
            eprintln!("{shape:?} {contacts} NT {nesterov_todd}: {report:?}, convex {convex:e}");
            assert!(
                convex <= 1e-8,
                "{shape:?} {contacts}: convex error {convex:e}"
            );
            assert!(report.iterations <= 40, "{report:?}");
            let expected = if report.error <= 1e-8 {
                SolveStatus::Converged
            } else {
                SolveStatus::RelaxationNotCoulomb
            };
            assert_eq!(report.status, expected);
        }
    }
}

/// Where every contact sticks or separates, the relaxation's solution is Coulomb's: with
/// `mu = 5` the pile's contacts stick and the default reports convergence on Coulomb's error.
/// Without friction (`mu = 0` everywhere, where Siconos' change of variables divides by zero)
/// the relaxation is the problem.
#[test]
fn the_relaxation_is_coulombs_solution_when_nothing_slides() {
    let p = scene(100, PileShape::Spheres);
    for mu in [5.0, 0.0] {
        let q = with_mu(&p, |_, _| mu);
        let (report, convex) = run(&q, &ipm(IpmOptions::default(), 1e-8));
        eprintln!("mu {mu}: {report:?}, convex {convex:e}");
        assert_eq!(report.status, SolveStatus::Converged, "mu {mu}: {report:?}");
        assert!(report.error <= 1e-8 && convex <= 1e-8);
    }
}

/// Frictionless contacts among frictional ones: the frictionless pairs live in a
/// one-dimensional cone, no NaN appears, and both laws are solved.
#[test]
fn contacts_without_friction_are_well_defined() {
    let p = with_mu(&scene(100, PileShape::Boxes), |c, mu| {
        if c % 3 == 0 {
            0.0
        } else {
            mu
        }
    });
    for update_s in [false, true] {
        let options = IpmOptions {
            update_s,
            ..Default::default()
        };
        let (report, convex) = run(&p, &ipm(options, 1e-8));
        eprintln!("update_s {update_s}: {report:?}, convex {convex:e}");
        if update_s {
            assert_eq!(report.status, SolveStatus::Converged, "{report:?}");
        } else {
            assert!(convex <= 1e-8, "{convex:e}");
        }
    }
}

/// With the De Saxcé update (Siconos' UPDATE_S = YES) the iteration seeks Coulomb's solution:
/// on box piles it reaches 1e-8 (100 contacts: 25 iterations, 300: 28); on sphere piles the
/// fixed point inside the iteration stalls once the iterates near the cones' boundaries (error
/// about 2e-4 after the 200 iterations, as Siconos' own run, which aborts or stalls there), and
/// the solve reports it.
#[test]
fn the_de_saxce_update_solves_coulomb_where_its_fixed_point_converges() {
    let coulomb = IpmOptions {
        update_s: true,
        ..Default::default()
    };
    for contacts in [100, 300] {
        let p = scene(contacts, PileShape::Boxes);
        let (report, _) = run(&p, &ipm(coulomb, 1e-8));
        eprintln!("boxes {contacts}: {report:?}");
        assert_eq!(report.status, SolveStatus::Converged, "{report:?}");
        assert!(report.iterations <= 40);
    }
    let p = scene(100, PileShape::Spheres);
    let (report, _) = run(&p, &ipm(coulomb, 1e-8));
    eprintln!("spheres 100: {report:?}");
    assert_eq!(report.status, SolveStatus::MaxIterationsReached);
    assert!(report.error < 1e-3, "{report:?}");
}

/// The observer sees every iteration with the error the run tests (the convex one by default),
/// the iteration limit holds, and so does the time budget.
#[test]
fn observer_iteration_limit_and_time_budget() {
    let p = scene(300, PileShape::Spheres);
    let (mut r, mut u, mut v) = (
        vec![0.0; p.size()],
        vec![0.0; p.size()],
        vec![0.0; p.ndof()],
    );
    let config = ipm(IpmOptions::default(), 1e-8);
    let mut errors = Vec::new();
    let report = solve_global_with_observer(&p, &config, &mut r, &mut u, &mut v, &mut |e| {
        errors.push((e.iteration, e.error))
    })
    .unwrap();
    assert_eq!(errors.len(), report.iterations);
    assert!(errors.iter().enumerate().all(|(k, e)| e.0 == k + 1));
    let last = errors.last().unwrap().1;
    assert!(last <= 1e-8);
    assert!((last - independent_error_of(&p, &r, &v, false)).abs() <= 1e-12);

    let short = GlobalConfig {
        max_iter: 3,
        ..config
    };
    let report = solve_global(&p, &short, &mut r, &mut u, &mut v).unwrap();
    check_triple(&p, &short, &report, &r, &u, &v);
    assert_eq!(
        (report.status, report.iterations),
        (SolveStatus::MaxIterationsReached, 3)
    );

    let budget = Duration::from_millis(20);
    let timed = GlobalConfig {
        time_budget: Some(budget),
        ..ipm(
            IpmOptions {
                update_s: true,
                ..Default::default()
            },
            1e-8,
        )
    };
    let big = scene(1000, PileShape::Spheres);
    let (mut r, mut u, mut v) = (
        vec![0.0; big.size()],
        vec![0.0; big.size()],
        vec![0.0; big.ndof()],
    );
    let started = Instant::now();
    let report = solve_global(&big, &timed, &mut r, &mut u, &mut v).unwrap();
    let elapsed = started.elapsed();
    check_triple(&big, &timed, &report, &r, &u, &v);
    eprintln!("budget {budget:?}: {report:?} in {elapsed:?}");
    assert_eq!(report.status, SolveStatus::TimeBudgetExhausted);
    assert!(report.iterations < 200);
}
