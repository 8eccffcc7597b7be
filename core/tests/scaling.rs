//! Rescaling: FC(alpha W, beta q, mu) for alpha, beta over 1e-8..1e8 solved with
//! `Rescaling::Scalar` takes the iterations of FC(W, q, mu) and reaches the same relative error
//! (the rescaled problems coincide up to rounding), and the reported error is the natural-map error
//! of the returned pair on the host's (scaled) problem.

use std::path::Path;

use fc3d_core::io::read_problem_file;
use fc3d_core::{
    natural_map_error, solve_with_observer, Delassus, FrictionProblem, NsgsOptions, Rescaling,
    SolveReport, SolverConfig,
};

fn load(name: &str) -> FrictionProblem<'static> {
    read_problem_file(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../shared/data/siconos")
            .join(name),
    )
    .expect("shared problem")
}

fn scaled(p: &FrictionProblem<'_>, alpha: f64, beta: f64) -> FrictionProblem<'static> {
    FrictionProblem::new(
        p.w().scaled(alpha).unwrap(),
        p.q().iter().map(|v| beta * v).collect::<Vec<_>>(),
        p.mu().to_vec(),
    )
    .unwrap()
}

fn run(p: &FrictionProblem<'_>, rescaling: Rescaling, tol: f64) -> (SolveReport, Vec<f64>) {
    let config = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(tol)
        .with_max_iter(20_000)
        .with_rescaling(rescaling);
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let report = solve_with_observer(p, &config, &mut r, &mut u, &mut |_| {}).unwrap();
    let mut u2 = vec![0.0; p.size()];
    assert_eq!(report.error, natural_map_error(p, &r, &mut u2));
    (report, r)
}

const SCALES: [f64; 5] = [1e-8, 1e-4, 1.0, 1e4, 1e8];

#[test]
fn rescaled_solves_are_scale_invariant() {
    let confeti = load("Confeti-ex13-Fc3D-SBM.dat");
    let csr = confeti
        .with_w(Delassus::Sparse(confeti.w().to_csr()))
        .unwrap();
    let problems = [
        ("Confeti-ex13 (sparse-block)", confeti),
        ("Confeti-ex13 (CSR)", csr),
        ("NESpheres_10_1 (dense)", load("NESpheres_10_1.dat")),
        ("Rover4396 (dense)", load("Rover4396.dat")),
        ("OneObject-i1028-138", load("OneObject-i1028-138.hdf5.dat")),
    ];
    let tol = 1e-8;
    for (name, p) in &problems {
        let (base, _) = run(p, Rescaling::Scalar, tol);
        assert!(base.converged(), "{name}: {base:?}");
        for alpha in SCALES {
            for beta in SCALES {
                let ps = scaled(p, alpha, beta);
                let (rep, r) = run(&ps, Rescaling::Scalar, tol);
                assert!(rep.converged(), "{name} alpha {alpha} beta {beta}: {rep:?}");
                assert!(r.iter().all(|v| v.is_finite()));
                // Same rescaled problem up to rounding: same iterations within a few, and the
                // same relative error within rounding of the error itself.
                let di = rep.iterations.abs_diff(base.iterations);
                assert!(
                    di <= 2 + base.iterations / 50,
                    "{name} alpha {alpha} beta {beta}: {} vs {} iterations",
                    rep.iterations,
                    base.iterations
                );
                assert!(
                    rep.error <= tol && (rep.error - base.error).abs() <= 0.5 * tol,
                    "{name} alpha {alpha} beta {beta}: {:e} vs {:e}",
                    rep.error,
                    base.error
                );
            }
        }
    }
}

#[test]
fn rescaling_none_is_the_plain_solve() {
    let p = load("Confeti-ex13-Fc3D-SBM.dat");
    let (a, ra) = run(&p, Rescaling::None, 1e-8);
    let config = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(1e-8)
        .with_max_iter(20_000);
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let b = fc3d_core::solve(&p, &config, &mut r, &mut u).unwrap();
    assert_eq!(a, b);
    assert_eq!(ra, r);
}
