//! One-contact solvers against answers derived by hand.
//!
//! Notation: `u = w r + q`, `r = (r_N, r_T)`, `K = {||r_T|| <= mu r_N}`.
//!
//! * Take-off (`q_N > 0`): `r = 0`, `u = q` (with r = 0, `u_N = q_N > 0` and `ũ ∈ int K*`).
//! * Diagonal `w = diag(a, b, b)`, `q_N < 0`: contact is closed, `u_N = a r_N + q_N = 0` gives
//!   `r_N = -q_N / a`. Stick needs `u_T = b r_T + q_T = 0`, i.e. `r_T = -q_T / b`, admissible iff
//!   `||q_T|| <= mu b r_N`. Otherwise slide: `r_T = -mu r_N q_T/||q_T||` (opposite to the sliding
//!   velocity) and `u_T = q_T + b r_T = (1 - mu b r_N / ||q_T||) q_T`, a positive multiple of `q_T`.
//! * mu = 0: `r_T = 0`, `r_N = max(0, -q_N / w_NN)`, whatever the off-diagonal entries.
//!
//! The one-step solvers (552, 557) do one projection per call; they are called repeatedly, as
//! NSGS does on a one-contact problem. Their step `rho = 1 / w_NN` is used on all three components
//! (as in Siconos), so the tangential stick iteration `r_T <- r_T - (w_TT r_T + q_T) / w_NN`
//! contracts only when `w_TT < 2 w_NN`: the diagonal cases below respect that, and
//! [`one_step_solvers_cannot_stick_when_tangent_is_stiffer_than_twice_normal`] documents the rest.

use super::*;
use crate::local::{LocalSolverKind, LocalSolverOptions};
use crate::math::linalg::{mat3_vec_add, norm3};
use approx::assert_relative_eq;
use proptest::prelude::*;

const EYE: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn is_one_step(kind: LocalSolverKind) -> bool {
    matches!(
        kind,
        LocalSolverKind::ProjectionOnCone
            | LocalSolverKind::ProjectionOnCylinder
            | LocalSolverKind::ProjectionOnConeWithRegularization
            | LocalSolverKind::ProjectionOnConeWithDiagonalization
            | LocalSolverKind::ProjectionOnConeVelocity
    )
}

/// Solves from `start` with solver `kind` (default options). Newton and locally iterated solvers
/// get one call, the one-step solvers up to 10000 calls until a call reports convergence (a
/// fixed point). Returns r and the number of calls.
fn solve_local(kind: LocalSolverKind, w: &Mat3, q: Vec3, mu: f64, start: Vec3) -> (Vec3, usize) {
    // Every solver at 1e-14: the answers are compared to 1e-11 on contacts with W as small as
    // 0.05, where 561's and 562's default 1e-12 residual allows a larger error in r.
    let mut options = LocalSolverOptions::new(kind);
    options.tolerance = options.tolerance.min(1e-14);
    match kind {
        // Siconos' 553 (the default variant) compares the squared absolute residual, its Newton
        // `||F||^2 / (2 ||q||)`.
        LocalSolverKind::ProjectionOnConeWithLocalIteration => options.tolerance = 1e-28,
        LocalSolverKind::NewtonAlartCurnier
        | LocalSolverKind::NewtonAlartCurnierGp
        | LocalSolverKind::NewtonHybrid => options.tolerance = 1e-24,
        _ => {}
    }
    let mut solver = AnyLocalSolver::new(&options);
    let p = LocalProblem { w, q, mu };
    let mut r = start;
    let max_calls = if is_one_step(kind) { 10_000 } else { 1 };
    for call in 1..=max_calls {
        let out = solver.solve(&p, &mut r);
        if out.converged {
            return (r, call);
        }
    }
    (r, max_calls)
}

/// Asserts that every local solver, from each start, finds `r_expected` (and `u = w r + q`
/// equals `u_expected`) to `tol` relative to the problem scale.
fn check_all(w: &Mat3, q: Vec3, mu: f64, r_expected: Vec3, u_expected: Vec3, tol: f64) {
    let starts = [[0.0; 3], [1.0, 0.3, -0.2], r_expected];
    let scale = norm3(&q).max(norm3(&r_expected)).max(1.0);
    for kind in LocalSolverKind::ALL {
        for start in starts {
            let (r, calls) = solve_local(kind, w, q, mu, start);
            let u = mat3_vec_add(w, &r, &q);
            for i in 0..3 {
                assert!(
                    (r[i] - r_expected[i]).abs() <= tol * scale
                        && (u[i] - u_expected[i]).abs() <= tol * scale,
                    "{kind:?} from {start:?}: r = {r:?}, u = {u:?}, expected {r_expected:?}, {u_expected:?}"
                );
            }
            let p = LocalProblem { w, q, mu };
            assert!(
                p.residual(&r) <= tol * scale,
                "{kind:?} from {start:?}: residual {} after {calls} calls",
                p.residual(&r)
            );
        }
    }
}

#[test]
fn take_off() {
    // r = 0, u = q, for several W including a coupled one and for mu = 0.
    let coupled = [[2.0, 0.3, -0.1], [0.3, 1.5, 0.2], [-0.1, 0.2, 1.0]];
    for (w, q, mu) in [
        (EYE, [1.0, 2.0, -1.0], 0.5),
        (coupled, [0.5, -3.0, 0.1], 0.8),
        (coupled, [1e-3, 0.0, 0.0], 0.0),
    ] {
        check_all(&w, q, mu, [0.0; 3], q, 1e-12);
    }
}

