//! The f32 copy of W's coupling blocks (issue 27 item 5, docs/convergence.md "Cheaper bytes"):
//! one sweep's time and bytes in f64 and on the f32 copy, the f64 error the f32 sweeps reach on
//! their own (their floor), and sweeps and time to tolerances with and without the copy:
//!
//! `cargo run --release -p fc3d-core --example f32_sweeps -- [--shape spheres|boxes]
//! [--timing K] [--tols 1e-4,1e-6] [--budget SECONDS] [--floor SWEEPS] [--dat FILE]... CONTACTS...`
//!
//! Per size: `K` sweeps of each kind (one thread, alternated, from the same point after 5
//! warm-up sweeps; median); the bytes of W a sweep reads (coupling blocks with their column
//! indices and row pointers, diagonal blocks); with `--floor N`, N sweeps on the copy alone
//! (never switching) and the f64 error they reach; then, per tolerance, one run of NSGS with
//! the error (133) measured after every sweep (the same iterates as the default test) in f64
//! and with `NsgsOptions::f32_sweeps` (default switch error): sweeps, sweeps on the copy, wall
//! time, the estimated sweep time (sweeps times the medians above), the final error and the
//! relative distance between the two runs' reactions.

use std::time::{Duration, Instant};

use fc3d_core::matrix::F32Coupling;
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::{
    solve, ErrorEvaluation, F32Sweeps, FrictionProblem, NsgsOptions, SolverConfig, Sweeper,
};

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "?".into())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// Median ms of one sweep in f64 and on the f32 copy, alternated.
fn sweep_times(p: &FrictionProblem<'_>, k: usize) -> (f64, f64) {
    let f64_options = NsgsOptions::default();
    let f32_options = NsgsOptions {
        f32_sweeps: Some(F32Sweeps::default()),
        ..Default::default()
    };
    let mut s64 = Sweeper::with_options(p, &f64_options, 1e-4).expect("sweeper");
    let mut s32 = Sweeper::with_options(p, &f32_options, 1e-4).expect("sweeper");
    let (q, mu) = (p.q(), p.mu());
    let mut r = vec![0.0; p.size()];
    for _ in 0..5 {
        s64.sweep(q, mu, &mut r);
    }
    let (mut r64, mut r32) = (r.clone(), r);
    let (mut t64, mut t32) = (Vec::new(), Vec::new());
    // F32_SWEEPS_ONLY=f64 or f32: one kind of sweep only (for an instruction count of it).
    let only = std::env::var("F32_SWEEPS_ONLY").unwrap_or_default();
    for _ in 0..k {
        if only != "f32" {
            let t = Instant::now();
            s64.sweep(q, mu, &mut r64);
            t64.push(t.elapsed().as_secs_f64() * 1e3);
        }
        if only != "f64" {
            let t = Instant::now();
            s32.sweep(q, mu, &mut r32);
            t32.push(t.elapsed().as_secs_f64() * 1e3);
        }
    }
    (median(t64), median(t32))
}

/// Bytes of W one sweep reads: in f64 (coupling blocks 72 + column 8 each, row pointers,
/// diagonal blocks 72 + their position 8) and with the f32 copy (its bytes: coupling blocks
/// 36 + column 4 each, row pointers, its f64 diagonal blocks 72).
fn sweep_bytes(p: &FrictionProblem<'_>) -> (usize, usize) {
    let rows = p.w().block_rows().expect("rows");
    let nc = rows.n_contacts();
    let diagonal = 80 * nc;
    let f64_bytes = 80 * rows.n_off_diagonal() + 8 * (nc + 1) + diagonal;
    let copy = F32Coupling::from_rows(&rows)
        .expect("copy")
        .expect("in range");
    (f64_bytes, copy.bytes())
}

/// The least f64 error of `sweeps` sweeps on the f32 copy alone (measured every 50 sweeps),
/// the sweep where it was reached, and the rounding floor estimate the switch rule uses at the
/// end (`2^-24 || |W_off| |r| || / max(||q||, ||r||, ||u||)`).
fn floor(p: &FrictionProblem<'_>, sweeps: usize) -> (f64, usize, f64) {
    let options = NsgsOptions {
        f32_sweeps: Some(F32Sweeps::default()),
        ..Default::default()
    };
    let mut s = Sweeper::with_options(p, &options, 0.0).expect("sweeper");
    let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
    let mut best = (f64::INFINITY, 0);
    for k in 1..=sweeps {
        s.sweep(p.q(), p.mu(), &mut r);
        if k % 50 == 0 {
            let e = s.natural_map_error(p, &r, &mut u);
            if e < best.0 {
                best = (e, k);
            }
        }
    }
    s.natural_map_error(p, &r, &mut u);
    let rows = p.w().block_rows().expect("rows");
    let copy = F32Coupling::from_rows(&rows)
        .expect("copy")
        .expect("in range");
    let scale = norm(p.q()).max(norm(&r)).max(norm(&u));
    let estimate = f64::from(f32::EPSILON) * copy.abs_product_norm_sq(&r).sqrt() / scale;
    (best.0, best.1, estimate)
}

