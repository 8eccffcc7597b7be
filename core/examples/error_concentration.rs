//! Where the error (133) of a stalled run sits: NSGS (Siconos' defaults) for a number of sweeps
//! on a generated pile, then the share of the squared error carried by the worst 10, 100 and
//! 1000 contacts and the statuses of the worst ones (docs/convergence.md):
//!
//! `cargo run --release -p fc3d-core --example error_concentration -- [SCENE] [SWEEPS]`
//! (default `contacts=10000,piles=4,seed=1` and 3000 sweeps).

use fc3d_core::diagnostics::{diagnose, DiagnosticOptions};
use fc3d_core::scenes::GeneratedScene;
use fc3d_core::{solve, NsgsOptions, SolverConfig};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let spec = args
        .first()
        .cloned()
        .unwrap_or_else(|| "contacts=10000,piles=4,seed=1".into());
    let sweeps: usize = args.get(1).map_or(3000, |s| s.parse().expect("sweeps"));
    let scene = GeneratedScene::parse(&spec).expect("scene");
    let p = scene.generate().expect("scene");
    let config = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(0.0)
        .with_max_iter(sweeps);
    let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
    let report = solve(&p, &config, &mut r, &mut u).expect("solve");
    let d = diagnose(
        &p,
        &r,
        &DiagnosticOptions {
            tolerance: 10.0 * report.error,
        },
    )
    .expect("diagnostics");
    let total: f64 = d
        .contacts
        .iter()
        .map(|c| c.error_contribution.powi(2))
        .sum();
    println!(
        "{spec}: {} contacts, {} sweeps, error {:.3e}; (take-off, stick, slide, apex) {:?}",
        p.n_contacts(),
        report.iterations,
        d.error,
        d.counts()
    );
    for k in [10, 100, 1000] {
        let share: f64 = d
            .worst(k)
            .iter()
            .map(|&c| d.contacts[c].error_contribution.powi(2))
            .sum::<f64>()
            / total;
        println!(
            "worst {k:>4} contacts: {:.1}% of the squared error",
            100.0 * share
        );
    }
    for &c in d.worst(10).iter() {
        let x = d.contacts[c];
        println!(
            "contact {c:>6}: e_c {:.2e}, {}, r_N {:.3e}, u_N {:.2e}, |u_T| {:.2e}",
            x.error_contribution,
            x.status.name(),
            x.normal_reaction,
            x.normal_velocity,
            x.tangential_velocity
        );
    }
}
