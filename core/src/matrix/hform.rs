//! The Delassus operator given as `W = H^T M^-1 H` (Siconos' global convention: H is
//! `ndof x m`, `u = H^T v + b`, `M v = q + H r`) rather than as W: M factored once
//! ([`MassFactor`]), H and H^T kept in compressed rows. It multiplies by W without assembling
//! it, maps a reaction to the global velocity, and assembles W in block-sparse storage when a
//! solver needs it (the reduction of the global problem to the local one), block by block of M
//! when M is block diagonal: no dense inverse and no solve with all of M per column.

use crate::error::{try_vec, Fc3dError};
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, MassFactor};

/// H, H^T and the factored M.
#[derive(Debug)]
pub struct HForm {
    h: CsrMatrix,
    ht: CsrMatrix,
    mass: MassFactor,
    /// Work vector of the size of M.
    work: Vec<f64>,
}

impl HForm {
    /// Factors M (square, `ndof`) and keeps H (`ndof x m`).
    pub fn new(m: &CsrMatrix, h: CsrMatrix) -> Result<Self, Fc3dError> {
        if h.nrows() != m.nrows() {
            return Err(Fc3dError::dims(
                "rows of H (the size of M)",
                m.nrows(),
                h.nrows(),
            ));
        }
        let mass = MassFactor::new(m)?;
        let ht = transpose(&h)?;
        let work = try_vec(m.nrows(), 0.0, "H-form work vector")?;
        Ok(HForm { h, ht, mass, work })
    }

    /// The unknowns of M (`ndof`).
    pub fn ndof(&self) -> usize {
        self.h.nrows()
    }

    /// The contact unknowns (`m`, the columns of H).
    pub fn size(&self) -> usize {
        self.h.ncols()
    }

    pub fn h(&self) -> &CsrMatrix {
        &self.h
    }

    /// `H^T` (`m x ndof`): row j is column j of H.
    pub fn ht(&self) -> &CsrMatrix {
        &self.ht
    }

    pub fn mass(&self) -> &MassFactor {
        &self.mass
    }

    /// `x <- M^-1 x`.
    pub fn solve_mass(&mut self, x: &mut [f64]) {
        self.mass.solve_in_place(x);
    }

    /// `y <- y + H r` (`y` of size `ndof`).
    pub fn h_mul_add(&self, r: &[f64], y: &mut [f64]) {
        self.h.mul_add(r, y);
    }

    /// `u <- u + H^T v` (`u` of size `m`).
    pub fn ht_mul_add(&self, v: &[f64], u: &mut [f64]) {
        self.ht.mul_add(v, u);
    }

    /// The global velocity `v = M^-1 (q + H r)`.
    pub fn global_velocity(&mut self, q: &[f64], r: &[f64], v: &mut [f64]) {
        v.copy_from_slice(q);
        self.h.mul_add(r, v);
        self.mass.solve_in_place(v);
    }

    /// `y <- y + W x = y + H^T M^-1 H x`, W not assembled.
    pub fn mul_add(&mut self, x: &[f64], y: &mut [f64]) {
        let mut t = std::mem::take(&mut self.work);
        t.iter_mut().for_each(|v| *v = 0.0);
        self.h.mul_add(x, &mut t);
        self.mass.solve_in_place(&mut t);
        self.ht.mul_add(&t, y);
        self.work = t;
    }

    /// The local free velocity `H^T M^-1 q + b`.
    pub fn local_q(&mut self, q: &[f64], b: &[f64]) -> Result<Vec<f64>, Fc3dError> {
        let mut t = try_vec(self.ndof(), 0.0, "M^-1 q")?;
        t.copy_from_slice(q);
        self.mass.solve_in_place(&mut t);
        let mut q_local = try_vec(self.size(), 0.0, "the local q")?;
        q_local.copy_from_slice(b);
        self.ht.mul_add(&t, &mut q_local);
        Ok(q_local)
    }

