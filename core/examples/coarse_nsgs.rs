//! Experiment: NSGS cycles with an aggregation coarse correction on the normal reactions of
//! the closed contacts (contacts grouped by index, `group` a group), against plain NSGS.
//!
//! `cargo run --release -p fc3d-core --example coarse_nsgs -- CONTACTS GROUP SWEEPS_PER_CYCLE SECONDS`

use std::time::Instant;

use fc3d_core::measure::natural_map_error;
use fc3d_core::scenes::GeneratedScene;
use fc3d_core::{solve, NsgsOptions, SolverConfig};

fn lu_solve(a: &mut [f64], n: usize, b: &mut [f64]) {
    for k in 0..n {
        let mut p = k;
        for i in k + 1..n {
            if a[i * n + k].abs() > a[p * n + k].abs() {
                p = i;
            }
        }
        if p != k {
            for j in 0..n {
                a.swap(k * n + j, p * n + j);
            }
            b.swap(k, p);
        }
        let d = a[k * n + k];
        if d.abs() < 1e-300 {
            continue;
        }
        for i in k + 1..n {
            let f = a[i * n + k] / d;
            for j in k..n {
                a[i * n + j] -= f * a[k * n + j];
            }
            b[i] -= f * b[k];
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for j in k + 1..n {
            s -= a[k * n + j] * b[j];
        }
        let d = a[k * n + k];
        b[k] = if d.abs() < 1e-300 { 0.0 } else { s / d };
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let contacts: usize = args.first().map_or(10000, |a| a.parse().unwrap());
    let group: usize = args.get(1).map_or(50, |a| a.parse().unwrap());
    let per_cycle: usize = args.get(2).map_or(20, |a| a.parse().unwrap());
    let seconds: f64 = args.get(3).map_or(20.0, |a| a.parse().unwrap());
    let p = GeneratedScene::parse(&format!("contacts={contacts},piles=4,seed=1"))
        .unwrap()
        .generate()
        .unwrap();
    let (m, nc) = (p.size(), p.n_contacts());
    for coarse in [false, true] {
        let t = Instant::now();
        let (mut r, mut u) = (vec![0.0; m], vec![0.0; m]);
        let config = SolverConfig::new(NsgsOptions::default())
            .with_tolerance(0.0)
            .with_max_iter(per_cycle);
        let groups = nc.div_ceil(group);
        let mut a_c: Option<(Vec<f64>, Vec<bool>)> = None;
        let mut sweeps = 0;
        let mut next_print = 0.0;
        while t.elapsed().as_secs_f64() < seconds {
            solve(&p, &config, &mut r, &mut u).unwrap();
            sweeps += per_cycle;
            if coarse {
                if a_c.is_none() {
                    // The closed set now, and Z^T W_NN Z on it, column by column.
                    let closed: Vec<bool> = (0..nc).map(|c| r[3 * c] > 0.0).collect();
                    let mut a = vec![0.0; groups * groups];
                    let mut x = vec![0.0; m];
                    let mut y = vec![0.0; m];
                    for g in 0..groups {
                        x.iter_mut().for_each(|v| *v = 0.0);
                        for c in g * group..((g + 1) * group).min(nc) {
                            if closed[c] {
                                x[3 * c] = 1.0;
                            }
                        }
                        y.iter_mut().for_each(|v| *v = 0.0);
                        p.w().mul_add(&x, &mut y);
                        for (h, row) in (0..groups).map(|h| (h, h * groups)) {
                            let s: f64 = (h * group..((h + 1) * group).min(nc))
                                .filter(|&c| closed[c])
                                .map(|c| y[3 * c])
                                .sum();
                            a[row + g] = s;
                        }
                    }
                    a_c = Some((a, closed));
                }
                let (a, closed) = a_c.as_ref().unwrap();
                natural_map_error(&p, &r, &mut u);
                let mut rhs: Vec<f64> = (0..groups)
                    .map(|g| {
                        -(g * group..((g + 1) * group).min(nc))
                            .filter(|&c| closed[c] && r[3 * c] > 0.0)
                            .map(|c| u[3 * c])
                            .sum::<f64>()
                    })
                    .collect();
                let mut aa = a.clone();
                lu_solve(&mut aa, groups, &mut rhs);
                for g in 0..groups {
                    for c in g * group..((g + 1) * group).min(nc) {
                        if closed[c] && r[3 * c] > 0.0 {
                            r[3 * c] = (r[3 * c] + rhs[g]).max(0.0);
                        }
                    }
                }
            }
            let e = natural_map_error(&p, &r, &mut u);
            if t.elapsed().as_secs_f64() >= next_print {
                println!(
                    "coarse {coarse} sweeps {sweeps} error {e:.3e} at {:.2} s",
                    t.elapsed().as_secs_f64()
                );
                next_print += seconds / 10.0;
            }
        }
        let e = natural_map_error(&p, &r, &mut u);
        println!("coarse {coarse} END sweeps {sweeps} error {e:.3e}");
    }
}
