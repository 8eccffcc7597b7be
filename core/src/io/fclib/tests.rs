//! Unit tests of the reduction of global problems and of the 3x3-block assembly.

use std::collections::BTreeMap;

use faer::Mat;

use super::global::{reduce_global, MassFactor, MassSolver};
use super::local::blocks_of;
use super::sparse::SparseEntries;
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus};

fn h_of(ndof: usize, n: usize, entries: Vec<(usize, usize, f64)>) -> SparseEntries {
    SparseEntries {
        nrows: ndof,
        ncols: n,
        entries,
    }
}

fn dense(n: usize, entries: &[(usize, usize, f64)]) -> Vec<f64> {
    let mut d = vec![0.0; n * n];
    for &(i, j, v) in entries {
        d[i * n + j] += v;
    }
    d
}

#[test]
fn reduction_matches_a_hand_computation() {
    // M = [[2, 1], [1, 2]] (SPD), M^-1 = [[2, -1], [-1, 2]] / 3; H = [[1, 0, 0], [0, 1, 1]].
    let m = [(0, 0, 2.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 2.0)];
    let h = h_of(2, 3, vec![(0, 0, 1.0), (1, 1, 1.0), (1, 2, 1.0)]);
    let (w, q) = reduce_global(2, &m, &h, &[3.0, 0.0], &[1.0, 2.0, 3.0]).unwrap();
    let wd = dense(3, &w);
    let expected = [2.0, -1.0, -1.0, -1.0, 2.0, 2.0, -1.0, 2.0, 2.0].map(|v| v / 3.0);
    for (a, b) in wd.iter().zip(expected) {
        assert!((a - b).abs() < 1e-14, "{wd:?}");
    }
    // M^-1 f = (2, -1); q = H^T (2, -1) + w = (3, 1, 2).
    for (a, b) in q.iter().zip([3.0, 1.0, 2.0]) {
        assert!((a - b).abs() < 1e-14, "{q:?}");
    }
}

#[test]
fn unsymmetric_mass_uses_lu_and_duplicates_are_summed() {
    // M = [[2, 1], [0, 4]] given with the 2 split in two triplets.
    let m = [(0, 0, 1.0), (0, 0, 1.0), (0, 1, 1.0), (1, 1, 4.0)];
    let solver = MassSolver::new(2, &m).unwrap();
    assert!(matches!(solver.factor, MassFactor::Lu(_)));
    let mut x = Mat::<f64>::zeros(2, 1);
    x[(0, 0)] = 3.0;
    x[(1, 0)] = 4.0;
    solver.solve(&mut x).unwrap();
    assert!((x[(0, 0)] - 1.0).abs() < 1e-15 && (x[(1, 0)] - 1.0).abs() < 1e-15);
}

#[test]
fn indefinite_symmetric_mass_falls_back_to_lu() {
    let m = [(0, 1, 1.0), (1, 0, 1.0)];
    let solver = MassSolver::new(2, &m).unwrap();
    assert!(matches!(solver.factor, MassFactor::Lu(_)));
}

/// `blocks_of` gives, bit for bit, what it replaced: compressed rows then
/// `to_block_sparse` (`drop_zeros`), and the map of every stored position (not).
#[test]
fn blocks_of_matches_the_map_based_assembly() {
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = |m: u64| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed % m
    };
    let values = [0.0, -0.0, 1.5, -2.25, 1e-300, 3.0];
    for _ in 0..200 {
        let nc = 1 + next(4) as usize;
        let count = next(40) as usize;
        let entries: Vec<(usize, usize, f64)> = (0..count)
            .map(|_| {
                let i = next(3 * nc as u64) as usize;
                let j = next(3 * nc as u64) as usize;
                (i, j, values[next(values.len() as u64) as usize])
            })
            .collect();
        let csr = CsrMatrix::from_triplets(3 * nc, 3 * nc, &entries).unwrap();
        let expected = Delassus::Sparse(csr).to_block_sparse().unwrap();
        let got = blocks_of(nc, &entries, true).unwrap();
        assert_eq!(got, expected);
        let bits = |m: &BlockSparseMatrix| {
            m.blocks()
                .flat_map(|b| b.map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&got), bits(&expected));

        // The map of every stored position, as `problem_as_stored` had it.
        let mut map = BTreeMap::<(usize, usize), ([f64; 9], [bool; 9])>::new();
        for c in 0..nc {
            map.insert((c, c), ([0.0; 9], [false; 9]));
        }
        for &(i, j, v) in &entries {
            let (block, seen) = map.entry((i / 3, j / 3)).or_insert(([0.0; 9], [false; 9]));
            let k = i % 3 + 3 * (j % 3);
            if seen[k] {
                block[k] += v;
            } else {
                block[k] = v;
                seen[k] = true;
            }
        }
        let stored = blocks_of(nc, &entries, false).unwrap();
        let pairs: Vec<(usize, usize)> = stored.iter_blocks().map(|(i, j, _)| (i, j)).collect();
        assert_eq!(pairs, map.keys().copied().collect::<Vec<_>>());
        let map_bits: Vec<u64> = map
            .values()
            .flat_map(|(b, _)| b.map(f64::to_bits))
            .collect();
        assert_eq!(bits(&stored), map_bits);
    }
}

#[test]
fn singular_mass_is_an_error_not_nans() {
    let h = h_of(2, 3, vec![(0, 0, 1.0), (1, 1, 1.0)]);
    for m in [
        vec![(0, 0, 1.0)],                                        // structurally singular
        vec![(0, 0, 1.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 1.0)], // numerically singular
    ] {
        let err = reduce_global(2, &m, &h, &[0.0, 0.0], &[0.0; 3]).unwrap_err();
        assert!(err.contains("singular"), "{err}");
    }
}
