//! Reading `/fclib_local`, with W rebuilt in the storage recorded in `fc3d_storage`, and the
//! assembly of W in 3x3 sparse-block storage.

use hdf5_metno as hdf5;

use super::reader::Reader;
#[cfg(doc)]
use super::write_fclib_file;
use super::{STORAGE_ATTRIBUTE, STORAGE_DENSE, STORAGE_SPARSE, STORAGE_SPARSE_BLOCK};
use crate::alloc::{reserve, try_collect, try_push};
use crate::error::{try_vec, Fc3dError};
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
use crate::problem::{FrictionProblem, DIMENSION};

impl Reader {
    pub(super) fn read_local(
        &self,
        g: &hdf5::Group,
    ) -> Result<FrictionProblem<'static>, Fc3dError> {
        let gp = "/fclib_local";
        self.spacedim(g, gp)?;
        for extra in ["R", "V"] {
            if g.link_exists(extra) {
                return Err(Fc3dError::Unsupported(format!(
                    "{}: {gp}/{extra} present: local problems with extra constraints (R, V, s) \
                     are not supported",
                    self.label
                )));
            }
        }
        let w = self.matrix(g, gp, "W")?;
        if w.nrows != w.ncols {
            return Err(self.invalid(format!(
                "{gp}/W is {}x{}, expected a square matrix",
                w.nrows, w.ncols
            )));
        }
        let nc = self.contacts(&format!("{gp}/W"), w.ncols)?;
        let vp = format!("{gp}/vectors");
        let v = self.group(g, gp, "vectors")?;
        let q = self.floats(&v, &vp, "q")?;
        self.check_len(&format!("{vp}/q"), q.len(), w.nrows, "the size of W")?;
        let mu = self.floats(&v, &vp, "mu")?;
        self.check_len(&format!("{vp}/mu"), mu.len(), nc, "one per contact")?;
        match self.storage(&self.group(g, gp, "W")?, &format!("{gp}/W"))? {
            Some(storage) => self.problem_as_stored(storage, w.nrows, &w.entries, q, mu),
            None => self.problem(w.nrows, &w.entries, q, mu),
        }
    }

    /// The storage recorded by [`write_fclib_file`] in the attribute `fc3d_storage` of the W
    /// group `wg`, `None` without the attribute.
    fn storage(&self, wg: &hdf5::Group, wpath: &str) -> Result<Option<i32>, Fc3dError> {
        let names = wg
            .attr_names()
            .map_err(|e| self.hdf5_error(&format!("{wpath} attributes"), e))?;
        if !names.iter().any(|n| n == STORAGE_ATTRIBUTE) {
            return Ok(None);
        }
        let apath = format!("{wpath} attribute {STORAGE_ATTRIBUTE}");
        let value = self.int_attribute(wg, STORAGE_ATTRIBUTE, &apath)?;
        match i32::try_from(value) {
            Ok(v @ (STORAGE_DENSE | STORAGE_SPARSE_BLOCK | STORAGE_SPARSE)) => Ok(Some(v)),
            _ => Err(self.invalid(format!(
                "{apath} = {value}: expected {STORAGE_DENSE} (dense), {STORAGE_SPARSE_BLOCK} \
                 (sparse-block) or {STORAGE_SPARSE} (sparse)"
            ))),
        }
    }

    /// Assembles the problem with W in the storage `storage` (an `fc3d_storage` code), from
    /// exactly the stored entries: the first value at a position is kept as it is (signed zeros
    /// included), duplicates are added to it.
    fn problem_as_stored(
        &self,
        storage: i32,
        n: usize,
        w_entries: &[(usize, usize, f64)],
        q: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<FrictionProblem<'static>, Fc3dError> {
        let w = match storage {
            STORAGE_DENSE => {
                let size = n
                    .checked_mul(n)
                    .filter(|&s| s as u64 <= self.max_values)
                    .ok_or_else(|| {
                        self.invalid(format!(
                            "/fclib_local/W is marked dense but {n}x{n} values are more than \
                             the file could describe"
                        ))
                    })?;
                let mut data = try_vec(size, 0.0, "the dense W of /fclib_local")?;
                let mut seen = try_vec(size, false, "the dense W of /fclib_local")?;
                for &(i, j, v) in w_entries {
                    let k = i + j * n;
                    if seen[k] {
                        data[k] += v;
                    } else {
                        data[k] = v;
                        seen[k] = true;
                    }
                }
                Delassus::Dense(DenseMatrix::new(n, n, data)?)
            }
            STORAGE_SPARSE_BLOCK => {
                Delassus::SparseBlock(blocks_of(n / DIMENSION, w_entries, false)?)
            }
            _ => Delassus::Sparse(CsrMatrix::from_triplets(n, n, w_entries)?),
        };
        FrictionProblem::new(w, q, mu)
    }

    /// Assembles the problem with W in 3x3 sparse-block storage.
    pub(super) fn problem(
        &self,
        n: usize,
        w_entries: &[(usize, usize, f64)],
        q: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<FrictionProblem<'static>, Fc3dError> {
        let blocks = blocks_of(n / DIMENSION, w_entries, true)?;
        FrictionProblem::new(Delassus::SparseBlock(blocks), q, mu)
    }
}

