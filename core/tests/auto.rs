//! AUTO (`Method::Auto`, fc3d id 590): stage switching on a stall, the limits across stages, the
//! anytime mode and the honesty of the reported error.

use std::time::{Duration, Instant};

use fc3d_core::io::dat::read_dat_file;
use fc3d_core::local::LocalSolverKind;
use fc3d_core::solvers::auto::{
    choose, stage, sweep_local_solver, PlannedStage, ProblemFeatures, PROBE, RULES,
};
use fc3d_core::{
    natural_map_error, solve, AutoOptions, Delassus, DenseMatrix, FrictionProblem, SolveStatus,
    SolverConfig, StageEnd, StageKind,
};

/// Two contacts whose normals are almost parallel (normal coupling `c`): Gauss-Seidel contracts
/// the error by about `c^2` per sweep (0.998 for c = 0.999), Newton solves it in a few steps.
fn coupled_pair(c: f64, mu: f64) -> FrictionProblem<'static> {
    let n = 6;
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        w[i + i * n] = 1.0;
    }
    w[3 * n] = c; // (0, 3)
    w[3] = c; // (3, 0)
    let dense = DenseMatrix::new(n, n, w).unwrap();
    FrictionProblem::new(
        Delassus::Dense(dense),
        vec![-1.0, 0.1, 0.0, -1.0, -0.1, 0.0],
        vec![mu, mu],
    )
    .unwrap()
}

