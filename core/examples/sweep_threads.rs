//! Time of one NSGS sweep, sequential and coloured on 1..=T threads, on a generated pile scene
//! (set-up excluded): `cargo run --release -p fc3d-core --example sweep_threads -- 100000 1 2`
//! (contacts, piles, largest thread count). Prints the median and minimum over 15 sweeps after
//! 5 warm-up sweeps, from r = 0.

use std::time::Instant;

use fc3d_core::scenes::{sphere_piles, PileSpec};
use fc3d_core::{Decomposition, NsgsOptions, Sweeper};

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number"))
        .collect();
    let contacts = args.first().copied().unwrap_or(100_000);
    let piles = args.get(1).copied().unwrap_or(1);
    let max_threads = args.get(2).copied().unwrap_or(2);
    let p = sphere_piles(&PileSpec {
        contacts,
        piles,
        seed: 1,
    })
    .expect("scene");
    let mut runs = vec![(Decomposition::Sequential, 1)];
    runs.extend((1..=max_threads).map(|t| (Decomposition::Coloured, t)));
    for (decomposition, threads) in runs {
        let options = NsgsOptions {
            decomposition,
            threads,
            ..Default::default()
        };
        let mut sweeper = Sweeper::with_options(&p, &options, 1e-14).expect("sweeper");
        let mut r = vec![0.0; 3 * p.n_contacts()];
        let mut times = Vec::new();
        for k in 0..20 {
            let t = Instant::now();
            sweeper.sweep(p.q(), p.mu(), &mut r);
            if k >= 5 {
                times.push(t.elapsed().as_secs_f64());
            }
        }
        times.sort_by(f64::total_cmp);
        println!(
            "{decomposition:?} threads {threads}: sweep median {:.2} ms, min {:.2} ms",
            1e3 * times[times.len() / 2],
            1e3 * times[0]
        );
    }
}