    /// W assembled for contacts of dimension `D`: in 3x3 sparse-block storage for `D = 3`
    /// (every diagonal block present), compressed rows otherwise. Exact zeros are not stored.
    pub fn assemble<const D: usize>(&mut self) -> Result<Delassus<'static>, Fc3dError> {
        let m = self.size();
        if !m.is_multiple_of(D) {
            return Err(Fc3dError::InvalidStructure(format!(
                "H has {m} columns, not a multiple of the contact dimension {D}"
            )));
        }
        if self.mass.is_block_diagonal() {
            self.block_assembly::<D>()?.into_delassus::<D>()
        } else {
            self.column_contributions::<D>()?.into_delassus::<D>(m / D)
        }
    }

    /// `H_S^T M_S^-1 H_S` for every diagonal block `M_S` of M, as D x D blocks of W: per block
    /// of M, the contacts whose H columns touch its unknowns (a body and its contacts). W's
    /// pattern is known before any value: contacts a and b are coupled when some block of M
    /// touches both, so the blocks are summed in place (no list of contributions to sort).
    fn block_assembly<const D: usize>(&self) -> Result<BlockAccumulator, Fc3dError> {
        let (dofs, offsets) = self.mass.blocks().expect("block-diagonal M");
        let n_blocks = offsets.len() - 1;
        let nc = self.size() / D;
        let (row_ptr, col_idx, values) = (self.h.row_ptr(), self.h.col_idx(), self.h.values());
        // The contacts of every block of M (compressed by block), in increasing order.
        let mut mark = try_vec(nc, usize::MAX, "W's assembly")?;
        let mut group_ptr = try_vec(n_blocks + 1, 0usize, "W's assembly")?;
        let mut group_contacts: Vec<usize> = Vec::new();
        for k in 0..n_blocks {
            let start = group_contacts.len();
            for &i in &dofs[offsets[k]..offsets[k + 1]] {
                for &j in &col_idx[row_ptr[i]..row_ptr[i + 1]] {
                    let c = j / D;
                    if mark[c] != k {
                        mark[c] = k;
                        group_contacts.push(c);
                    }
                }
            }
            group_contacts[start..].sort_unstable();
            group_ptr[k + 1] = group_contacts.len();
        }
        let mut acc = BlockAccumulator::new(nc, D * D, &group_ptr, &group_contacts)?;
        let mut place = try_vec(nc, 0usize, "W's assembly")?;
        let (mut hs, mut xs, mut column) = (Vec::new(), Vec::new(), Vec::new());
        let mut positions = Vec::new();
        for k in 0..n_blocks {
            let contacts = &group_contacts[group_ptr[k]..group_ptr[k + 1]];
            if contacts.is_empty() {
                continue;
            }
            let block_dofs = &dofs[offsets[k]..offsets[k + 1]];
            let s = block_dofs.len();
            for (p, &c) in contacts.iter().enumerate() {
                place[c] = p;
            }
            // H_S, column-major: s rows, D columns a contact.
            let cols = D * contacts.len();
            hs.clear();
            hs.resize(s * cols, 0.0);
            for (li, &i) in block_dofs.iter().enumerate() {
                for p in row_ptr[i]..row_ptr[i + 1] {
                    let j = col_idx[p];
                    let col = D * place[j / D] + j % D;
                    hs[col * s + li] += values[p];
                }
            }
            // X = M_S^-1 H_S, column by column.
            xs.clear();
            xs.extend_from_slice(&hs);
            column.resize(s, 0.0);
            for col in 0..cols {
                let x = &mut xs[col * s..(col + 1) * s];
                column.copy_from_slice(x);
                self.mass.solve_block_in_place(k, &mut column);
                x.copy_from_slice(&column);
            }
            // W_S = H_S^T X, block (a, b) for every pair of the block's contacts; the places
            // of a row's blocks by one merge of two increasing lists.
            for (a, &ca) in contacts.iter().enumerate() {
                acc.places_in_row(ca, contacts, &mut positions);
                for (b, &p) in positions.iter().enumerate() {
                    let block = acc.block_at(p);
                    for bj in 0..D {
                        let x = &xs[(D * b + bj) * s..(D * b + bj + 1) * s];
                        for ai in 0..D {
                            let h = &hs[(D * a + ai) * s..(D * a + ai + 1) * s];
                            // Column-major D x D block: entry (ai, bj).
                            block[ai + D * bj] += h.iter().zip(x).map(|(p, q)| p * q).sum::<f64>();
                        }
                    }
                }
            }
        }
        Ok(acc)
    }

    /// W column by column for a general M: `X = M^-1 H e_j`, `W e_j = H^T X`.
    fn column_contributions<const D: usize>(&mut self) -> Result<BlockList, Fc3dError> {
        let (n, m) = (self.ndof(), self.size());
        let dd = D * D;
        let mut x = try_vec(n, 0.0, "W's assembly")?;
        let mut w_col = try_vec(m, 0.0, "W's assembly")?;
        let mut list = BlockList::default();
        let mut touched: Vec<usize> = Vec::new();
        let mut seen = try_vec(m, false, "W's assembly")?;
        let (row_ptr, col_idx, values) = (self.h.row_ptr(), self.h.col_idx(), self.h.values());
        let mut place = std::collections::HashMap::<(usize, usize), usize>::new();
        for j in 0..m {
            x.iter_mut().for_each(|v| *v = 0.0);
            for (row, value) in self.ht_row(j) {
                x[row] += value;
            }
            self.mass.solve_in_place(&mut x);
            touched.clear();
            for (k, &xk) in x.iter().enumerate() {
                if xk != 0.0 {
                    for p in row_ptr[k]..row_ptr[k + 1] {
                        let i = col_idx[p];
                        w_col[i] += values[p] * xk;
                        if !seen[i] {
                            seen[i] = true;
                            touched.push(i);
                        }
                    }
                }
            }
            for &i in &touched {
                seen[i] = false;
                let v = std::mem::take(&mut w_col[i]);
                if v != 0.0 {
                    let key = (i / D, j / D);
                    let start = *place
                        .entry(key)
                        .or_insert_with(|| list.push(key.0, key.1, dd));
                    list.values[start + i % D + D * (j % D)] = v;
                }
            }
        }
        Ok(list)
    }

    /// The entries `(row, value)` of column j of H (row j of H^T).
    fn ht_row(&self, j: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let range = self.ht.row_ptr()[j]..self.ht.row_ptr()[j + 1];
        self.ht.col_idx()[range.clone()]
            .iter()
            .copied()
            .zip(self.ht.values()[range].iter().copied())
    }
}