#[test]
fn stick_identity() {
    // W = I, q = (-1, 0.1, 0), mu = 0.5: r = -q = (1, -0.1, 0) is inside K (0.1 <= 0.5), u = 0.
    check_all(
        &EYE,
        [-1.0, 0.1, 0.0],
        0.5,
        [1.0, -0.1, 0.0],
        [0.0; 3],
        1e-12,
    );
}

#[test]
fn slide_identity() {
    // W = I, q = (-1, 2, 0), mu = 0.5: r_N = 1; stick would need ||r_T|| = 2 > 0.5, so slide:
    // r_T = -0.5 (1, 0), u_T = 2 - 0.5 = 1.5 along +t1, u_N = 0.
    check_all(
        &EYE,
        [-1.0, 2.0, 0.0],
        0.5,
        [1.0, -0.5, 0.0],
        [0.0, 1.5, 0.0],
        1e-12,
    );
}

/// The closed form for `w = diag(a, b, b)`, `q_N < 0` (see the module doc).
fn diagonal_answer(a: f64, b: f64, q: Vec3, mu: f64) -> (Vec3, Vec3) {
    let rn = -q[0] / a;
    let nqt = q[1].hypot(q[2]);
    if nqt <= mu * b * rn {
        ([rn, -q[1] / b, -q[2] / b], [0.0; 3])
    } else {
        let s = mu * rn / nqt;
        let k = 1.0 - mu * b * rn / nqt;
        ([rn, -s * q[1], -s * q[2]], [0.0, k * q[1], k * q[2]])
    }
}

#[test]
fn diagonal_closed_form_by_hand() {
    // a = 2, b = 3, q = (-4, 3, 4), mu = 0.5: r_N = 2, ||q_T|| = 5 > mu b r_N = 3, slide:
    // r_T = -0.5 * 2 * (3, 4)/5 = (-0.6, -0.8), u_T = (1 - 3/5) (3, 4) = (1.2, 1.6).
    let (r, u) = diagonal_answer(2.0, 3.0, [-4.0, 3.0, 4.0], 0.5);
    for (x, y) in r.iter().zip([2.0, -0.6, -0.8]) {
        assert_relative_eq!(*x, y, epsilon = 1e-15);
    }
    for (x, y) in u.iter().zip([0.0, 1.2, 1.6]) {
        assert_relative_eq!(*x, y, epsilon = 1e-15);
    }
    // Same with mu = 1: mu b r_N = 6 >= 5, stick: r_T = -(3, 4)/3, u = 0.
    let (r, u) = diagonal_answer(2.0, 3.0, [-4.0, 3.0, 4.0], 1.0);
    assert_relative_eq!(r[1], -1.0, epsilon = 1e-15);
    assert_relative_eq!(r[2], -4.0 / 3.0, epsilon = 1e-15);
    assert_eq!(u, [0.0; 3]);
}

#[test]
fn diagonal_stick_and_slide() {
    // b < 2a so that the one-step solvers contract (module doc).
    for (a, b) in [
        (1.0, 1.0),
        (2.0, 3.0),
        (1.0, 0.25),
        (10.0, 15.0),
        (0.1, 0.05),
    ] {
        for q in [
            [-1.0, 0.1, 0.0],
            [-1.0, 2.0, 0.0],
            [-4.0, 3.0, 4.0],
            [-0.5, -0.2, 0.7],
            [-2.0, 0.0, 0.0],
        ] {
            for mu in [0.1, 0.5, 1.0, 2.0] {
                let w = [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, b]];
                let (r, u) = diagonal_answer(a, b, q, mu);
                check_all(&w, q, mu, r, u, 1e-11);
            }
        }
    }
}

#[test]
fn frictionless() {
    // mu = 0: r_T = 0 and r_N = -q_N / w_NN (u_N = 0) whatever the coupling; u = w r + q.
    let w = [[2.0, 0.3, -0.1], [0.3, 1.5, 0.2], [-0.1, 0.2, 1.0]];
    for q in [[-1.0, 0.5, -0.3], [-3.0, 10.0, 0.0], [-0.2, 0.0, 0.0]] {
        let r = [-q[0] / 2.0, 0.0, 0.0];
        let u = mat3_vec_add(&w, &r, &q);
        assert_relative_eq!(u[0], 0.0, epsilon = 1e-15);
        check_all(&w, q, 0.0, r, u, 1e-12);
    }
}

/// A non-symmetric w with positive definite symmetric part
/// `[[2, 0.1, 0.05], [0.1, 1, 0], [0.05, 0, 1.5]]`.
const W_NONSYM: Mat3 = [[2.0, 0.5, 0.0], [-0.3, 1.0, 0.2], [0.1, -0.2, 1.5]];

#[test]
fn non_symmetric_stick() {
    // Choose r = (1, 0.2, -0.1) inside K(0.5) (||r_T|| = 0.224) and q = -W r so that u = 0:
    // W r = (2 + 0.1 + 0, -0.3 + 0.2 - 0.02, 0.1 - 0.04 - 0.15) = (2.1, -0.12, -0.09).
    check_all(
        &W_NONSYM,
        [-2.1, 0.12, 0.09],
        0.5,
        [1.0, 0.2, -0.1],
        [0.0; 3],
        1e-12,
    );
}

