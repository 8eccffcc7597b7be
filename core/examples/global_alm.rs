//! The SSN-ALM (690) on generated global piles: time and error, against 607 and 613.
//!
//! `cargo run --release -p fc3d-core --example global_alm -- [spheres|boxes] contacts tol budget_s`

use std::time::{Duration, Instant};

use fc3d_core::global::{solve_global_with_observer, GlobalConfig, GlobalMethod};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let shape = if args.first().map(String::as_str) == Some("boxes") {
        PileShape::Boxes
    } else {
        PileShape::Spheres
    };
    let contacts: usize = args.get(1).map_or(1000, |a| a.parse().unwrap());
    let tol: f64 = args.get(2).map_or(1e-4, |a| a.parse().unwrap());
    let budget: f64 = args.get(3).map_or(30.0, |a| a.parse().unwrap());
    let methods: Vec<String> = if args.len() > 4 {
        args[4..].to_vec()
    } else {
        vec!["690".into()]
    };
    let scene = GeneratedScene {
        pile: PileSpec {
            contacts,
            piles: 4,
            seed: 1,
        },
        shape,
    };
    let p = scene.generate_global().unwrap();
    println!("{} contacts, {} unknowns", p.n_contacts(), p.ndof());
    for name in &methods {
        let method = GlobalMethod::preset(name).unwrap();
        let mut config = GlobalConfig::new(method);
        config.tolerance = tol;
        config.max_iter = 1_000_000;
        config.time_budget = Some(Duration::from_secs_f64(budget));
        let (mut r, mut u, mut v) = (
            vec![0.0; p.size()],
            vec![0.0; p.size()],
            vec![0.0; p.ndof()],
        );
        let t = Instant::now();
        let report = solve_global_with_observer(&p, &config, &mut r, &mut u, &mut v, &mut |e| {
            eprintln!(
                "  it {:6} error {:.3e} at {:.3} s",
                e.iteration,
                e.error,
                t.elapsed().as_secs_f64()
            );
        })
        .unwrap();
        println!(
            "{:>16} {:?} iterations {} error {:.3e} time {:.3} s",
            method.label(),
            report.status,
            report.iterations,
            report.error,
            t.elapsed().as_secs_f64()
        );
    }
}
