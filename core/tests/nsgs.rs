//! NSGS end to end: the built-in scenes with every local solver, the shortcuts and input errors of
//! `solve`, storage independence, and the Siconos collection in `shared/data/siconos`.
//!
//! Every reported error is checked against an independent recomputation (entry-wise `u = W r + q`
//! and a projection on the cone written here from its dot-product form), not `natural_map_error`.

mod common;
use common::honesty::{check_report, norm};

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use approx::assert_relative_eq;
use fc3d_core::scenes::{default_scenes, Scene, DT, GRAVITY};
use fc3d_core::{
    solve, BlockSparseMatrix, Delassus, DenseMatrix, Fc3dError, FrictionProblem, LocalSolverKind,
    NsgsOptions, SolveReport, SolveStatus, SolverConfig,
};

// ---------------------------------------------------------------------------------------------
// Helpers.

fn config(kind: LocalSolverKind, tol: f64, max_iter: usize) -> SolverConfig {
    SolverConfig::new(NsgsOptions::with_local(kind))
        .with_tolerance(tol)
        .with_max_iter(max_iter)
}

/// Solves from r = 0; returns (report, r, u, solve time).
fn run(p: &FrictionProblem<'_>, c: &SolverConfig) -> (SolveReport, Vec<f64>, Vec<f64>, Duration) {
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let t = Instant::now();
    let report = solve(p, c, &mut r, &mut u).expect("valid problem");
    (report, r, u, t.elapsed())
}

fn scene(name: &str) -> Scene {
    default_scenes()
        .into_iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("no scene {name}"))
}

// ---------------------------------------------------------------------------------------------
// Built-in scenes.

/// Local solvers that cannot reach 1e-8 on a scene, and why. They use `rho = 1 / W_NN` on all
/// three components (as Siconos does), so a sticking contact whose tangential stiffness exceeds
/// twice the normal one is not a contraction: every sphere contact has `W_TT = 3.5 W_NN` and
/// the pile has sticking sphere contacts with tangential load (see
/// `local::tests::one_step_solvers_cannot_stick_when_tangent_is_stiffer_than_twice_normal`).
/// 554 and 558 take 552's step. 555's tangential fixed point is not the Coulomb law when
/// W_T1T1 != W_T2T2 (as in Siconos). EAL (572) is plain Newton with one rho = 1/W_NN for the
/// tangential part too, where W_TT = 3.5 W_NN: it cycles, like 550 on such contacts.
const KNOWN_SCENE_FAILURES: [(LocalSolverKind, &str); 7] = [
    // One projection step per contact and sweep is not a contraction when W_TT > 2 W_NN.
    (LocalSolverKind::ProjectionOnCone, "sphere_pile"),
    (LocalSolverKind::ProjectionOnCylinder, "sphere_pile"),
    (
        LocalSolverKind::ProjectionOnConeWithRegularization,
        "sphere_pile",
    ),
    (LocalSolverKind::ProjectionOnConeVelocity, "sphere_pile"),
    // Diagonal rho from W_cc's diagonal alone stalls (1e-3) on the coupled stacks.
    (
        LocalSolverKind::ProjectionOnConeWithDiagonalization,
        "box_stack",
    ),
    (
        LocalSolverKind::ProjectionOnConeWithDiagonalization,
        "gyro_stack",
    ),
    // Full Newton steps without a line search cycle on the pile (error 8e-2).
    (LocalSolverKind::EnhancedAugmentedLagrangian, "sphere_pile"),
];