#[test]
fn non_symmetric_slide() {
    // Choose a sliding solution: r_N = 1, mu = 0.4, slip along +t1 with speed 0.7:
    // r = (1, -0.4, 0), u = (0, 0.7, 0). Then W r = (2 - 0.2, -0.3 - 0.4, 0.1 + 0.08)
    // = (1.8, -0.7, 0.18) and q = u - W r = (-1.8, 1.4, -0.18).
    check_all(
        &W_NONSYM,
        [-1.8, 1.4, -0.18],
        0.4,
        [1.0, -0.4, 0.0],
        [0.0, 0.7, 0.0],
        1e-11,
    );
}

#[test]
fn one_step_solvers_cannot_stick_when_tangent_is_stiffer_than_twice_normal() {
    // A sphere on a plane has w = diag(1/m, 3.5/m, 3.5/m). For a sticking contact with a
    // tangential load the tangential step multiplies the error by 1 - 3.5 = -2.5: the iterates of
    // 552 and 557 jump between the two sides of the cone and never settle, while the Newton and
    // the self-adaptive projection (553) solvers find r = (1, -0.1/3.5, 0), u = 0.
    let w = [[1.0, 0.0, 0.0], [0.0, 3.5, 0.0], [0.0, 0.0, 3.5]];
    let q = [-1.0, 0.1, 0.0];
    let expected = [1.0, -0.1 / 3.5, 0.0];
    for kind in LocalSolverKind::ALL {
        let (r, _) = solve_local(kind, &w, q, 0.5, [0.0; 3]);
        let p = LocalProblem { w: &w, q, mu: 0.5 };
        if kind == LocalSolverKind::ProjectionOnConeWithDiagonalization {
            // Its tangential step is 1 / W_TT, not 1 / W_NN: it sticks.
            for i in 0..3 {
                assert_relative_eq!(r[i], expected[i], epsilon = 1e-12);
            }
        } else if is_one_step(kind) {
            assert!(p.residual(&r) > 1e-3, "{kind:?} unexpectedly converged");
            assert!(r.iter().all(|v| v.is_finite()));
            // Bounded by the cone all the same.
            assert!(r[1].hypot(r[2]) <= 0.5 * r[0] * (1.0 + 1e-12));
        } else {
            for i in 0..3 {
                assert_relative_eq!(r[i], expected[i], epsilon = 1e-12);
            }
        }
    }
}

#[test]
fn local_rho_rules() {
    let w = [[2.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, 1.0]];
    assert_eq!(local_rho(&w, RhoRule::Constant(0.3)), (0.3, 0.3));
    assert_eq!(local_rho(&w, RhoRule::SpectralNorm), (0.25, 0.25));
    assert_eq!(local_rho(&w, RhoRule::SplitSpectralNorm), (0.5, 0.25));
    // lambda_min(W_TT) / lambda_max(W_TT)^2 = 1 / 16.
    assert_eq!(
        local_rho(&w, RhoRule::SplitSpectralNormCond),
        (0.5, 1.0 / 16.0)
    );
    // A zero block falls back to 1.
    assert_eq!(
        local_rho(&[[0.0; 3]; 3], RhoRule::SplitSpectralNorm),
        (1.0, 1.0)
    );
}

#[test]
fn alart_curnier_function_vanishes_at_solutions() {
    // F(r) = 0 exactly at the Coulomb solutions above, for any rho > 0.
    let cases: [(Mat3, Vec3, f64, Vec3); 4] = [
        (EYE, [-1.0, 0.1, 0.0], 0.5, [1.0, -0.1, 0.0]),
        (EYE, [-1.0, 2.0, 0.0], 0.5, [1.0, -0.5, 0.0]),
        (EYE, [1.0, 2.0, 0.0], 0.5, [0.0; 3]),
        (W_NONSYM, [-1.8, 1.4, -0.18], 0.4, [1.0, -0.4, 0.0]),
    ];
    for (w, q, mu, r) in cases {
        let p = LocalProblem { w: &w, q, mu };
        for (rn, rt) in [(1.0, 1.0), (0.3, 2.0), (5.0, 0.1)] {
            let (f, _) = alart_curnier_function(&p, rn, rt, &r);
            assert!(norm3(&f) <= 1e-14, "F = {f:?} at {r:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Property tests.

/// Rotation matrix of the unit quaternion along `v` (|v| > 0).
fn rotation(v: [f64; 4]) -> Mat3 {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]).sqrt();
    let [w, x, y, z] = [v[0] / n, v[1] / n, v[2] / n, v[3] / n];
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// `Q diag(l) Q^T` with Q the rotation of `quat`.
fn spd(quat: [f64; 4], l: Vec3) -> Mat3 {
    let q = rotation(quat);
    let mut w = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            w[i][j] = (0..3).map(|k| q[i][k] * l[k] * q[j][k]).sum();
        }
    }
    w
}

fn quaternion() -> impl Strategy<Value = [f64; 4]> {
    prop::array::uniform4(-1.0f64..1.0).prop_filter("non-degenerate quaternion", |v| {
        v.iter().map(|x| x * x).sum::<f64>() > 0.01
    })
}

/// Random SPD 3x3 with eigenvalues in [0.1, 10].
fn spd_matrix() -> impl Strategy<Value = Mat3> {
    (quaternion(), prop::array::uniform3(0.1f64..10.0)).prop_map(|(q, l)| spd(q, l))
}

/// Brute-force largest eigenvalue of the symmetric part: Jacobi rotations until the
/// off-diagonal part vanishes.
fn jacobi_lambda_max(w: &Mat3) -> f64 {
    let mut a = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            a[i][j] = 0.5 * (w[i][j] + w[j][i]);
        }
    }
    for _ in 0..100 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = 0.5 * (2.0 * a[p][q]).atan2(a[q][q] - a[p][p]);
            let (s, c) = theta.sin_cos();
            // a <- J^T a J with J the rotation in the (p, q) plane.
            let mut b = a;
            for k in 0..3 {
                b[k][p] = c * a[k][p] - s * a[k][q];
                b[k][q] = s * a[k][p] + c * a[k][q];
            }
            let mut d = b;
            for k in 0..3 {
                d[p][k] = c * b[p][k] - s * b[q][k];
                d[q][k] = s * b[p][k] + c * b[q][k];
            }
            a = d;
        }
    }
    a[0][0].max(a[1][1]).max(a[2][2])
}

