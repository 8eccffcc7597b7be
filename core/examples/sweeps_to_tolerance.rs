//! Sweeps and time NSGS needs for the error (133) to reach 1e-4 and 1e-6, measured at every
//! sweep (not the stopping test), for a list of NSGS configurations; and the sweeps at which
//! Siconos' stopping test (light error with a full final check) stops. Diagnosis of the gap to
//! So-bogus on the Capsules problems:
//! `cargo run --release -p fc3d-core --example sweeps_to_tolerance -- ../shared/data/siconos/Capsules-*.dat`

use std::path::Path;
use std::time::Instant;

use fc3d_core::io::read_problem_file;
use fc3d_core::{
    solve, solve_with_observer, ErrorEvaluation, LocalSolverKind, LocalSolverOptions, NsgsOptions,
    SolverConfig,
};

fn main() {
    let files: Vec<String> = std::env::args().skip(1).collect();
    let mut configs: Vec<(String, NsgsOptions)> =
        vec![("565 (Siconos default)".into(), NsgsOptions::default())];
    for kind in [
        LocalSolverKind::NewtonAlartCurnierGp,
        LocalSolverKind::Quartic,
        LocalSolverKind::ProjectionOnConeWithLocalIteration,
    ] {
        configs.push((
            format!("{}", kind.siconos_id()),
            NsgsOptions::with_local(kind),
        ));
    }
    let fc3d_variant = NsgsOptions {
        local: LocalSolverOptions {
            variant: fc3d_core::AlgorithmVariant::Fc3d,
            ..LocalSolverOptions::default()
        },
        ..Default::default()
    };
    configs.push(("565 fc3d variant".into(), fc3d_variant));
    for omega in [1.2, 1.4, 1.6] {
        configs.push((
            format!("565 omega {omega}"),
            NsgsOptions {
                relaxation: Some(omega),
                ..Default::default()
            },
        ));
    }
    for f in &files {
        let p = read_problem_file(Path::new(f)).expect("problem");
        let n = 3 * p.n_contacts();
        println!(
            "{} ({} contacts, asymmetry {:.2e})",
            Path::new(f).file_name().unwrap().to_string_lossy(),
            p.n_contacts(),
            p.w().relative_asymmetry()
        );
        for (name, o) in &configs {
            // Every sweep measured: the first sweep at which (133) passes each tolerance.
            let mut config = SolverConfig::new(NsgsOptions {
                error_evaluation: ErrorEvaluation::Full,
                ..*o
            });
            config.tolerance = 1e-6;
            config.max_iter = 20000;
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let mut first = [None, None];
            let t = Instant::now();
            let mut times = [0.0; 2];
            let report = solve_with_observer(&p, &config, &mut r, &mut u, &mut |e| {
                for (k, tol) in [1e-4, 1e-6].into_iter().enumerate() {
                    if first[k].is_none() && e.error <= tol {
                        first[k] = Some(e.iteration);
                        times[k] = t.elapsed().as_secs_f64();
                    }
                }
            })
            .expect("solve");
            // Siconos' stopping test at 1e-4 (light error, full final check).
            let mut config = SolverConfig::new(*o);
            config.tolerance = 1e-4;
            config.max_iter = 20000;
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let t = Instant::now();
            let stop = solve(&p, &config, &mut r, &mut u).expect("solve");
            let stop_time = t.elapsed().as_secs_f64();
            let show = |s: Option<usize>| s.map_or("-".to_string(), |s| s.to_string());
            println!(
                "  {name:<22} full test every sweep: 1e-4 at sweep {:>5} ({:.2} ms), 1e-6 at {:>5} ({:.2} ms) (final {:.1e});  Siconos' light stop at 1e-4: {:>5} sweeps, {:.2} ms (error {:.1e})",
                show(first[0]),
                1e3 * times[0],
                show(first[1]),
                1e3 * times[1],
                report.error,
                stop.iterations,
                1e3 * stop_time,
                stop.error
            );
        }
    }
}