#[test]
fn every_local_solver_on_every_scene() {
    let tol = 1e-8;
    let mut table = Vec::new();
    let mut failures = Vec::new();
    for s in default_scenes() {
        for kind in LocalSolverKind::ALL {
            let (report, r, u, time) = run(&s.problem, &config(kind, tol, 100_000));
            check_report(s.name, &s.problem, tol, &report, &r, &u);
            table.push(format!(
                "{:16} {:3} {:6} {:8.2e} {:?} {:?}",
                s.name,
                kind.siconos_id(),
                report.iterations,
                report.error,
                report.status,
                time
            ));
            let known = KNOWN_SCENE_FAILURES.contains(&(kind, s.name));
            if known {
                // Not converged, but bounded and finite.
                assert!(r.iter().all(|v| v.is_finite()), "{}", s.name);
                assert!(report.error.is_finite());
            } else if !report.converged() {
                failures.push(format!(
                    "{} with {kind:?}: error {:e} after {} sweeps",
                    s.name, report.error, report.iterations
                ));
            }
        }
    }
    eprintln!("{}", table.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn sphere_scenes_match_physics() {
    let c = config(LocalSolverKind::NewtonHybrid, 1e-12, 1000);
    // Mass 1: the impulse that stops the fall during one step is m g dt.
    let rn = GRAVITY * DT;

    let s = scene("sphere_rest");
    let (report, r, u, _) = run(&s.problem, &c);
    assert!(report.converged());
    assert_relative_eq!(r[0], rn, max_relative = 1e-12);
    assert_relative_eq!(r[1], 0.0, epsilon = 1e-15);
    assert_relative_eq!(norm(&u), 0.0, epsilon = 1e-15);

    // v = (2, 0.5, 0), W = diag(1, 3.5, 3.5): stick would need ||r_T|| = ||v_T|| / 3.5 = 0.589 >
    // mu r_N = 0.0294, so it slides: r_T = -mu r_N v_T / ||v_T||, u_T = v_T + 3.5 r_T.
    let s = scene("sphere_slide");
    let (report, r, u, _) = run(&s.problem, &c);
    assert!(report.converged());
    let nv = 2.0f64.hypot(0.5);
    let expected_r = [rn, -0.3 * rn * 2.0 / nv, -0.3 * rn * 0.5 / nv];
    for i in 0..3 {
        assert_relative_eq!(r[i], expected_r[i], max_relative = 1e-12);
    }
    assert_relative_eq!(u[0], 0.0, epsilon = 1e-14);
    assert_relative_eq!(u[1], 2.0 + 3.5 * expected_r[1], max_relative = 1e-12);
    assert_relative_eq!(u[2], 0.5 + 3.5 * expected_r[2], max_relative = 1e-12);

    let s = scene("sphere_takeoff");
    let (report, r, u, _) = run(&s.problem, &c);
    assert_eq!(report.iterations, 0);
    assert_eq!(r, vec![0.0; 3]);
    assert_eq!(u, s.problem.q().to_vec());
    assert_relative_eq!(u[0], 2.0 - rn, max_relative = 1e-15);
}

#[test]
fn resting_box_carries_its_weight() {
    // 4 contacts, 12 unknowns, 6 dofs: r is not unique but the box stays at rest (u = 0) and
    // the impulses add up to m g dt (m = 2), with no net tangential impulse.
    let s = scene("box_on_ground");
    let (report, r, u, _) = run(
        &s.problem,
        &config(LocalSolverKind::NewtonHybrid, 1e-12, 10_000),
    );
    assert!(report.converged(), "{report:?}");
    assert!(norm(&u) <= 1e-12, "{u:?}");
    let total: [f64; 3] = [0, 1, 2].map(|k| (0..4).map(|c| r[3 * c + k]).sum());
    assert_relative_eq!(total[0], 2.0 * GRAVITY * DT, max_relative = 1e-10);
    assert_relative_eq!(total[1], 0.0, epsilon = 1e-12);
    assert_relative_eq!(total[2], 0.0, epsilon = 1e-12);
}

#[test]
fn scenes_have_the_announced_structure() {
    for s in default_scenes() {
        let p = &s.problem;
        let asym = p.w().relative_asymmetry();
        if s.name == "gyro_stack" {
            assert!((1e-5..1e-3).contains(&asym), "{}: {asym:e}", s.name);
        } else {
            assert_eq!(asym, 0.0, "{}", s.name);
        }
        let expected_storage = if p.n_contacts() == 1 {
            "dense"
        } else {
            "sparse-block"
        };
        assert_eq!(p.w().storage_name(), expected_storage, "{}", s.name);
    }
    let mu: Vec<f64> = scene("sphere_pile").problem.mu().to_vec();
    assert!(mu.contains(&0.0) && mu.iter().any(|&m| m > 0.0));
    // More contact rows than degrees of freedom (3 boxes = 18 dofs).
    assert_eq!(scene("box_stack").problem.size(), 36);
    assert_eq!(scene("box_bridge").problem.size(), 48);
}

// ---------------------------------------------------------------------------------------------
// Shortcuts and input errors of `solve`.

#[test]
fn trivial_case_gives_zero_reaction_without_iterating() {
    // The stack's W with every contact separating (q_N >= 0, one exactly 0).
    let p = scene("box_stack").problem;
    let mut q = p.q().to_vec();
    for (c, qc) in q.chunks_exact_mut(3).enumerate() {
        qc[0] = 0.01 * c as f64;
        qc[1] = 0.3 - 0.05 * c as f64;
    }
    let p = FrictionProblem::new(p.w().clone(), q.clone(), p.mu().to_vec()).unwrap();
    for kind in LocalSolverKind::ALL {
        let mut r: Vec<f64> = (0..p.size()).map(|i| 1.0 + i as f64).collect();
        let mut u = vec![7.0; p.size()];
        let report = solve(&p, &config(kind, 1e-8, 100), &mut r, &mut u).unwrap();
        assert_eq!(report.iterations, 0);
        assert_eq!(report.status, SolveStatus::Converged);
        assert_eq!(report.error, 0.0);
        assert!(r.iter().all(|&v| v == 0.0));
        assert_eq!(u, q);
        check_report("trivial", &p, 1e-8, &report, &r, &u);
    }
}

#[test]
fn zero_contacts() {
    let dense = Delassus::Dense(DenseMatrix::new(0, 0, Vec::new()).unwrap());
    let sparse = Delassus::SparseBlock(
        BlockSparseMatrix::new(0, 0, vec![0], Vec::new(), Vec::new()).unwrap(),
    );
    for w in [dense, sparse] {
        let p = FrictionProblem::new(w, Vec::new(), Vec::new()).unwrap();
        assert_eq!(p.n_contacts(), 0);
        let report = solve(
            &p,
            &SolverConfig::new(NsgsOptions::default()),
            &mut [],
            &mut [],
        )
        .unwrap();
        assert_eq!(report.iterations, 0);
        assert!(report.converged());
        assert_eq!(report.error, 0.0);
    }
}

#[test]
fn bad_inputs_are_errors_and_leave_r_u_untouched() {
    let p = scene("box_stack").problem;
    let n = p.size();
    let c = SolverConfig::new(NsgsOptions::default());

    // Wrong lengths.
    for (nr, nu) in [(n - 1, n), (n + 3, n), (n, n - 3), (0, 0)] {
        let mut r = vec![0.5; nr];
        let mut u = vec![-0.5; nu];
        let e = solve(&p, &c, &mut r, &mut u).unwrap_err();
        assert!(
            matches!(e, Fc3dError::DimensionMismatch { .. }),
            "{nr} {nu}: {e}"
        );
        assert!(r.iter().all(|&v| v == 0.5) && u.iter().all(|&v| v == -0.5));
    }

    // A NaN or an infinity in the initial reaction.
    for bad in [f64::NAN, f64::INFINITY] {
        let mut r = vec![0.25; n];
        r[7] = bad;
        let before = r.clone();
        let mut u = vec![3.0; n];
        let e = solve(&p, &c, &mut r, &mut u).unwrap_err();
        assert!(matches!(e, Fc3dError::NonFinite { index: 7, .. }), "{e}");
        assert!(r
            .iter()
            .zip(&before)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(u.iter().all(|&v| v == 3.0));
    }

    // An invalid option.
    let o = SolverConfig::new(NsgsOptions::default()).with_tolerance(f64::NAN);
    let mut r = vec![0.0; n];
    let mut u = vec![1.0; n];
    assert!(matches!(
        solve(&p, &o, &mut r, &mut u),
        Err(e) if e.is_invalid_option()
    ));
    assert!(r.iter().all(|&v| v == 0.0) && u.iter().all(|&v| v == 1.0));
}

// ---------------------------------------------------------------------------------------------
// Storage independence.

fn assert_same_solution(
    name: &str,
    a: &(SolveReport, Vec<f64>, Vec<f64>),
    b: &(SolveReport, Vec<f64>, Vec<f64>),
) {
    assert_eq!(
        a.0.iterations, b.0.iterations,
        "{name}: {:?} vs {:?}",
        a.0, b.0
    );
    assert_eq!(a.0.status, b.0.status, "{name}");
    let sr = norm(&a.1).max(1e-300);
    let su = norm(&a.2).max(norm(&a.1)).max(1e-300);
    for (x, y) in a.1.iter().zip(&b.1) {
        assert!((x - y).abs() <= 1e-12 * sr, "{name}: r {x} vs {y}");
    }
    for (x, y) in a.2.iter().zip(&b.2) {
        assert!((x - y).abs() <= 1e-12 * su, "{name}: u {x} vs {y}");
    }
    // The errors are measured with each storage's own product W r: equal up to rounding.
    assert!(
        (a.0.error - b.0.error).abs() <= 1e-9 * a.0.error + 1e-14,
        "{name}: error {:e} vs {:e}",
        a.0.error,
        b.0.error
    );
}

#[test]
fn dense_sparse_block_and_csr_give_the_same_result() {
    for s in default_scenes() {
        let p = &s.problem;
        let dense = p.with_w(Delassus::Dense(p.w().to_dense())).unwrap();
        let csr = p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap();
        for kind in [
            LocalSolverKind::NewtonHybrid,
            LocalSolverKind::ProjectionOnConeWithLocalIteration,
        ] {
            let c = config(kind, 1e-8, 100_000);
            let run3 = |q: &FrictionProblem<'_>| {
                let (rep, r, u, _) = run(q, &c);
                (rep, r, u)
            };
            let base = run3(p);
            assert_same_solution(s.name, &base, &run3(&dense));
            assert_same_solution(s.name, &base, &run3(&csr));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The Siconos collection.

fn siconos_dir() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/siconos"
    ))
}

/// The 3D reduced-form problems of the collection: `*.dat` except the global (GFC3D_), 2D
/// (gfc2d_, fc2d_, FC2D_, FrictionContactProblem*) ones and ACinputs.dat.
fn siconos_fc3d_files() -> Vec<PathBuf> {
    let dir = siconos_dir();
    let Ok(entries) = std::fs::read_dir(&dir) else {
        panic!("{} is missing", dir.display());
    };
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            name.ends_with(".dat")
                && ![
                    "GFC3D_",
                    "gfc2d_",
                    "fc2d_",
                    "FC2D_",
                    "FrictionContactProblem",
                ]
                .iter()
                .any(|pre| name.starts_with(pre))
                && name != "ACinputs.dat"
        })
        .collect();
    files.sort();
    files
}

