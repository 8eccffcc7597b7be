//! The workspace: warm starts matched by contact id (appearing and vanishing contacts), the
//! reuse of the prepared W structure and its detection of a pattern change, and equality with a
//! cold solve started from the same iterate.

use fc3d_core::matrix::BlockRows;
use fc3d_core::scenes::sequences::{box_slide, pile_settling, pile_settling_in_bin, Sequence};
use fc3d_core::solvers::auto::choose;
use fc3d_core::{
    solve, AutoOptions, BlockSparseMatrix, Decomposition, Delassus, FrictionProblem, Method,
    NsgsOptions, NsnFormulation, NsnOptions, ProblemFeatures, Rescaling, SolverConfig, Workspace,
};

/// `k` independent spheres on a plane (W block diagonal), each pushed down by `push[c]`.
fn spheres(push: &[f64]) -> FrictionProblem<'static> {
    let nc = push.len();
    let row_ptr: Vec<usize> = (0..=nc).collect();
    let col_idx: Vec<usize> = (0..nc).collect();
    let blocks = vec![[1.0, 0.0, 0.0, 0.0, 3.5, 0.0, 0.0, 0.0, 3.5]; nc];
    let w = BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks).unwrap();
    let q: Vec<f64> = push.iter().flat_map(|&p| [-p, 0.1, 0.0]).collect();
    FrictionProblem::new(Delassus::SparseBlock(w), q, vec![0.5; nc]).unwrap()
}

fn nsgs() -> SolverConfig {
    SolverConfig::new(NsgsOptions::default()).with_tolerance(1e-10)
}

fn cold_stepper(config: SolverConfig) -> impl FnMut(&FrictionProblem<'_>) -> Vec<f64> {
    move |p| {
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        solve(p, &config, &mut r, &mut u).unwrap();
        r
    }
}

#[test]
fn contacts_are_matched_by_id_new_ones_start_cold_vanished_ones_are_dropped() {
    let mut ws = Workspace::new();
    let p1 = spheres(&[1.0, 2.0, 3.0]);
    let (mut r, mut u) = (vec![0.0; 9], vec![0.0; 9]);
    let report = ws
        .solve(&p1, &nsgs(), &[10, 20, 30], &mut r, &mut u)
        .unwrap();
    assert!(report.converged());
    let r30 = ws.last_reaction(30).unwrap();
    let r10 = ws.last_reaction(10).unwrap();
    assert!(r10[0] > 0.0 && r30[0] > r10[0]);
    assert_eq!(ws.was_active(20), Some(true));

    // Step 2: contact 20 vanished, 40 appeared, the others moved in the arrays.
    let p2 = spheres(&[3.0, 5.0, 1.0]);
    let ids2 = [30, 40, 10];
    let mut guess = vec![f64::NAN; 9];
    let start = ws.initial_guess(&ids2, &mut guess).unwrap();
    assert_eq!((start.warm, start.cold), (2, 1));
    assert_eq!(&guess[0..3], &r30);
    assert_eq!(&guess[3..6], &[0.0; 3]);
    assert_eq!(&guess[6..9], &r10);
    let (mut r2, mut u2) = (vec![0.0; 9], vec![0.0; 9]);
    ws.solve(&p2, &nsgs(), &ids2, &mut r2, &mut u2).unwrap();
    assert_eq!(ws.last_reaction(20), None);
    assert_eq!(ws.was_active(20), None);
    assert_eq!(ws.n_remembered(), 3);
    // Contacts 30 and 10 kept their pushes: their warm start was the answer already.
    let s = ws.stats();
    assert_eq!((s.solves, s.warm_contacts, s.cold_contacts), (2, 2, 4));
}

#[test]
fn invalid_ids_are_rejected_and_nothing_changes() {
    let mut ws = Workspace::new();
    let p = spheres(&[1.0, 2.0]);
    let (mut r, mut u) = (vec![7.0; 6], vec![7.0; 6]);
    assert!(ws.solve(&p, &nsgs(), &[1, 1], &mut r, &mut u).is_err());
    assert!(ws.solve(&p, &nsgs(), &[1], &mut r, &mut u).is_err());
    assert!(ws.solve(&p, &nsgs(), &[1, 2], &mut r[..3], &mut u).is_err());
    assert!(r.iter().chain(&u).all(|&v| v == 7.0));
    assert_eq!(ws.n_remembered(), 0);
    assert_eq!(ws.stats().solves, 0);
}

