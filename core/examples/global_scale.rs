//! The reduction of generated global scenes against their size: factoring M, assembling
//! W = H^T M^-1 H block-sparse, q_loc, and recovering v = M^-1 (q + H r), each timed
//! (median of `reps` runs). Shows that no step grows faster than the contacts.
//!
//! `cargo run --release -p fc3d-core --example global_scale -- [reps] [sizes...]`

use std::time::Instant;

use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let reps: usize = args.first().map_or(5, |a| a.parse().unwrap());
    let sizes: Vec<usize> = if args.len() > 1 {
        args[1..].iter().map(|a| a.parse().unwrap()).collect()
    } else {
        vec![1_000, 3_000, 10_000, 30_000, 100_000]
    };
    println!("shape,contacts,bodies,ndof,w_blocks,factor_ms,assemble_ms,q_local_ms,velocity_ms,total_ms,ns_per_contact");
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        for &contacts in &sizes {
            let scene = GeneratedScene {
                pile: PileSpec {
                    contacts,
                    piles: 1,
                    seed: 1,
                },
                shape,
            };
            let p = scene.generate_global().unwrap();
            let (mut f, mut a, mut ql, mut vel) = (vec![], vec![], vec![], vec![]);
            let mut blocks = 0;
            for _ in 0..reps {
                let t = Instant::now();
                let mut op = p.operator().unwrap();
                f.push(t.elapsed().as_secs_f64() * 1e3);
                let t = Instant::now();
                let w = op.assemble::<3>().unwrap();
                a.push(t.elapsed().as_secs_f64() * 1e3);
                if let fc3d_core::Delassus::SparseBlock(b) = &w {
                    blocks = b.n_blocks();
                }
                let t = Instant::now();
                let q = op.local_q(p.q(), p.b()).unwrap();
                ql.push(t.elapsed().as_secs_f64() * 1e3);
                let r: Vec<f64> = q.iter().map(|x| x.abs()).collect();
                let mut v = vec![0.0; p.ndof()];
                let t = Instant::now();
                op.global_velocity(p.q(), &r, &mut v);
                vel.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let (f, a, ql, vel) = (median(f), median(a), median(ql), median(vel));
            let total = f + a + ql + vel;
            println!(
                "{:?},{},{},{},{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.0}",
                shape,
                p.n_contacts(),
                p.ndof() / 6,
                p.ndof(),
                blocks,
                f,
                a,
                ql,
                vel,
                total,
                total * 1e6 / p.n_contacts() as f64
            );
        }
    }
}
