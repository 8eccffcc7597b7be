use super::Delassus;
use crate::error::Fc3dError;
use crate::math::linalg::{mat3_vec_add, Mat3, Vec3};

/// Block-row view of a square W with 3x3 blocks, built once per solve for Gauss-Seidel sweeps:
/// for each contact, its diagonal block and its non-zero off-diagonal blocks (row-major).
/// All-zero blocks are not stored, whatever the storage they came from.
#[derive(Debug, Clone)]
pub struct BlockRows {
    n_contacts: usize,
    diagonal: Vec<Mat3>,
    row_ptr: Vec<usize>,
    cols: Vec<usize>,
    blocks: Vec<Mat3>,
}

impl BlockRows {
    pub fn from_delassus(w: &Delassus<'_>) -> Result<Self, Fc3dError> {
        let n = w.nrows();
        if n != w.ncols() || n % 3 != 0 {
            return Err(Fc3dError::InvalidStructure(format!(
                "W must be square with 3x3 blocks, got {}x{}",
                w.nrows(),
                w.ncols()
            )));
        }
        let nc = n / 3;
        let mut diagonal = vec![[[0.0; 3]; 3]; nc];
        let mut have_diag = vec![false; nc];
        // (block row, block col, block) collected row by row; duplicates merged below.
        let mut entries: Vec<(usize, usize, Mat3)> = Vec::new();
        match w {
            Delassus::Dense(d) => {
                for bi in 0..nc {
                    for bj in 0..nc {
                        let mut b = [[0.0; 3]; 3];
                        let mut nonzero = false;
                        for (i, row) in b.iter_mut().enumerate() {
                            for (j, v) in row.iter_mut().enumerate() {
                                *v = d.get(3 * bi + i, 3 * bj + j);
                                nonzero |= *v != 0.0;
                            }
                        }
                        if bi == bj {
                            diagonal[bi] = b;
                            have_diag[bi] = true;
                        } else if nonzero {
                            entries.push((bi, bj, b));
                        }
                    }
                }
            }
            Delassus::SparseBlock(s) => {
                for (bi, bj, cm) in s.iter_blocks() {
                    let b = crate::math::linalg::mat3_from_col_major(cm);
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
                let mut map = std::collections::BTreeMap::<(usize, usize), Mat3>::new();
                s.for_each_entry(|i, j, v| {
                    let b = map.entry((i / 3, j / 3)).or_insert([[0.0; 3]; 3]);
                    b[i % 3][j % 3] += v;
                });
                for ((bi, bj), b) in map {
                    if bi == bj {
                        diagonal[bi] = b;
                    } else if b.iter().flatten().any(|&v| v != 0.0) {
                        entries.push((bi, bj, b));
                    }
                }
                have_diag.iter_mut().for_each(|h| *h = true);
            }
        }
        entries.sort_by_key(|e| (e.0, e.1));
        let mut row_ptr = vec![0usize; nc + 1];
        let mut cols = Vec::with_capacity(entries.len());
        let mut blocks: Vec<Mat3> = Vec::with_capacity(entries.len());
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
    pub fn diagonal(&self, c: usize) -> &Mat3 {
        &self.diagonal[c]
    }

    /// `u <- W r + q` through the stored blocks (zero blocks skipped, so a dense W costs what
    /// its coupling costs).
    pub fn velocity(&self, q: &[f64], r: &[f64], u: &mut [f64]) {
        for c in 0..self.n_contacts {
            let rc = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
            let uc =
                crate::math::linalg::mat3_vec_add(&self.diagonal[c], &rc, &self.local_q(c, q, r));
            u[3 * c..3 * c + 3].copy_from_slice(&uc);
        }
    }

    /// The normal component of [`BlockRows::local_q`]: all a frictionless contact needs (one
    /// row of each coupled block instead of three).
    #[inline]
    pub fn local_q_normal(&self, c: usize, q: &[f64], r: &[f64]) -> f64 {
        let mut acc = q[3 * c];
        for k in self.row_ptr[c]..self.row_ptr[c + 1] {
            let b = self.cols[k];
            let row = &self.blocks[k][0];
            acc += row[0] * r[3 * b] + row[1] * r[3 * b + 1] + row[2] * r[3 * b + 2];
        }
        acc
    }

    /// `q_c + sum_{b != c} W_cb r_b`: the local q of contact c for the current r.
    #[inline]
    pub fn local_q(&self, c: usize, q: &[f64], r: &[f64]) -> Vec3 {
        let mut acc: Vec3 = [q[3 * c], q[3 * c + 1], q[3 * c + 2]];
        for k in self.row_ptr[c]..self.row_ptr[c + 1] {
            let b = self.cols[k];
            let rb = [r[3 * b], r[3 * b + 1], r[3 * b + 2]];
            acc = mat3_vec_add(&self.blocks[k], &rb, &acc);
        }
        acc
    }
}

fn add_into(a: &mut Mat3, b: &Mat3) {
    for i in 0..3 {
        for j in 0..3 {
            a[i][j] += b[i][j];
        }
    }
}
