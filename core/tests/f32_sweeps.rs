//! NSGS with early sweeps on an f32 copy of W's coupling blocks (`NsgsOptions::f32_sweeps`,
//! issue 27 item 5): it reaches the tolerances f64 NSGS reaches, in about as many sweeps, on
//! generated piles and shared problems; the error it reports is an independent f64
//! recomputation on the problem's W; it is bitwise identical for 1 and 2 threads; and the
//! default path (no copy) still computes the per-contact update of the public
//! `update_contact`, bit for bit.

mod common;

use std::path::Path;

use common::honesty::{check_report, norm};
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::solvers::nsgs::{update_contact, ContactStep, LocalStep};
use fc3d_core::{
    solve, Decomposition, ErrorEvaluation, F32Sweeps, FrictionProblem, NsgsOptions, SolveReport,
    SolveStatus, SolverConfig,
};

fn siconos(name: &str) -> FrictionProblem<'static> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos/");
    read_dat_file(&Path::new(dir).join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn pile(shape: PileShape, contacts: usize) -> FrictionProblem<'static> {
    GeneratedScene {
        pile: PileSpec {
            contacts,
            piles: 4,
            seed: 1,
        },
        shape,
    }
    .generate()
    .unwrap()
}

fn mixed(options: NsgsOptions) -> NsgsOptions {
    NsgsOptions {
        f32_sweeps: Some(F32Sweeps::default()),
        ..options
    }
}

fn run(
    p: &FrictionProblem<'_>,
    options: NsgsOptions,
    tol: f64,
    max_iter: usize,
) -> (SolveReport, Vec<f64>, Vec<f64>) {
    let config = SolverConfig::new(options)
        .with_tolerance(tol)
        .with_max_iter(max_iter);
    let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
    let report = solve(p, &config, &mut r, &mut u).unwrap();
    (report, r, u)
}

/// NSGS in f64 and with the f32 copy (the same other options) to `tol`: both converge, the
/// mixed run's reported error is the independent recomputation, its sweeps are within
/// `slack` of the f64 run's, and its sweeps on the copy are counted. Returns (f64 sweeps,
/// mixed sweeps, sweeps on the copy).
fn compare(
    name: &str,
    p: &FrictionProblem<'_>,
    options: NsgsOptions,
    tol: f64,
    slack: f64,
) -> (usize, usize, usize) {
    let max_iter = 200_000;
    let (f64_report, r64, _) = run(p, options, tol, max_iter);
    let (report, r, u) = run(p, mixed(options), tol, max_iter);
    println!(
        "{name} at {tol:e}: f64 {} sweeps ({:.3e}), f32 copy {} sweeps ({:?} on the copy, {:.3e})",
        f64_report.iterations, f64_report.error, report.iterations, report.f32_sweeps, report.error
    );
    assert_eq!(f64_report.status, SolveStatus::Converged, "{name} f64");
    assert_eq!(f64_report.f32_sweeps, None, "{name}");
    assert_eq!(report.status, SolveStatus::Converged, "{name} f32 copy");
    check_report(name, p, tol, &report, &r, &u);
    let on_copy = report.f32_sweeps.expect("sweeps on the copy counted");
    assert!(on_copy >= 1 && on_copy <= report.iterations, "{name}");
    let (a, b) = (f64_report.iterations as f64, report.iterations as f64);
    assert!(
        b <= a * (1.0 + slack) + 2.0,
        "{name} at {tol:e}: {b} sweeps with the f32 copy against {a} in f64"
    );
    // Both runs stop near one solution: the reactions agree to far better than their norm.
    let d: Vec<f64> = r.iter().zip(&r64).map(|(x, y)| x - y).collect();
    assert!(
        norm(&d) <= 1e-3 * norm(&r64),
        "{name}: {}",
        norm(&d) / norm(&r64)
    );
    (f64_report.iterations, report.iterations, on_copy)
}

