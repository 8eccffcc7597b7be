//! Convergence history of NSGS variants on a generated pile: the error (133) and |r| at sweeps
//! 1, 2, 4, 8, ... and the first sweep that passes 1e-3, 1e-4, 1e-6.
//! `cargo run --release -p fc3d-core --example scale_convergence -- CONTACTS PILES MAX_SWEEPS`

use std::time::Instant;

use fc3d_core::scenes::{sphere_piles, PileSpec};
use fc3d_core::{solve_with_observer, Acceleration, ErrorEvaluation, NsgsOptions, SolverConfig};

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let (contacts, piles, max) = (args[0], args[1], args[2]);
    let p = sphere_piles(&PileSpec {
        contacts,
        piles,
        seed: 1,
    })
    .unwrap();
    let n = 3 * p.n_contacts();
    let f = fc3d_core::ProblemFeatures::of(&p);
    println!(
        "{contacts} contacts, {piles} piles: AUTO's features: density {:.2e}, mu {:.2}..{:.2}, \
         normal-row dominance {:.3}, strongly coupled {}",
        f.block_density,
        f.mu_min,
        f.mu_max,
        f.diagonal_dominance,
        f.strongly_coupled()
    );
    let mut configs: Vec<(String, NsgsOptions)> = vec![("plain".into(), NsgsOptions::default())];
    for omega in [1.3, 1.6, 1.8] {
        configs.push((
            format!("omega {omega}"),
            NsgsOptions {
                relaxation: Some(omega),
                ..Default::default()
            },
        ));
    }
    for memory in [3, 5, 10] {
        configs.push((
            format!("anderson {memory}"),
            NsgsOptions {
                acceleration: Acceleration::Anderson { memory },
                ..Default::default()
            },
        ));
    }
    let only: Option<String> = std::env::var("ONLY").ok();
    for (name, o) in &configs {
        if only.as_ref().is_some_and(|s| !name.contains(s.as_str())) {
            continue;
        }
        let mut config = SolverConfig::new(NsgsOptions {
            error_evaluation: ErrorEvaluation::Full,
            ..*o
        });
        config.tolerance = 1e-6;
        config.max_iter = max;
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let mut first = [None, None, None];
        let t = Instant::now();
        let mut history = String::new();
        let report = solve_with_observer(&p, &config, &mut r, &mut u, &mut |e| {
            for (k, tol) in [1e-3, 1e-4, 1e-6].into_iter().enumerate() {
                if first[k].is_none() && e.error <= tol {
                    first[k] = Some((e.iteration, t.elapsed().as_secs_f64()));
                }
            }
            if e.iteration.is_power_of_two() {
                let norm = e.reaction.iter().map(|x| x * x).sum::<f64>().sqrt();
                history += &format!(" {}:{:.2e}|{:.2e}", e.iteration, e.error, norm);
            }
        })
        .unwrap();
        let independent = independent_error(&p, &r);
        let show = |s: Option<(usize, f64)>| {
            s.map_or("-".to_string(), |(k, t)| format!("{k} ({:.2} s)", t))
        };
        println!(
            "{name:<12} 1e-3 {} 1e-4 {} 1e-6 {} final {:.2e} (recomputed independently {:.2e}) after {} sweeps\n   sweep:error|r| {history}",
            show(first[0]),
            show(first[1]),
            show(first[2]),
            report.error,
            independent,
            report.iterations
        );
    }
}

/// The error (133) recomputed from scratch, without the library's error code: `u = W r + q`
/// from W's stored blocks (column-major), the natural map `r - P_K(r - (u + mu |u_T| e_N))` with the cone
/// projection written out here, over `max(|q|, |r|, |u|)`.
fn independent_error(p: &fc3d_core::FrictionProblem<'_>, r: &[f64]) -> f64 {
    let fc3d_core::Delassus::SparseBlock(w) = p.w() else {
        panic!("sparse-block W expected");
    };
    let mut u = p.q().to_vec();
    for (c, d, block) in w.iter_blocks() {
        for i in 0..3 {
            for j in 0..3 {
                u[3 * c + i] += block[3 * j + i] * r[3 * d + j];
            }
        }
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut residual = 0.0;
    for (c, &mu) in p.mu().iter().enumerate() {
        let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
        let slide = (uc[1] * uc[1] + uc[2] * uc[2]).sqrt();
        let z = [rc[0] - (uc[0] + mu * slide), rc[1] - uc[1], rc[2] - uc[2]];
        let zt = (z[1] * z[1] + z[2] * z[2]).sqrt();
        let proj = if zt <= mu * z[0] {
            z
        } else if mu * zt <= -z[0] {
            [0.0; 3]
        } else {
            let a = (z[0] + mu * zt) / (1.0 + mu * mu);
            [a, mu * a * z[1] / zt, mu * a * z[2] / zt]
        };
        for k in 0..3 {
            residual += (rc[k] - proj[k]).powi(2);
        }
    }
    residual.sqrt() / norm(p.q()).max(norm(r)).max(norm(&u))
}
