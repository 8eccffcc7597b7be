//! Total solve time over the generated time-stepping sequences, each step solved cold (the
//! host's driver call from r = 0, everything prepared anew) and through a [`Workspace`] (warm
//! start by contact id, prepared W structure reused), at the same tolerance.
//!
//! `cargo run --release -p fc3d-core --example warm_start [-- REPEATS [pile|box]]`
//!
//! Prints, per sequence and solver, the median over REPEATS (default 5) of the total solve time
//! cold, with the warm start alone (the host keeps the reactions by id and calls `solve`; W's
//! structures are rebuilt) and through the workspace ("warm"), the ratio cold / warm, and for cold
//! and warm the total iterations, the largest error and the steps not converged. With
//! `FC3D_TRACE_STEPS` set, each step's solve is printed on stderr (time, iterations, error,
//! AUTO's rule and stages).

use std::collections::HashMap;
use std::time::Instant;

use fc3d_core::scenes::sequences::{box_slide, pile_settling, Sequence};
use fc3d_core::{solve, NsgsOptions, NsnFormulation, NsnOptions, SolverConfig, Workspace};

fn reference_solve(p: &fc3d_core::FrictionProblem<'_>) -> Vec<f64> {
    let config = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(1e-8)
        .with_max_iter(2_000);
    let n = p.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let t = Instant::now();
    let rep = solve(p, &config, &mut r, &mut u).expect("valid step");
    if std::env::var_os("FC3D_TRACE").is_some() {
        eprintln!(
            "{} contacts: {:?} {} it {:.1e} in {:.1} ms",
            p.n_contacts(),
            rep.status,
            rep.iterations,
            rep.error,
            1e3 * t.elapsed().as_secs_f64()
        );
    }
    r
}

struct Totals {
    seconds: f64,
    iterations: usize,
    max_error: f64,
    not_converged: usize,
}

/// How each step is solved.
#[derive(Clone, Copy, PartialEq)]
enum Mode {
    /// `solve` from r = 0 (a host calling the driver).
    Cold,
    /// `solve` from the previous step's reactions matched by id, kept by the host (warm start
    /// alone: everything built from W is rebuilt).
    WarmOnly,
    /// Through a `Workspace` (warm start and the prepared W structure kept).
    Workspace,
}

