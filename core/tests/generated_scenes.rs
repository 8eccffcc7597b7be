//! Generated pile scenes (`scenes::sphere_piles`) are real problems: NSGS solves a small one to a
//! tight tolerance with Siconos' default local solver, and the answer is checked independently
//! (complementarity on every contact from `u = W r + q` recomputed entry by entry).

mod common;
use common::honesty::check_report;

use fc3d_core::scenes::{box_piles, sphere_piles, PileSpec};
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

/// A box scene of a few hundred contacts (4 points per face contact: W rank-deficient) is a real
/// problem too: NSGS reaches 1e-6, the error (133) recomputed independently, and the reactions
/// satisfy Coulomb's law with the ground and the boxes carrying the piles' weight.
#[test]
fn a_small_box_scene_solves_with_nsgs() {
    let spec = PileSpec {
        contacts: 400,
        piles: 2,
        seed: 5,
    };
    let p = box_piles(&spec).unwrap();
    assert_eq!(p.n_contacts(), 400);
    let tol = 1e-6;
    let config = SolverConfig::new(NsgsOptions::default())
        .with_tolerance(tol)
        .with_max_iter(100_000);
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    let report = solve(&p, &config, &mut r, &mut u).unwrap();
    eprintln!("{report:?}");
    assert!(report.converged(), "{report:?}");
    check_report("box scene", &p, tol, &report, &r, &u);
    let (mut touching, mut sliding) = (0, 0);
    let scale = p.q().iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for c in 0..p.n_contacts() {
        let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
        assert!(rc[0] >= -1e-12 && rc[1].hypot(rc[2]) <= p.mu()[c] * rc[0] * (1.0 + 1e-6) + 1e-12);
        assert!(uc[0] >= -1e-4 * scale, "contact {c} penetrates: {}", uc[0]);
        if rc[0] > 1e-9 {
            touching += 1;
            sliding += usize::from(uc[1].hypot(uc[2]) > 1e-4 * scale);
        }
    }
    eprintln!(
        "touching {touching} (sliding {sliding}) of {}",
        p.n_contacts()
    );
    assert!(touching > p.n_contacts() / 2);
}

/// The contact graph of W (`Delassus::for_each_coupling`) is the same on dense, sparse-block and
/// CSR storage of one matrix, and is the one its non-zero entries give.
#[test]
fn the_coupling_pairs_are_those_of_the_non_zero_entries_in_every_storage() {
    use fc3d_core::Delassus;
    use std::collections::BTreeSet;
    let spec = PileSpec {
        contacts: 150,
        piles: 3,
        seed: 2,
    };
    let p = sphere_piles(&spec).unwrap();
    let (mut entries, mut triplets) = (BTreeSet::new(), Vec::new());
    p.w().for_each_entry(|i, j, v| {
        if v != 0.0 && i / 3 != j / 3 {
            entries.insert((i / 3, j / 3));
        }
        triplets.push((i, j, v));
    });
    assert!(entries.len() > 150);
    let n = p.size();
    let dense = Delassus::Dense(p.w().to_dense());
    let csr = Delassus::Sparse(fc3d_core::CsrMatrix::from_triplets(n, n, &triplets).unwrap());
    for w in [p.w(), &dense, &csr] {
        let mut pairs = BTreeSet::new();
        w.for_each_coupling(|a, b| {
            pairs.insert((a, b));
        })
        .unwrap();
        assert_eq!(pairs, entries);
    }
}

