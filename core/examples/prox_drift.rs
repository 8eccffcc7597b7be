//! Does a proximal term hold the drift that stalls the sphere piles?
//!
//! `cargo run --release -p fc3d-core --example prox_drift -- [--seconds S] CONTACTS SHIFT...`
//!
//! On the generated sphere pile (4 piles, seed 1), from r = 0, each run cut at S seconds
//! (default 30): NSGS with Siconos' defaults (500/565), then the proximal point method with NSGS
//! inside (502 PROX-NSGS: FC(W + a I, q - a r_k, mu) solved to `max(error / 10, tol / n)`) with
//! Siconos' adaptive shift (`a = 5 error`, SHIFT `adaptive`) and with each fixed shift SHIFT given
//! as a multiple of the mean normal diagonal `mean(W_NN)`; with SHIFT `tikhonov:K`, NSGS on the
//! regularized problem FC(W + K mean(W_NN) I, q, mu) itself (one solution selected: W + aI is
//! positive definite), its iterates measured on the pile's own problem. Prints the error (133) and `||r||`
//! after each outer iteration at powers of two and at the end, with the seconds spent, and the
//! error of the returned iterate (docs/convergence.md, "What stalls the sphere piles").

use std::time::{Duration, Instant};

use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::{
    natural_map_error, solve_with_observer, ErrorEvaluation, FrictionProblem, Method, NsgsOptions,
    ProxInternal, ProxOptions, SolverConfig,
};

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn main() {
    let mut seconds = 30.0;
    let mut words = Vec::new();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--seconds" => seconds = it.next().expect("seconds").parse().expect("seconds"),
            word => words.push(word.to_string()),
        }
    }
    let (contacts, shifts) = words.split_first().expect("CONTACTS SHIFT...");
    let p = GeneratedScene {
        pile: PileSpec {
            contacts: contacts.parse().expect("contacts"),
            piles: 4,
            seed: 1,
        },
        shape: PileShape::Spheres,
    }
    .generate()
    .expect("scene");
    let n = p.size();
    let nc = p.n_contacts();
    let mean_wnn = (0..nc).map(|c| p.w().get(3 * c, 3 * c)).sum::<f64>() / nc as f64;
    println!("{nc} contacts, mean W_NN {mean_wnn:.3e}");
    // NSGS measures the full error after every sweep (its default schedule reports a cheaper
    // estimate between full tests), as friction_wall does.
    let nsgs = NsgsOptions {
        error_evaluation: ErrorEvaluation::Full,
        ..Default::default()
    };
    let mut runs: Vec<(String, Method)> = vec![("NSGS".into(), Method::Nsgs(nsgs))];
    let mut tikhonov = Vec::new();
    for s in shifts {
        if let Some(k) = s.strip_prefix("tikhonov:") {
            tikhonov.push(k.parse::<f64>().expect("tikhonov:K"));
            continue;
        }
        let (label, alpha) = if s == "adaptive" {
            ("PROX-NSGS adaptive (a = 5 error)".to_string(), 1e4)
        } else {
            let k: f64 = s.parse().expect("a shift factor or `adaptive`");
            (format!("PROX-NSGS fixed a = {k} mean(W_NN)"), -k * mean_wnn)
        };
        runs.push((
            label,
            Method::Prox(ProxOptions {
                alpha,
                internal: ProxInternal::Nsgs(NsgsOptions::default()),
                ..ProxOptions::default()
            }),
        ));
    }
    let mut problems: Vec<(String, Method, Option<FrictionProblem<'static>>)> = runs
        .into_iter()
        .map(|(label, method)| (label, method, None))
        .collect();
    for k in tikhonov {
        let regularized = FrictionProblem::new(
            p.w().shifted(k * mean_wnn).expect("W + aI"),
            p.q().to_vec(),
            p.mu().to_vec(),
        )
        .expect("problem");
        problems.push((
            format!("NSGS on FC(W + {k} mean(W_NN) I, q, mu), error on FC(W, q, mu)"),
            Method::Nsgs(nsgs),
            Some(regularized),
        ));
    }
    let mut work = vec![0.0; n];
    for (label, method, regularized) in problems {
        let solved = regularized.as_ref().unwrap_or(&p);
        let config = SolverConfig::new(method)
            .with_tolerance(1e-4)
            .with_max_iter(usize::MAX)
            .with_time_budget(Some(Duration::from_secs_f64(seconds)));
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let start = Instant::now();
        let mut points = Vec::new();
        let mut last = (0, f64::NAN, 0.0, 0.0);
        let report = solve_with_observer(solved, &config, &mut r, &mut u, &mut |e| {
            let mut own = || {
                if regularized.is_some() {
                    natural_map_error(&p, e.reaction, &mut work)
                } else {
                    e.error
                }
            };
            last = (e.iteration, f64::NAN, norm(e.reaction), 0.0);
            if e.iteration.is_power_of_two() {
                last.1 = own();
                last.3 = start.elapsed().as_secs_f64();
                points.push(last);
            }
        })
        .expect("solve");
        let own_error = natural_map_error(&p, &r, &mut work);
        if points.last().is_none_or(|p| p.0 != last.0) {
            points.push((last.0, own_error, last.2, start.elapsed().as_secs_f64()));
        }
        let mut line = format!(
            "{label}: {} after {} iterations ({:.2e} on the pile's problem, |r| {:.2})",
            report.status.name(),
            report.iterations,
            own_error,
            norm(&r)
        );
        for &(k, error, r_norm, t) in &points {
            line.push_str(&format!(" {k}:{error:.2e}(|r| {r_norm:.2}, {t:.1} s)"));
        }
        println!("{line}");
    }
}
