//! The promises of the hardening issue kept by the core: every solver honours a 50 ms budget
//! whatever its iteration limits (local, inner and line-search limits included); a problem with
//! no solution is never reported solved; data near the overflow threshold gives finite answers
//! and a finite, honest error.

mod common;

use std::time::{Duration, Instant};

use common::honesty::check_report;
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::{
    solve, Delassus, DenseMatrix, FrictionProblem, InnerTolerance, LocalSolverKind, Method,
    NsgsOptions, NsnLineSearch, ProxInternal, SelfAdaptiveStep, SolveStatus, SolverConfig,
    StepSize,
};

/// Every preset of every family and NSGS with every local solver.
fn all_methods() -> Vec<Method> {
    let mut v = Method::presets();
    v.extend(LocalSolverKind::ALL.map(|k| Method::Nsgs(NsgsOptions::with_local(k))));
    v
}

/// The largest limits a C host can set (INT_MAX) in every loop an option bounds.
fn with_largest_limits(method: Method) -> Method {
    const BIG: usize = i32::MAX as usize;
    match method {
        Method::Nsgs(mut o) => {
            o.local.max_iter = BIG;
            o.local.line_search_max_iter = BIG;
            o.local.hybrid_max_loop = BIG;
            o.local.hybrid_max_iter = BIG;
            o.local.tolerance = 0.0;
            Method::Nsgs(o)
        }
        Method::Vi(mut o) => {
            if let StepSize::SelfAdaptive(s) = o.step {
                o.step = StepSize::SelfAdaptive(SelfAdaptiveStep {
                    max_trials: BIG,
                    ..s
                });
            }
            Method::Vi(o)
        }
        Method::Nsn(mut o) => {
            o.line_search_max_iter = BIG;
            if o.line_search == NsnLineSearch::None {
                o.line_search = NsnLineSearch::GoldsteinPrice;
            }
            Method::Nsn(o)
        }
        Method::Prox(mut o) => {
            o.internal_max_iter = Some(BIG);
            if let ProxInternal::NsnAc(ref mut n) = o.internal {
                n.line_search_max_iter = BIG;
            }
            Method::Prox(o)
        }
        Method::Tresca(mut o) => {
            o.inner_max_iter = BIG;
            o.inner_tolerance = InnerTolerance::Given(0.0);
            Method::Tresca(o)
        }
        Method::Pfp(mut o) => {
            o.inner_max_iter = BIG;
            o.inner_tolerance = InnerTolerance::Given(0.0);
            Method::Pfp(o)
        }
        Method::Aclm(mut o) => {
            o.inner_max_iter = BIG;
            o.inner_tolerance = InnerTolerance::Given(0.0);
            Method::Aclm(o)
        }
        other => other,
    }
}

fn rockpile() -> FrictionProblem<'static> {
    read_dat_file(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/siconos/RockPile_tob1.dat"
    )))
    .unwrap()
}

/// 50 ms with tolerance 0 and the largest limits everywhere: every solver returns within the
/// budget plus one sweep or Newton step (asserted with a margin for a loaded machine), with
/// info 2 and the true error of what it returns.
#[test]
fn every_solver_keeps_a_50_ms_budget_whatever_its_limits() {
    let p = rockpile();
    let n = p.size();
    let budget = Duration::from_millis(50);
    let mut worst = (String::new(), Duration::ZERO);
    for method in all_methods() {
        let config = SolverConfig::new(with_largest_limits(method))
            .with_tolerance(0.0)
            .with_max_iter(i32::MAX as usize)
            .with_time_budget(Some(budget));
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let start = Instant::now();
        let report = solve(&p, &config, &mut r, &mut u).unwrap();
        let elapsed = start.elapsed();
        let name = config.label();
        eprintln!(
            "{name:>14}: {:>8.1} ms, {:?}, {} iterations, error {:.2e}",
            elapsed.as_secs_f64() * 1e3,
            report.status,
            report.iterations,
            report.error
        );
        assert!(
            elapsed <= budget + Duration::from_millis(250),
            "{name} took {elapsed:?} on a {budget:?} budget"
        );
        assert!(
            matches!(
                report.status,
                SolveStatus::TimeBudgetExhausted
                    | SolveStatus::RelaxationNotCoulomb
                    | SolveStatus::Unbounded
            ),
            "{name}: {:?}",
            report.status
        );
        check_report(&name, &p, 0.0, &report, &r, &u);
        if elapsed > worst.1 {
            worst = (name, elapsed);
        }
    }
    eprintln!("slowest return: {} after {:?}", worst.0, worst.1);
}

fn dense(n: usize, values: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> FrictionProblem<'static> {
    FrictionProblem::new(
        Delassus::Dense(DenseMatrix::new(n, n, values).unwrap()),
        q,
        mu,
    )
    .unwrap()
}