#[test]
fn the_f32_copy_reaches_the_f64_tolerances_on_generated_piles() {
    let spheres = pile(PileShape::Spheres, 1000);
    // At 1e-4 the copy carries the whole run (its rounding floor is far below).
    let (_, sweeps, on_copy) =
        compare("spheres 1000", &spheres, NsgsOptions::default(), 1e-4, 0.01);
    assert_eq!(on_copy, sweeps);
    // At 1e-6 the run leaves the copy at the switch error (1e-5, the cheap error's).
    let (_, sweeps, on_copy) =
        compare("spheres 1000", &spheres, NsgsOptions::default(), 1e-6, 0.01);
    assert!(on_copy < sweeps);
    let boxes = pile(PileShape::Boxes, 3000);
    for tol in [1e-4, 1e-6] {
        compare("boxes 3000", &boxes, NsgsOptions::default(), tol, 0.01);
    }
    // The full error tested after every sweep: the switch at a full error of 1e-5.
    let full = NsgsOptions {
        error_evaluation: ErrorEvaluation::Full,
        ..Default::default()
    };
    compare("spheres 1000 (full test)", &spheres, full, 1e-6, 0.01);
}

#[test]
fn the_f32_copy_reaches_the_f64_tolerances_on_shared_problems() {
    for (name, tol) in [
        ("Capsules-i100-889.dat", 1e-6),
        ("Capsules-i103-990.dat", 1e-6),
        ("OneObject-i1028-138.hdf5.dat", 1e-6),
        ("Capsules-i100-1090.dat", 1e-8),
        ("Confeti-ex03-Fc3D-SBM.dat", 1e-8),
        ("NESpheres_10_1.dat", 1e-8),
    ] {
        let p = siconos(name);
        compare(name, &p, NsgsOptions::default(), tol, 0.02);
    }
}

/// With a switch error far below the tolerance, the floor rule ends the f32 sweeps: the full
/// error tested after every sweep comes within 4x of the f32 rounding floor estimate (about
/// 4e-9 on this problem, where 20000 f32 sweeps alone stop near 5e-10), and f64 sweeps go on
/// to the tolerance.
#[test]
fn the_floor_rule_leaves_the_copy() {
    let p = siconos("Capsules-i100-889.dat");
    let full = NsgsOptions {
        error_evaluation: ErrorEvaluation::Full,
        ..Default::default()
    };
    let tol = 1e-9;
    let (f64_report, _, _) = run(&p, full, tol, 400_000);
    let options = NsgsOptions {
        f32_sweeps: Some(F32Sweeps {
            switch_error: 1e-14,
        }),
        ..full
    };
    let (report, r, u) = run(&p, options, tol, 400_000);
    println!(
        "f64 {} sweeps ({:.3e}); f32 copy {} sweeps, {:?} on the copy, {:.3e}",
        f64_report.iterations, f64_report.error, report.iterations, report.f32_sweeps, report.error
    );
    assert_eq!(f64_report.status, SolveStatus::Converged);
    assert_eq!(report.status, SolveStatus::Converged);
    check_report("Capsules-i100-889", &p, tol, &report, &r, &u);
    assert!(report.f32_sweeps.unwrap() < report.iterations);
    assert!(report.iterations as f64 <= 1.05 * f64_report.iterations as f64);
}

