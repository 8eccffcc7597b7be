//! NSGS with each of the one-contact solvers added beside 550-553/557/565 (554, 555, 558, 561,
//! 562, 564, 570, 571, 572 and the Jean-Moreau formulation of the Newton solvers) on small
//! shared problems, in the three storages: the reported error is honest, the solution is the
//! same whatever the storage, and the solvers that converge there (measured with `fc3d bench`)
//! do converge.

use std::path::{Path, PathBuf};

use fc3d_core::{
    natural_map_error, solve, Delassus, FrictionProblem, LocalSolverKind, LocalSolverOptions,
    NsgsOptions, SolveReport, SolverConfig,
};

fn shared(name: &str) -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/siconos"
    ))
    .join(name)
}

fn config(local: LocalSolverOptions, tol: f64, max_iter: usize) -> SolverConfig {
    SolverConfig::new(NsgsOptions {
        local,
        ..NsgsOptions::default()
    })
    .with_tolerance(tol)
    .with_max_iter(max_iter)
}

fn run(p: &FrictionProblem<'_>, c: &SolverConfig) -> (SolveReport, Vec<f64>, Vec<f64>) {
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let report = solve(p, c, &mut r, &mut u).expect("valid problem");
    (report, r, u)
}

fn new_local_solvers() -> Vec<(String, LocalSolverOptions)> {
    let mut v: Vec<(String, LocalSolverOptions)> = [
        LocalSolverKind::ProjectionOnConeWithRegularization,
        LocalSolverKind::ProjectionOnConeWithDiagonalization,
        LocalSolverKind::ProjectionOnConeVelocity,
        LocalSolverKind::FischerBurmeisterNewton,
        LocalSolverKind::Quartic,
        LocalSolverKind::ProjectionOnCylinderWithLocalIteration,
        LocalSolverKind::FpViUpk,
        LocalSolverKind::EnhancedBipotential,
        LocalSolverKind::EnhancedAugmentedLagrangian,
    ]
    .into_iter()
    .map(|k| (format!("{k:?}"), LocalSolverOptions::new(k)))
    .collect();
    for k in [
        LocalSolverKind::NewtonAlartCurnierGp,
        LocalSolverKind::NewtonHybrid,
    ] {
        let mut o = LocalSolverOptions::new(k);
        o.formulation = fc3d_core::NewtonFormulation::JeanMoreau;
        v.push((format!("{k:?}-JeanMoreau"), o));
    }
    v
}

fn assert_honest(name: &str, p: &FrictionProblem<'_>, rep: &SolveReport, r: &[f64], u: &[f64]) {
    assert!(
        r.iter().chain(u).all(|x| x.is_finite()),
        "{name}: non-finite output"
    );
    // natural_map_error recomputes u = W r + q into its buffer.
    let mut u2 = u.to_vec();
    let e = natural_map_error(p, r, &mut u2);
    assert!(
        (e - rep.error).abs() <= 1e-12 + 1e-6 * e,
        "{name}: reported {} but measured {e}",
        rep.error
    );
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The one-step projection variants 554 and 558 (552's step) and EAL (572, plain Newton like
/// 550 but with Dumont's single rho) do not reach 1e-8 on Confeti-ex03 within 20000 sweeps
/// (neither do 552 and 557); the others do, as does Siconos' 555.
fn expected_to_converge(file: &str, name: &str) -> bool {
    file == "FC3D_Example1_SBM.dat"
        || !matches!(
            name,
            "ProjectionOnConeWithRegularization"
                | "ProjectionOnConeVelocity"
                | "EnhancedAugmentedLagrangian"
        )
}

/// NSGS with every new local solver on two small problems: honest error, the same answer in
/// sparse-block, dense and CSR storage, and convergence to 1e-8 where expected.
#[test]
fn new_local_solvers_solve_small_problems_in_every_storage() {
    for file in ["FC3D_Example1_SBM.dat", "Confeti-ex03-Fc3D-SBM.dat"] {
        let p = fc3d_core::io::read_problem_file(Path::new(&shared(file))).unwrap();
        let dense = p.with_w(Delassus::Dense(p.w().to_dense())).unwrap();
        let csr = p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap();
        for (name, local) in new_local_solvers() {
            let c = config(local, 1e-8, 20_000);
            let (rep, r, u) = run(&p, &c);
            let label = format!("{file} {name}");
            assert_honest(&label, &p, &rep, &r, &u);
            if expected_to_converge(file, &name) {
                assert!(rep.converged(), "{label}: {rep:?}");
                assert!(rep.error <= 1e-8, "{label}: {rep:?}");
            } else {
                assert!(!rep.converged(), "{label} now converges: update the list");
            }
            for (storage, q) in [("dense", &dense), ("csr", &csr)] {
                let (rep2, r2, u2) = run(q, &c);
                assert_honest(&label, q, &rep2, &r2, &u2);
                assert_eq!(rep.iterations, rep2.iterations, "{label} {storage}");
                let scale = r.iter().fold(1.0f64, |m, x| m.max(x.abs()));
                assert!(
                    max_diff(&r, &r2) <= 1e-10 * scale,
                    "{label} {storage}: r differs by {}",
                    max_diff(&r, &r2)
                );
            }
        }
    }
}

/// On a 138-contact dense problem with non-symmetric W: each new solver either converges or
/// reports an honest error with finite r.
#[test]
fn new_local_solvers_are_honest_on_a_rover_problem() {
    let p = fc3d_core::io::read_problem_file(Path::new(&shared("Rover1040.dat"))).unwrap();
    for (name, local) in new_local_solvers() {
        let c = config(local, 1e-8, 2_000);
        let (rep, r, u) = run(&p, &c);
        assert_honest(&format!("Rover1040 {name}"), &p, &rep, &r, &u);
    }
}