/// W's D x D blocks on a pattern fixed in advance (block-sparse rows, columns increasing),
/// values column-major, summed in place.
struct BlockAccumulator {
    dd: usize,
    row_ptr: Vec<usize>,
    col_idx: Vec<usize>,
    values: Vec<f64>,
}

impl BlockAccumulator {
    /// The pattern where contacts a and b are coupled when a group holds both (and every
    /// diagonal block): `group_contacts[group_ptr[k]..group_ptr[k + 1]]` lists group k's.
    fn new(
        nc: usize,
        dd: usize,
        group_ptr: &[usize],
        group_contacts: &[usize],
    ) -> Result<Self, Fc3dError> {
        // The groups of every contact.
        let mut count = try_vec(nc + 1, 0usize, "W's pattern")?;
        for &c in group_contacts {
            count[c + 1] += 1;
        }
        for c in 0..nc {
            count[c + 1] += count[c];
        }
        let mut next = count.clone();
        let mut groups_of = try_vec(group_contacts.len(), 0usize, "W's pattern")?;
        for k in 0..group_ptr.len() - 1 {
            for &c in &group_contacts[group_ptr[k]..group_ptr[k + 1]] {
                groups_of[next[c]] = k;
                next[c] += 1;
            }
        }
        let mut row_ptr = try_vec(nc + 1, 0usize, "W's pattern")?;
        let mut col_idx: Vec<usize> = Vec::new();
        for a in 0..nc {
            let start = col_idx.len();
            col_idx.push(a);
            for &k in &groups_of[count[a]..count[a + 1]] {
                col_idx.extend_from_slice(&group_contacts[group_ptr[k]..group_ptr[k + 1]]);
            }
            sort_and_dedup_from(&mut col_idx, start);
            row_ptr[a + 1] = col_idx.len();
        }
        let values = try_vec(col_idx.len() * dd, 0.0, "W's blocks")?;
        Ok(BlockAccumulator {
            dd,
            row_ptr,
            col_idx,
            values,
        })
    }

    /// The places of blocks `(a, b)` for the increasing `columns` b, all in the pattern.
    fn places_in_row(&self, a: usize, columns: &[usize], places: &mut Vec<usize>) {
        places.clear();
        let mut p = self.row_ptr[a];
        for &b in columns {
            while self.col_idx[p] != b {
                p += 1;
            }
            places.push(p);
        }
    }

    /// The values of the block at place `p`.
    fn block_at(&mut self, p: usize) -> &mut [f64] {
        &mut self.values[p * self.dd..(p + 1) * self.dd]
    }

    fn into_delassus<const D: usize>(self) -> Result<Delassus<'static>, Fc3dError> {
        blocks_to_delassus::<D>(self.row_ptr, self.col_idx, self.values)
    }
}