/// A dense W whose blocks are mostly zero is solved through its sparse-block form: every family
/// gives the same iterates, bit for bit, as on the sparse-block copy of the same matrix.
#[test]
fn a_mostly_zero_dense_w_is_solved_as_sparse_blocks() {
    use fc3d_core::{Delassus, Method};
    let spec = PileSpec {
        contacts: 120,
        piles: 3,
        seed: 4,
    };
    let sparse = sphere_piles(&spec).unwrap();
    let dense = sparse
        .with_w(Delassus::Dense(sparse.w().to_dense()))
        .unwrap();
    let view = dense
        .w()
        .sparse_block_view()
        .expect("a pile's W is mostly zero blocks");
    assert_eq!(Delassus::SparseBlock(view), *sparse.w());
    // A full W is left dense.
    let full = fc3d_core::DenseMatrix::new(6, 6, vec![1.0; 36]).unwrap();
    assert!(Delassus::Dense(full).sparse_block_view().is_none());
    for id in [500, 512, 507] {
        let method = Method::presets()
            .into_iter()
            .find(|m| m.siconos_id() == id)
            .unwrap();
        let config = SolverConfig::new(method)
            .with_tolerance(1e-5)
            .with_max_iter(300);
        let run = |p: &fc3d_core::FrictionProblem<'_>| {
            let mut r = vec![0.0; p.size()];
            let mut u = vec![0.0; p.size()];
            let report = solve(p, &config, &mut r, &mut u).unwrap();
            (
                report.iterations,
                r.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            )
        };
        assert_eq!(run(&dense), run(&sparse), "solver {id}");
    }
}

/// The facts docs/convergence.md ("Contact order along the load path") rests on, recomputed from
/// the bodies (H) on small piles: W couples two contacts exactly when they share a body; the
/// contacts W shows as supports (their coupled contacts all coupled to each other) are exactly
/// those touching one body; and the scene's index order already runs bottom-up: no two contacts
/// sharing a body are visited higher level first (levels: breadth-first distance from the
/// one-body contacts through shared bodies), so NSGS in index order is the load-path sweep.
#[test]
fn generated_contacts_come_bottom_up_from_the_supports() {
    use fc3d_core::scenes::{GeneratedScene, PileShape};
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        let scene = GeneratedScene {
            pile: PileSpec {
                contacts: 1000,
                piles: 2,
                seed: 5,
            },
            shape,
        };
        let global = scene.generate_global().unwrap();
        let nc = global.n_contacts();
        let mut bodies = vec![Vec::new(); nc];
        global.h().for_each_entry(|dof, col, v| {
            if v != 0.0 && !bodies[col / 3].contains(&(dof / 6)) {
                bodies[col / 3].push(dof / 6);
            }
        });
        let share = |c: usize, d: usize| bodies[c].iter().any(|b| bodies[d].contains(b));
        // W's graph, from the local form of the same scene.
        let mut coupled = vec![Vec::new(); nc];
        scene.generate().unwrap().w().for_each_entry(|i, j, v| {
            let (c, d) = (i / 3, j / 3);
            if c != d && v != 0.0 && !coupled[c].contains(&d) {
                coupled[c].push(d);
            }
        });
        let mut pairs = 0;
        for c in 0..nc {
            for d in (0..nc).filter(|&d| d != c) {
                assert_eq!(coupled[c].contains(&d), share(c, d), "{shape:?} {c} {d}");
            }
            pairs += coupled[c].len();
        }
        let supports: Vec<bool> = (0..nc)
            .map(|c| {
                let nb = &coupled[c];
                nb.iter()
                    .all(|&a| nb.iter().all(|&b| a == b || coupled[a].contains(&b)))
            })
            .collect();
        for c in 0..nc {
            assert_eq!(supports[c], bodies[c].len() == 1, "{shape:?} contact {c}");
        }
        let mut level = vec![usize::MAX; nc];
        let mut queue: std::collections::VecDeque<usize> =
            (0..nc).filter(|&c| bodies[c].len() == 1).collect();
        queue.iter().for_each(|&c| level[c] = 0);
        while let Some(c) = queue.pop_front() {
            for d in 0..nc {
                if level[d] == usize::MAX && share(c, d) {
                    level[d] = level[c] + 1;
                    queue.push_back(d);
                }
            }
        }
        assert!(level.iter().all(|&l| l != usize::MAX), "{shape:?}");
        let depth = level.iter().max().unwrap() + 1;
        assert!(depth >= 3, "{shape:?}: {depth} levels");
        for c in 0..nc {
            for &d in coupled[c].iter().filter(|&&d| d > c) {
                assert!(
                    level[c] <= level[d],
                    "{shape:?}: {c} (level {}) before {d} (level {})",
                    level[c],
                    level[d]
                );
            }
        }
        eprintln!(
            "{shape:?}: {nc} contacts, {} supports, {depth} levels, {pairs} coupled (ordered) pairs",
            supports.iter().filter(|&&s| s).count()
        );
    }
}