/// The `nc x nc` 3x3-block matrix of `entries` (all within `3 nc`), allocated fallibly: the
/// entries at one position are summed in their order (the first value kept as it is, signed
/// zeros included, the later ones added to it); every block holding an entry is stored, and
/// every diagonal block (zero when nothing is there). `drop_zeros`: leave out the positions whose
/// sum is zero and the blocks left with none (what a compressed-row copy of W then
/// `Delassus::to_block_sparse` give, with the same values).
pub(super) fn blocks_of(
    nc: usize,
    entries: &[(usize, usize, f64)],
    drop_zeros: bool,
) -> Result<BlockSparseMatrix<'static>, Fc3dError> {
    const WHAT: &str = "the 3x3 blocks of W";
    let d = DIMENSION;
    let mut order = try_collect(0..entries.len(), WHAT)?;
    // The entry number breaks ties: duplicates are summed in their order.
    order.sort_unstable_by_key(|&k| {
        let (i, j, _) = entries[k];
        (i / d, j / d, i, j, k)
    });
    let mut summed: Vec<(usize, usize, f64)> = Vec::new();
    reserve(&mut summed, order.len(), WHAT)?;
    for k in order {
        let (i, j, v) = entries[k];
        match summed.last_mut() {
            Some(last) if (last.0, last.1) == (i, j) => last.2 += v,
            _ => summed.push((i, j, v)),
        }
    }
    if drop_zeros {
        summed.retain(|e| e.2 != 0.0);
    }
    let mut row_ptr = try_vec(nc + 1, 0usize, WHAT)?;
    let mut col_idx = Vec::new();
    let mut blocks = Vec::new();
    let mut e = 0;
    for bi in 0..nc {
        let mut diagonal = false;
        loop {
            let next = summed.get(e).filter(|x| x.0 / d == bi).map(|x| x.1 / d);
            if !diagonal && next.is_none_or(|bj| bj > bi) {
                try_push(&mut col_idx, bi, WHAT)?;
                try_push(&mut blocks, [0.0; 9], WHAT)?;
                diagonal = true;
                continue;
            }
            let Some(bj) = next else { break };
            diagonal |= bj == bi;
            let mut block = [0.0; 9];
            while let Some(&(i, j, v)) = summed.get(e).filter(|x| x.0 / d == bi && x.1 / d == bj) {
                block[i % d + d * (j % d)] = v;
                e += 1;
            }
            try_push(&mut col_idx, bj, WHAT)?;
            try_push(&mut blocks, block, WHAT)?;
        }
        row_ptr[bi + 1] = col_idx.len();
    }
    BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks)
}