#[test]
fn lambda_max_sym3_special_cases() {
    assert_eq!(lambda_max_sym3(&EYE), 1.0);
    assert_eq!(
        lambda_max_sym3(&[[1.0, 0.0, 0.0], [0.0, -2.0, 0.0], [0.0, 0.0, 0.5]]),
        1.0
    );
    // [[2, 1, 0], [1, 2, 0], [0, 0, 1]]: eigenvalues 3, 1, 1.
    assert_relative_eq!(
        lambda_max_sym3(&[[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 1.0]]),
        3.0,
        epsilon = 1e-14
    );
    // Skew part ignored: [[1, 2, 0], [-2, 1, 0], [0, 0, 0.5]] has symmetric part diag(1, 1, 0.5).
    assert_relative_eq!(
        lambda_max_sym3(&[[1.0, 2.0, 0.0], [-2.0, 1.0, 0.0], [0.0, 0.0, 0.5]]),
        1.0,
        epsilon = 1e-15
    );
    // All ones: eigenvalues 3, 0, 0.
    assert_relative_eq!(lambda_max_sym3(&[[1.0; 3]; 3]), 3.0, epsilon = 1e-14);
}

/// Max of `x^T A x / x^T x` over a grid of unit vectors (a lower bound of lambda_max).
fn sampled_rayleigh_max(w: &Mat3) -> f64 {
    let mut best = f64::NEG_INFINITY;
    let n = 60;
    for i in 0..=n {
        let th = std::f64::consts::PI * f64::from(i) / f64::from(n);
        for j in 0..2 * n {
            let ph = std::f64::consts::PI * f64::from(j) / f64::from(n);
            let x = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
            let wx = crate::math::linalg::mat3_vec(w, &x);
            best = best.max(crate::math::linalg::dot3(&x, &wx));
        }
    }
    best
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// lambda_max_sym3 equals the Jacobi eigenvalue of the symmetric part, bounds every
    /// sampled Rayleigh quotient, and is close to the best of them.
    #[test]
    fn lambda_max_sym3_matches_brute_force(m in prop::array::uniform3(prop::array::uniform3(-5.0f64..5.0))) {
        let l = lambda_max_sym3(&m);
        let scale = m.iter().flatten().fold(1e-300f64, |a, v| a.max(v.abs()));
        let jac = jacobi_lambda_max(&m);
        prop_assert!((l - jac).abs() <= 1e-10 * scale, "closed form {l}, Jacobi {jac}");
        let sampled = sampled_rayleigh_max(&m);
        prop_assert!(sampled <= l + 1e-12 * scale);
        prop_assert!(l - sampled <= 1e-2 * scale, "closed form {l}, sampled {sampled}");
    }

    /// On SPD matrices (eigenvalues in [0.1, 10]). The trigonometric closed form loses a few
    /// digits when the two largest eigenvalues nearly coincide (2.4e-12 relative seen in 50000
    /// cases), hence 1e-10; rho only needs a couple of digits.
    #[test]
    fn lambda_max_sym3_on_spd(w in spd_matrix()) {
        let l = lambda_max_sym3(&w);
        prop_assert!((l - jacobi_lambda_max(&w)).abs() <= 1e-10 * l);
    }

    /// Away from the switching surfaces (s_N = 0, ||s_T|| = R, s_T = 0) F is smooth and the
    /// Jacobian returned by `alart_curnier_function` is its derivative.
    #[test]
    fn alart_curnier_jacobian_matches_finite_differences(
        sym in spd_matrix(),
        skew in prop::array::uniform3(-0.05f64..0.05),
        q in prop::array::uniform3(-2.0f64..2.0),
        r in prop::array::uniform3(-2.0f64..2.0),
        mu in 0.0f64..2.0,
        rule in 0usize..3,
    ) {
        let mut w = sym;
        // + small skew-symmetric part: non-symmetric W as in real problems.
        w[0][1] += skew[2]; w[1][0] -= skew[2];
        w[0][2] -= skew[1]; w[2][0] += skew[1];
        w[1][2] += skew[0]; w[2][1] -= skew[0];
        let rule = [RhoRule::SplitSpectralNorm, RhoRule::SplitSpectralNormCond, RhoRule::SpectralNorm][rule];
        let (rho_n, rho_t) = local_rho(&w, rule);
        let p = LocalProblem { w: &w, q, mu };

        // Distance to the switching surfaces, in the variables where they are defined.
        let u = p.velocity(&r);
        let s_n = r[0] - rho_n * u[0];
        let s_t = [r[1] - rho_t * u[1], r[2] - rho_t * u[2]];
        let ns = s_t[0].hypot(s_t[1]);
        let radius = mu * s_n.max(0.0);
        let delta = 1e-3;
        prop_assume!(s_n.abs() > delta && ns > delta && (ns - radius).abs() > delta);

        let (_, jac) = alart_curnier_function(&p, rho_n, rho_t, &r);
        let h = 1e-6;
        for j in 0..3 {
            let mut rp = r;
            let mut rm = r;
            rp[j] += h;
            rm[j] -= h;
            let (fp, _) = alart_curnier_function(&p, rho_n, rho_t, &rp);
            let (fm, _) = alart_curnier_function(&p, rho_n, rho_t, &rm);
            for i in 0..3 {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                prop_assert!(
                    (fd - jac[i][j]).abs() <= 1e-6 * (1.0 + jac[i][j].abs()),
                    "J[{i}][{j}] = {} but finite difference {fd}", jac[i][j]
                );
            }
        }
    }

}

