//! 2D friction (Siconos' fc2d ids 400-405) on the 2D problems of `../shared/data/siconos`
//! (never copied into the repository): every file reads as a 2D problem, and every solver's
//! answer is checked by the natural-map error measured here, independently of the solver.

use std::path::{Path, PathBuf};

use fc3d_core::io::dat::{read_dat_file_any, DatProblem};
use fc3d_core::measure::natural_map_error;
use fc3d_core::{
    solve_planar, ContactOrder, FrictionProblem2d, PlanarConfig, PlanarMethod, PlanarNsgsOptions,
    SolveStatus,
};

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

/// The reduced-form 2D files (the `gfc2d_` ones are global problems).
fn planar_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(DATA_DIR)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            name.ends_with(".dat")
                && (name.starts_with("fc2d_")
                    || name.starts_with("FC2D_")
                    || name.starts_with("FrictionContactProblem00"))
        })
        .collect();
    files.sort();
    files
}

fn read_planar(path: &Path) -> FrictionProblem2d<'static> {
    match read_dat_file_any(path) {
        Ok(DatProblem::Planar(p)) => p,
        other => panic!("{}: {other:?}", path.display()),
    }
}

fn run(
    p: &FrictionProblem2d<'_>,
    config: &PlanarConfig,
) -> (Vec<f64>, Vec<f64>, f64, usize, SolveStatus) {
    let n = p.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let report = solve_planar(p, config, &mut r, &mut u).unwrap();
    // The reported error is the one measured on the returned pair.
    let mut u2 = vec![0.0; n];
    let e = natural_map_error(p, &r, &mut u2);
    assert_eq!(e, report.error);
    for (a, b) in u.iter().zip(&u2) {
        assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "u is not W r + q");
    }
    (r, u, report.error, report.iterations, report.status)
}

#[test]
fn every_2d_file_reads_as_a_planar_problem() {
    let files = planar_files();
    assert!(files.len() >= 10, "only {} 2D files", files.len());
    for f in &files {
        let p = read_planar(f);
        assert_eq!(p.size(), 2 * p.n_contacts());
        assert!(p.n_contacts() > 0);
    }
}

