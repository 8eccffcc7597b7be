//! fc3d's global method 691 (`NSGS_HFORM`, NSGS swept in the velocity form on H and a
//! block-diagonal M): its sweeps are NSGS's on the assembled W up to round-off, its reported
//! error is the global error of the triple it returns, the coloured sweep gives the same bits
//! on 1 and 2 threads, and the iteration limit and the time budget hold.

use std::path::Path;
use std::time::{Duration, Instant};

use fc3d_core::global::{
    global_error, solve_global, ContactLaw, GlobalConfig, GlobalMethod, GlobalProblem, HFormSweep,
};
use fc3d_core::io::dat::{read_global_dat_file, GlobalDatProblem};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::{CsrMatrix, Decomposition, Method, NsgsOptions, SolveStatus, Sweeper};

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn pile(shape: PileShape, contacts: usize) -> GlobalProblem<'static> {
    GeneratedScene {
        pile: PileSpec {
            contacts,
            piles: 1,
            seed: 2,
        },
        shape,
    }
    .generate_global()
    .unwrap()
}

fn inf(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
}

/// The global error of `r` measured from scratch: v from a fresh factorization of M.
fn independent_error(problem: &GlobalProblem<'_>, r: &[f64]) -> (f64, Vec<f64>, Vec<f64>) {
    let mut operator = problem.operator().unwrap();
    let mut v = vec![0.0; problem.ndof()];
    operator.global_velocity(problem.q(), r, &mut v);
    let mut u = vec![0.0; problem.size()];
    let e = global_error(problem, ContactLaw::Coulomb, r, &mut u, &v);
    (e, u, v)
}

/// `(r, u, v)` of zeros for `problem`.
fn zeros(problem: &GlobalProblem<'_>) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (
        vec![0.0; problem.size()],
        vec![0.0; problem.size()],
        vec![0.0; problem.ndof()],
    )
}

fn hform(decomposition: Decomposition, threads: usize) -> GlobalMethod {
    GlobalMethod::HForm(NsgsOptions {
        decomposition,
        threads,
        ..Default::default()
    })
}

#[test]
fn hform_sweeps_are_nsgs_sweeps_on_the_assembled_w() {
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        let g = pile(shape, 600);
        let mut operator = g.operator().unwrap();
        let local = g.reduce(&mut operator).unwrap();
        let options = NsgsOptions::default();
        let mut on_w = Sweeper::with_options(&local, &options, 0.0).unwrap();
        let mut on_h = HFormSweep::new(&g, &options).unwrap();
        let nc = g.n_contacts();
        let mut worst_diagonal = 0.0_f64;
        let mut w_scale = 0.0_f64;
        for c in 0..nc {
            let d = on_h.diagonal(c);
            for (i, row) in d.iter().enumerate() {
                for (j, x) in row.iter().enumerate() {
                    let w = local.w().get(3 * c + i, 3 * c + j);
                    worst_diagonal = worst_diagonal.max((x - w).abs());
                    w_scale = w_scale.max(w.abs());
                }
            }
        }
        assert!(worst_diagonal <= 1e-13 * w_scale, "{worst_diagonal:e}");
        let (mut r_w, mut r_h) = (vec![0.0; 3 * nc], vec![0.0; 3 * nc]);
        let mut v = vec![0.0; g.ndof()];
        on_h.global_velocity(&g, &r_h, &mut v);
        for sweep in 1..=40 {
            let inc_w = on_w.sweep(local.q(), local.mu(), &mut r_w);
            let inc_h = on_h.sweep(&g, &mut r_h, &mut v);
            let diff: Vec<f64> = r_w.iter().zip(&r_h).map(|(a, b)| a - b).collect();
            let rel = inf(&diff) / inf(&r_w);
            assert!(rel <= 1e-9, "{shape:?} sweep {sweep}: {rel:e}");
            assert!((inc_w - inc_h).abs() <= 1e-8 * inc_w, "{inc_w} {inc_h}");
        }
        // The velocity kept up to date equals M^-1 (q + H r) of the final r.
        let (_, _, v_exact) = independent_error(&g, &r_h);
        let dv: Vec<f64> = v.iter().zip(&v_exact).map(|(a, b)| a - b).collect();
        assert!(inf(&dv) <= 1e-10 * inf(&v_exact), "{:e}", inf(&dv));
    }
}