/// Fixed-seed proptest configuration for the convergence properties: they hold on the fixed
/// sample (and on 20000 cases of a second sample but one, see
/// [`hybrid_default_budget_can_be_too_short`]), so a random seed would make them flaky.
fn fixed_seed(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5eed_fc3d),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Solves `p` from r = 0 with `kind` (default options), calling the solver up to `max_calls`
/// times as NSGS would on a one-contact problem; true when the natural-map residual reaches
/// `1e-10 * scale`.
fn newton_reaches(kind: LocalSolverKind, p: &LocalProblem<'_>, max_calls: usize) -> bool {
    let mut solver = AnyLocalSolver::new(&LocalSolverOptions::new(kind));
    let mut r = [0.0; 3];
    for _ in 0..max_calls {
        solver.solve(p, &mut r);
        if p.residual(&r) <= 1e-10 * p.scale(&r) {
            return true;
        }
    }
    false
}

proptest! {
    #![proptest_config(fixed_seed(512))]

    /// The hybrid Newton solver (565, Siconos' default) solves random SPD one-contact problems
    /// (eigenvalues in [0.1, 10], q in [-10, 10]^3, mu in [0, 2]) to 1e-10 of the local scale in
    /// one call from r = 0.
    #[test]
    fn hybrid_newton_reaches_tight_residual(
        w in spd_matrix(),
        q in prop::array::uniform3(-10.0f64..10.0),
        mu in 0.0f64..2.0,
    ) {
        let p = LocalProblem { w: &w, q, mu };
        prop_assert!(newton_reaches(LocalSolverKind::NewtonHybrid, &p, 1));
    }
}

/// The same sample for the plain (550) and line-search (551) Newton solvers, which are not
/// globally convergent: 550 cycles on some problems ([`plain_newton_can_cycle`]) and 551 can stop
/// at a kink of the merit function ([`line_search_newton_can_stall_at_a_kink`]). Measured on
/// 20000 cases: 550 fails on 392 (2.0 %), 551 on 48 (0.24 %), 565 on 1; repeated calls do not help
/// (the solvers restart from the same point). The bounds below are those rates with margin.
#[test]
fn plain_and_line_search_newton_failure_rates() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let strategy = (
        spd_matrix(),
        prop::array::uniform3(-10.0f64..10.0),
        0.0f64..2.0,
    );
    let n = 2000;
    let mut failures = [0usize; 3];
    let kinds = [
        LocalSolverKind::NewtonAlartCurnier,
        LocalSolverKind::NewtonAlartCurnierGp,
        LocalSolverKind::NewtonHybrid,
    ];
    for _ in 0..n {
        let (w, q, mu) = strategy.new_tree(&mut runner).unwrap().current();
        let p = LocalProblem { w: &w, q, mu };
        for (k, kind) in kinds.iter().enumerate() {
            if !newton_reaches(*kind, &p, 20) {
                failures[k] += 1;
            }
        }
    }
    eprintln!("failures out of {n} (550, 551, 565): {failures:?}");
    assert!(failures[0] <= n / 20, "550: {failures:?}");
    assert!(failures[1] <= n / 100, "551: {failures:?}");
    assert!(failures[2] <= 1, "565: {failures:?}");
}

/// Plain Newton (550) on this problem goes from r = 0 to the unconstrained solution
/// `r = -W^-1 q` (stick branch, rho-scaled W as Jacobian), where `r_N < 0` puts it on the
/// inactive branch with Jacobian I, whose step leads back to exactly r = 0: a 2-cycle. The
/// line-search (551) and hybrid (565) solvers find the solution.
#[test]
fn plain_newton_can_cycle() {
    let w = [
        [7.291370436448853, 1.752133447910275, 0.0],
        [1.752133447910275, 0.5268966042586344, 0.0],
        [0.0, 0.0, 4.318461488265054],
    ];
    let p = LocalProblem {
        w: &w,
        q: [-5.910430959023707, -6.571503120054419, 0.0],
        mu: 1.0930062391059865,
    };
    let mut solver = AnyLocalSolver::new(&LocalSolverOptions::new(
        LocalSolverKind::NewtonAlartCurnier,
    ));
    let mut r = [0.0; 3];
    let out = solver.solve(&p, &mut r);
    assert!(!out.converged);
    // 10 iterations = 5 round trips: back at the start.
    assert_eq!(r, [0.0; 3]);
    assert!(newton_reaches(LocalSolverKind::NewtonAlartCurnierGp, &p, 1));
    assert!(newton_reaches(LocalSolverKind::NewtonHybrid, &p, 1));
}