/// Every step of `seq` through a workspace equals a plain solve from the workspace's warm start.
fn check_equal_to_cold_from_same_iterate(seq: &Sequence, config: &SolverConfig) {
    let mut ws = Workspace::new();
    for step in &seq.steps {
        let n = step.problem.size();
        let mut r_cold = vec![0.0; n];
        ws.initial_guess(&step.ids, &mut r_cold).unwrap();
        let mut u_cold = vec![0.0; n];
        let cold = solve(&step.problem, config, &mut r_cold, &mut u_cold).unwrap();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let warm = ws
            .solve(&step.problem, config, &step.ids, &mut r, &mut u)
            .unwrap();
        assert_eq!(warm.iterations, cold.iterations, "{}", config.label());
        assert_eq!(warm.status, cold.status);
        assert_eq!(warm.error.to_bits(), cold.error.to_bits());
        assert_eq!(r, r_cold);
        assert_eq!(u, u_cold);
    }
    let s = ws.stats();
    assert!(s.structure_reused > 0, "{}: {s:?}", config.label());
}

#[test]
fn equals_a_cold_solve_from_the_same_iterate_nsgs_and_nsn() {
    let seq = box_slide(60, &mut cold_stepper(nsgs()));
    check_equal_to_cold_from_same_iterate(&seq, &nsgs());
    let nsn =
        SolverConfig::new(NsnOptions::new(NsnFormulation::AlartCurnier)).with_tolerance(1e-10);
    check_equal_to_cold_from_same_iterate(&seq, &nsn);
    // Under a rescaling the prepared structures are those of the rescaled W, refilled alike.
    check_equal_to_cold_from_same_iterate(&seq, &nsgs().with_rescaling(Rescaling::Scalar));
    // A family without prepared structure goes through its plain run.
    let prox = SolverConfig::new(
        Method::presets()
            .into_iter()
            .find(|m| m.label().starts_with("PROX"))
            .unwrap(),
    );
    check_equal_to_cold_from_same_iterate_no_reuse(&seq, &prox);
}

fn check_equal_to_cold_from_same_iterate_no_reuse(seq: &Sequence, config: &SolverConfig) {
    let mut ws = Workspace::new();
    for step in seq.steps.iter().take(10) {
        let n = step.problem.size();
        let mut r_cold = vec![0.0; n];
        ws.initial_guess(&step.ids, &mut r_cold).unwrap();
        let mut u_cold = vec![0.0; n];
        let cold = solve(&step.problem, config, &mut r_cold, &mut u_cold).unwrap();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let warm = ws
            .solve(&step.problem, config, &step.ids, &mut r, &mut u)
            .unwrap();
        assert_eq!(warm.iterations, cold.iterations);
        assert_eq!(r, r_cold);
    }
}

#[test]
fn pattern_changes_are_detected() {
    // Same pattern, new values: reused. A new contact set: rebuilt.
    let mut ws = Workspace::new();
    let run = |ws: &mut Workspace, p: &FrictionProblem<'_>, ids: &[i64]| {
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        ws.solve(p, &nsgs(), ids, &mut r, &mut u).unwrap();
    };
    run(&mut ws, &spheres(&[1.0, 2.0]), &[1, 2]);
    assert_eq!(
        (ws.stats().structure_built, ws.stats().structure_reused),
        (1, 0)
    );
    run(&mut ws, &spheres(&[2.0, 0.5]), &[1, 2]);
    assert_eq!(
        (ws.stats().structure_built, ws.stats().structure_reused),
        (1, 1)
    );
    run(&mut ws, &spheres(&[2.0, 0.5, 1.0]), &[1, 2, 3]);
    assert_eq!(
        (ws.stats().structure_built, ws.stats().structure_reused),
        (2, 1)
    );

    // Over the pile, the prepared rows match a fresh build at every step.
    let seq = pile_settling(16, 120, &mut cold_stepper(nsgs()));
    let mut kept: Option<BlockRows> = None;
    let (mut reused, mut rebuilt) = (0, 0);
    for step in &seq.steps {
        let w = step.problem.w();
        let fresh = w.block_rows().unwrap();
        let rows = match kept.take() {
            Some(mut rows) => {
                if rows.refill_from(w) {
                    reused += 1;
                    rows
                } else {
                    rebuilt += 1;
                    w.block_rows().unwrap()
                }
            }
            None => {
                rebuilt += 1;
                w.block_rows().unwrap()
            }
        };
        let n = step.problem.size();
        let r: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        rows.velocity(step.problem.q(), &r, &mut a);
        fresh.velocity(step.problem.q(), &r, &mut b);
        assert_eq!(a, b);
        assert_eq!(rows.n_off_diagonal(), fresh.n_off_diagonal());
        kept = Some(rows);
    }
    assert!(
        reused > 0 && rebuilt > 1,
        "reused {reused}, rebuilt {rebuilt}"
    );
}

