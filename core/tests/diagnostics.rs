//! "Why did this step not converge": the per-contact diagnostics point at the contacts that
//! make a solve fail.

use fc3d_core::scenes::default_scenes;
use fc3d_core::{
    diagnose, solve, ContactStatus, Delassus, DenseMatrix, DiagnosticOptions, FrictionProblem,
    NsgsOptions, SolverConfig,
};

/// Contact 0: a sphere on a plane (solvable). Contact 1: frictionless, `W_NN = 0`, pushed in by
/// q: no reaction can stop it (`u_N = q_N < 0` whatever `r_N`), the problem has no solution.
#[test]
fn a_frictionless_contact_with_zero_normal_stiffness_is_the_worst_and_penetrates() {
    let n = 6;
    let mut data = vec![0.0; n * n];
    for (i, v) in [1.0, 3.5, 3.5, 0.0, 1.0, 1.0].into_iter().enumerate() {
        data[i + i * n] = v;
    }
    let w = Delassus::Dense(DenseMatrix::new(n, n, data).unwrap());
    let p = FrictionProblem::new(w, vec![-1.0, 0.2, 0.0, -0.5, 0.0, 0.0], vec![0.5, 0.0]).unwrap();
    let config = SolverConfig::new(NsgsOptions::default()).with_max_iter(50);
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let report = solve(&p, &config, &mut r, &mut u).unwrap();
    assert!(!report.converged(), "{report:?}");
    let d = diagnose(&p, &r, &DiagnosticOptions::default()).unwrap();
    assert_eq!(d.worst(1), vec![1]);
    let bad = d.contacts[1];
    assert_eq!(bad.normal_velocity, -0.5, "penetrating at q_N");
    assert!(bad.error_contribution > 100.0 * d.contacts[0].error_contribution);
    assert_eq!(d.contacts[0].status, ContactStatus::Stick);
    assert!((d.error - report.error).abs() <= 1e-14);
}

/// A box resting on its 4 corners (12 contact rows for 6 degrees of freedom: hyperstatic, W
/// singular, the reactions not unique) next to an independent sphere. A few Gauss-Seidel sweeps
/// settle the sphere exactly; the error left is the box cluster's.
#[test]
fn the_error_left_sits_in_the_hyperstatic_cluster() {
    let boxed = default_scenes()
        .into_iter()
        .find(|s| s.name == "box_on_ground")
        .unwrap()
        .problem;
    let wb = boxed.w().to_dense();
    let nb = boxed.size();
    let n = nb + 3;
    let mut data = vec![0.0; n * n];
    for j in 0..nb {
        for i in 0..nb {
            data[i + j * n] = wb.get(i, j);
        }
    }
    for (k, v) in [1.0, 3.5, 3.5].into_iter().enumerate() {
        data[(nb + k) + (nb + k) * n] = v;
    }
    let mut q = boxed.q().to_vec();
    q.extend([-0.1, 0.05, 0.0]);
    let mut mu = boxed.mu().to_vec();
    mu.push(0.5);
    let w = Delassus::Dense(DenseMatrix::new(n, n, data).unwrap());
    let p = FrictionProblem::new(w, q, mu).unwrap();
    let config = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(1e-12)
        .with_max_iter(3);
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let report = solve(&p, &config, &mut r, &mut u).unwrap();
    assert!(!report.converged(), "{report:?}");
    let d = diagnose(&p, &r, &DiagnosticOptions::default()).unwrap();
    let sphere = p.n_contacts() - 1;
    let mut worst = d.worst(4);
    worst.sort_unstable();
    assert_eq!(worst, vec![0, 1, 2, 3], "{:?}", d.contacts);
    assert!(d.contacts[sphere].error_contribution < 1e-14);
    assert_eq!(d.contacts[sphere].status, ContactStatus::Stick);
}