/// Newton with the Goldstein-Price search (551) reaches a point just across the switching
/// surface `s_N = 0` where the Newton direction of the inactive branch (-r) increases
/// `||F||^2` for every step the search tries (1, 1/2, ..., 1/512): it stops there, F != 0, and
/// later calls stop at once. The hybrid solver (565) leaves through the projection steps.
#[test]
fn line_search_newton_can_stall_at_a_kink() {
    let w = [
        [2.0003534852058054, -3.178900126940444, -0.8929145321705115],
        [-3.178900126940444, 5.417645425302321, 1.4936621748329115],
        [-0.8929145321705115, 1.4936621748329115, 0.519551608670814],
    ];
    let p = LocalProblem {
        w: &w,
        q: [-1.062874216230127, -4.025041205144657, 1.2410860721402235],
        mu: 1.3188284615455688,
    };
    // fc3d's variant: Siconos' takes the last trial of a failed search and moves on.
    let mut options = LocalSolverOptions::new(LocalSolverKind::NewtonAlartCurnierGp);
    options.variant = AlgorithmVariant::Fc3d;
    let mut solver = AnyLocalSolver::new(&options);
    let mut r = [0.0; 3];
    assert!(!solver.solve(&p, &mut r).converged);
    let stalled = r;
    assert!(p.residual(&r) > 0.1);
    let again = solver.solve(&p, &mut r);
    assert_eq!((again.converged, again.iterations, r), (false, 0, stalled));
    assert!(newton_reaches(LocalSolverKind::NewtonHybrid, &p, 1));
}

/// With Siconos' default budget (one round of at most 100 projection steps) the hybrid solver
/// cannot solve this stick problem, where the projection needs about 800 steps and Newton
/// fails from every point it is tried from; repeated calls restart from the same best point.
/// A second round, which continues the projection where the first left it, solves it.
#[test]
fn hybrid_default_budget_can_be_too_short() {
    let w = [
        [4.023020550233524, -3.296321619772585, 0.772944406917071],
        [-3.296321619772585, 4.782013482039486, 0.7940365484899029],
        [0.7729444069170708, 0.794036548489903, 2.9315906016959965],
    ];
    let p = LocalProblem {
        w: &w,
        q: [-0.5238498109044823, -1.9921729771996008, 9.494905628119952],
        mu: 1.712863834791536,
    };
    // fc3d's variant (Siconos' keeps or discards differently and restarts 553 from its rho).
    let mut options = LocalSolverOptions::new(LocalSolverKind::NewtonHybrid);
    options.variant = AlgorithmVariant::Fc3d;
    let mut solver = AnyLocalSolver::new(&options);
    let mut r = [0.0; 3];
    for _ in 0..20 {
        solver.solve(&p, &mut r);
        assert!(p.residual(&r) > 1e-10 * p.scale(&r));
    }
    options.hybrid_max_loop = 2;
    let mut r = [0.0; 3];
    let out = AnyLocalSolver::new(&options).solve(&p, &mut r);
    assert!(out.converged, "{out:?}");
    assert!(p.residual(&r) <= 1e-12 * p.scale(&r));
    // The solution sticks: u = 0 with r inside the cone.
    let u = p.velocity(&r);
    assert!(norm3(&u) <= 1e-12 * norm3(&r));
    assert!(r[1].hypot(r[2]) < p.mu * r[0]);
}

// ---------------------------------------------------------------------------------------------
// The solvers added beside 550-553/557/565: Jean-Moreau Newton, EBP, QUARTIC, Dumont's rho.

/// The Newton solvers with the Jean-Moreau formulation (59) on the hand-derived cases.
#[test]
fn jean_moreau_newton_solves_analytic_contacts() {
    let coupled = [[2.0, 0.3, -0.1], [0.3, 1.5, 0.2], [-0.1, 0.2, 1.0]];
    let mut cases: Vec<(Mat3, Vec3, f64, Vec3, Vec3)> = vec![
        (coupled, [0.5, -3.0, 0.1], 0.8, [0.0; 3], [0.5, -3.0, 0.1]),
        (EYE, [-1.0, 0.1, 0.0], 0.5, [1.0, -0.1, 0.0], [0.0; 3]),
        (
            EYE,
            [-1.0, 2.0, 0.0],
            0.5,
            [1.0, -0.5, 0.0],
            [0.0, 1.5, 0.0],
        ),
        (
            EYE,
            [-2.0, 3.0, -1.0],
            0.0,
            [2.0, 0.0, 0.0],
            [0.0, 3.0, -1.0],
        ),
    ];
    for (a, b) in [(2.0, 3.0), (1.0, 0.25), (0.1, 0.05)] {
        for q in [[-4.0, 3.0, 4.0], [-0.5, -0.2, 0.7]] {
            for mu in [0.1, 1.0] {
                let w = [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, b]];
                let (r, u) = diagonal_answer(a, b, q, mu);
                cases.push((w, q, mu, r, u));
            }
        }
    }
    for kind in [
        LocalSolverKind::NewtonAlartCurnier,
        LocalSolverKind::NewtonAlartCurnierGp,
        LocalSolverKind::NewtonHybrid,
    ] {
        let mut options = LocalSolverOptions::new(kind);
        options.formulation = crate::local::NewtonFormulation::JeanMoreau;
        for (w, q, mu, r_expected, u_expected) in &cases {
            let mut solver = AnyLocalSolver::new(&options);
            let p = LocalProblem { w, q: *q, mu: *mu };
            let mut r = [0.0; 3];
            let out = solver.solve(&p, &mut r);
            let u = mat3_vec_add(w, &r, q);
            let scale = norm3(q).max(norm3(r_expected)).max(1.0);
            assert!(out.converged, "{kind:?} JM on {w:?} {q:?} mu {mu}: {out:?}");
            for i in 0..3 {
                assert_relative_eq!(r[i], r_expected[i], epsilon = 1e-11 * scale);
                assert_relative_eq!(u[i], u_expected[i], epsilon = 1e-11 * scale);
            }
        }
    }
}

