//! Helpers shared by the tests of the optimization-based solvers (TFP, PFP, ACLMFP, SOCLCP):
//! problems in the three storages, an independent error measure, single-contact problems.
#![allow(dead_code)]

use fc3d_core::{Delassus, DenseMatrix, FrictionProblem, SolveReport, SolverConfig};

pub const DATA: &str = "../../shared/data/siconos";

pub fn load(name: &str) -> FrictionProblem<'static> {
    fc3d_core::io::read_problem_file(std::path::Path::new(&format!("{DATA}/{name}")))
        .expect("shared problem")
}

/// (label, problem) in dense, sparse-block and CSR storage: a dense file, a sparse-block file,
/// and the sparse-block file converted to CSR.
pub fn storages() -> Vec<(&'static str, FrictionProblem<'static>)> {
    let dense = load("Rover1039.dat");
    assert_eq!(dense.w().storage_name(), "dense");
    let sbm = load("Confeti-ex03-Fc3D-SBM.dat");
    assert_eq!(sbm.w().storage_name(), "sparse-block");
    let csr = sbm.with_w(Delassus::Sparse(sbm.w().to_csr())).unwrap();
    vec![("dense", dense), ("sparse-block", sbm), ("csr", csr)]
}

pub fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The natural-map error recomputed entry by entry (De Saxcé velocity, projection on the cone
/// written from its dot-product form), independent of the crate's `natural_map_error`.
pub fn independent_error(p: &FrictionProblem<'_>, r: &[f64]) -> f64 {
    let mut u = p.q().to_vec();
    p.w().for_each_entry(|i, j, v| u[i] += v * r[j]);
    let mut sum = 0.0;
    for (c, &mu) in p.mu().iter().enumerate() {
        let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
        let ut = (uc[1] * uc[1] + uc[2] * uc[2]).sqrt();
        let x = [rc[0] - (uc[0] + mu * ut), rc[1] - uc[1], rc[2] - uc[2]];
        let nt = (x[1] * x[1] + x[2] * x[2]).sqrt();
        let pr = if x[0] >= 0.0 && nt <= mu * x[0] {
            x
        } else if mu * nt <= -x[0] {
            [0.0; 3]
        } else {
            let s = 1.0 / (1.0 + mu * mu).sqrt();
            let d = [s, s * mu * x[1] / nt, s * mu * x[2] / nt];
            let t = x[0] * d[0] + x[1] * d[1] + x[2] * d[2];
            [t * d[0], t * d[1], t * d[2]]
        };
        sum += (0..3).map(|i| (rc[i] - pr[i]).powi(2)).sum::<f64>();
    }
    let scale = norm(p.q()).max(norm(r)).max(norm(&u));
    sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }
}

/// Solves from r = 0 and checks what every result must satisfy: finite r and u, u = W r + q,
/// and a reported error equal to the independent one.
pub fn run(p: &FrictionProblem<'_>, c: &SolverConfig) -> (SolveReport, Vec<f64>, Vec<f64>) {
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let report = fc3d_core::solve(p, c, &mut r, &mut u).expect("valid problem");
    assert!(r.iter().chain(&u).all(|v| v.is_finite()));
    let e = independent_error(p, &r);
    approx::assert_relative_eq!(report.error, e, max_relative = 1e-6, epsilon = 1e-15);
    (report, r, u)
}

/// One contact with W = [[1, 0.1, 0], [0.1, 1, 0], [0, 0, 1]] (symmetric positive definite).
pub fn one_contact(q: [f64; 3], mu: f64) -> FrictionProblem<'static> {
    let w = DenseMatrix::new(3, 3, vec![1.0, 0.1, 0.0, 0.1, 1.0, 0.0, 0.0, 0.0, 1.0]).unwrap();
    FrictionProblem::new(Delassus::Dense(w), q.to_vec(), vec![mu]).unwrap()
}

/// Two uncoupled contacts, W = I: contact 0 with `q0`, contact 1 taking off (q = (1, 3, 0)).
pub fn two_contacts(q0: [f64; 3], mu: f64) -> FrictionProblem<'static> {
    two_contacts_with(q0, [1.0, 3.0, 0.0], mu)
}

/// Two uncoupled contacts, W = I, with `q0` and `q1`.
pub fn two_contacts_with(q0: [f64; 3], q1: [f64; 3], mu: f64) -> FrictionProblem<'static> {
    let mut w = vec![0.0; 36];
    for i in 0..6 {
        w[i * 6 + i] = 1.0;
    }
    let w = DenseMatrix::new(6, 6, w).unwrap();
    let q = vec![q0[0], q0[1], q0[2], q1[0], q1[1], q1[2]];
    FrictionProblem::new(Delassus::Dense(w), q, vec![mu, mu]).unwrap()
}

/// Checks the analytic single-contact cases on `two_contacts` (W = I, mu = 0.5): stick
/// (q0 = (-1, 0.2, -0.1): r0 = -q0, u0 = 0), slide (q0 = (-1, 2, 0): r0 = (1, -0.5, 0), u0 =
/// (0, 1.5, 0)), and the take-off contact 1 (r1 = 0) in both.
pub fn check_analytic(make: impl Fn(f64) -> SolverConfig) {
    let c = make(1e-12);
    let (rep, r, _) = run(&two_contacts([-1.0, 0.2, -0.1], 0.5), &c);
    assert!(rep.converged(), "{rep:?}");
    for (a, b) in r.iter().zip([1.0, -0.2, 0.1, 0.0, 0.0, 0.0]) {
        approx::assert_abs_diff_eq!(*a, b, epsilon = 1e-10);
    }
    let (rep, r, u) = run(&two_contacts([-1.0, 2.0, 0.0], 0.5), &c);
    assert!(rep.converged(), "{rep:?}");
    for (a, b) in r.iter().zip([1.0, -0.5, 0.0, 0.0, 0.0, 0.0]) {
        approx::assert_abs_diff_eq!(*a, b, epsilon = 1e-10);
    }
    approx::assert_abs_diff_eq!(u[0], 0.0, epsilon = 1e-10);
    approx::assert_abs_diff_eq!(u[1], 1.5, epsilon = 1e-10);
    // A coupled single contact: the slide direction is opposite to u_T.
    let (rep, r, u) = run(&one_contact([-1.0, 3.0, 1.0], 0.3), &c);
    assert!(rep.converged(), "{rep:?}");
    let (nt, nu) = (
        (r[1] * r[1] + r[2] * r[2]).sqrt(),
        (u[1] * u[1] + u[2] * u[2]).sqrt(),
    );
    approx::assert_relative_eq!(nt, 0.3 * r[0], max_relative = 1e-9);
    approx::assert_relative_eq!(r[1] / nt, -u[1] / nu, epsilon = 1e-9);
    approx::assert_relative_eq!(r[2] / nt, -u[2] / nu, epsilon = 1e-9);
}
