use super::Delassus;
use crate::error::Fc3dError;
use crate::math::linalg::{block_vec_add, contact_of, Block};

/// Block-row view of a square W with `D x D` blocks (`D` the contact dimension, 3 by default),
/// built once per solve for Gauss-Seidel sweeps: for each contact, its diagonal block and its
/// non-zero off-diagonal blocks (row-major). All-zero blocks are not stored, whatever the storage
/// they came from.
#[derive(Debug, Clone)]
pub struct BlockRows<const D: usize = 3> {
    n_contacts: usize,
    diagonal: Vec<Block<D>>,
    row_ptr: Vec<usize>,
    cols: Vec<usize>,
    blocks: Vec<Block<D>>,
}

impl<const D: usize> BlockRows<D> {
    pub fn from_delassus(w: &Delassus<'_>) -> Result<Self, Fc3dError> {
        let n = w.nrows();
        if n != w.ncols() || n % D != 0 {
            return Err(Fc3dError::InvalidStructure(format!(
                "W must be square with {D}x{D} blocks, got {}x{}",
                w.nrows(),
                w.ncols()
            )));
        }
        let nc = n / D;
        let zero: Block<D> = [[0.0; D]; D];
        let mut diagonal = vec![zero; nc];
        // (block row, block col, block) collected row by row; duplicates merged below.
        let mut entries: Vec<(usize, usize, Block<D>)> = Vec::new();
        match w {
            Delassus::Dense(d) => {
                for bi in 0..nc {
                    for bj in 0..nc {
                        let mut b = zero;
                        let mut nonzero = false;
                        for (i, row) in b.iter_mut().enumerate() {
                            for (j, v) in row.iter_mut().enumerate() {
                                *v = d.get(D * bi + i, D * bj + j);
                                nonzero |= *v != 0.0;
                            }
                        }
                        if bi == bj {
                            diagonal[bi] = b;
                        } else if nonzero {
                            entries.push((bi, bj, b));
                        }
                    }
                }
            }
            Delassus::SparseBlock(s) => {
                if D != 3 {
                    return Err(Fc3dError::InvalidStructure(format!(
                        "a 3x3 sparse-block W cannot be cut into {D}x{D} contact blocks"
                    )));
                }
                let mut have_diag = vec![false; nc];
                for (bi, bj, cm) in s.iter_blocks() {
                    // Column-major 3x3 to row-major D x D (D = 3 here).
                    let mut b = zero;
                    for (i, row) in b.iter_mut().enumerate() {
                        for (j, v) in row.iter_mut().enumerate() {
                            *v = cm[i + 3 * j];
                        }
                    }
                    if bi == bj {
                        add_into(&mut diagonal[bi], &b);
                        have_diag[bi] = true;
                    } else if b.iter().flatten().any(|&v| v != 0.0) {
                        entries.push((bi, bj, b));
                    }
                }
                if let Some(c) = have_diag.iter().position(|&h| !h) {
                    return Err(Fc3dError::MissingDiagonalBlock { contact: c });
                }
            }
            Delassus::Sparse(s) => {
                let mut map = std::collections::BTreeMap::<(usize, usize), Block<D>>::new();
                s.for_each_entry(|i, j, v| {
                    let b = map.entry((i / D, j / D)).or_insert(zero);
                    b[i % D][j % D] += v;
                });
                for ((bi, bj), b) in map {
                    if bi == bj {
                        diagonal[bi] = b;
                    } else if b.iter().flatten().any(|&v| v != 0.0) {
                        entries.push((bi, bj, b));
                    }
                }
            }
        }
        entries.sort_by_key(|e| (e.0, e.1));
        let mut row_ptr = vec![0usize; nc + 1];
        let mut cols = Vec::with_capacity(entries.len());
        let mut blocks: Vec<Block<D>> = Vec::with_capacity(entries.len());
        let mut last = None;
        for (bi, bj, b) in entries {
            if last == Some((bi, bj)) {
                add_into(blocks.last_mut().expect("previous block"), &b);
            } else {
                cols.push(bj);
                blocks.push(b);
                row_ptr[bi + 1] += 1;
                last = Some((bi, bj));
            }
        }
        for i in 0..nc {
            row_ptr[i + 1] += row_ptr[i];
        }
        Ok(BlockRows {
            n_contacts: nc,
            diagonal,
            row_ptr,
            cols,
            blocks,
        })
    }

    pub fn n_contacts(&self) -> usize {
        self.n_contacts
    }

    /// Number of stored off-diagonal blocks.
    pub fn n_off_diagonal(&self) -> usize {
        self.blocks.len()
    }

    #[inline]
    pub fn diagonal(&self, c: usize) -> &Block<D> {
        &self.diagonal[c]
    }

    /// `u <- W r + q` through the stored blocks (zero blocks skipped, so a dense W costs what
    /// its coupling costs).
    pub fn velocity(&self, q: &[f64], r: &[f64], u: &mut [f64]) {
        for c in 0..self.n_contacts {
            let uc = block_vec_add(&self.diagonal[c], &contact_of(r, c), &self.local_q(c, q, r));
            u[D * c..D * c + D].copy_from_slice(&uc);
        }
    }

    /// The stored off-diagonal blocks of contact `c`'s row: `(b, W_cb)` for each contact `b`
    /// coupled to `c`, in increasing `b` (the contact graph of parallel and island sweeps).
    #[inline]
    pub fn row(&self, c: usize) -> impl Iterator<Item = (usize, &Block<D>)> + '_ {
        let range = self.row_ptr[c]..self.row_ptr[c + 1];
        self.cols[range.clone()]
            .iter()
            .copied()
            .zip(&self.blocks[range])
    }

    /// The normal component of [`BlockRows::local_q`]: all a frictionless contact needs (one
    /// row of each coupled block instead of `D`).
    #[inline]
    pub fn local_q_normal(&self, c: usize, q: &[f64], r: &[f64]) -> f64 {
        let mut acc = q[D * c];
        for k in self.row_ptr[c]..self.row_ptr[c + 1] {
            let b = self.cols[k];
            let row = &self.blocks[k][0];
            let mut s = row[0] * r[D * b];
            for j in 1..D {
                s += row[j] * r[D * b + j];
            }
            acc += s;
        }
        acc
    }

    /// `q_c + sum_{b != c} W_cb r_b`: the local q of contact c for the current r.
    #[inline]
    pub fn local_q(&self, c: usize, q: &[f64], r: &[f64]) -> [f64; D] {
        let mut acc = contact_of(q, c);
        for k in self.row_ptr[c]..self.row_ptr[c + 1] {
            let rb = contact_of(r, self.cols[k]);
            acc = block_vec_add(&self.blocks[k], &rb, &acc);
        }
        acc
    }
}

fn add_into<const D: usize>(a: &mut Block<D>, b: &Block<D>) {
    for (ra, rb) in a.iter_mut().zip(b) {
        for (x, y) in ra.iter_mut().zip(rb) {
            *x += y;
        }
    }
}