fn shared(name: &str) -> FrictionProblem<'static> {
    read_dat_file(std::path::Path::new(&format!(
        "{}/../../shared/data/siconos/{name}",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap()
}

fn true_error(p: &FrictionProblem<'_>, r: &[f64]) -> f64 {
    let mut u = vec![0.0; p.size()];
    natural_map_error(p, r, &mut u)
}

const SWEEPS_THEN_NEWTON: &[PlannedStage] =
    &[stage(StageKind::Nsgs, None), stage(StageKind::Newton, None)];

#[test]
fn a_stalled_stage_hands_over_and_the_next_one_converges() {
    let p = coupled_pair(0.999, 0.3);
    let config = SolverConfig::new(AutoOptions {
        plan: Some(SWEEPS_THEN_NEWTON),
    })
    .with_tolerance(1e-10)
    .with_max_iter(10_000);
    let (mut r, mut u) = (vec![0.0; 6], vec![0.0; 6]);
    let report = solve(&p, &config, &mut r, &mut u).unwrap();
    assert_eq!(report.status, SolveStatus::Converged, "{report:?}");
    let log = report.stages.expect("AUTO reports its stages");
    let stages: Vec<_> = log.stages().copied().collect();
    assert_eq!(stages.len(), 2, "{stages:?}");
    assert_eq!(stages[0].kind, StageKind::Nsgs);
    assert_eq!(stages[0].end, StageEnd::Stalled);
    // NSGS stalled after its first chunk of 10 sweeps: it contracts by ~0.98 per chunk.
    assert!(stages[0].iterations <= 20, "{stages:?}");
    assert!(stages[0].error > 1e-10);
    assert_eq!(stages[1].kind, StageKind::Newton);
    assert_eq!(stages[1].end, StageEnd::Converged);
    assert!(stages[1].error <= 1e-10);
    assert_eq!(
        report.iterations,
        stages.iter().map(|s| s.iterations).sum::<usize>()
    );
    assert_eq!(log.packed_codes(), 12);
    // Newton went on from the sweeps' iterate: the exact solution r_N = 1 / 1.999 each.
    assert!((r[0] - 1.0 / 1.999).abs() < 1e-8 && (r[3] - 1.0 / 1.999).abs() < 1e-8);
    assert_eq!(report.error, true_error(&p, &r));
}

#[test]
fn the_iteration_limit_holds_across_stages() {
    let p = coupled_pair(0.999, 0.3);
    for max_iter in [1, 7, 10, 13, 25] {
        let config = SolverConfig::new(AutoOptions {
            plan: Some(SWEEPS_THEN_NEWTON),
        })
        .with_tolerance(0.0)
        .with_max_iter(max_iter);
        let (mut r, mut u) = (vec![0.0; 6], vec![0.0; 6]);
        let report = solve(&p, &config, &mut r, &mut u).unwrap();
        let log = report.stages.unwrap();
        let sum: usize = log.stages().map(|s| s.iterations).sum();
        assert!(report.iterations <= max_iter, "{max_iter}: {report:?}");
        assert_eq!(report.iterations, sum, "{max_iter}: {log:?}");
        assert_eq!(report.error, true_error(&p, &r));
    }
}

#[test]
fn the_time_budget_holds_across_stages_and_the_best_iterate_is_returned() {
    // RockPile_tob1 (463 contacts): no solver reaches 1e-8 in seconds, so with tolerance 0 the
    // budget is what stops AUTO, whatever stage it is in.
    let p = shared("RockPile_tob1.dat");
    let n = p.size();
    for budget_ms in [5u64, 50] {
        let budget = Duration::from_millis(budget_ms);
        let config = SolverConfig::new(AutoOptions::default())
            .with_tolerance(0.0)
            .with_max_iter(usize::MAX)
            .with_time_budget(Some(budget));
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let start = Instant::now();
        let report = solve(&p, &config, &mut r, &mut u).unwrap();
        let elapsed = start.elapsed();
        assert_eq!(
            report.status,
            SolveStatus::TimeBudgetExhausted,
            "{report:?}"
        );
        // Generous: one sweep or Newton step after the deadline, on a shared machine.
        assert!(elapsed < budget + Duration::from_secs(2), "{elapsed:?}");
        assert_eq!(report.error, true_error(&p, &r));
        // The returned iterate is the best the stages handed over.
        let log = report.stages.unwrap();
        let best = log.stages().map(|s| s.error).fold(f64::INFINITY, f64::min);
        assert!(report.error <= best, "{} > {best}", report.error);
        assert!(report.error < true_error(&p, &vec![0.0; n]));
    }
}

#[test]
fn default_auto_solves_shared_problems_and_reports_the_true_error() {
    for name in [
        "Rover1039.dat",
        "Confeti-ex13-Fc3D-SBM.dat",
        "OneObject-i1028-138.hdf5.dat",
        "Capsules-i101-404.dat",
    ] {
        let p = shared(name);
        let n = p.size();
        for tol in [1e-4, 1e-8] {
            let config = SolverConfig::new(AutoOptions::default())
                .with_tolerance(tol)
                .with_time_budget(Some(Duration::from_secs(20)));
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let report = solve(&p, &config, &mut r, &mut u).unwrap();
            assert_eq!(
                report.status,
                SolveStatus::Converged,
                "{name} {tol}: {report:?}"
            );
            assert!(report.error <= tol);
            assert_eq!(report.error, true_error(&p, &r), "{name}");
            let log = report.stages.unwrap();
            assert!(!log.is_empty());
            assert_eq!(
                log.stages().last().unwrap().end,
                StageEnd::Converged,
                "{name}: {log:?}"
            );
        }
    }
}

#[test]
fn the_rule_table_is_total_and_singular_contacts_start_with_prox() {
    assert!(RULES
        .iter()
        .all(|r| !r.plan.is_empty() && !r.why.is_empty()));
    // The last rule holds for anything.
    let p = coupled_pair(0.5, 0.3);
    let f = ProblemFeatures::of(&p);
    assert_eq!(f.n_contacts, 2);
    assert_eq!(f.singular_contacts, 0);
    assert!((f.diagonal_dominance - 2.0).abs() < 1e-12);
    let (rule, _) = choose(&f, 1e-12, None);
    assert!(rule < RULES.len());
    // A contact with W_NN = 0.
    let mut w = vec![0.0; 36];
    for i in 1..6 {
        w[i + 6 * i] = 1.0;
    }
    let singular = FrictionProblem::new(
        Delassus::Dense(DenseMatrix::new(6, 6, w).unwrap()),
        vec![-1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        vec![0.5, 0.5],
    )
    .unwrap();
    let f = ProblemFeatures::of(&singular);
    assert_eq!(f.singular_contacts, 1);
    let (_, plan) = choose(&f, 1e-6, None);
    assert_eq!(plan[0].kind, StageKind::Prox);
}

#[test]
fn the_budget_and_the_tolerance_select_the_rows_of_strongly_coupled_problems() {
    // OneObject-i1028-138: mu 0.3, normal-row dominance 0.14, 23 contacts.
    let f = ProblemFeatures::of(&shared("OneObject-i1028-138.hdf5.dat"));
    assert!(f.strongly_coupled());
    // The first stage after the TFP-APGD probe of rule 10 (tests/auto_rules.rs).
    let after_probe =
        |plan: &[PlannedStage]| plan.iter().find(|s| s.allowance != PROBE).unwrap().kind;
    let first = |tol: f64, budget: Option<Duration>| after_probe(choose(&f, tol, budget).1);
    assert_eq!(first(0.0, Some(Duration::from_millis(1))), StageKind::Nsgs);
    assert_eq!(first(0.0, Some(Duration::from_secs(1))), StageKind::Prox);
    assert_eq!(first(1e-8, None), StageKind::Prox);
    assert_eq!(first(1e-6, None), StageKind::Prox);
    assert_eq!(first(1e-4, None), StageKind::Admm);
    // BoxesStack1 (52 contacts, mu 0.7): ADMM first to 1e-6.
    let f = ProblemFeatures::of(&shared("BoxesStack1-i100000-32.hdf5.dat"));
    assert!(f.strongly_coupled() && f.mu_max >= 0.5);
    assert_eq!(after_probe(choose(&f, 1e-6, None).1), StageKind::Admm);
    // Capsules-i101-404: 225 contacts, EG first at loose tolerances.
    let f = ProblemFeatures::of(&shared("Capsules-i101-404.dat"));
    assert_eq!(choose(&f, 1e-4, None).1[0].kind, StageKind::ExtraGradient);
    // A weakly coupled problem: NSGS first whatever the tolerance.
    let f = ProblemFeatures::of(&shared("Confeti-ex13-Fc3D-SBM.dat"));
    assert!(!f.strongly_coupled());
    assert_eq!(choose(&f, 1e-8, None).1[0].kind, StageKind::Nsgs);
    // Budget rows: on the Capsules and BoxesStack (40-300 contacts) an anytime solve starts
    // with NSGS under 7 ms, with ADMM from 7 to 20 ms, with PROX above (after the TFP-APGD
    // probe); OneObject (23
    // contacts) and RockPile (463) keep NSGS up to 20 ms.
    let anytime = |name: &str, ms: u64| {
        let f = ProblemFeatures::of(&shared(name));
        after_probe(choose(&f, 0.0, Some(Duration::from_millis(ms))).1)
    };
    for name in ["Capsules-i101-404.dat", "BoxesStack1-i100000-32.hdf5.dat"] {
        assert_eq!(anytime(name, 1), StageKind::Nsgs, "{name}");
        assert_eq!(anytime(name, 10), StageKind::Admm, "{name}");
        assert_eq!(anytime(name, 100), StageKind::Prox, "{name}");
    }
    assert_eq!(anytime("OneObject-i1028-138.hdf5.dat", 10), StageKind::Nsgs);
    assert_eq!(anytime("RockPile_tob1.dat", 10), StageKind::Nsgs);
    // RockPile (463 contacts) sweeps to the limits under a short budget: no factorizing stage,
    // whose first step takes longer than the budget there.
    let f = ProblemFeatures::of(&shared("RockPile_tob1.dat"));
    let (rule, plan) = choose(&f, 0.0, Some(Duration::from_millis(10)));
    assert_eq!(plan.len(), 1);
    assert_eq!(plan[0].allowance, Some(usize::MAX));
    // The NSGS stages of strongly coupled problems sweep with QUARTIC (562), the others with
    // the Newton local solver 551.
    assert_eq!(sweep_local_solver(rule), LocalSolverKind::Quartic);
    let f = ProblemFeatures::of(&shared("Confeti-ex13-Fc3D-SBM.dat"));
    let (rule, _) = choose(&f, 0.0, Some(Duration::from_millis(10)));
    assert_eq!(
        sweep_local_solver(rule),
        LocalSolverKind::NewtonAlartCurnierGp
    );
}

#[test]
fn an_anytime_solve_stops_at_round_off() {
    // FC3D_Example1 (3 contacts) is solved to 1e-17 in a few sweeps: with tolerance 0 and a
    // budget of 10 s AUTO returns at round-off instead of running its stages for 10 s.
    let p = shared("FC3D_Example1.dat");
    let n = p.size();
    let config = SolverConfig::new(AutoOptions::default())
        .with_tolerance(0.0)
        .with_max_iter(usize::MAX)
        .with_time_budget(Some(Duration::from_secs(10)));
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let start = Instant::now();
    let report = solve(&p, &config, &mut r, &mut u).unwrap();
    assert!(start.elapsed() < Duration::from_secs(5), "{report:?}");
    assert!(
        report.error <= fc3d_core::solvers::auto::ROUND_OFF,
        "{report:?}"
    );
    assert_eq!(report.error, true_error(&p, &r));
}

#[test]
fn the_features_are_the_same_in_every_storage() {
    for name in ["OneObject-i1028-138.hdf5.dat", "Capsules-i101-404.dat"] {
        let p = shared(name);
        let f = ProblemFeatures::of(&p);
        assert!(
            f.block_asymmetry > 0.0 && f.diagonal_dominance.is_finite(),
            "{f:?}"
        );
        for w in [
            Delassus::Dense(p.w().to_dense()),
            Delassus::Sparse(p.w().to_csr()),
        ] {
            let q = FrictionProblem::new(w, p.q().to_vec(), p.mu().to_vec()).unwrap();
            let g = ProblemFeatures::of(&q);
            assert_eq!(g.n_contacts, f.n_contacts);
            assert_eq!(g.mu_max, f.mu_max);
            assert_eq!(g.singular_contacts, f.singular_contacts);
            for (a, b) in [
                (g.diagonal_dominance, f.diagonal_dominance),
                (g.block_asymmetry, f.block_asymmetry),
                (g.diagonal_spread, f.diagonal_spread),
            ] {
                assert!((a - b).abs() <= 1e-12 * b.abs(), "{name}: {a} vs {b}");
            }
        }
    }
}
