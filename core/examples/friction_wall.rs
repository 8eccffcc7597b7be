//! Is the stall of NSGS on generated sphere piles the conditioning of W or the friction?
//!
//! `cargo run --release -p fc3d-core --example friction_wall -- [--shape spheres|boxes]
//! [--seconds S] [--csv FILE] CONTACTS MU_SCALE...`
//!
//! Solves the generated pile (4 piles, seed 1) with every friction coefficient multiplied by each
//! MU_SCALE (0: frictionless, a convex problem with the same W and q), by NSGS with Siconos'
//! defaults (500, local solver 565) from r = 0, the error (133) measured after every sweep (the
//! default run's iterates), cut at S seconds (default 60). Prints, per scale, the error and
//! `||r||` at sweeps 2^k and the first sweep below 1e-3, 1e-4 and 1e-6; `--csv` writes
//! `shape,contacts,mu_scale,sweep,error,r_norm` at sweeps 2^k and at the last sweep
//! (docs/convergence.md, "What stalls the sphere piles").

use std::io::Write;
use std::time::Duration;

use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::{solve_with_observer, ErrorEvaluation, FrictionProblem, NsgsOptions, SolverConfig};

const TOLERANCES: [f64; 3] = [1e-3, 1e-4, 1e-6];

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn main() {
    let mut shape = PileShape::Spheres;
    let mut seconds = 60.0;
    let mut csv = None;
    let mut numbers = Vec::new();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().expect("a value after the option");
        match arg.as_str() {
            "--shape" => shape = PileShape::from_name(&value()).expect("shape"),
            "--seconds" => seconds = value().parse().expect("seconds"),
            "--csv" => csv = Some(std::fs::File::create(value()).expect("csv file")),
            number => numbers.push(number.parse::<f64>().expect("a number")),
        }
    }
    let (&contacts, scales) = numbers.split_first().expect("CONTACTS MU_SCALE...");
    let contacts = contacts as usize;
    if let Some(f) = csv.as_mut() {
        writeln!(f, "shape,contacts,mu_scale,sweep,error,r_norm").unwrap();
    }
    let scene = GeneratedScene {
        pile: PileSpec {
            contacts,
            piles: 4,
            seed: 1,
        },
        shape,
    };
    let p = scene.generate().expect("scene");
    let n = p.size();
    for &scale in scales {
        let mu: Vec<f64> = p.mu().iter().map(|m| m * scale).collect();
        let scaled = FrictionProblem::new(p.w().clone(), p.q().to_vec(), mu).expect("problem");
        let config = SolverConfig::new(NsgsOptions {
            error_evaluation: ErrorEvaluation::Full,
            ..Default::default()
        })
        .with_tolerance(1e-8)
        .with_max_iter(usize::MAX)
        .with_time_budget(Some(Duration::from_secs_f64(seconds)));
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let mut points = Vec::new();
        let mut first = [None; 3];
        let mut last = (0, f64::NAN, 0.0);
        solve_with_observer(&scaled, &config, &mut r, &mut u, &mut |e| {
            for (k, tol) in TOLERANCES.into_iter().enumerate() {
                if first[k].is_none() && e.error <= tol {
                    first[k] = Some(e.iteration);
                }
            }
            last = (e.iteration, e.error, norm(e.reaction));
            if e.iteration.is_power_of_two() {
                points.push(last);
            }
        })
        .expect("solve");
        if points.last().is_none_or(|p| p.0 != last.0) {
            points.push(last);
        }
        let reached: Vec<String> = TOLERANCES
            .iter()
            .zip(first)
            .map(|(t, s)| format!("{t:.0e}: {}", s.map_or("-".into(), |s| s.to_string())))
            .collect();
        let mut line = format!(
            "{} {contacts} mu x {scale}: [{}]",
            shape.label(),
            reached.join(", ")
        );
        for &(sweep, error, r_norm) in &points {
            line.push_str(&format!(" {sweep}:{error:.2e}(|r| {r_norm:.2})"));
            if let Some(f) = csv.as_mut() {
                writeln!(
                    f,
                    "{},{contacts},{scale},{sweep},{error:.4e},{r_norm:.6}",
                    shape.label()
                )
                .unwrap();
            }
        }
        println!("{line}");
    }
}