#[test]
fn sequences_have_contacts_that_appear_and_vanish() {
    let seq = pile_settling(32, 200, &mut cold_stepper(nsgs()));
    assert!(
        seq.steps.len() >= 150,
        "{} steps with contacts",
        seq.steps.len()
    );
    let (mut appeared, mut vanished) = (0, 0);
    for pair in seq.steps.windows(2) {
        let before: std::collections::HashSet<_> = pair[0].ids.iter().collect();
        let after: std::collections::HashSet<_> = pair[1].ids.iter().collect();
        appeared += after.difference(&before).count();
        vanished += before.difference(&after).count();
    }
    assert!(
        appeared > 10 && vanished > 0,
        "appeared {appeared}, vanished {vanished}"
    );
    // The pile comes to rest: the last step's contacts barely slip (u_N holds the gap / dt of
    // contacts not yet closed).
    let last = seq.steps.last().unwrap();
    let n = last.problem.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    solve(&last.problem, &nsgs(), &mut r, &mut u).unwrap();
    // Frictional contacts only: a sphere rolling along a frictionless wall slides on it.
    let slip = u
        .chunks_exact(3)
        .zip(last.problem.mu())
        .filter(|(_, &mu)| mu > 0.0)
        .fold(0.0_f64, |m, (uc, _)| m.max(uc[1].hypot(uc[2])));
    assert!(slip < 0.02, "largest slip velocity at the end {slip}");
}

#[test]
fn the_colouring_of_a_coloured_sweep_is_kept_while_the_pattern_holds() {
    let coloured = SolverConfig::new(NsgsOptions {
        decomposition: Decomposition::Coloured,
        threads: 2,
        ..NsgsOptions::default()
    })
    .with_tolerance(1e-10);
    // Bitwise the cold solve from the same iterate, with the colouring taken over.
    let seq = box_slide(40, &mut cold_stepper(nsgs()));
    let mut ws = Workspace::new();
    for step in &seq.steps {
        let n = step.problem.size();
        let mut r_cold = vec![0.0; n];
        ws.initial_guess(&step.ids, &mut r_cold).unwrap();
        let mut u_cold = vec![0.0; n];
        let cold = solve(&step.problem, &coloured, &mut r_cold, &mut u_cold).unwrap();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let warm = ws
            .solve(&step.problem, &coloured, &step.ids, &mut r, &mut u)
            .unwrap();
        assert_eq!(warm.iterations, cold.iterations);
        assert_eq!(r, r_cold);
        assert_eq!(u, u_cold);
    }
    let s = *ws.stats();
    assert!(s.structure_reused > 0, "{s:?}");
    assert_eq!(s.colouring_reused, s.structure_reused, "{s:?}");

    // A pattern change drops it; a plain NSGS solve in between keeps it.
    let mut ws = Workspace::new();
    let run = |ws: &mut Workspace, config: &SolverConfig, p: &FrictionProblem<'_>, ids: &[i64]| {
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        ws.solve(p, config, ids, &mut r, &mut u).unwrap();
    };
    run(&mut ws, &coloured, &spheres(&[1.0, 2.0]), &[1, 2]);
    run(&mut ws, &nsgs(), &spheres(&[1.5, 2.0]), &[1, 2]);
    run(&mut ws, &coloured, &spheres(&[2.0, 0.5]), &[1, 2]);
    assert_eq!(ws.stats().colouring_reused, 1);
    run(&mut ws, &coloured, &spheres(&[2.0, 0.5, 1.0]), &[1, 2, 3]);
    assert_eq!(ws.stats().colouring_reused, 1);
    run(&mut ws, &coloured, &spheres(&[2.0, 0.5, 1.5]), &[1, 2, 3]);
    assert_eq!(ws.stats().colouring_reused, 2);
}