#[test]
fn jean_moreau_function_vanishes_at_solutions_only() {
    let w = [[2.0, 0.3, -0.1], [0.3, 1.5, 0.2], [-0.1, 0.2, 1.0]];
    let (a, b) = (2.0, 3.0);
    let wd = [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, b]];
    let q = [-4.0, 3.0, 4.0];
    let (r, _) = diagonal_answer(a, b, q, 0.5);
    let p = LocalProblem { w: &wd, q, mu: 0.5 };
    let (f, _) = jean_moreau_function(&p, 0.5, 0.3, &r);
    assert!(norm3(&f) <= 1e-14, "{f:?}");
    // Off the solution F does not vanish.
    let (f, _) = jean_moreau_function(&p, 0.5, 0.3, &[1.0, 0.0, 0.0]);
    assert!(norm3(&f) > 1e-3);
    let p = LocalProblem {
        w: &w,
        q: [1.0, 0.2, 0.0],
        mu: 0.5,
    };
    let (f, _) = jean_moreau_function(&p, 0.5, 0.5, &[0.0; 3]);
    assert!(norm3(&f) == 0.0, "take-off: {f:?}");
}

#[test]
fn dumont_rho_rule_is_alpha_over_w_nn() {
    let w = [[4.0, 0.3, 0.0], [0.3, 9.0, 0.0], [0.0, 0.0, 1.0]];
    assert_eq!(local_rho(&w, RhoRule::Dumont(1.0)), (0.25, 0.25));
    assert_eq!(local_rho(&w, RhoRule::Dumont(2.0)), (0.5, 0.5));
    // Degenerate blocks fall back like the other rules.
    let z = [[0.0; 3]; 3];
    assert_eq!(local_rho(&z, RhoRule::Dumont(1.0)), (1.0, 1.0));
    assert_eq!(
        LocalSolverOptions::new(LocalSolverKind::EnhancedBipotential).rho_rule,
        RhoRule::Dumont(1.0)
    );
}

/// EAL is the Alart-Curnier Newton (fc3d's variant): on a contact both give the same iterates.
#[test]
fn eal_is_plain_alart_curnier_newton_with_dumont_rho() {
    let w = [[2.0, 0.3, -0.1], [0.25, 1.5, 0.2], [-0.1, 0.2, 1.0]];
    let q = [-1.0, 0.7, -0.4];
    let p = LocalProblem { w: &w, q, mu: 0.4 };
    let mut eal = AnyLocalSolver::new(&LocalSolverOptions::new(
        LocalSolverKind::EnhancedAugmentedLagrangian,
    ));
    let mut ac_options = LocalSolverOptions::new(LocalSolverKind::NewtonAlartCurnier);
    ac_options.rho_rule = RhoRule::Dumont(1.0);
    ac_options.max_iter = 20;
    ac_options.variant = AlgorithmVariant::Fc3d;
    let mut ac = AnyLocalSolver::new(&ac_options);
    let (mut r1, mut r2) = ([0.0; 3], [0.0; 3]);
    let o1 = eal.solve(&p, &mut r1);
    let o2 = ac.solve(&p, &mut r2);
    assert_eq!(o1, o2);
    assert_eq!(r1, r2);
    assert!(o1.converged);
}

/// A contact whose solution is known by construction: `r*` and `u*` satisfy the Coulomb law,
/// and `q = u* - W r*`.
fn constructed(w: &Mat3, mu: f64, regime: usize, a: f64, b: f64, theta: f64) -> (Vec3, Vec3) {
    let d = [theta.cos(), theta.sin()];
    let (r, u) = match regime {
        // take-off: r = 0, u_N > 0
        0 => ([0.0; 3], [a, b * d[0], b * d[1]]),
        // stick: r strictly inside K, u = 0
        1 => ([a, 0.9 * mu * a * d[0], 0.9 * mu * a * d[1]], [0.0; 3]),
        // slide: r on the boundary opposing u_T = b d
        _ => (
            [a, -mu * a * d[0], -mu * a * d[1]],
            [0.0, b * d[0], b * d[1]],
        ),
    };
    let wr = crate::math::linalg::mat3_vec(w, &r);
    (r, [u[0] - wr[0], u[1] - wr[1], u[2] - wr[2]])
}

