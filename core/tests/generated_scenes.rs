//! Generated pile scenes (`scenes::sphere_piles`) are real problems: NSGS solves a small one to a
//! tight tolerance with Siconos' default local solver, and the answer is checked independently
//! (complementarity on every contact from `u = W r + q` recomputed entry by entry).

use fc3d_core::scenes::{sphere_piles, PileSpec};
use fc3d_core::{solve, NsgsOptions, SolverConfig};

#[test]
fn a_small_pile_scene_solves_with_nsgs() {
    let spec = PileSpec {
        contacts: 300,
        piles: 2,
        seed: 11,
    };
    let p = sphere_piles(&spec).unwrap();
    let config = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(1e-6)
        .with_max_iter(20_000);
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let report = solve(&p, &config, &mut r, &mut u).unwrap();
    assert!(report.converged(), "{report:?}");
    eprintln!("{report:?}");
    assert!(report.error <= 1e-6, "{}", report.error);
    // u = W r + q, entry by entry.
    let mut w_r = vec![0.0; p.size()];
    p.w().for_each_entry(|i, j, v| w_r[i] += v * r[j]);
    let (mut touching, mut sliding, mut open) = (0, 0, 0);
    let scale = p.q().iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for c in 0..p.n_contacts() {
        let uc: Vec<f64> = (0..3).map(|i| w_r[3 * c + i] + p.q()[3 * c + i]).collect();
        let rc = &r[3 * c..3 * c + 3];
        let mu = p.mu()[c];
        let rt = rc[1].hypot(rc[2]);
        assert!(
            rc[0] >= -1e-12 && rt <= mu * rc[0] * (1.0 + 1e-6) + 1e-12,
            "contact {c}"
        );
        assert!(uc[0] >= -1e-5 * scale, "contact {c} penetrates: {}", uc[0]);
        if rc[0] > 1e-9 {
            touching += 1;
            if uc[1].hypot(uc[2]) > 1e-5 * scale {
                sliding += 1;
            }
        } else {
            open += 1;
        }
    }
    assert!(touching > 0 && open + touching == p.n_contacts());
    eprintln!("touching {touching} (sliding {sliding}), open {open}");
}
