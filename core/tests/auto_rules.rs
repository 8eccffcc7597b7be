//! AUTO's rules against the misses of issue 27 item 6, in counts (stages and iterations, not
//! times): the TFP-APGD probe in front of the factorizing plans and TFP-APGD as the second
//! stage of the weakly coupled plan, NSGS with over-relaxation and freezing on the Capsules at
//! 1e-6. The wall-clock check of the 10x rule on every shared
//! problem is `fc3d bench ... --auto-max-ratio 10` (docs/auto.md).

use fc3d_core::io::dat::read_dat_file;
use fc3d_core::scenes::{box_towers, TowerMotion, TowerSpec};
use fc3d_core::solvers::auto::{choose, ProblemFeatures, PROBE, RULES};
use fc3d_core::{
    natural_map_error, solve, AutoOptions, FrictionProblem, SolveReport, SolveStatus, SolverConfig,
    StageEnd, StageKind,
};

fn shared(name: &str) -> FrictionProblem<'static> {
    read_dat_file(std::path::Path::new(&format!(
        "{}/../../shared/data/siconos/{name}",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap()
}

fn auto(p: &FrictionProblem<'_>, tol: f64) -> SolveReport {
    let n = p.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let config = SolverConfig::new(AutoOptions::default()).with_tolerance(tol);
    let report = solve(p, &config, &mut r, &mut u).unwrap();
    let mut check = vec![0.0; n];
    assert_eq!(report.error, natural_map_error(p, &r, &mut check));
    report
}

/// (kind, iterations, end) of each stage.
fn stages(report: &SolveReport) -> Vec<(StageKind, usize, StageEnd)> {
    report
        .stages
        .as_ref()
        .unwrap()
        .stages()
        .map(|s| (s.kind, s.iterations, s.end))
        .collect()
}

#[test]
fn the_mu_ge_half_plans_start_with_a_tresca_apgd_probe_and_the_moderate_mu_one_does_not() {
    // Strongly coupled, no short budget: ADMM first (rule 10) and PROX first at 1e-8 (rule 11)
    // behind the probe; PROX first with mu < 0.5 (rule 8) without it (on the generated
    // 40-contact pile, mu 0.42, PROX from the probe's iterate took 54-63 ms where PROX alone
    // took 36 ms).
    let mut probed = Vec::new();
    for (rule, r) in RULES.iter().enumerate() {
        if r.when.strongly_coupled != Some(true) || r.when.max_budget.is_some() {
            continue;
        }
        if r.plan[0].allowance == PROBE {
            assert_eq!(r.plan[0].kind, StageKind::TrescaApgd, "rule {rule}");
            assert!(
                matches!(r.plan[1].kind, StageKind::Admm | StageKind::Prox),
                "rule {rule}"
            );
            assert_eq!(r.when.max_mu, None, "rule {rule}");
            probed.push(rule);
        }
    }
    assert_eq!(probed.len(), 2, "{probed:?}");
    let moderate = RULES
        .iter()
        .find(|r| r.when.max_mu.is_some())
        .expect("the moderate-mu row");
    assert_eq!(moderate.plan[0].kind, StageKind::Prox);
}

#[test]
fn the_probe_hands_over_on_boxes_stack_within_its_cap() {
    // BoxesStack1 (52 contacts, mu 0.7): at 1e-4 TFP-APGD gets there in 4 outer steps; at 1e-6
    // its later steps cost more and more products, the cap ends it and ADMM converges.
    let p = shared("BoxesStack1-i100000-32.hdf5.dat");
    let f = ProblemFeatures::of(&p);
    assert_eq!(choose(&f, 1e-6, None).1[0].allowance, PROBE);
    let loose = auto(&p, 1e-4);
    assert_eq!(loose.status, SolveStatus::Converged);
    assert_eq!(
        stages(&loose),
        vec![(StageKind::TrescaApgd, 4, StageEnd::Converged)]
    );
    let tight = auto(&p, 1e-6);
    assert_eq!(tight.status, SolveStatus::Converged);
    let s = stages(&tight);
    assert_eq!(
        (s[0].0, s[0].2),
        (StageKind::TrescaApgd, StageEnd::Allowance),
        "{s:?}"
    );
    assert!(s[0].1 <= 6, "{s:?}");
    assert_eq!(s[1].0, StageKind::Admm, "{s:?}");
    assert_eq!(s.len(), 2, "{s:?}");
}

#[test]
fn a_tall_tower_of_boxes_takes_tresca_apgd_after_the_sweeps() {
    // One tower of 142 boxes (568 contacts, normal-row dominance 0.17: the weakly coupled row).
    // Before, TFP with Gauss-Seidel sub-problems stalled after 5-20 outer steps and PROX ended
    // the solve (0.97-1.4 s, 5.7-15x behind the best fixed solver); TFP-APGD converges in 6-20.
    for (motion, tol, most) in [
        (TowerMotion::Rest, 1e-6, 8),
        (TowerMotion::Settling, 1e-4, 10),
    ] {
        let p = box_towers(&TowerSpec {
            towers: 1,
            height: 142,
            motion,
            seed: 1,
        })
        .unwrap();
        let report = auto(&p, tol);
        assert!(report.error <= tol, "{motion:?}: {report:?}");
        let s = stages(&report);
        assert_eq!(s[0].0, StageKind::Nsgs, "{s:?}");
        assert_eq!(
            (s[1].0, s[1].2),
            (StageKind::TrescaApgd, StageEnd::Converged),
            "{motion:?}: {s:?}"
        );
        assert!(s[1].1 <= most, "{motion:?}: {s:?}");
    }
}

/// LMGC_100_PR_PerioBox (60 contacts, FCLIB): before, ADMM first (3000 iterations to 6.6e-4)
/// then PROX, 100-170 ms where TFP takes 0.04 ms to 1e-4 and PFP 0.05 ms to 1e-6. The probe's
/// first outer step (a frictionless solve) is at 9.7e-5; it goes on to 1e-6 in 5, to 1e-8 in 11.
#[cfg(feature = "fclib")]
#[test]
fn the_probe_solves_the_periodic_box() {
    let p = fc3d_core::io::read_problem_file(std::path::Path::new(&format!(
        "{}/../../shared/data/siconos/LMGC_100_PR_PerioBox-i00361-60-03000.hdf5",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap();
    let loose = auto(&p, 1e-4);
    assert_eq!(
        stages(&loose),
        vec![(StageKind::TrescaApgd, 1, StageEnd::Converged)]
    );
    let tight = auto(&p, 1e-6);
    assert_eq!(
        stages(&tight),
        vec![(StageKind::TrescaApgd, 5, StageEnd::Converged)]
    );
    // At 1e-8 the cap ended the probe after 7 outer steps at 3.0e-8 and PROX's factorization
    // took the last step (5-8 ms, 7.9-18x behind TFP-SPG's 0.66 ms): a probe whose mean rate
    // reaches the tolerance within as many steps again runs on, and converges in 11.
    let tightest = auto(&p, 1e-8);
    assert_eq!(
        stages(&tightest),
        vec![(StageKind::TrescaApgd, 11, StageEnd::Converged)]
    );
}

#[test]
fn the_capsules_sweep_with_over_relaxation_and_freezing_at_1e_6() {
    // Strongly coupled, mu 0.7, 225-276 contacts, 1e-6: NSGS (QUARTIC) with omega = 1.3 and
    // freezing for 5 sweeps first. Before, the TFP-APGD probe then ADMM (86-595 ADMM
    // iterations after 6-7 probe steps); NSGS alone took 101-259 sweeps on three of them, and
    // on Capsules-i101-404 ADMM ends the solve after the sweeps stalled near 1e-6.
    use fc3d_core::solvers::auto::{PSOR_FREEZE_SWEEPS, PSOR_FREEZING, PSOR_OMEGA};
    assert_eq!(PSOR_FREEZING.relaxation, Some(PSOR_OMEGA));
    assert_eq!(PSOR_FREEZING.freezing, Some(PSOR_FREEZE_SWEEPS));
    // The sweeper is built once per solve with the options of the plan's NSGS stage.
    for (rule, r) in RULES.iter().enumerate() {
        let sweeps = r.plan.iter().filter(|s| s.kind == StageKind::Nsgs).count();
        assert!(sweeps <= 1, "rule {rule}: {sweeps} NSGS stages");
    }
    for (name, most_sweeps) in [
        ("Capsules-i100-1090.dat", 110),
        ("Capsules-i100-889.dat", 115),
        ("Capsules-i103-990.dat", 280),
    ] {
        let p = shared(name);
        let (_, plan) = choose(&ProblemFeatures::of(&p), 1e-6, None);
        assert_eq!(plan[0].kind, StageKind::Nsgs, "{name}");
        assert_eq!(plan[0].sweep, PSOR_FREEZING, "{name}");
        let report = auto(&p, 1e-6);
        assert_eq!(report.status, SolveStatus::Converged, "{name}");
        let s = stages(&report);
        assert_eq!(s.len(), 1, "{name}: {s:?}");
        assert_eq!(s[0].2, StageEnd::Converged, "{name}: {s:?}");
        assert!(s[0].1 <= most_sweeps, "{name}: {s:?}");
    }
    let p = shared("Capsules-i101-404.dat");
    let report = auto(&p, 1e-6);
    assert_eq!(report.status, SolveStatus::Converged);
    let s = stages(&report);
    assert_eq!(
        (s[0].0, s[0].2),
        (StageKind::Nsgs, StageEnd::Stalled),
        "{s:?}"
    );
    assert_eq!(s[1].0, StageKind::Admm, "{s:?}");
    // The rule stops at 1e-6: at 1e-8 the probe and PROX (5-20x ahead of any NSGS), below 100
    // contacts (BoxesStack1: 57-100k sweeps to 1e-6) ADMM behind the probe.
    assert_eq!(
        choose(&ProblemFeatures::of(&p), 1e-8, None).1[0].allowance,
        PROBE
    );
    let boxes = shared("BoxesStack1-i100000-32.hdf5.dat");
    assert_eq!(
        choose(&ProblemFeatures::of(&boxes), 1e-6, None).1[0].allowance,
        PROBE
    );
}