proptest! {
    #![proptest_config(fixed_seed(1024))]

    /// QUARTIC (562) and the hybrid Newton (565) find the same reaction to 1e-12 of the scale on
    /// random single contacts in the three regimes. W is SPD with eigenvalues in [0.1, 10] and
    /// mu <= 0.6, where one contact has a unique solution: both must find the constructed one.
    #[test]
    fn quartic_agrees_with_newton(
        w in spd_matrix(),
        mu in 0.05f64..0.6,
        regime in 0usize..3,
        a in 0.1f64..3.0,
        b in 0.1f64..3.0,
        theta in 0.0f64..std::f64::consts::TAU,
    ) {
        let (r_star, q) = constructed(&w, mu, regime, a, b, theta);
        let p = LocalProblem { w: &w, q, mu };
        let scale = norm3(&q).max(norm3(&r_star));
        let mut quartic = AnyLocalSolver::new(&LocalSolverOptions::new(LocalSolverKind::Quartic));
        let mut newton = AnyLocalSolver::new(&LocalSolverOptions::new(LocalSolverKind::NewtonHybrid));
        let (mut r1, mut r2) = ([0.0; 3], [0.0; 3]);
        quartic.solve(&p, &mut r1);
        newton.solve(&p, &mut r2);
        for i in 0..3 {
            prop_assert!((r1[i] - r2[i]).abs() <= 1e-12 * scale,
                "regime {regime}: quartic {r1:?}, newton {r2:?}, constructed {r_star:?}");
            prop_assert!((r1[i] - r_star[i]).abs() <= 1e-12 * scale,
                "regime {regime}: quartic {r1:?}, constructed {r_star:?}");
        }
    }

    /// The condensed EBP matrix (32) is the derivative of G(r) = r - P_K(r - rho ũ) away from
    /// the switching surfaces of the projection and from u_T = 0.
    #[test]
    fn bipotential_jacobian_matches_finite_differences(
        sym in spd_matrix(),
        skew in prop::array::uniform3(-0.05f64..0.05),
        q in prop::array::uniform3(-2.0f64..2.0),
        r in prop::array::uniform3(-2.0f64..2.0),
        mu in 0.05f64..2.0,
    ) {
        let mut w = sym;
        w[0][1] += skew[2]; w[1][0] -= skew[2];
        w[0][2] -= skew[1]; w[2][0] += skew[1];
        w[1][2] += skew[0]; w[2][1] -= skew[0];
        let rho = 1.0 / w[0][0];
        let p = LocalProblem { w: &w, q, mu };
        let g = |x: &Vec3| {
            let ut = crate::math::cone::modified_velocity(&p.velocity(x), mu);
            let tau = [x[0] - rho * ut[0], x[1] - rho * ut[1], x[2] - rho * ut[2]];
            let pr = crate::math::cone::project_on_cone(&tau, mu);
            ([x[0] - pr[0], x[1] - pr[1], x[2] - pr[2]], tau, p.velocity(x))
        };
        let (_, tau, u) = g(&r);
        let nt = tau[1].hypot(tau[2]);
        let delta = 1e-3;
        prop_assume!(u[1].hypot(u[2]) > delta && nt > delta);
        prop_assume!((nt - mu * tau[0]).abs() > delta && (mu * nt + tau[0]).abs() > delta);
        let jac = super::dumont::bipotential_jacobian(&p, rho, &tau, &u);
        let h = 1e-6;
        for j in 0..3 {
            let mut rp = r;
            let mut rm = r;
            rp[j] += h;
            rm[j] -= h;
            let (gp, _, _) = g(&rp);
            let (gm, _, _) = g(&rm);
            for i in 0..3 {
                let fd = (gp[i] - gm[i]) / (2.0 * h);
                prop_assert!((fd - jac[i][j]).abs() <= 1e-6 * (1.0 + jac[i][j].abs()),
                    "J[{i}][{j}] = {} but finite difference {fd}", jac[i][j]);
            }
        }
    }

    /// Same for the Jean-Moreau Jacobian.
    #[test]
    fn jean_moreau_jacobian_matches_finite_differences(
        sym in spd_matrix(),
        q in prop::array::uniform3(-2.0f64..2.0),
        r in prop::array::uniform3(-2.0f64..2.0),
        mu in 0.0f64..2.0,
    ) {
        let w = sym;
        let (rho_n, rho_t) = local_rho(&w, RhoRule::SplitSpectralNorm);
        let p = LocalProblem { w: &w, q, mu };
        let u = p.velocity(&r);
        let s_n = r[0] - rho_n * u[0];
        let s_t = [r[1] - rho_t * u[1], r[2] - rho_t * u[2]];
        let ns = s_t[0].hypot(s_t[1]);
        let radius = mu * r[0].max(0.0);
        let delta = 1e-3;
        prop_assume!(s_n.abs() > delta && r[0].abs() > delta && ns > delta && (ns - radius).abs() > delta);
        let (_, jac) = jean_moreau_function(&p, rho_n, rho_t, &r);
        let h = 1e-6;
        for j in 0..3 {
            let mut rp = r;
            let mut rm = r;
            rp[j] += h;
            rm[j] -= h;
            let (fp, _) = jean_moreau_function(&p, rho_n, rho_t, &rp);
            let (fm, _) = jean_moreau_function(&p, rho_n, rho_t, &rm);
            for i in 0..3 {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                prop_assert!((fd - jac[i][j]).abs() <= 1e-6 * (1.0 + jac[i][j].abs()),
                    "J[{i}][{j}] = {} but finite difference {fd}", jac[i][j]);
            }
        }
    }
}

proptest! {
    #![proptest_config(fixed_seed(512))]

    /// EBP (571, damped Newton with the 553 restart) and QUARTIC (562) solve random SPD contacts
    /// (the sample of `hybrid_newton_reaches_tight_residual`) in one call from r = 0. EAL (572)
    /// is 550's plain Newton and fails on about 1.7 % of such contacts, like 550.
    #[test]
    fn ebp_and_quartic_reach_tight_residual(
        w in spd_matrix(),
        q in prop::array::uniform3(-10.0f64..10.0),
        mu in 0.0f64..2.0,
    ) {
        let p = LocalProblem { w: &w, q, mu };
        prop_assert!(newton_reaches(LocalSolverKind::EnhancedBipotential, &p, 1));
        prop_assert!(newton_reaches(LocalSolverKind::Quartic, &p, 1));
        prop_assert!(newton_reaches(LocalSolverKind::FischerBurmeisterNewton, &p, 1));
    }
}