/// W = 0 with q pushing one contact in (u = q whatever r: no solution), and a singular W whose
/// two contacts cannot both stop penetrating (u_N1 + u_N2 = -2 whatever r): no solver reports
/// either as solved; the error reported is the returned pair's.
#[test]
fn problems_without_solution_are_never_reported_solved() {
    let zero = dense(3, vec![0.0; 9], vec![-1.0, 0.3, 0.0], vec![0.5]);
    #[rustfmt::skip]
    let singular_w = vec![
        1.0, 0.0, 0.0, -1.0, 0.0, 0.0,
        0.0, 1.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 0.0, 0.0, 0.0,
        -1.0, 0.0, 0.0, 1.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    let singular = dense(
        6,
        singular_w,
        vec![-1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        vec![0.5, 0.5],
    );
    for (label, p) in [("W = 0", &zero), ("singular W", &singular)] {
        for method in all_methods() {
            let config = SolverConfig::new(method)
                .with_tolerance(1e-4)
                .with_max_iter(100_000)
                .with_time_budget(Some(Duration::from_millis(300)));
            let n = p.size();
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let report = solve(p, &config, &mut r, &mut u).unwrap();
            let name = format!("{label}, {}", config.label());
            assert_ne!(report.status, SolveStatus::Converged, "{name}: {report:?}");
            assert!(r.iter().chain(&u).all(|v| v.is_finite()), "{name}");
            let (e, _) = common::honesty::independent_error(p, &r);
            assert!(
                (report.error - e).abs() <= 1e-9 * e + 1e-14,
                "{name}: reported {:e}, recomputed {e:e}",
                report.error
            );
        }
    }
}

/// The natural-map error of `r` recomputed independently on the problem scaled by its largest
/// entry (the error is invariant under a common scaling of r, u and q), so that squares near the
/// overflow threshold stay finite.
fn independent_scaled_error(p: &FrictionProblem<'_>, r: &[f64]) -> f64 {
    let mut u = p.q().to_vec();
    p.w().for_each_entry(|i, j, v| u[i] += v * r[j]);
    let s = r
        .iter()
        .chain(&u)
        .chain(p.q())
        .fold(0.0_f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let (rs, us, qs): (Vec<f64>, Vec<f64>, Vec<f64>) = (
        r.iter().map(|v| v / s).collect(),
        u.iter().map(|v| v / s).collect(),
        p.q().iter().map(|v| v / s).collect(),
    );
    let mut sum = 0.0;
    for (c, &mu) in p.mu().iter().enumerate() {
        let (rc, uc) = (&rs[3 * c..3 * c + 3], &us[3 * c..3 * c + 3]);
        let ut = (uc[1] * uc[1] + uc[2] * uc[2]).sqrt();
        let x = [rc[0] - (uc[0] + mu * ut), rc[1] - uc[1], rc[2] - uc[2]];
        let pr = common::honesty::cone_projection(x, mu);
        sum += (0..3).map(|i| (rc[i] - pr[i]).powi(2)).sum::<f64>();
    }
    let norm = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>().sqrt();
    let scale = norm(&qs).max(norm(&rs)).max(norm(&us));
    sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }
}

/// W and q up to 1e300, friction up to 1e3 (De Saxcé velocities beyond f64's range): finite r,
/// u and error for every solver, the error equal to an independent recomputation, never info 0
/// with a non-finite error.
#[test]
fn data_near_the_overflow_threshold_gives_finite_honest_answers() {
    let cases = [
        (
            "W 1e300",
            dense(
                3,
                vec![1e300, 0.0, 0.0, 0.0, 1e300, 0.0, 0.0, 0.0, 1e300],
                vec![-1e300, 5e299, 0.0],
                vec![0.5],
            ),
        ),
        (
            "q 1e306, mu 1e3",
            dense(
                3,
                vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                vec![-1e306, 1e306, 0.0],
                vec![1e3],
            ),
        ),
        (
            "q 1e300 coupled",
            dense(
                6,
                vec![
                    2.0, 0.1, 0.0, 0.5, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
                    0.0, 0.0, 0.5, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0,
                    0.0, 0.0, 0.0, 1.0,
                ],
                vec![-1e300, 3e299, 0.0, -2e300, 0.0, 1e300],
                vec![0.3, 8.0],
            ),
        ),
    ];
    for (label, p) in &cases {
        for method in all_methods() {
            let config = SolverConfig::new(method)
                .with_tolerance(1e-8)
                .with_max_iter(2000)
                .with_time_budget(Some(Duration::from_millis(200)));
            let n = p.size();
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let report = solve(p, &config, &mut r, &mut u).unwrap();
            let name = format!("{label}, {}", config.label());
            assert!(
                r.iter().chain(&u).all(|v| v.is_finite()),
                "{name}: r {r:?} u {u:?}"
            );
            assert!(report.error.is_finite(), "{name}: error {}", report.error);
            let e = independent_scaled_error(p, &r);
            assert!(
                (report.error - e).abs() <= 1e-9 * e + 1e-14,
                "{name}: reported {:e}, recomputed {e:e}",
                report.error
            );
            assert_eq!(
                report.status == SolveStatus::Converged,
                report.error <= 1e-8 && report.status != SolveStatus::Unbounded,
                "{name}: {report:?}"
            );
        }
    }
}
