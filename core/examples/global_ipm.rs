//! Times Siconos' global interior-point method (615) on generated piles: iterations, the time to
//! the first iteration's end (set-up and one iteration) and in all, status and errors.
//!
//! `cargo run --release -p fc3d-core --example global_ipm -- [contacts...] [--boxes]
//! [--update-s] [--arrow]` (default: 1000 and 10000 sphere contacts, Siconos' default options).

use std::time::Instant;

use fc3d_core::global::{
    global_error, solve_global_with_observer, ContactLaw, GlobalConfig, GlobalMethod, IpmOptions,
};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str| args.iter().any(|a| a == name);
    let shape = if flag("--boxes") {
        PileShape::Boxes
    } else {
        PileShape::Spheres
    };
    let options = IpmOptions {
        update_s: flag("--update-s"),
        nesterov_todd: !flag("--arrow"),
        ..Default::default()
    };
    let mut sizes: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![1000, 10000];
    }
    let config = GlobalConfig::new(GlobalMethod::Ipm(options));
    println!("{} ({shape:?})", config.method.label());
    for contacts in sizes {
        let pile = PileSpec {
            contacts,
            piles: 1,
            seed: 7,
        };
        let p = GeneratedScene { pile, shape }.generate_global().unwrap();
        let (mut r, mut u, mut v) = (
            vec![0.0; p.size()],
            vec![0.0; p.size()],
            vec![0.0; p.ndof()],
        );
        let start = Instant::now();
        let mut first = None;
        let report = solve_global_with_observer(&p, &config, &mut r, &mut u, &mut v, &mut |_| {
            first.get_or_insert(start.elapsed());
        })
        .unwrap();
        let total = start.elapsed();
        let convex = global_error(&p, ContactLaw::Convex, &r, &mut u, &v);
        println!(
            "{contacts} contacts, ndof {}: {} iterations, first at {:.3} s, total {:.3} s \
             ({:.3} s per iteration after the first); {}, Coulomb error {:.2e}, convex {:.2e}",
            p.ndof(),
            report.iterations,
            first.unwrap_or_default().as_secs_f64(),
            total.as_secs_f64(),
            (total - first.unwrap_or_default()).as_secs_f64()
                / (report.iterations.max(2) - 1) as f64,
            report.status.name(),
            report.error,
            convex
        );
    }
}
