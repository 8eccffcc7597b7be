//! Unit tests of the reduction of global problems and of the 3x3-block assembly.

use std::collections::BTreeMap;

use super::local::blocks_of;
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus};
use crate::problem::GlobalProblem;

/// W as `(row, col, value)` entries, and q.
type Reduced = (Vec<(usize, usize, f64)>, Vec<f64>);

/// The reduced W (as `(row, col, value)`) and q of M (`ndof`), H (`ndof x n`), f and w.
fn reduce(
    ndof: usize,
    m: &[(usize, usize, f64)],
    h: &[(usize, usize, f64)],
    f: &[f64],
    w: &[f64],
) -> Result<Reduced, String> {
    let n = w.len();
    let p = GlobalProblem::<3>::new(
        CsrMatrix::from_triplets(ndof, ndof, m).unwrap(),
        CsrMatrix::from_triplets(ndof, n, h).unwrap(),
        f.to_vec(),
        w.to_vec(),
        vec![0.5; n / 3],
    )
    .unwrap();
    let mut operator = p.operator().map_err(|e| e.to_string())?;
    let local = p.reduce(&mut operator).map_err(|e| e.to_string())?;
    let mut entries = Vec::new();
    local.w().for_each_entry(|i, j, v| entries.push((i, j, v)));
    Ok((entries, local.q().to_vec()))
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
    let h = [(0, 0, 1.0), (1, 1, 1.0), (1, 2, 1.0)];
    let (w, q) = reduce(2, &m, &h, &[3.0, 0.0], &[1.0, 2.0, 3.0]).unwrap();
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
fn unsymmetric_mass_and_duplicates_are_summed() {
    // M = [[2, 1], [0, 4]] given with the 2 split in two triplets; H = I (two rows of one
    // contact's three columns).
    let m = [(0, 0, 1.0), (0, 0, 1.0), (0, 1, 1.0), (1, 1, 4.0)];
    let h = [(0, 0, 1.0), (1, 1, 1.0)];
    let (w, q) = reduce(2, &m, &h, &[3.0, 4.0], &[0.0; 3]).unwrap();
    // M^-1 = [[1/2, -1/8], [0, 1/4]]; M^-1 (3, 4) = (1, 1).
    let wd = dense(3, &w);
    for (a, b) in wd
        .iter()
        .zip([0.5, -0.125, 0.0, 0.0, 0.25, 0.0, 0.0, 0.0, 0.0])
    {
        assert!((a - b).abs() < 1e-15, "{wd:?}");
    }
    assert_eq!(q, [1.0, 1.0, 0.0]);
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
    let h = [(0, 0, 1.0), (1, 1, 1.0)];
    for m in [
        vec![(0, 0, 1.0)],                                        // structurally singular
        vec![(0, 0, 1.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 1.0)], // numerically singular
    ] {
        let err = reduce(2, &m, &h, &[0.0, 0.0], &[0.0; 3]).unwrap_err();
        assert!(err.contains("singular"), "{err}");
    }
}
