use crate::alloc::reserve;
use crate::error::{check_finite, try_copy, try_vec, Fc3dError};

/// General sparse matrix in compressed sparse row form, column indices sorted within each row and
/// free of duplicates (constructors sort and sum).
#[derive(Debug, Clone, PartialEq)]
pub struct CsrMatrix {
    nrows: usize,
    ncols: usize,
    row_ptr: Vec<usize>,
    col_idx: Vec<usize>,
    values: Vec<f64>,
}

impl CsrMatrix {
    /// `alpha * self`, same structure, allocated fallibly.
    pub fn scaled(&self, alpha: f64) -> Result<CsrMatrix, Fc3dError> {
        let mut m = self.try_clone()?;
        m.values.iter_mut().for_each(|v| *v *= alpha);
        Ok(m)
    }

    /// Replaces every stored entry `a_ij` by `f(i, j, a_ij)` (same structure).
    pub fn scale_entries(&mut self, f: impl Fn(usize, usize, f64) -> f64) {
        for i in 0..self.nrows {
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                self.values[k] = f(i, self.col_idx[k], self.values[k]);
            }
        }
    }

    /// A copy, allocated fallibly.
    pub fn try_clone(&self) -> Result<CsrMatrix, Fc3dError> {
        Ok(CsrMatrix {
            nrows: self.nrows,
            ncols: self.ncols,
            row_ptr: try_copy(&self.row_ptr, "the row pointers of a sparse W")?,
            col_idx: try_copy(&self.col_idx, "the column indices of a sparse W")?,
            values: try_copy(&self.values, "the values of a sparse W")?,
        })
    }

    /// From triplets `(row, col, value)`, in any order; duplicates are summed.
    pub fn from_triplets(
        nrows: usize,
        ncols: usize,
        triplets: &[(usize, usize, f64)],
    ) -> Result<Self, Fc3dError> {
        for (k, &(i, j, v)) in triplets.iter().enumerate() {
            if i >= nrows || j >= ncols {
                return Err(Fc3dError::InvalidStructure(format!(
                    "entry {k} at ({i}, {j}) is outside a {nrows}x{ncols} matrix"
                )));
            }
            if !v.is_finite() {
                return Err(Fc3dError::NonFinite {
                    what: "W".into(),
                    index: k,
                });
            }
        }
        // The entries grouped by row (a counting sort, stable: filled from the last entry back
        // into each row's end), then each row's by column and entry index: the order of a stable
        // sort by (row, column), so duplicates are summed in input order. Memory: the row
        // pointers, one index per entry and the result, all allocated fallibly.
        let rows_plus_one = nrows
            .checked_add(1)
            .ok_or_else(|| Fc3dError::InvalidStructure(format!("{nrows} rows")))?;
        let mut row_ptr = try_vec(rows_plus_one, 0usize, "the row pointers of a sparse W")?;
        for &(i, _, _) in triplets {
            row_ptr[i + 1] += 1;
        }
        for i in 0..nrows {
            row_ptr[i + 1] += row_ptr[i];
        }
        let mut order = try_vec(triplets.len(), 0usize, "the entries of a sparse W by row")?;
        for (k, &(i, _, _)) in triplets.iter().enumerate().rev() {
            row_ptr[i + 1] -= 1;
            order[row_ptr[i + 1]] = k;
        }
        // row_ptr[i + 1] is now where row i starts.
        let mut col_idx = Vec::new();
        reserve(
            &mut col_idx,
            triplets.len(),
            "the column indices of a sparse W",
        )?;
        let mut values: Vec<f64> = Vec::new();
        reserve(&mut values, triplets.len(), "the values of a sparse W")?;
        for i in 0..nrows {
            let start = row_ptr[i + 1];
            let end = if i + 1 < nrows {
                row_ptr[i + 2]
            } else {
                triplets.len()
            };
            let row = &mut order[start..end];
            row.sort_unstable_by_key(|&k| (triplets[k].1, k));
            row_ptr[i + 1] = row_ptr[i];
            let mut last = None;
            for &k in row.iter() {
                let (_, j, v) = triplets[k];
                if last == Some(j) {
                    *values.last_mut().expect("a previous entry exists") += v;
                } else {
                    col_idx.push(j);
                    values.push(v);
                    row_ptr[i + 1] += 1;
                    last = Some(j);
                }
            }
        }
        Ok(CsrMatrix {
            nrows,
            ncols,
            row_ptr,
            col_idx,
            values,
        })
    }

    /// `self^T`, allocated fallibly. A counting pass over the entries: the rows of `self` are
    /// read in order, so every row of the transpose comes out sorted and free of duplicates
    /// (no sort; H^T of the 10^5-contact sphere pile took 0.17 s through triplets).
    pub fn transposed(&self) -> Result<CsrMatrix, Fc3dError> {
        let mut row_ptr = try_vec(self.ncols + 1, 0usize, "the row pointers of a transpose")?;
        for &j in &self.col_idx {
            row_ptr[j + 1] += 1;
        }
        for j in 0..self.ncols {
            row_ptr[j + 1] += row_ptr[j];
        }
        let nnz = self.nnz();
        let mut col_idx = try_vec(nnz, 0usize, "the column indices of a transpose")?;
        let mut values = try_vec(nnz, 0.0, "the values of a transpose")?;
        let mut next = try_copy(&row_ptr[..self.ncols], "the row pointers of a transpose")?;
        for i in 0..self.nrows {
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                let at = &mut next[self.col_idx[k]];
                col_idx[*at] = i;
                values[*at] = self.values[k];
                *at += 1;
            }
        }
        Ok(CsrMatrix {
            nrows: self.ncols,
            ncols: self.nrows,
            row_ptr,
            col_idx,
            values,
        })
    }

    /// From compressed rows. Unsorted columns and duplicates are accepted (sorted, summed).
    pub fn from_csr(
        nrows: usize,
        ncols: usize,
        row_ptr: &[usize],
        col_idx: &[usize],
        values: &[f64],
    ) -> Result<Self, Fc3dError> {
        let triplets = compressed_to_triplets(nrows, row_ptr, col_idx, values, "row")?;
        Self::from_triplets(nrows, ncols, &triplets)
    }

    /// From compressed columns (CSparse's native form). Unsorted rows and duplicates are accepted.
    pub fn from_csc(
        nrows: usize,
        ncols: usize,
        col_ptr: &[usize],
        row_idx: &[usize],
        values: &[f64],
    ) -> Result<Self, Fc3dError> {
        let transposed = compressed_to_triplets(ncols, col_ptr, row_idx, values, "column")?;
        let triplets: Vec<_> = transposed.into_iter().map(|(j, i, v)| (i, j, v)).collect();
        Self::from_triplets(nrows, ncols, &triplets)
    }

    pub fn nrows(&self) -> usize {
        self.nrows
    }
    pub fn ncols(&self) -> usize {
        self.ncols
    }
    pub fn nnz(&self) -> usize {
        self.values.len()
    }
    pub fn row_ptr(&self) -> &[usize] {
        &self.row_ptr
    }
    pub fn col_idx(&self) -> &[usize] {
        &self.col_idx
    }
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    pub fn get(&self, i: usize, j: usize) -> f64 {
        let cols = &self.col_idx[self.row_ptr[i]..self.row_ptr[i + 1]];
        match cols.binary_search(&j) {
            Ok(k) => self.values[self.row_ptr[i] + k],
            Err(_) => 0.0,
        }
    }

    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.nrows) {
            let mut s = 0.0;
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                s += self.values[k] * x[self.col_idx[k]];
            }
            *yi += s;
        }
    }

    /// Into `cols`, sorted: the block columns (`d x d` blocks) of block row `bi` (rows `d bi` to
    /// `d bi + d - 1`) that hold a non-zero entry, and `bi` itself (room allocated fallibly).
    pub(crate) fn block_columns(
        &self,
        d: usize,
        bi: usize,
        cols: &mut Vec<usize>,
    ) -> Result<(), Fc3dError> {
        let entries = self.row_ptr[d * bi]..self.row_ptr[d * bi + d];
        cols.clear();
        reserve(cols, entries.len() + 1, "a block row of W")?;
        cols.extend(
            entries
                .filter(|&k| self.values[k] != 0.0)
                .map(|k| self.col_idx[k] / d),
        );
        cols.push(bi);
        cols.sort_unstable();
        cols.dedup();
        Ok(())
    }

    pub fn for_each_entry(&self, mut f: impl FnMut(usize, usize, f64)) {
        for i in 0..self.nrows {
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                f(i, self.col_idx[k], self.values[k]);
            }
        }
    }
}

