//! AUTO on large strongly coupled problems (generated piles from 5000 contacts): Gauss-Seidel
//! first, then extragradient to the limits (from 30000 contacts, the Tresca fixed point to the
//! limits);
//! no stage that factorizes a matrix of W's size; the
//! budget holds and the error reported is the one measured on the returned reactions.

use std::time::{Duration, Instant};

use fc3d_core::scenes::{sphere_piles, PileSpec};
use fc3d_core::solvers::auto::{choose, HUGE_PROBLEM, LARGE_PROBLEM, TO_THE_LIMITS};
use fc3d_core::{natural_map_error, solve, AutoOptions, ProblemFeatures, SolverConfig, StageKind};

#[test]
fn large_piles_get_sweeps_then_extragradient_to_the_limits() {
    let pile = |contacts| {
        sphere_piles(&PileSpec {
            contacts,
            piles: 2,
            seed: 3,
        })
        .expect("scene")
    };
    let large = ProblemFeatures::of(&pile(LARGE_PROBLEM));
    assert!(large.strongly_coupled());
    for (tol, budget) in [
        (1e-4, None),
        (1e-8, None),
        (0.0, Some(Duration::from_secs(1))),
    ] {
        let (_, plan) = choose(&large, tol, budget);
        let kinds: Vec<StageKind> = plan.iter().map(|s| s.kind).collect();
        assert_eq!(kinds, [StageKind::Nsgs, StageKind::ExtraGradient]);
        assert_eq!(plan[1].allowance, TO_THE_LIMITS);
    }
    // From HUGE_PROBLEM on, the Tresca fixed point only (features of a pile that size; not
    // solved here).
    let huge = ProblemFeatures {
        n_contacts: HUGE_PROBLEM,
        ..large
    };
    let (_, plan) = choose(&huge, 1e-4, None);
    assert_eq!(plan.len(), 1);
    assert_eq!(plan[0].kind, StageKind::Tresca);
    assert_eq!(plan[0].allowance, TO_THE_LIMITS);
    // Below the threshold the rows of the shared problems still apply.
    let small = ProblemFeatures::of(&pile(1000));
    let (_, plan) = choose(&small, 1e-4, None);
    assert_ne!(plan[0].kind, StageKind::Nsgs);
}

#[test]
fn a_large_pile_under_a_budget_runs_to_it_and_reports_the_measured_error() {
    let p = sphere_piles(&PileSpec {
        contacts: 6000,
        piles: 2,
        seed: 3,
    })
    .expect("scene");
    let mut config = SolverConfig::new(AutoOptions::default());
    config.tolerance = 1e-4;
    config.time_budget = Some(Duration::from_millis(400));
    let n = 3 * p.n_contacts();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let start = Instant::now();
    let report = solve(&p, &config, &mut r, &mut u).expect("solve");
    let spent = start.elapsed();
    let log = report.stages.expect("AUTO reports its stages");
    let last = log.stages().last().expect("a stage").kind;
    // The run is not ended by a stall: it reaches the extragradient stage and the budget.
    assert_eq!(last, StageKind::ExtraGradient, "{log:?}");
    assert!(spent >= Duration::from_millis(400), "{spent:?}");
    assert!(spent < Duration::from_secs(3), "{spent:?}");
    let mut check = vec![0.0; n];
    assert_eq!(report.error, natural_map_error(&p, &r, &mut check));
    assert!(report.error < 5e-2, "{}", report.error);
}