#[test]
fn auto_resumes_from_the_stage_that_finished_while_the_rule_holds() {
    let auto = SolverConfig::new(AutoOptions::default()).with_tolerance(1e-8);
    let seq = box_slide(40, &mut cold_stepper(nsgs()));
    let mut ws = Workspace::new();
    let mut resumed = 0;
    for (k, step) in seq.steps.iter().enumerate() {
        let n = step.problem.size();
        let before = ws.auto_choice().copied();
        let resumes = ws.stats().auto_resumed;
        let mut r_cold = vec![0.0; n];
        ws.initial_guess(&step.ids, &mut r_cold).unwrap();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let warm = ws
            .solve(&step.problem, &auto, &step.ids, &mut r, &mut u)
            .unwrap();
        assert!(warm.converged(), "step {k}: {:e}", warm.error);
        let choice = *ws.auto_choice().expect("AUTO records its choice");
        let log = warm.stages.expect("AUTO logs its stages");
        assert_eq!(log.rule, choice.rule);
        assert_eq!(log.stages().last().unwrap().kind, choice.kind());
        if ws.stats().auto_resumed > resumes {
            // Resumed: the plan from the stage that finished last time, the same rule, and
            // the same result as a cold solve of that part of the plan.
            resumed += 1;
            let before = before.expect("a resumed solve follows a recorded one");
            assert_eq!(log.rule, before.rule);
            assert_eq!(log.stages().next().unwrap().kind, before.kind(), "step {k}");
            let rest = SolverConfig::new(AutoOptions {
                plan: Some(&before.plan[before.stage..]),
            })
            .with_tolerance(1e-8);
            let mut u_cold = vec![0.0; n];
            let cold = solve(&step.problem, &rest, &mut r_cold, &mut u_cold).unwrap();
            assert_eq!(warm.iterations, cold.iterations, "step {k}");
            assert_eq!(r, r_cold, "step {k}");
        } else {
            // Not resumed: the rule the features give.
            let f = ProblemFeatures::of(&step.problem);
            assert_eq!(choose(&f, 1e-8, None).0, log.rule, "step {k}");
        }
    }
    assert!(resumed > 0, "{:?}", ws.stats());

    // Another tolerance, another method in between, or another pattern whose features give
    // another rule: no resume. Another pattern with the same rule (a contact appeared) resumes.
    let mut ws = Workspace::new();
    let run = |ws: &mut Workspace, config: &SolverConfig, p: &FrictionProblem<'_>, ids: &[i64]| {
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        ws.solve(p, config, ids, &mut r, &mut u).unwrap();
        ws.stats().auto_resumed
    };
    assert_eq!(run(&mut ws, &auto, &spheres(&[1.0, 2.0]), &[1, 2]), 0);
    assert_eq!(run(&mut ws, &auto, &spheres(&[1.5, 2.0]), &[1, 2]), 1);
    let looser = auto.clone().with_tolerance(1e-4);
    assert_eq!(run(&mut ws, &looser, &spheres(&[1.5, 2.5]), &[1, 2]), 1);
    assert_eq!(
        run(&mut ws, &looser, &spheres(&[1.0, 2.5, 1.0]), &[1, 2, 3]),
        2
    );
    assert_eq!(
        run(&mut ws, &looser, &spheres(&[1.0, 2.5, 2.0]), &[1, 2, 3]),
        3
    );
    // One contact left: the one-contact rule, not the kept one; and back.
    let one = choose(&ProblemFeatures::of(&spheres(&[1.0])), 1e-4, None).0;
    let three = choose(&ProblemFeatures::of(&spheres(&[1.0, 2.5, 2.0])), 1e-4, None).0;
    assert_ne!(one, three);
    assert_eq!(run(&mut ws, &looser, &spheres(&[1.0]), &[2]), 3);
    assert_eq!(ws.auto_choice().map(|c| c.rule), Some(one));
    assert_eq!(
        run(&mut ws, &looser, &spheres(&[1.0, 2.5, 2.0]), &[1, 2, 3]),
        3
    );
    assert_eq!(ws.auto_choice().map(|c| c.rule), Some(three));
    assert_eq!(
        run(&mut ws, &nsgs(), &spheres(&[1.0, 2.5, 2.0]), &[1, 2, 3]),
        3
    );
    assert!(ws.auto_choice().is_none());
    assert_eq!(
        run(&mut ws, &looser, &spheres(&[1.0, 2.5, 2.0]), &[1, 2, 3]),
        3
    );
    assert!(ws.auto_choice().is_some());
    // A solve that stops short of its tolerance leaves no choice: the next one chooses afresh.
    let short = SolverConfig::new(AutoOptions::default())
        .with_tolerance(1e-12)
        .with_max_iter(1);
    let seq = box_slide(10, &mut cold_stepper(nsgs()));
    let step = seq.steps.last().unwrap();
    let (mut r, mut u) = (
        vec![0.0; step.problem.size()],
        vec![0.0; step.problem.size()],
    );
    let report = ws
        .solve(&step.problem, &short, &step.ids, &mut r, &mut u)
        .unwrap();
    assert!(!report.converged());
    assert!(ws.auto_choice().is_none());
}

#[test]
fn the_settling_pile_in_a_bin_of_4_is_pile_settling_and_hands_over_its_ids() {
    let kept = pile_settling(32, 40, &mut cold_stepper(nsgs()));
    let mut stepper = cold_stepper(nsgs());
    let mut seen = 0;
    let solved = pile_settling_in_bin(32, 4, 40, &mut |step| {
        let same = &kept.steps[seen];
        assert_eq!(step.ids, same.ids, "step {seen}");
        assert_eq!(step.problem.q(), same.problem.q(), "step {seen}");
        seen += 1;
        stepper(&step.problem)
    });
    assert_eq!((solved, seen), (kept.steps.len(), kept.steps.len()));
    assert!(solved > 0);
}