#[test]
fn reports_the_error_of_its_triple_and_matches_nsgs_on_w() {
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        let g = pile(shape, 1000);
        // Boxes reach 1e-4 in the global error; NSGS on sphere piles stalls above it for
        // thousands of sweeps: those run a fixed number of sweeps.
        let (tolerance, max_iter) = match shape {
            PileShape::Boxes => (1e-4, 20_000),
            PileShape::Spheres | PileShape::Fcc => (0.0, 300),
        };
        let mut runs = Vec::new();
        for method in [
            hform(Decomposition::Sequential, 1),
            GlobalMethod::Reduced(Method::Nsgs(NsgsOptions::default())),
        ] {
            let config = GlobalConfig {
                tolerance,
                max_iter,
                ..GlobalConfig::new(method)
            };
            let (mut r, mut u, mut v) = zeros(&g);
            let report = solve_global(&g, &config, &mut r, &mut u, &mut v).unwrap();
            let (e, u2, v2) = independent_error(&g, &r);
            assert!(
                (report.error - e).abs() <= 1e-12 * e,
                "{} vs {e}",
                report.error
            );
            let du: Vec<f64> = u.iter().zip(&u2).map(|(a, b)| a - b).collect();
            let dv: Vec<f64> = v.iter().zip(&v2).map(|(a, b)| a - b).collect();
            assert!(inf(&du) <= 1e-12 * inf(&u2).max(1.0));
            assert!(inf(&dv) <= 1e-12 * inf(&v2).max(1.0));
            runs.push((report.status, report.iterations, report.error));
        }
        eprintln!("{shape:?} 1000: (H form, NSGS on W) {runs:?}");
        let ((hs, hi, he), (ws, wi, we)) = (runs[0], runs[1]);
        if tolerance > 0.0 {
            // The same sweeps, stopped on the global error (the H form) or on the local one
            // and tightened until the global one passes (NSGS on W).
            assert_eq!((hs, ws), (SolveStatus::Converged, SolveStatus::Converged));
            assert!(he <= 1e-4 && we <= 1e-4);
            let (h, w) = (hi as f64, wi as f64);
            assert!(h <= 1.5 * w && h >= 0.5 * w, "{runs:?}");
        } else {
            // The same iterates up to round-off: the same error after the same sweeps.
            assert_eq!((hi, wi), (max_iter, max_iter));
            assert!((he - we).abs() <= 1e-6 * we, "{runs:?}");
        }
    }
}

#[test]
fn two_rods_reaches_the_reduced_nsgs_solution() {
    let path = Path::new(DATA_DIR).join("GFC3D_TwoRods1.dat");
    if !path.is_file() {
        eprintln!("skipped: {} missing", path.display());
        return;
    }
    let GlobalDatProblem::Spatial(g) = read_global_dat_file(&path).unwrap().problem else {
        panic!("a 3D problem");
    };
    let mut solutions = Vec::new();
    for method in [
        hform(Decomposition::Sequential, 1),
        GlobalMethod::Reduced(Method::Nsgs(NsgsOptions::default())),
    ] {
        let config = GlobalConfig {
            tolerance: 1e-10,
            max_iter: 10_000,
            ..GlobalConfig::new(method)
        };
        let (mut r, mut u, mut v) = zeros(&g);
        let report = solve_global(&g, &config, &mut r, &mut u, &mut v).unwrap();
        eprintln!("TwoRods1 {}: {report:?}", method.label());
        assert!(report.converged(), "{report:?}");
        let (e, _, _) = independent_error(&g, &r);
        assert!((report.error - e).abs() <= 1e-12 * e.max(1e-300));
        solutions.push(r);
    }
    let diff: Vec<f64> = solutions[0]
        .iter()
        .zip(&solutions[1])
        .map(|(a, b)| a - b)
        .collect();
    assert!(inf(&diff) <= 1e-6 * inf(&solutions[1]), "{:e}", inf(&diff));
}

#[test]
fn coloured_sweeps_give_the_same_bits_on_one_and_two_threads() {
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        let g = pile(shape, 3000);
        let colouring = HFormSweep::new(
            &g,
            &NsgsOptions {
                decomposition: Decomposition::Coloured,
                threads: 1,
                ..Default::default()
            },
        )
        .unwrap()
        .colouring()
        .unwrap();
        assert!(colouring.0 >= 2 && colouring.1 >= 5, "{colouring:?}");
        let mut runs = Vec::new();
        for threads in [1, 2] {
            let config = GlobalConfig {
                tolerance: 1e-9,
                max_iter: 60,
                ..GlobalConfig::new(hform(Decomposition::Coloured, threads))
            };
            let (mut r, mut u, mut v) = zeros(&g);
            let report = solve_global(&g, &config, &mut r, &mut u, &mut v).unwrap();
            assert_eq!(report.iterations, 60);
            let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            runs.push((report.error.to_bits(), bits(&r), bits(&u), bits(&v)));
        }
        assert!(runs[0] == runs[1], "{shape:?}: 1 and 2 threads differ");
    }
}

