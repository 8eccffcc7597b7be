//! The cost of the body-space matrix `M + rho H H^T` the SSN-ALM (690) factors at every Newton
//! step, against the size of generated piles: unknowns, stored entries (lower triangle), the
//! Cholesky factor's entries (AMD order) and the times of the analysis and of one numeric
//! factorization (median of `reps`).
//!
//! `cargo run --release -p fc3d-core --example body_space_cost -- [reps] [sizes...]`

use std::time::Instant;

use fc3d_core::math::sparse_cholesky::SparseCholesky;
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let reps: usize = args.first().map_or(3, |a| a.parse().unwrap());
    let sizes: Vec<usize> = if args.len() > 1 {
        args[1..].iter().map(|a| a.parse().unwrap()).collect()
    } else {
        vec![1_000, 10_000, 100_000]
    };
    println!("shape,contacts,unknowns,entries,factor_entries,analysis_ms,factor_ms");
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        for &contacts in &sizes {
            let p = GeneratedScene {
                pile: PileSpec {
                    contacts,
                    piles: 4,
                    seed: 1,
                },
                shape,
            }
            .generate_global()
            .unwrap();
            let n = p.ndof();
            // M's entries, then H's columns' outer products (contact by contact), as the
            // SSN-ALM assembles them.
            let mut positions = Vec::new();
            let mut values = Vec::new();
            p.m().for_each_entry(|i, j, x| {
                positions.push((i, j));
                values.push(x);
            });
            let mut columns: Vec<Vec<(usize, f64)>> = vec![Vec::new(); p.size()];
            p.h().for_each_entry(|i, j, x| columns[j].push((i, x)));
            let rho = 10.0;
            for col in &columns {
                for &(i, a) in col {
                    for &(k, b) in col {
                        positions.push((i, k));
                        values.push(rho * a * b);
                    }
                }
            }
            let t = Instant::now();
            let (mut chol, slots) =
                SparseCholesky::from_positions(n, &positions, "M + rho H H^T").unwrap();
            let analysis = t.elapsed().as_secs_f64() * 1e3;
            let vals = chol.values_mut();
            for (k, &s) in slots.iter().enumerate() {
                let (i, j) = positions[k];
                // Both triangles are given: the lower one carries the value.
                if i >= j {
                    vals[s] += values[k];
                }
            }
            let mut times = Vec::new();
            for _ in 0..reps {
                let t = Instant::now();
                chol.factor().unwrap();
                times.push(t.elapsed().as_secs_f64() * 1e3);
            }
            times.sort_by(f64::total_cmp);
            println!(
                "{shape:?},{contacts},{n},{},{},{analysis:.1},{:.1}",
                chol.nnz(),
                chol.factor_nnz(),
                times[times.len() / 2]
            );
        }
    }
}