/// Problems that need more than a few thousand sweeps (seconds in a release build): run by
/// [`siconos_collection_slow`] only (`cargo test --release -- --ignored`).
const SLOW: [&str; 7] = [
    "BoxesStack1-i100000-32.hdf5.dat",
    "Capsules-i100-1090.dat",
    "Capsules-i100-889.dat",
    "Capsules-i101-404.dat",
    "Capsules-i103-990.dat",
    "OneObject-i100000-316.hdf5.dat",
    "RockPile_tob1.dat",
];

/// Problems on which default NSGS does not reach 1e-6 in 10^5 sweeps. Siconos 4.4 fails on the
/// same three at 1e-8 (shared/data/siconos-reference-1e-8.csv: 1.27e-6, 1.69e-3, 3.53e-4).
const NOT_CONVERGING: [&str; 3] = [
    "BoxesStack1-i100000-32.hdf5.dat",
    "OneObject-i100000-316.hdf5.dat",
    "RockPile_tob1.dat",
];

fn solve_collection(files: &[PathBuf]) {
    let tol = 1e-6;
    let c = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(tol)
        .with_max_iter(100_000);
    let mut lines = vec![format!(
        "{:34} {:>8} {:>10} {:>9} {:>12} status",
        "problem", "contacts", "iterations", "error", "time"
    )];
    let mut failures = Vec::new();
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let p = fc3d_core::io::dat::read_dat_file(path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let (report, r, u, time) = run(&p, &c);
        check_report(&name, &p, tol, &report, &r, &u);
        lines.push(format!(
            "{:34} {:>8} {:>10} {:>9.2e} {:>12?} {}",
            name,
            p.n_contacts(),
            report.iterations,
            report.error,
            time,
            if report.converged() {
                "converged"
            } else {
                "NOT converged"
            }
        ));
        if !report.converged() && !NOT_CONVERGING.contains(&name.as_str()) {
            failures.push(name);
        }
    }
    eprintln!("{}", lines.join("\n"));
    assert!(failures.is_empty(), "unexpected failures: {failures:?}");
}

