//! Time to a tolerance of the exact-Coulomb fixed points (TFP, ACLMFP, PFP) with each inner
//! solver of their convex sub-problems, on the generated piles (docs/convergence.md):
//!
//! `cargo run --release -p fc3d-core --example inner_solvers -- [--shape spheres|boxes]
//! [--piles P] [--seed S] [--tols 1e-4,1e-6] [--budget SECONDS] [--solvers TFP,TFP-APGD,...] [--csv FILE]
//! [--inner-ratio R] [--inner-max N] CONTACTS...`
//!
//! `--inner-ratio R` sets the adaptive inner tolerance of every solver to `outer error / R`
//! (default: each preset's, Siconos' 10), `--inner-max N` the iterations of each inner solve.
//!
//! One run per (size, solver, tolerance), from r = 0, cut by the budget (default 60 s): wall
//! time, outer iterations, work in products with W (`SolveReport::products`), the error the
//! solve reports and the same error recomputed here from W's product and the cone projection
//! (`fc3d_core::natural_map_error` on the returned r), and the machine's load average.

use std::io::Write;
use std::time::{Duration, Instant};

use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::{natural_map_error, solve, InnerTolerance, Method, SolverConfig};

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "?".into())
}

fn main() {
    let mut shape = PileShape::Spheres;
    let mut piles = 4;
    let mut seed = 1;
    let mut budget = 60.0;
    let mut tols = vec![1e-4, 1e-6];
    let mut solvers: Vec<String> = [
        "TFP",
        "TFP-APGD",
        "TFP-SPG",
        "ACLMFP",
        "ACLMFP-APGD",
        "ACLMFP-SPG",
    ]
    .map(String::from)
    .to_vec();
    let mut csv_path = None;
    let mut inner_ratio: Option<f64> = None;
    let mut inner_max: Option<usize> = None;
    let mut sizes = Vec::new();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().expect("a value after the option");
        match arg.as_str() {
            "--shape" => shape = PileShape::from_name(&value()).expect("shape"),
            "--piles" => piles = value().parse().expect("piles"),
            "--seed" => seed = value().parse().expect("seed"),
            "--budget" => budget = value().parse().expect("seconds"),
            "--tols" => {
                tols = value()
                    .split(',')
                    .map(|t| t.parse().expect("tol"))
                    .collect()
            }
            "--solvers" => solvers = value().split(',').map(String::from).collect(),
            "--csv" => csv_path = Some(value()),
            "--inner-ratio" => inner_ratio = Some(value().parse().expect("ratio")),
            "--inner-max" => inner_max = Some(value().parse().expect("iterations")),
            size => sizes.push(size.parse::<usize>().expect("a contact count")),
        }
    }
    let shape_name = shape.label();
    let header = "shape,contacts,piles,solver,tolerance,status,seconds,outer_iterations,products,\
                  reported_error,recomputed_error,load_before,load_after,inner_ratio,inner_max";
    println!("{header}");
    let mut csv = csv_path.map(|f| std::fs::File::create(f).expect("csv"));
    if let Some(f) = csv.as_mut() {
        writeln!(f, "{header}").unwrap();
    }
    for contacts in sizes {
        let scene = GeneratedScene {
            pile: PileSpec {
                contacts,
                piles,
                seed,
            },
            shape,
        };
        let p = scene.generate().expect("scene");
        let n = p.size();
        for name in &solvers {
            let mut method =
                Method::preset(name).unwrap_or_else(|| panic!("unknown solver {name}"));
            let inner = match &mut method {
                Method::Tresca(o) => Some((&mut o.inner_tolerance, &mut o.inner_max_iter)),
                Method::Pfp(o) => Some((&mut o.inner_tolerance, &mut o.inner_max_iter)),
                Method::Aclm(o) => Some((&mut o.inner_tolerance, &mut o.inner_max_iter)),
                _ => None,
            };
            // Other presets (NSGS, ...) run as they are, for comparison.
            if let Some((tolerance, max_iter)) = inner {
                if let Some(ratio) = inner_ratio {
                    *tolerance = InnerTolerance::Adaptive { ratio };
                }
                if let Some(n) = inner_max {
                    *max_iter = n;
                }
            }
            for &tol in &tols {
                let config = SolverConfig::new(method)
                    .with_tolerance(tol)
                    .with_max_iter(100_000)
                    .with_time_budget(Some(Duration::from_secs_f64(budget)));
                let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
                let load_before = load_average();
                let t = Instant::now();
                let report = solve(&p, &config, &mut r, &mut u).expect("solve");
                let seconds = t.elapsed().as_secs_f64();
                let recomputed = natural_map_error(&p, &r, &mut u);
                let line = format!(
                    "{shape_name},{contacts},{piles},{name},{tol:e},{},{seconds:.3},{},{},{:.3e},{recomputed:.3e},{load_before},{}",
                    report.status.name(),
                    report.iterations,
                    report.products.map_or("-".to_string(), |k| k.to_string()),
                    report.error,
                    load_average()
                ) + &format!(
                    ",{},{}",
                    inner_ratio.map_or("-".to_string(), |r| r.to_string()),
                    inner_max.map_or("-".to_string(), |n| n.to_string())
                );
                println!("{line}");
                if let Some(f) = csv.as_mut() {
                    writeln!(f, "{line}").unwrap();
                }
            }
        }
    }
}
