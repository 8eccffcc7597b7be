//! The H-form sweep (global method 691) against NSGS on the assembled W, side by side in one
//! run, on a generated global pile: bytes a sweep reads, time per sweep (alternating, from the
//! same start), sweeps to a tolerance in the global error.
//!
//! `cargo run --release -p fc3d-core --example hform_sweeps -- spheres 10000 2 20 0`
//! (shape, contacts, threads of the coloured runs, timed sweeps, time budget in seconds of the
//! runs to 1e-4; 0 skips them).

use std::time::Instant;

use fc3d_core::global::{
    global_error, solve_global, ContactLaw, GlobalConfig, GlobalMethod, GlobalProblem, HFormSweep,
};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::{Decomposition, Delassus, Method, NsgsOptions, Sweeper};

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let shape = match args.first().map(String::as_str) {
        Some("boxes") => PileShape::Boxes,
        _ => PileShape::Spheres,
    };
    let number = |i: usize, d: usize| args.get(i).map_or(d, |a| a.parse().expect("a number"));
    let contacts = number(1, 10_000);
    let threads = number(2, 2);
    let timed = number(3, 20);
    let budget = number(4, 0);
    let g = GeneratedScene {
        pile: PileSpec {
            contacts,
            piles: 1,
            seed: 1,
        },
        shape,
    }
    .generate_global()
    .expect("scene");
    let nc = g.n_contacts();
    let t = Instant::now();
    let mut operator = g.operator().expect("M factored");
    let operator_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let local = g.reduce(&mut operator).expect("W assembled");
    let reduce_s = t.elapsed().as_secs_f64();
    let w_blocks = match local.w() {
        Delassus::SparseBlock(w) => w.n_blocks(),
        _ => panic!("sparse-block W"),
    };
    // A sweep reads every stored block (72 bytes) and its column index (8 bytes).
    let w_bytes = w_blocks * (72 + 8);
    println!(
        "{shape:?} pile: {nc} contacts, {} bodies' unknowns; M factored and H^T formed in \
         {:.3} s, then W assembled in {:.3} s",
        g.ndof(),
        operator_s,
        reduce_s
    );
    println!(
        "bytes a sweep reads besides r, q, mu: W {:.0} a contact ({:.1} blocks a contact)",
        w_bytes as f64 / nc as f64,
        w_blocks as f64 / nc as f64
    );
    for (decomposition, threads) in [
        (Decomposition::Sequential, 1),
        (Decomposition::Coloured, threads),
    ] {
        let options = NsgsOptions {
            decomposition,
            threads,
            ..Default::default()
        };
        let t = Instant::now();
        let mut on_h = HFormSweep::new(&g, &options).expect("H form");
        let setup_h = t.elapsed().as_secs_f64();
        let mut on_w = Sweeper::with_options(&local, &options, 1e-14).expect("sweeper");
        if decomposition == Decomposition::Sequential {
            let (own, v) = on_h.bytes_per_sweep();
            println!(
                "H form {:.0} a contact (H_c^T and M^-1 H_c on the contact's unknowns, indices, \
                 W_cc: {:.0}; v read and written: {:.0}): W / H form = {:.2}",
                (own + v) as f64 / nc as f64,
                own as f64 / nc as f64,
                v as f64 / nc as f64,
                w_bytes as f64 / (own + v) as f64
            );
        }
        let (mut r_w, mut r_h) = (vec![0.0; 3 * nc], vec![0.0; 3 * nc]);
        let mut v = vec![0.0; g.ndof()];
        on_h.global_velocity(&g, &r_h, &mut v);
        let (mut t_w, mut t_h) = (Vec::new(), Vec::new());
        for k in 0..timed + 3 {
            let t = Instant::now();
            on_w.sweep(local.q(), local.mu(), &mut r_w);
            let a = t.elapsed().as_secs_f64();
            let t = Instant::now();
            on_h.sweep(&g, &mut r_h, &mut v);
            let b = t.elapsed().as_secs_f64();
            if k >= 3 {
                t_w.push(a);
                t_h.push(b);
            }
        }
        let (mw, mh) = (median(t_w), median(t_h));
        println!(
            "{decomposition:?} threads {threads}{}: sweep median W {:.3} ms, H form {:.3} ms \
             (H / W {:.2}); H-form set-up {:.3} s",
            on_h.colouring()
                .map_or(String::new(), |(c, u)| format!(" ({c} colours, {u} units)")),
            1e3 * mw,
            1e3 * mh,
            mh / mw,
            setup_h
        );
        if budget == 0 {
            continue;
        }
        for method in [
            GlobalMethod::HForm(options),
            GlobalMethod::Reduced(Method::Nsgs(options)),
        ] {
            let config = GlobalConfig {
                tolerance: 1e-4,
                max_iter: 1_000_000,
                time_budget: Some(std::time::Duration::from_secs(budget as u64)),
                ..GlobalConfig::new(method)
            };
            let (mut r, mut u, mut v) = (vec![0.0; 3 * nc], vec![0.0; 3 * nc], vec![0.0; g.ndof()]);
            let t = Instant::now();
            let report = solve_global(&g, &config, &mut r, &mut u, &mut v).expect("solve");
            let s = t.elapsed().as_secs_f64();
            let check = independent(&g, &r);
            println!(
                "  {}: {:?} after {} sweeps, global error {:.3e} (recomputed {:.3e}), {:.2} s",
                method.label(),
                report.status,
                report.iterations,
                report.error,
                check,
                s
            );
        }
    }
}

fn independent(g: &GlobalProblem<'_>, r: &[f64]) -> f64 {
    let mut operator = g.operator().expect("M");
    let mut v = vec![0.0; g.ndof()];
    operator.global_velocity(g.q(), r, &mut v);
    let mut u = vec![0.0; g.size()];
    global_error(g, ContactLaw::Coulomb, r, &mut u, &v)
}
