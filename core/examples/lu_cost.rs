//! Calibration of `math::lu_cost::FLOPS_PER_SECOND`: on generated pile scenes, the predicted
//! flops and factor entries of faer's sparse LU of `W + I` (ADMM's system; NSN's Newton matrix
//! has W's block pattern too), the time of the symbolic analysis, of the prediction and of one
//! numeric factorization, and the rate flops / time. Sequential, single-threaded:
//! `cargo run --release -p fc3d-core --example lu_cost -- 1000 2000 5000 10000`
//! (contacts per scene; 1 pile each, or `piles=K` as first argument; `predict` before the sizes:
//! the prediction only, no numeric factorization).

use std::time::Instant;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu};
use faer::sparse::{SparseColMat, Triplet};
use faer::Par;
use fc3d_core::math::lu_cost::{predict_lu_cost, FLOPS_PER_SECOND};
use fc3d_core::math::lu_fill::lu_factor_nnz;
use fc3d_core::scenes::{sphere_piles, PileSpec};

fn main() {
    let mut piles = 1;
    let mut sizes = Vec::new();
    let mut predict_only = false;
    for a in std::env::args().skip(1) {
        if a == "predict" {
            predict_only = true;
            continue;
        }
        match a.strip_prefix("piles=") {
            Some(k) => piles = k.parse().expect("a number of piles"),
            None => sizes.push(a.parse::<usize>().expect("a number of contacts")),
        }
    }
    println!("contacts piles n nnz | symbolic s predict s | predicted entries, flops, s | numeric s, faer entries | rate flops/s");
    for contacts in sizes {
        let p = sphere_piles(&PileSpec {
            contacts,
            piles,
            seed: 1,
        })
        .expect("scene");
        let n = p.size();
        let mut triplets = Vec::new();
        p.w().for_each_entry(|i, j, v| {
            if v != 0.0 {
                triplets.push(Triplet::new(i, j, v));
            }
        });
        triplets.extend((0..n).map(|i| Triplet::new(i, i, 1.0)));
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets).unwrap();
        let t = Instant::now();
        let symbolic = factorize_symbolic_lu(a.symbolic(), Default::default()).unwrap();
        let t_symbolic = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let cost = predict_lu_cost(a.symbolic(), symbolic.col_perm()).unwrap();
        let t_predict = t.elapsed().as_secs_f64();
        if predict_only {
            println!(
                "{contacts} {piles} {n} {} | {t_symbolic:.3} {t_predict:.3} | {:.3e} {:.3e} {:.3} | - | -",
                a.val().len(),
                cost.factor_entries,
                cost.flops,
                cost.flops / FLOPS_PER_SECOND,
            );
            continue;
        }
        let mut buffer = MemBuffer::new(
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
        );
        let mut numeric = NumericLu::new();
        let t = Instant::now();
        let lu = symbolic
            .factorize_numeric_lu(
                &mut numeric,
                a.as_ref(),
                Par::Seq,
                MemStack::new(&mut buffer),
                Default::default(),
            )
            .unwrap();
        let t_numeric = t.elapsed().as_secs_f64();
        let actual = lu_factor_nnz(
            n,
            a.symbolic().col_ptr(),
            a.symbolic().row_idx(),
            lu.row_perm().arrays().1,
            lu.col_perm().arrays().0,
        )
        .unwrap();
        println!(
            "{contacts} {piles} {n} {} | {t_symbolic:.3} {t_predict:.3} | {:.3e} {:.3e} {:.3} | {t_numeric:.3} {actual} | {:.3e}",
            a.val().len(),
            cost.factor_entries,
            cost.flops,
            cost.flops / FLOPS_PER_SECOND,
            cost.flops / t_numeric,
        );
    }
}
