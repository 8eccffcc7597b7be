//! The accelerated solvers on small convex QPs whose solutions are known or checked by their
//! optimality conditions.

use super::*;
use crate::math::cone::{project_on_cone, project_on_cylinder};
use crate::matrix::{Delassus, DenseMatrix};
use crate::problem::FrictionProblem;

struct Cylinders(Vec<f64>);

impl ConvexSet for Cylinders {
    fn project(&self, x: &mut [f64]) {
        for (c, &rad) in self.0.iter().enumerate() {
            let p = project_on_cylinder(&[x[3 * c], x[3 * c + 1], x[3 * c + 2]], rad);
            x[3 * c..3 * c + 3].copy_from_slice(&p);
        }
    }
}

struct Cones(Vec<f64>);

impl ConvexSet for Cones {
    fn project(&self, x: &mut [f64]) {
        for (c, &m) in self.0.iter().enumerate() {
            let p = project_on_cone(&[x[3 * c], x[3 * c + 1], x[3 * c + 2]], m);
            x[3 * c..3 * c + 3].copy_from_slice(&p);
        }
    }
}

/// Two contacts coupled through an SPD W, with cylinders or cones.
fn problem() -> FrictionProblem<'static> {
    #[rustfmt::skip]
    let w = vec![
        3.0, 0.2, 0.1, 0.5, 0.0, 0.1,
        0.2, 2.0, 0.0, 0.1, 0.3, 0.0,
        0.1, 0.0, 2.5, 0.0, 0.0, 0.2,
        0.5, 0.1, 0.0, 4.0, 0.3, 0.0,
        0.0, 0.3, 0.0, 0.3, 1.5, 0.1,
        0.1, 0.0, 0.2, 0.0, 0.1, 2.0,
    ];
    FrictionProblem::new(
        Delassus::Dense(DenseMatrix::new(6, 6, w).unwrap()),
        vec![-1.0, 2.0, -0.5, -2.0, -0.3, 0.4],
        vec![0.5, 0.3],
    )
    .unwrap()
}

fn methods() -> [FirstOrderMethod; 2] {
    [
        FirstOrderMethod::Apgd(ApgdSettings::default()),
        FirstOrderMethod::Spg(SpgSettings::default()),
    ]
}

fn solve_with<S: ConvexSet>(
    method: FirstOrderMethod,
    set: &S,
    tol: f64,
) -> (Vec<f64>, usize, usize) {
    let p = problem();
    let rows = p.w().block_rows().unwrap();
    let sub = ConvexSubproblem {
        rows: &rows,
        linear: p.q(),
        set,
        norm_q: norm(p.q()),
    };
    let mut work = FirstOrderWork::new(6, method).unwrap();
    let mut r = vec![0.0; 6];
    let it = work.solve(&sub, tol, 10_000, None, &mut r);
    (r, it, work.products)
}

/// The variational inequality's natural map `||r - P(r - (W r + q))||`, recomputed.
fn natural_map<S: ConvexSet>(set: &S, r: &[f64]) -> f64 {
    let p = problem();
    let mut u = p.q().to_vec();
    p.w().mul_add(r, &mut u);
    let mut x: Vec<f64> = r.iter().zip(&u).map(|(r, u)| r - u).collect();
    set.project(&mut x);
    r.iter()
        .zip(&x)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn both_methods_solve_the_tresca_and_cone_problems() {
    let cylinders = Cylinders(vec![0.4, 0.2]);
    let cones = Cones(vec![0.5, 0.3]);
    for method in methods() {
        let (r, it, products) = solve_with(method, &cylinders, 1e-12);
        assert!(natural_map(&cylinders, &r) <= 1e-10, "{method:?}: {r:?}");
        // One product a step, the 10 Lanczos steps and the first gradient besides.
        assert!(
            products <= it + 11 + it / 4,
            "{method:?}: {products} for {it}"
        );
        let (r, _, _) = solve_with(method, &cones, 1e-12);
        assert!(natural_map(&cones, &r) <= 1e-10, "{method:?}: {r:?}");
        for c in 0..2 {
            assert!(r[3 * c] >= 0.0);
        }
    }
    // Both reach the same (unique: W is positive definite) solution.
    let (a, _, _) = solve_with(methods()[0], &cones, 1e-13);
    let (b, _, _) = solve_with(methods()[1], &cones, 1e-13);
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() <= 1e-10, "{a:?} {b:?}");
    }
}

#[test]
fn limits_hold() {
    let cylinders = Cylinders(vec![0.4, 0.2]);
    let p = problem();
    let rows = p.w().block_rows().unwrap();
    let sub = ConvexSubproblem {
        rows: &rows,
        linear: p.q(),
        set: &cylinders,
        norm_q: norm(p.q()),
    };
    for method in methods() {
        let mut work = FirstOrderWork::new(6, method).unwrap();
        let mut r = vec![0.0; 6];
        assert_eq!(work.solve(&sub, 0.0, 3, None, &mut r), 3);
        // A deadline in the past: no iteration, r projected and finite.
        let mut r = vec![5.0; 6];
        let past = Some(Instant::now());
        assert_eq!(work.solve(&sub, 0.0, 100, past, &mut r), 0);
        assert!(r.iter().all(|v| v.is_finite()));
        assert!(r[1].hypot(r[2]) <= 0.4 + 1e-15);
    }
}

#[test]
fn bad_settings_are_rejected() {
    let bad_apgd = ApgdSettings {
        step_shrink: 0.0,
        ..Default::default()
    };
    assert!(FirstOrderMethod::Apgd(bad_apgd).validate().is_err());
    let bad_spg = SpgSettings {
        sigma_low: 0.95,
        ..Default::default()
    };
    assert!(FirstOrderMethod::Spg(bad_spg).validate().is_err());
    for m in methods() {
        assert!(m.validate().is_ok());
    }
}