fn main() {
    let mut shape = PileShape::Spheres;
    let mut timing = 15;
    let mut tols = vec![1e-4, 1e-6];
    let mut budget = 120.0;
    let mut floor_sweeps = 0;
    let mut sizes = Vec::new();
    let mut dat = Vec::new();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().expect("a value after the option");
        match arg.as_str() {
            "--shape" => shape = PileShape::from_name(&value()).expect("shape"),
            "--timing" => timing = value().parse().expect("sweeps"),
            "--tols" => {
                let v = value();
                tols = if v.is_empty() {
                    Vec::new()
                } else {
                    v.split(',')
                        .map(|t| t.parse().expect("tolerance"))
                        .collect()
                };
            }
            "--budget" => budget = value().parse().expect("seconds"),
            "--floor" => floor_sweeps = value().parse().expect("sweeps"),
            "--dat" => dat.push(value()),
            size => sizes.push(size.parse::<usize>().expect("a contact count")),
        }
    }
    let mut problems: Vec<(String, FrictionProblem<'static>)> = Vec::new();
    for file in dat {
        let p =
            fc3d_core::io::dat::read_dat_file(std::path::Path::new(&file)).expect("a .dat file");
        problems.push((file.rsplit('/').next().unwrap_or(&file).to_string(), p));
    }
    for contacts in sizes {
        let scene = GeneratedScene {
            pile: PileSpec {
                contacts,
                piles: 4,
                seed: 1,
            },
            shape,
        };
        let p = scene.generate().expect("scene");
        problems.push((format!("{} {}", shape.label(), p.n_contacts()), p));
    }
    for (name, p) in problems {
        let n = p.size();
        let (b64, b32) = sweep_bytes(&p);
        let load = load_average();
        let (t64, t32) = if timing > 0 {
            sweep_times(&p, timing)
        } else {
            (f64::NAN, f64::NAN)
        };
        println!(
            "{name}: sweep {t64:.3} ms f64, {t32:.3} ms f32 copy ({:.2}x); W bytes a sweep \
             {:.1} MB f64, {:.1} MB f32 copy ({:.2}x); load {load} -> {}",
            t32 / t64,
            b64 as f64 / 1e6,
            b32 as f64 / 1e6,
            b32 as f64 / b64 as f64,
            load_average()
        );
        if floor_sweeps > 0 {
            let (e, k, estimate) = floor(&p, floor_sweeps);
            println!(
                "{name}: f32 sweeps alone: least f64 error {e:.3e} at sweep {k} of \
                 {floor_sweeps}; floor estimate {estimate:.3e}"
            );
        }
        for &tol in &tols {
            let mut reactions = Vec::new();
            for f32_sweeps in [None, Some(F32Sweeps::default())] {
                let config = SolverConfig::new(NsgsOptions {
                    error_evaluation: ErrorEvaluation::Full,
                    f32_sweeps,
                    ..Default::default()
                })
                .with_tolerance(tol)
                .with_max_iter(usize::MAX)
                .with_time_budget(Some(Duration::from_secs_f64(budget)));
                let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
                let load = load_average();
                let t = Instant::now();
                let report = solve(&p, &config, &mut r, &mut u).expect("solve");
                let wall = t.elapsed().as_secs_f64();
                let on_copy = report.f32_sweeps.unwrap_or(0);
                let estimate = on_copy as f64 * t32 + (report.iterations - on_copy) as f64 * t64;
                println!(
                    "{name} tol {tol:.0e} {}: {:?} after {} sweeps ({on_copy} on the copy), \
                     error {:.3e}, wall {wall:.2} s, sweeps {:.2} s; load {load} -> {}",
                    if f32_sweeps.is_some() {
                        "f32 copy"
                    } else {
                        "f64"
                    },
                    report.status,
                    report.iterations,
                    report.error,
                    estimate / 1e3,
                    load_average()
                );
                reactions.push(r);
            }
            let d: Vec<f64> = reactions[0]
                .iter()
                .zip(&reactions[1])
                .map(|(a, b)| a - b)
                .collect();
            println!(
                "{name} tol {tol:.0e}: ||r_f32 - r_f64|| / ||r_f64|| = {:.2e}",
                norm(&d) / norm(&reactions[0])
            );
        }
    }
}