/// Writing a 2D problem and reading it back gives the same problem, bit for bit (W in the
/// storage it was read into: dense, or CSR for sparse-block and sparse files).
#[test]
fn write_then_read_2d_is_bit_exact() {
    use fc3d_core::io::dat::{parse_dat_any, write_dat};
    for f in planar_files() {
        let p = read_planar(&f);
        let mut text = Vec::new();
        write_dat(&p, &mut text).unwrap();
        let text = String::from_utf8(text).unwrap();
        assert!(text.starts_with("2\n"));
        match parse_dat_any(&text, "written") {
            Ok(DatProblem::Planar(back)) => assert_eq!(back, p, "{}", f.display()),
            other => panic!("{}: {other:?}", f.display()),
        }
    }
    // A 2D sparse-block body must be made of 2x2 blocks.
    let text = "2 1 1 2 2 1 1 1 3 3 2 1 0 1 0 0 1 2 3 4 5 6 7 8 9 0 0 0.5";
    match parse_dat_any(text, "wrong-block.dat") {
        Err(fc3d_core::Fc3dError::Unsupported(m)) => assert!(m.contains("2x2"), "{m}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn nsgs_solves_every_2d_file() {
    for f in planar_files() {
        let p = read_planar(&f);
        let mut config = PlanarConfig::new(PlanarMethod::Nsgs(PlanarNsgsOptions::default()));
        // The granular flow of 2020 contacts is slow: 6.5e-7 after 1e5 sweeps.
        let hard = f.to_string_lossy().contains("02020");
        config.tolerance = if hard { 1e-5 } else { 1e-8 };
        config.max_iter = 100_000;
        let (_, _, error, iterations, status) = run(&p, &config);
        println!(
            "{}: nc {} NSGS error {error:.3e} in {iterations} sweeps",
            f.display(),
            p.n_contacts()
        );
        assert_eq!(status, SolveStatus::Converged, "{}", f.display());
        assert!(error <= config.tolerance);
    }
}

#[test]
fn shuffled_and_frozen_nsgs_converge() {
    for f in planar_files()
        .iter()
        .filter(|f| f.to_string_lossy().contains("FrictionContactProblem00"))
    {
        let p = read_planar(f);
        for options in [
            PlanarNsgsOptions {
                order: ContactOrder::ShuffledEachSweep { seed: 3 },
                ..Default::default()
            },
            PlanarNsgsOptions {
                freezing: Some(10),
                ..Default::default()
            },
        ] {
            let mut config = PlanarConfig::new(PlanarMethod::Nsgs(options));
            config.tolerance = 1e-6;
            config.max_iter = 100_000;
            let (_, _, error, _, status) = run(&p, &config);
            assert_eq!(
                status,
                SolveStatus::Converged,
                "{} {options:?}: {error:e}",
                f.display()
            );
        }
    }
}

#[test]
fn lemke_cpg_and_enumeration() {
    for f in planar_files() {
        let p = read_planar(&f);
        let nc = p.n_contacts();
        for method in [
            PlanarMethod::Lemke,
            PlanarMethod::Cpg,
            PlanarMethod::Enumeration { seed: 0 },
        ] {
            if matches!(method, PlanarMethod::Enumeration { .. }) && nc > 4 {
                continue;
            }
            if matches!(method, PlanarMethod::Lemke) && nc > 400 {
                continue;
            }
            let mut config = PlanarConfig::new(method);
            config.tolerance = 1e-5;
            config.max_iter = config.max_iter.max(10_000);
            let (r, _, error, iterations, status) = run(&p, &config);
            println!(
                "{}: nc {nc} {method:?} error {error:.3e} in {iterations} ({status:?})",
                f.display()
            );
            let independent = independent_error_2d(&p, &r);
            assert!(
                // (Both relative; near rounding level the two computations differ by rounding.)
                (error - independent).abs() <= 1e-9 * independent + 1e-12,
                "{error} vs {independent}"
            );
        }
    }
}

/// Ten contacts, nine of them open (q_N > 0): enumeration must reach case 2^27 or beyond, so a
/// budget of 50 ms stops it long before; Lemke with one pivot and NSGS with one sweep stop at
/// their limits. Every run returns a finite pair with the error measured on it.
#[test]
fn limits_hold_for_every_2d_solver() {
    use fc3d_core::{Delassus, DenseMatrix, FrictionProblem2d};
    use std::time::{Duration, Instant};
    let nc = 10;
    let n = 2 * nc;
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        w[i + n * i] = 2.0;
    }
    // A coupling between the normals of contacts 0 and 1 (column-major).
    w[2] = 0.3;
    w[2 * n] = 0.3;
    let mut q = vec![0.0; n];
    q[0] = -1.0;
    q[1] = 0.5;
    for c in 1..nc {
        q[2 * c] = 1.0;
    }
    let mu = vec![0.3; nc];
    let p = FrictionProblem2d::new_2d(Delassus::Dense(DenseMatrix::new(n, n, w).unwrap()), q, mu)
        .unwrap();
    let mut config = PlanarConfig::new(PlanarMethod::Enumeration { seed: 0 });
    config.time_budget = Some(Duration::from_millis(50));
    let start = Instant::now();
    let (r, _, error, _, status) = run(&p, &config);
    assert!(start.elapsed() < Duration::from_secs(2));
    assert_eq!(status, SolveStatus::TimeBudgetExhausted);
    assert!(r.iter().all(|v| v.is_finite()) && error.is_finite());
    // An iteration limit of 1000 cases stops it there.
    let mut config = PlanarConfig::new(PlanarMethod::Enumeration { seed: 0 });
    config.max_iter = 1000;
    let (_, _, _, iterations, status) = run(&p, &config);
    assert_eq!(
        (iterations, status),
        (1000, SolveStatus::MaxIterationsReached)
    );

    for method in [
        PlanarMethod::Lemke,
        PlanarMethod::Nsgs(PlanarNsgsOptions::default()),
    ] {
        let mut config = PlanarConfig::new(method);
        config.max_iter = 1;
        config.tolerance = 1e-14;
        let (_, _, _, iterations, status) = run(&p, &config);
        assert!(iterations <= 1, "{method:?}");
        assert_ne!(status, SolveStatus::TimeBudgetExhausted);
    }
    // Without limits, NSGS and Lemke solve it exactly (contact 0 slides, the others stay open;
    // CPG, like Siconos', stalls on a sliding contact).
    for method in [
        PlanarMethod::Lemke,
        PlanarMethod::Nsgs(PlanarNsgsOptions::default()),
    ] {
        let mut config = PlanarConfig::new(method);
        config.tolerance = 1e-12;
        config.max_iter = 1000;
        let (r, _, error, _, status) = run(&p, &config);
        assert_eq!(status, SolveStatus::Converged, "{method:?}: {error:e}");
        assert!(r[2..].iter().all(|&v| v == 0.0), "{method:?}: {r:?}");
    }
}

/// The relative natural-map error of `r` for a 2D problem, recomputed here from W's entries:
/// `u = W r + q`, per contact `r_c - P_K(r_c - (u_N + mu |u_T|, u_T))` with `K` the cone
/// `|t| <= mu n`, over `max(||q||, ||r||, ||u||)`.
fn independent_error_2d(p: &FrictionProblem2d<'_>, r: &[f64]) -> f64 {
    let mut u = p.q().to_vec();
    p.w().for_each_entry(|i, j, v| u[i] += v * r[j]);
    let mut sum = 0.0;
    for (c, &mu) in p.mu().iter().enumerate() {
        let (rn, rt, un, ut) = (r[2 * c], r[2 * c + 1], u[2 * c], u[2 * c + 1]);
        let (x, y) = (rn - (un + mu * ut.abs()), rt - ut);
        let (pn, pt) = if y.abs() <= mu * x {
            (x, y)
        } else if mu * y.abs() <= -x {
            (0.0, 0.0)
        } else {
            let n = (x + mu * y.abs()) / (1.0 + mu * mu);
            (n, mu * n * y.signum())
        };
        sum += (rn - pn).powi(2) + (rt - pt).powi(2);
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let scale = norm(p.q()).max(norm(r)).max(norm(&u));
    sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }
}

/// Enumeration (405) on the 667-contact granular flow, an LCP of 2001 unknowns, in Siconos'
/// order: each case is a dense 2001x2001 solve. It stops at the iteration limit (cases) and at
/// the time budget, even within a case, returning r = 0 with its true error (no early case is
/// a solution: the flow's contacts slide and stick in both directions, where the first cases
/// change the first few unknowns only). Without either limit it is refused. (Siconos 4.4 tries
/// no case at all there: it counts the 2^2001 cases in 64 bits, 0, and returns r = 0 as
/// converged, its absolute error 3e-18 being below the tolerance on data of order 1e-18.)
#[test]
fn enumeration_of_a_large_problem_holds_its_limits() {
    use std::time::{Duration, Instant};
    let p = read_planar(&Path::new(DATA_DIR).join("fc2d_granularflowonwall_00667_00000.dat"));
    assert_eq!(p.n_contacts(), 667);
    let mut config = PlanarConfig::new(PlanarMethod::Enumeration { seed: 0 });
    let n = p.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let refused = solve_planar(&p, &config, &mut r, &mut u).unwrap_err();
    assert!(refused.to_string().contains("max_iter"), "{refused}");

    config.max_iter = 2;
    let start = Instant::now();
    let (r, _, error, iterations, status) = run(&p, &config);
    let per_case = start.elapsed() / 2;
    assert_eq!((iterations, status), (2, SolveStatus::MaxIterationsReached));
    assert!(r.iter().all(|&v| v == 0.0));
    let independent = independent_error_2d(&p, &r);
    assert!(
        (error - independent).abs() <= 1e-12 * independent,
        "{error} vs {independent}"
    );
    eprintln!("two cases: {per_case:?} a case; error of r = 0: {error:.3e}");

    config.max_iter = 0;
    let budget = Duration::from_millis(300);
    config.time_budget = Some(budget);
    let start = Instant::now();
    let (r, _, error, iterations, status) = run(&p, &config);
    let elapsed = start.elapsed();
    eprintln!("budget {budget:?}: {iterations} cases in {elapsed:?}");
    assert_eq!(status, SolveStatus::TimeBudgetExhausted);
    assert!(elapsed < budget + Duration::from_millis(250), "{elapsed:?}");
    assert!(r.iter().all(|&v| v == 0.0));
    let independent = independent_error_2d(&p, &r);
    assert!(
        (error - independent).abs() <= 1e-12 * independent,
        "{error} vs {independent}"
    );
}
