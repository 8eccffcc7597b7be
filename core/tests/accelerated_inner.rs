//! The accelerated inner solvers (APGD, SPG) of the exact-Coulomb fixed points: TFP's Tresca
//! sub-problems, PFP's tangent problems and ACLMFP's SOCLCPs, on the analytic single-contact
//! cases, on shared problems in dense, sparse-block and CSR storage and on generated piles; every
//! reported error equals an independent recomputation (`opt5_common::run`), results are
//! deterministic and the work is counted in products with W.

mod opt5_common;

use fc3d_core::scenes::GeneratedScene;
use fc3d_core::{
    natural_map_error, AclmInnerSolver, AclmOptions, ApgdSettings, Method, PfpOptions,
    SolverConfig, SpgSettings, TrescaInnerSolver, TrescaOptions,
};
use opt5_common::*;

fn accelerated() -> [TrescaInnerSolver; 2] {
    [TrescaInnerSolver::apgd(), TrescaInnerSolver::spg()]
}

fn aclm_accelerated() -> [AclmInnerSolver; 2] {
    [
        AclmInnerSolver::Apgd(ApgdSettings::default()),
        AclmInnerSolver::Spg(SpgSettings::default()),
    ]
}

fn tfp(inner: TrescaInnerSolver) -> SolverConfig {
    SolverConfig::new(TrescaOptions {
        inner,
        ..Default::default()
    })
}

fn pfp(tangent: TrescaInnerSolver) -> SolverConfig {
    SolverConfig::new(PfpOptions {
        tangent,
        ..Default::default()
    })
}

fn aclm(inner: AclmInnerSolver) -> SolverConfig {
    SolverConfig::new(AclmOptions {
        inner,
        ..Default::default()
    })
}

/// Every configuration with an accelerated inner solver.
fn configs() -> Vec<SolverConfig> {
    let mut v: Vec<SolverConfig> = accelerated()
        .into_iter()
        .flat_map(|i| [tfp(i), pfp(i)])
        .collect();
    v.extend(aclm_accelerated().map(aclm));
    v
}

#[test]
fn presets_name_the_accelerated_variants() {
    for (name, label) in [
        ("TFP-APGD", "TFP/APGD"),
        ("TFP-SPG", "TFP/SPG"),
        ("ACLMFP-APGD", "ACLMFP-APGD"),
        ("ACLMFP-SPG", "ACLMFP-SPG"),
    ] {
        let m = Method::preset(name).expect(name);
        assert_eq!(SolverConfig::new(m).label(), label);
    }
    // The Siconos ids still name Siconos' defaults.
    assert_eq!(
        Method::preset("503"),
        Some(Method::Tresca(TrescaOptions::default()))
    );
    assert_eq!(
        Method::preset("516"),
        Some(Method::Aclm(AclmOptions::default()))
    );
    assert_eq!(TrescaInnerSolver::apgd().siconos_id(), None);
}

#[test]
fn analytic_single_contact_cases() {
    for c in configs() {
        check_analytic(|tol| c.with_tolerance(tol));
    }
}

#[test]
fn shared_problems_in_three_storages() {
    for (storage, p) in storages() {
        for c in configs() {
            let (rep, _, _) = run(&p, &c.with_tolerance(1e-6));
            assert!(rep.converged(), "{storage} {}: {rep:?}", c.label());
            assert!(rep.products.unwrap() >= rep.iterations, "{rep:?}");
        }
    }
}

#[test]
fn generated_piles_converge_deterministically() {
    for spec in [
        "contacts=1000,piles=4,seed=1",
        "contacts=1000,piles=4,seed=1,shape=boxes",
    ] {
        let p = GeneratedScene::parse(spec).unwrap().generate().unwrap();
        for c in [
            tfp(TrescaInnerSolver::apgd()),
            tfp(TrescaInnerSolver::spg()),
            aclm(aclm_accelerated()[0]),
        ] {
            let c = c.with_tolerance(1e-4).with_max_iter(400);
            let (rep, r, _) = run(&p, &c);
            assert!(rep.converged(), "{spec} {}: {rep:?}", c.label());
            let mut u = vec![0.0; p.size()];
            approx::assert_relative_eq!(
                natural_map_error(&p, &r, &mut u),
                rep.error,
                max_relative = 1e-12
            );
            let (again, r2, _) = run(&p, &c);
            assert_eq!(again, rep);
            assert!(r.iter().zip(&r2).all(|(a, b)| a.to_bits() == b.to_bits()));
        }
    }
}

#[test]
fn limits_hold_and_bad_settings_are_rejected() {
    let p = load("Confeti-ex03-Fc3D-SBM.dat");
    for c in configs() {
        // One outer iteration of one inner iteration: an honest failure.
        let mut limited = c.with_max_iter(1).with_tolerance(1e-12);
        match &mut limited.method {
            Method::Tresca(o) => o.inner_max_iter = 1,
            Method::Pfp(o) => {
                o.inner_max_iter = 1;
                o.normal_max_iter = 1;
            }
            Method::Aclm(o) => o.inner_max_iter = 1,
            _ => unreachable!(),
        }
        let (rep, _, _) = run(&p, &limited);
        assert_eq!(rep.iterations, 1, "{}", c.label());
        assert!(!rep.converged());
        let budget = c
            .with_tolerance(1e-14)
            .with_time_budget(Some(std::time::Duration::from_nanos(1)));
        let (rep, _, _) = run(&p, &budget);
        assert_eq!(rep.iterations, 1, "{}", c.label());
        assert_eq!(rep.status, fc3d_core::SolveStatus::TimeBudgetExhausted);
    }
    let bad = [
        tfp(TrescaInnerSolver::Apgd(ApgdSettings {
            spectral_steps: 0,
            ..Default::default()
        })),
        pfp(TrescaInnerSolver::Spg(SpgSettings {
            memory: 0,
            ..Default::default()
        })),
        aclm(AclmInnerSolver::Spg(SpgSettings {
            alpha_max: f64::INFINITY,
            ..Default::default()
        })),
    ];
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    for c in bad {
        let e = fc3d_core::solve(&p, &c, &mut r, &mut u).unwrap_err();
        assert!(e.is_invalid_option(), "{e}");
        assert!(r.iter().all(|v| *v == 0.0));
    }
}