fn run(seq: &Sequence, config: &SolverConfig, mode: Mode) -> Totals {
    let mut ws = Workspace::new();
    let mut previous: HashMap<i64, [f64; 3]> = HashMap::new();
    let mut t = Totals {
        seconds: 0.0,
        iterations: 0,
        max_error: 0.0,
        not_converged: 0,
    };
    for (k, step) in seq.steps.iter().enumerate() {
        let n = step.problem.size();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let start = Instant::now();
        let report = match mode {
            Mode::Workspace => ws.solve(&step.problem, config, &step.ids, &mut r, &mut u),
            Mode::Cold => solve(&step.problem, config, &mut r, &mut u),
            Mode::WarmOnly => {
                for (rc, id) in r.chunks_exact_mut(3).zip(&step.ids) {
                    rc.copy_from_slice(previous.get(id).unwrap_or(&[0.0; 3]));
                }
                let report = solve(&step.problem, config, &mut r, &mut u);
                previous.clear();
                for (rc, &id) in r.chunks_exact(3).zip(&step.ids) {
                    previous.insert(id, [rc[0], rc[1], rc[2]]);
                }
                report
            }
        }
        .expect("valid step");
        let elapsed = start.elapsed().as_secs_f64();
        t.seconds += elapsed;
        if std::env::var_os("FC3D_TRACE_STEPS").is_some() {
            let stages = report.stages.map(|log| {
                log.stages()
                    .map(|s| format!("{}:{}:{:?}", s.kind.name(), s.iterations, s.end))
                    .collect::<Vec<_>>()
                    .join(" ")
            });
            eprintln!(
                "step {} contacts {} {:.1} ms it {} err {:.1e} rule {:?} {}",
                k,
                step.ids.len(),
                1e3 * elapsed,
                report.iterations,
                report.error,
                report.stages.map(|l| l.rule),
                stages.unwrap_or_default()
            );
        }
        t.iterations += report.iterations;
        t.max_error = t.max_error.max(report.error);
        t.not_converged += usize::from(!report.converged());
    }
    t
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let repeats: usize = std::env::args()
        .nth(1)
        .map(|a| a.parse().expect("REPEATS is a number"))
        .unwrap_or(5);
    let only = std::env::args().nth(2);
    let wanted = |name: &str| only.as_deref().is_none_or(|o| name.starts_with(o));
    let mut sequences = Vec::new();
    if wanted("pile") {
        sequences.push(pile_settling(32, 250, &mut reference_solve));
    }
    if wanted("box") {
        sequences.push(box_slide(250, &mut reference_solve));
    }
    let nsgs = |tol: f64| SolverConfig::new(NsgsOptions::default()).with_tolerance(tol);
    let nsn = |tol: f64| {
        SolverConfig::new(NsnOptions::new(NsnFormulation::AlartCurnier)).with_tolerance(tol)
    };
    let configs = [
        ("NSGS tol 1e-4", nsgs(1e-4)),
        ("NSGS tol 1e-6", nsgs(1e-6)),
        ("NSN-AC tol 1e-8", nsn(1e-8)),
        (
            "AUTO tol 1e-6",
            SolverConfig::new(fc3d_core::AutoOptions::default()).with_tolerance(1e-6),
        ),
    ];
    println!(
        "{:<14} {:>5} {:>8} {:<16} {:>11} {:>11} {:>11} {:>7} {:>9} {:>9} {:>9} {:>9}",
        "sequence",
        "steps",
        "contacts",
        "solver",
        "cold ms",
        "warm-only ms",
        "warm ms",
        "ratio",
        "cold it",
        "warm it",
        "cold err",
        "warm err"
    );
    for seq in &sequences {
        let contacts: usize = seq.steps.iter().map(|s| s.ids.len()).max().unwrap_or(0);
        // NSN-AC does not solve the pile's hyperstatic steps (most end at its iteration limit,
        // cold or warm, after minutes): it runs on the box only.
        let skip_nsn = seq.name == "pile_settling";
        for (label, config) in configs
            .iter()
            .filter(|(l, _)| !(skip_nsn && l.starts_with("NSN")))
        {
            let (mut cold, mut warm, mut warm_only) = (Vec::new(), Vec::new(), Vec::new());
            let (mut cold_t, mut warm_t) = (None, None);
            for _ in 0..repeats {
                let c = run(seq, config, Mode::Cold);
                let o = run(seq, config, Mode::WarmOnly);
                let w = run(seq, config, Mode::Workspace);
                cold.push(c.seconds);
                warm_only.push(o.seconds);
                warm.push(w.seconds);
                cold_t = Some(c);
                warm_t = Some(w);
            }
            let (c, w) = (cold_t.expect("repeats > 0"), warm_t.expect("repeats > 0"));
            let (cm, wm, om) = (median(cold), median(warm), median(warm_only));
            println!(
                "{:<14} {:>5} {:>8} {:<16} {:>11.2} {:>11.2} {:>11.2} {:>7.2} {:>9} {:>9} {:>9.1e} {:>9.1e}{}",
                seq.name,
                seq.steps.len(),
                contacts,
                label,
                1e3 * cm,
                1e3 * om,
                1e3 * wm,
                cm / wm,
                c.iterations,
                w.iterations,
                c.max_error,
                w.max_error,
                if c.not_converged + w.not_converged > 0 {
                    format!(
                        "  (not converged: cold {}, warm {})",
                        c.not_converged, w.not_converged
                    )
                } else {
                    String::new()
                }
            );
        }
    }
}