/// D x D blocks `(block row, block column)` in any order, duplicates to be summed; values
/// column-major, `D * D` a block.
#[derive(Default)]
struct BlockList {
    keys: Vec<(usize, usize)>,
    values: Vec<f64>,
}

impl BlockList {
    /// Appends a zero block; returns the start of its values.
    fn push(&mut self, row: usize, col: usize, dd: usize) -> usize {
        self.keys.push((row, col));
        let start = self.values.len();
        self.values.resize(start + dd, 0.0);
        start
    }

    /// The blocks summed into W of `nc` contacts (every diagonal block present).
    fn into_delassus<const D: usize>(mut self, nc: usize) -> Result<Delassus<'static>, Fc3dError> {
        let dd = D * D;
        for c in 0..nc {
            self.push(c, c, dd);
        }
        let mut order: Vec<usize> = (0..self.keys.len()).collect();
        order.sort_unstable_by_key(|&k| self.keys[k]);
        let mut row_ptr = vec![0usize; nc + 1];
        let mut col_idx: Vec<usize> = Vec::new();
        let mut summed: Vec<f64> = Vec::new();
        let mut last = None;
        for k in order {
            let key = self.keys[k];
            if last != Some(key) {
                row_ptr[key.0 + 1] += 1;
                col_idx.push(key.1);
                summed.extend(std::iter::repeat_n(0.0, dd));
                last = Some(key);
            }
            let start = summed.len() - dd;
            for (s, v) in summed[start..]
                .iter_mut()
                .zip(&self.values[k * dd..(k + 1) * dd])
            {
                *s += v;
            }
        }
        for c in 0..nc {
            row_ptr[c + 1] += row_ptr[c];
        }
        blocks_to_delassus::<D>(row_ptr, col_idx, summed)
    }
}

/// W from its blocks (block-sparse rows, values column-major): 3x3 sparse-block storage for
/// `D = 3`, compressed rows otherwise (exact zeros left out).
fn blocks_to_delassus<const D: usize>(
    row_ptr: Vec<usize>,
    col_idx: Vec<usize>,
    summed: Vec<f64>,
) -> Result<Delassus<'static>, Fc3dError> {
    let nc = row_ptr.len() - 1;
    let dd = D * D;
    if D == 3 {
        let blocks = summed
            .chunks_exact(9)
            .map(|b| b.try_into().expect("9 values a block"))
            .collect();
        return Ok(Delassus::SparseBlock(BlockSparseMatrix::new(
            nc, nc, row_ptr, col_idx, blocks,
        )?));
    }
    let mut triplets = Vec::new();
    for bi in 0..nc {
        for p in row_ptr[bi]..row_ptr[bi + 1] {
            let bj = col_idx[p];
            for c in 0..D {
                for r in 0..D {
                    let v = summed[p * dd + r + D * c];
                    if v != 0.0 {
                        triplets.push((D * bi + r, D * bj + c, v));
                    }
                }
            }
        }
    }
    Ok(Delassus::Sparse(CsrMatrix::from_triplets(
        D * nc,
        D * nc,
        &triplets,
    )?))
}

/// Sorts `v[start..]` and removes its repeats (`v[..start]` untouched): a list of lists built
/// one list at a time, each kept sorted and without repeats.
pub(crate) fn sort_and_dedup_from(v: &mut Vec<usize>, start: usize) {
    v[start..].sort_unstable();
    let mut kept = start;
    for p in start..v.len() {
        if p == start || v[p] != v[kept - 1] {
            v[kept] = v[p];
            kept += 1;
        }
    }
    v.truncate(kept);
}

/// `y <- y + A^T x`.
pub fn transpose_mul_add(a: &CsrMatrix, x: &[f64], y: &mut [f64]) {
    let (row_ptr, col_idx, values) = (a.row_ptr(), a.col_idx(), a.values());
    for (i, &xi) in x.iter().enumerate().take(a.nrows()) {
        if xi != 0.0 {
            for k in row_ptr[i]..row_ptr[i + 1] {
                y[col_idx[k]] += values[k] * xi;
            }
        }
    }
}

