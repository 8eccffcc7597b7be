//! Sweeps NSGS (Siconos' defaults, local solver 565) needs to bring the error (133) below 1e-3,
//! 1e-4 and 1e-6 on the generated piles, against their size (docs/convergence.md):
//!
//! `cargo run --release -p fc3d-core --example sweeps_vs_size -- [--shape spheres|boxes]
//! [--piles P] [--budget SECONDS] [--csv FILE] [--history FILE] CONTACTS...`
//!
//! Per size: the time of one sweep (a 20-sweep run with the default options, no error measured,
//! divided by 20), then one run with the error measured after every sweep (the same iterates as
//! the default options, whose stopping test only reads a cheaper error) to 1e-6, cut by the time
//! budget (default 600 s): the first sweep at which each tolerance holds, the error where the
//! run stopped, and the load average of the machine before and after (it is shared). With
//! `--history`, the error at sweeps 1, 2, 4, 8, ... and at the last sweep, for the picture.

use std::io::Write;
use std::time::{Duration, Instant};

use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::{solve, solve_with_observer, ErrorEvaluation, NsgsOptions, SolverConfig};

const TOLERANCES: [f64; 3] = [1e-3, 1e-4, 1e-6];

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "?".into())
}

fn main() {
    let mut shape = PileShape::Spheres;
    let mut piles = 4;
    let mut budget = 600.0;
    let mut csv_path = None;
    let mut history_path = None;
    let mut sizes = Vec::new();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().expect("a value after the option");
        match arg.as_str() {
            "--shape" => shape = PileShape::from_name(&value()).expect("shape"),
            "--piles" => piles = value().parse().expect("piles"),
            "--budget" => budget = value().parse().expect("seconds"),
            "--csv" => csv_path = Some(value()),
            "--history" => history_path = Some(value()),
            size => sizes.push(size.parse::<usize>().expect("a contact count")),
        }
    }
    let shape_name = shape.label();
    let header = "shape,contacts,piles,layers,sweep_ms,sweeps_1e-3,sweeps_1e-4,sweeps_1e-6,\
                  est_s_1e-3,est_s_1e-4,est_s_1e-6,last_sweep,last_error,run_s,load_before,load_after";
    println!("{header}");
    let mut csv = csv_path.map(|f| std::fs::File::create(f).expect("csv"));
    if let Some(f) = csv.as_mut() {
        writeln!(f, "{header}").unwrap();
    }
    let mut history = history_path.map(|f| std::fs::File::create(f).expect("history csv"));
    if let Some(f) = history.as_mut() {
        writeln!(f, "shape,contacts,sweep,error").unwrap();
    }
    for contacts in sizes {
        let scene = GeneratedScene {
            pile: PileSpec {
                contacts,
                piles,
                seed: 1,
            },
            shape,
        };
        let layers = scene.pile_layers().into_iter().max().unwrap_or(0);
        let p = scene.generate().expect("scene");
        let n = p.size();
        let load_before = load_average();
        // One sweep's time: 20 sweeps with the default options (tolerance 0: no stop).
        let timing = SolverConfig::new(NsgsOptions::default())
            .with_tolerance(0.0)
            .with_max_iter(20);
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let t = Instant::now();
        solve(&p, &timing, &mut r, &mut u).expect("solve");
        let sweep = t.elapsed().as_secs_f64() / 20.0;
        let config = SolverConfig::new(NsgsOptions {
            error_evaluation: ErrorEvaluation::Full,
            ..Default::default()
        })
        .with_tolerance(1e-6)
        .with_max_iter(usize::MAX)
        .with_time_budget(Some(Duration::from_secs_f64(budget)));
        r.iter_mut().for_each(|v| *v = 0.0);
        let mut first = [None; 3];
        let mut points: Vec<(usize, f64)> = Vec::new();
        let mut last = (0, f64::NAN);
        let t = Instant::now();
        solve_with_observer(&p, &config, &mut r, &mut u, &mut |e| {
            for (k, tol) in TOLERANCES.into_iter().enumerate() {
                if first[k].is_none() && e.error <= tol {
                    first[k] = Some(e.iteration);
                }
            }
            if e.iteration.is_power_of_two() {
                points.push((e.iteration, e.error));
            }
            last = (e.iteration, e.error);
        })
        .expect("solve");
        let run_s = t.elapsed().as_secs_f64();
        if points.last().is_none_or(|&(k, _)| k != last.0) {
            points.push(last);
        }
        let sweeps = |k: usize| first[k].map_or("-".to_string(), |s| s.to_string());
        let estimate =
            |k: usize| first[k].map_or("-".to_string(), |s| format!("{:.3}", s as f64 * sweep));
        let line = format!(
            "{shape_name},{contacts},{piles},{layers},{:.3},{},{},{},{},{},{},{},{:.3e},{run_s:.1},{load_before},{}",
            1e3 * sweep,
            sweeps(0),
            sweeps(1),
            sweeps(2),
            estimate(0),
            estimate(1),
            estimate(2),
            last.0,
            last.1,
            load_average()
        );
        println!("{line}");
        if let Some(f) = csv.as_mut() {
            writeln!(f, "{line}").unwrap();
        }
        if let Some(f) = history.as_mut() {
            for (k, e) in points {
                writeln!(f, "{shape_name},{contacts},{k},{e:.6e}").unwrap();
            }
        }
    }
}