#[test]
fn siconos_collection() {
    let files: Vec<PathBuf> = siconos_fc3d_files()
        .into_iter()
        .filter(|p| !SLOW.contains(&p.file_name().unwrap().to_str().unwrap()))
        .collect();
    assert!(files.len() >= 20, "{files:?}");
    solve_collection(&files);
}

#[test]
#[ignore = "about 20 s in a release build (RockPile_tob1 alone 11 s): cargo test --release -- --ignored"]
fn siconos_collection_slow() {
    let files: Vec<PathBuf> = siconos_fc3d_files()
        .into_iter()
        .filter(|p| SLOW.contains(&p.file_name().unwrap().to_str().unwrap()))
        .collect();
    assert_eq!(files.len(), SLOW.len());
    solve_collection(&files);
}

#[test]
fn small_siconos_problems_in_every_storage() {
    for name in [
        "FC3D_Example1_SBM.dat",
        "Confeti-ex03-Fc3D-SBM.dat",
        "Rover1040.dat",
    ] {
        let path = siconos_dir().join(name);
        let p = fc3d_core::io::dat::read_dat_file(Path::new(&path)).unwrap();
        let c = config(LocalSolverKind::NewtonHybrid, 1e-10, 10_000);
        let run3 = |q: &FrictionProblem<'_>| {
            let (rep, r, u, _) = run(q, &c);
            (rep, r, u)
        };
        let base = run3(&p);
        assert_same_solution(
            name,
            &base,
            &run3(&p.with_w(Delassus::Dense(p.w().to_dense())).unwrap()),
        );
        assert_same_solution(
            name,
            &base,
            &run3(&p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap()),
        );
    }
}