/// Expands a compressed (row or column) structure into `(outer, inner, value)` triplets, checking
/// the pointer array and the index ranges.
fn compressed_to_triplets(
    n_outer: usize,
    ptr: &[usize],
    idx: &[usize],
    values: &[f64],
    outer_name: &str,
) -> Result<Vec<(usize, usize, f64)>, Fc3dError> {
    if ptr.len() != n_outer + 1 {
        return Err(Fc3dError::dims(
            format!("{outer_name} pointers"),
            n_outer + 1,
            ptr.len(),
        ));
    }
    if ptr[0] != 0 || ptr.windows(2).any(|w| w[0] > w[1]) {
        return Err(Fc3dError::InvalidStructure(format!(
            "{outer_name} pointers must start at 0 and be non-decreasing"
        )));
    }
    let nnz = ptr[n_outer];
    if idx.len() < nnz || values.len() < nnz {
        return Err(Fc3dError::dims(
            "sparse entries",
            nnz,
            idx.len().min(values.len()),
        ));
    }
    check_finite("W", &values[..nnz])?;
    let mut out = Vec::new();
    reserve(&mut out, nnz, "the entries of a sparse W")?;
    for o in 0..n_outer {
        for k in ptr[o]..ptr[o + 1] {
            out.push((o, idx[k], values[k]));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicates_are_summed_and_rows_sorted() {
        let m =
            CsrMatrix::from_triplets(2, 3, &[(1, 2, 1.0), (0, 1, 2.0), (1, 0, 3.0), (1, 2, 4.0)])
                .unwrap();
        assert_eq!(m.row_ptr(), &[0, 1, 3]);
        assert_eq!(m.col_idx(), &[1, 0, 2]);
        assert_eq!(m.values(), &[2.0, 3.0, 5.0]);
        assert_eq!(m.get(1, 2), 5.0);
        assert_eq!(m.get(0, 0), 0.0);
    }

    /// Duplicates are summed in input order (1e16 + 1 rounds to 1e16, then -1e16 gives 0; in
    /// another order the sum would be 1), whatever the order of the rows around them; empty
    /// rows and a matrix without entries have their pointers.
    #[test]
    fn duplicates_are_summed_in_input_order() {
        let m = CsrMatrix::from_triplets(
            3,
            2,
            &[
                (2, 1, 5.0),
                (0, 0, 1e16),
                (2, 0, 4.0),
                (0, 0, 1.0),
                (0, 0, -1e16),
            ],
        )
        .unwrap();
        assert_eq!(m.row_ptr(), &[0, 1, 1, 3]);
        assert_eq!(m.col_idx(), &[0, 0, 1]);
        assert_eq!(m.values(), &[0.0, 4.0, 5.0]);
        let empty = CsrMatrix::from_triplets(4, 4, &[]).unwrap();
        assert_eq!((empty.row_ptr(), empty.nnz()), (&[0, 0, 0, 0, 0][..], 0));
    }

    #[test]
    fn csc_with_unsorted_rows_equals_triplets() {
        // 2x2 [[1, 2], [3, 4]] with column 0 rows given in reverse order.
        let a =
            CsrMatrix::from_csc(2, 2, &[0, 2, 4], &[1, 0, 0, 1], &[3.0, 1.0, 2.0, 4.0]).unwrap();
        let b =
            CsrMatrix::from_triplets(2, 2, &[(0, 0, 1.0), (0, 1, 2.0), (1, 0, 3.0), (1, 1, 4.0)])
                .unwrap();
        assert_eq!(a, b);
    }

    #[test]
    fn bad_pointers_are_rejected() {
        assert!(CsrMatrix::from_csr(2, 2, &[0, 2, 1], &[0, 1], &[1.0, 1.0]).is_err());
        assert!(CsrMatrix::from_csr(2, 2, &[0, 1, 2], &[0, 5], &[1.0, 1.0]).is_err());
    }

    /// The counting transpose equals the transpose built through triplets (sorted, the same
    /// entries), empty rows and columns included; transposing twice gives the matrix back.
    #[test]
    fn transposed_equals_the_transpose_through_triplets() {
        let entries = [
            (0, 3, 1.5),
            (0, 0, -2.0),
            (2, 1, 3.0),
            (2, 3, 4.0),
            (3, 0, 5.0),
            (3, 2, -6.0),
        ];
        let a = CsrMatrix::from_triplets(4, 5, &entries).unwrap();
        let swapped: Vec<_> = entries.iter().map(|&(i, j, v)| (j, i, v)).collect();
        let at = a.transposed().unwrap();
        assert_eq!(at, CsrMatrix::from_triplets(5, 4, &swapped).unwrap());
        assert_eq!(at.transposed().unwrap(), a);
        let empty = CsrMatrix::from_triplets(2, 3, &[])
            .unwrap()
            .transposed()
            .unwrap();
        assert_eq!(
            (empty.nrows(), empty.ncols(), empty.row_ptr()),
            (3, 2, &[0, 0, 0, 0][..])
        );
    }
}
