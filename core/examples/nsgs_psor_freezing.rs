//! NSGS with over-relaxation (PSOR) and freezing against AUTO and the factorizing solvers, to a
//! list of tolerances: for each problem and tolerance one line per configuration with its
//! iterations, status, error and the best wall-clock time of `reps` runs. NSGS stops on the
//! true error (133) measured after every sweep (one product with W a sweep: its times are upper
//! bounds). Behind AUTO's rule table (docs/auto.md, "NSGS with PSOR and freezing"):
//!
//! `cargo run --release -p fc3d-core --example nsgs_psor_freezing -- 1e-6,1e-8 3 all ../shared/data/siconos/Capsules-*.dat`

use std::path::Path;
use std::time::{Duration, Instant};

use fc3d_core::io::read_problem_file;
use fc3d_core::{solve, ErrorEvaluation, LocalSolverKind, Method, NsgsOptions, SolverConfig};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let tolerances: Vec<f64> = args[0].split(',').map(|t| t.parse().unwrap()).collect();
    let reps: usize = args[1].parse().unwrap();
    // `all`: omega 1.1-1.5 and k 2, 5, 10; `short`: omega 1.3 and 1.5, k 5.
    let short = args[2] == "short";
    let files = &args[3..];
    let mut configs: Vec<(String, Method)> = Vec::new();
    for label in ["AUTO", "ADMM", "PROX", "NSN-AC", "TFP-APGD", "EG"] {
        let m = Method::presets()
            .into_iter()
            .find(|m| m.label() == label || m.name() == label)
            .unwrap_or_else(|| panic!("no preset {label}"));
        configs.push((label.to_string(), m));
    }
    let (omegas, ks): (&[Option<f64>], &[Option<usize>]) = if short {
        (&[None, Some(1.3), Some(1.5)], &[None, Some(5)])
    } else {
        (
            &[None, Some(1.1), Some(1.2), Some(1.3), Some(1.4), Some(1.5)],
            &[None, Some(2), Some(5), Some(10)],
        )
    };
    for &omega in omegas {
        for &freezing in ks {
            let o = NsgsOptions {
                error_evaluation: ErrorEvaluation::Full,
                relaxation: omega,
                freezing,
                ..NsgsOptions::with_local(LocalSolverKind::Quartic)
            };
            configs.push((
                format!(
                    "NSGS/562 w={} k={}",
                    omega.map_or("-".into(), |w: f64| w.to_string()),
                    freezing.map_or("-".into(), |k: usize| k.to_string())
                ),
                Method::Nsgs(o),
            ));
        }
    }
    for f in files {
        let p = read_problem_file(Path::new(f)).expect("problem");
        let n = 3 * p.n_contacts();
        for &tol in &tolerances {
            println!(
                "{} ({} contacts) tol {tol:e}",
                Path::new(f).file_name().unwrap().to_string_lossy(),
                p.n_contacts()
            );
            for (name, m) in &configs {
                let mut config = SolverConfig::new(*m)
                    .with_tolerance(tol)
                    .with_max_iter(100_000)
                    .with_time_budget(Some(Duration::from_secs(2)));
                config.tolerance = tol;
                let mut best = f64::INFINITY;
                let mut last = None;
                for _ in 0..reps {
                    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
                    let t = Instant::now();
                    let rep = solve(&p, &config, &mut r, &mut u).expect("solve");
                    best = best.min(t.elapsed().as_secs_f64());
                    last = Some(rep);
                }
                let rep = last.unwrap();
                let stages = rep
                    .stages
                    .as_ref()
                    .map_or(String::new(), |s| format!("{s:?}"));
                println!(
                    "  {name:<22} {:>6} it. {:<12} {:.2e} {:>10.3} ms {}",
                    rep.iterations,
                    format!("{:?}", rep.status),
                    rep.error,
                    1e3 * best,
                    if stages.len() > 80 {
                        &stages[..80]
                    } else {
                        &stages
                    }
                );
            }
        }
    }
}