#[test]
fn f32_sweeps_are_bitwise_identical_for_one_and_two_threads() {
    let p = pile(PileShape::Boxes, 3000);
    let mut runs = Vec::new();
    for threads in [1, 2] {
        let options = mixed(NsgsOptions {
            decomposition: Decomposition::Coloured,
            threads,
            error_evaluation: ErrorEvaluation::Full,
            ..Default::default()
        });
        let (report, r, u) = run(&p, options, 1e-6, 100_000);
        assert_eq!(report.status, SolveStatus::Converged);
        check_report("boxes 3000 coloured", &p, 1e-6, &report, &r, &u);
        let on_copy = report.f32_sweeps.unwrap();
        assert!(on_copy > 0 && on_copy < report.iterations, "{report:?}");
        runs.push((report.iterations, on_copy, report.error.to_bits(), r));
    }
    let bits = |r: &[f64]| r.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(runs[0].0, runs[1].0);
    assert_eq!(runs[0].1, runs[1].1);
    assert_eq!(runs[0].2, runs[1].2);
    assert_eq!(bits(&runs[0].3), bits(&runs[1].3));
}

/// The default NSGS path (no f32 copy) computes, sweep after sweep, the update of the public
/// one-contact `update_contact` on W's f64 block rows, bit for bit; the f32 copy moves the
/// iterates by about its rounding only.
#[test]
fn the_default_path_is_unchanged() {
    for (name, p) in [
        ("Capsules-i101-404", siconos("Capsules-i101-404.dat")),
        ("spheres 1000", pile(PileShape::Spheres, 1000)),
    ] {
        let sweeps = 40;
        let (_, r_default, _) = run(&p, NsgsOptions::default(), 0.0, sweeps);
        let (_, r_none, _) = run(
            &p,
            NsgsOptions {
                f32_sweeps: None,
                ..Default::default()
            },
            0.0,
            sweeps,
        );
        let rows = p.w().block_rows().unwrap();
        let local = NsgsOptions::default().local;
        let step = LocalStep::new(&rows, &local).unwrap();
        let mut worker = step.worker();
        let mut memory = vec![1.0; p.n_contacts()];
        let mut r = vec![0.0; p.size()];
        for _ in 0..sweeps {
            for c in 0..p.n_contacts() {
                let rc = update_contact(
                    &rows,
                    &step,
                    &mut worker,
                    None,
                    c,
                    p.q(),
                    p.mu(),
                    &r,
                    &mut memory[c],
                );
                r[3 * c..3 * c + 3].copy_from_slice(&rc);
            }
        }
        let bits = |r: &[f64]| r.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&r_default), bits(&r), "{name}");
        assert_eq!(bits(&r_none), bits(&r), "{name}");
        // 40 sweeps on the copy (a switch error no cheap error reaches so early; tolerance 0:
        // no full test in the loop).
        let on_copy = NsgsOptions {
            f32_sweeps: Some(F32Sweeps {
                switch_error: 1e-30,
            }),
            ..Default::default()
        };
        let (report, r32, _) = run(&p, on_copy, 0.0, sweeps);
        assert_eq!(report.f32_sweeps, Some(sweeps), "{name}");
        let d: Vec<f64> = r32.iter().zip(&r).map(|(x, y)| x - y).collect();
        assert!(bits(&r32) != bits(&r), "{name}: the copy was not read");
        assert!(
            norm(&d) <= 1e-4 * norm(&r),
            "{name}: {}",
            norm(&d) / norm(&r)
        );
    }
}

#[test]
fn f32_sweeps_options_are_checked() {
    let p = siconos("Capsules-i101-404.dat");
    for (options, what) in [
        (
            NsgsOptions {
                f32_sweeps: Some(F32Sweeps { switch_error: 0.0 }),
                ..Default::default()
            },
            "switch_error",
        ),
        (
            NsgsOptions {
                f32_sweeps: Some(F32Sweeps {
                    switch_error: f64::NAN,
                }),
                ..Default::default()
            },
            "switch_error",
        ),
        (
            mixed(NsgsOptions {
                decomposition: Decomposition::Islands,
                ..Default::default()
            }),
            "f32_sweeps",
        ),
    ] {
        let config = SolverConfig::new(options);
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        let e = solve(&p, &config, &mut r, &mut u).unwrap_err();
        assert!(e.to_string().contains(what), "{e}");
        assert!(r.iter().all(|&v| v == 0.0));
    }
}