#[test]
fn iteration_limit_and_time_budget_hold() {
    let g = pile(PileShape::Spheres, 2000);
    let config = GlobalConfig {
        tolerance: 1e-12,
        max_iter: 3,
        ..GlobalConfig::new(hform(Decomposition::Sequential, 1))
    };
    let (mut r, mut u, mut v) = zeros(&g);
    let report = solve_global(&g, &config, &mut r, &mut u, &mut v).unwrap();
    assert_eq!(report.iterations, 3);
    assert_eq!(report.status, SolveStatus::MaxIterationsReached);
    assert_eq!(report.error, independent_error(&g, &r).0);

    let g = pile(PileShape::Spheres, 10_000);
    for method in [
        hform(Decomposition::Sequential, 1),
        hform(Decomposition::Coloured, 2),
    ] {
        let budget = Duration::from_millis(20);
        let config = GlobalConfig {
            tolerance: 1e-12,
            max_iter: 1_000_000,
            time_budget: Some(budget),
            ..GlobalConfig::new(method)
        };
        let (mut r, mut u, mut v) = zeros(&g);
        let start = Instant::now();
        let report = solve_global(&g, &config, &mut r, &mut u, &mut v).unwrap();
        let elapsed = start.elapsed();
        assert_eq!(report.status, SolveStatus::TimeBudgetExhausted);
        assert!(report.iterations < 1_000_000);
        assert_eq!(report.error, independent_error(&g, &r).0);
        // The budget counts from the call; M's preparation (before the clock can stop
        // anything) and the final error (a product) come on top.
        assert!(elapsed < Duration::from_secs(5), "{elapsed:?}");
    }
    // A budget spent before the sweep's set-up ends stops it: no sweep, r untouched.
    let config = GlobalConfig {
        tolerance: 1e-12,
        max_iter: 1_000_000,
        time_budget: Some(Duration::from_nanos(1)),
        ..GlobalConfig::new(hform(Decomposition::Sequential, 1))
    };
    let (mut r, mut u, mut v) = zeros(&g);
    let report = solve_global(&g, &config, &mut r, &mut u, &mut v).unwrap();
    assert_eq!(report.status, SolveStatus::TimeBudgetExhausted);
    assert_eq!(report.iterations, 0);
    assert!(r.iter().all(|&x| x == 0.0));
    assert_eq!(report.error, independent_error(&g, &r).0);
}

#[test]
fn general_m_and_unsupported_options_are_refused() {
    // One connected M of 120 unknowns (tridiagonal): factored as a whole, no blocks.
    let n = 120;
    let mut m = Vec::new();
    for i in 0..n {
        m.push((i, i, 4.0));
        if i + 1 < n {
            m.push((i, i + 1, -1.0));
            m.push((i + 1, i, -1.0));
        }
    }
    let h = vec![(0, 0, 1.0), (1, 1, 1.0), (2, 2, 1.0)];
    let g = GlobalProblem::new(
        CsrMatrix::from_triplets(n, n, &m).unwrap(),
        CsrMatrix::from_triplets(n, 3, &h).unwrap(),
        vec![-1.0; n],
        vec![0.0; 3],
        vec![0.5],
    )
    .unwrap();
    let config = GlobalConfig::new(hform(Decomposition::Sequential, 1));
    let (mut r, mut u, mut v) = (vec![0.0; 3], vec![0.0; 3], vec![0.0; n]);
    let e = solve_global(&g, &config, &mut r, &mut u, &mut v).unwrap_err();
    assert!(e.to_string().contains("block-diagonal M"), "{e}");
    assert_eq!(r, [0.0; 3]);

    let islands = GlobalConfig::new(hform(Decomposition::Islands, 1));
    assert!(islands.validate().is_err());

    assert_eq!(
        GlobalMethod::preset("691"),
        Some(hform(Decomposition::Sequential, 0))
    );
    for (name, decomposition) in [
        ("NSGS_HFORM", Decomposition::Sequential),
        ("gfc3d_nsgs_hform_coloured", Decomposition::Coloured),
    ] {
        let m = GlobalMethod::preset(name).unwrap();
        assert_eq!(m, hform(decomposition, 0));
        assert_eq!(m.siconos_id(), 691);
        assert_eq!(GlobalMethod::preset(m.name().unwrap()), Some(m), "{name}");
    }
}