/// `A^T` in compressed rows.
pub fn transpose(a: &CsrMatrix) -> Result<CsrMatrix, Fc3dError> {
    a.transposed()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two bodies of 3 unknowns (non-diagonal, non-symmetric M blocks), three contacts: two
    /// on body 0 alone, one between the bodies.
    fn two_bodies() -> (CsrMatrix, CsrMatrix) {
        let mut m = Vec::new();
        for b in 0..2 {
            let o = 3 * b;
            for (i, j, v) in [
                (0, 0, 4.0),
                (0, 1, 1.0),
                (1, 0, 0.5),
                (1, 1, 3.0),
                (2, 2, 2.0),
                (2, 0, 0.25),
            ] {
                m.push((o + i, o + j, v + b as f64));
            }
        }
        let mut h = Vec::new();
        for (i, j, v) in [
            (0, 0, 1.0),
            (1, 1, 1.0),
            (2, 2, 1.0),
            (0, 3, 1.0),
            (1, 4, -0.5),
            (2, 5, 2.0),
            (0, 6, -1.0),
            (1, 7, 0.3),
            (3, 6, 1.0),
            (4, 7, -0.3),
            (5, 8, 1.0),
            (2, 8, 0.7),
        ] {
            h.push((i, j, v));
        }
        (
            CsrMatrix::from_triplets(6, 6, &m).unwrap(),
            CsrMatrix::from_triplets(6, 9, &h).unwrap(),
        )
    }

    /// W from a dense inverse: `H^T M^-1 H` column by column with a Gauss elimination.
    fn dense_w(m: &CsrMatrix, h: &CsrMatrix) -> Vec<Vec<f64>> {
        let n = m.nrows();
        let mut a = vec![vec![0.0; n]; n];
        m.for_each_entry(|i, j, v| a[i][j] += v);
        let cols = h.ncols();
        let mut w = vec![vec![0.0; cols]; cols];
        for j in 0..cols {
            let mut b: Vec<f64> = (0..n).map(|i| h.get(i, j)).collect();
            // Gauss-Jordan on a copy.
            let mut g = a.clone();
            for k in 0..n {
                let p = (k..n)
                    .max_by(|&x, &y| g[x][k].abs().total_cmp(&g[y][k].abs()))
                    .unwrap();
                g.swap(k, p);
                b.swap(k, p);
                for i in 0..n {
                    if i != k {
                        let l = g[i][k] / g[k][k];
                        for c in 0..n {
                            g[i][c] -= l * g[k][c];
                        }
                        b[i] -= l * b[k];
                    }
                }
            }
            let x: Vec<f64> = (0..n).map(|i| b[i] / g[i][i]).collect();
            for i in 0..cols {
                w[i][j] = (0..n).map(|k| h.get(k, i) * x[k]).sum();
            }
        }
        w
    }

    #[test]
    fn assembled_w_and_products_equal_the_dense_reduction() {
        let (m, h) = two_bodies();
        let expected = dense_w(&m, &h);
        let mut hf = HForm::new(&m, h.clone()).unwrap();
        assert!(hf.mass().is_block_diagonal());
        let w = hf.assemble::<3>().unwrap();
        assert!(matches!(w, Delassus::SparseBlock(_)));
        for (i, row) in expected.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                assert!(
                    (w.get(i, j) - e).abs() < 1e-13,
                    "({i}, {j}): {} vs {e}",
                    w.get(i, j)
                );
            }
        }
        // The same W through a general (sparse LU) M: a third body coupling both makes M one
        // component, so check the column path on the same data by forcing it.
        let list = hf.column_contributions::<3>().unwrap();
        let w_columns = list.into_delassus::<3>(3).unwrap();
        for (i, row) in expected.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                assert!((w_columns.get(i, j) - e).abs() < 1e-13);
            }
        }
        // Products without assembly.
        let x: Vec<f64> = (0..9).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut y = vec![1.0; 9];
        hf.mul_add(&x, &mut y);
        for i in 0..9 {
            let e: f64 = 1.0 + (0..9).map(|j| expected[i][j] * x[j]).sum::<f64>();
            assert!((y[i] - e).abs() < 1e-13);
        }
    }

    #[test]
    fn global_velocity_solves_the_balance() {
        let (m, h) = two_bodies();
        let mut hf = HForm::new(&m, h.clone()).unwrap();
        let q = [1.0, -2.0, 0.5, 0.0, 3.0, -1.0];
        let r: Vec<f64> = (0..9).map(|i| i as f64 * 0.1).collect();
        let mut v = vec![0.0; 6];
        hf.global_velocity(&q, &r, &mut v);
        let mut balance: Vec<f64> = q.iter().map(|x| -x).collect();
        m.mul_add(&v, &mut balance);
        let mut hr = vec![0.0; 6];
        h.mul_add(&r, &mut hr);
        for i in 0..6 {
            assert!((balance[i] - hr[i]).abs() < 1e-13);
        }
    }
}
