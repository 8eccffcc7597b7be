//! The fill of a sparse LU factorization, counted from the matrix's pattern and the two
//! permutations the factorization chose: `P A Q = L U`, `(P A Q)[i][j] = A[row[i]][col[j]]`.
//! faer does not expose the size of its supernodal factors, so the count is structural (every
//! entry that elimination can make nonzero, no numerical cancellation assumed), by the symbolic
//! part of Gilbert and Peierls' left-looking LU: column `j` of `L` and `U` is the set reached
//! from the pattern of `(P A Q)[:, j]` through the columns of `L` already known, with symmetric
//! pruning of those columns.

/// `nnz(L) + nnz(U)` of `P A Q = L U` with `L` unit lower triangular, its unit diagonal not
/// counted (so a factorization without fill has as many entries as `A`'s pattern). `A` is
/// `n x n` in compressed columns (`col_ptr`, `row_idx`); `row_inverse[r]` is the position of
/// original row `r` in `P A Q`, `col_forward[j]` the original column at position `j`. `None`
/// when the work arrays (as large as the strictly lower factor) cannot be allocated.
pub fn lu_factor_nnz(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
    row_inverse: &[usize],
    col_forward: &[usize],
) -> Option<usize> {
    debug_assert!(col_ptr.len() == n + 1 && row_inverse.len() == n && col_forward.len() == n);
    // The strictly lower part of L, column by column, in positions of P A Q.
    let mut l_ptr: Vec<usize> = Vec::new();
    l_ptr.try_reserve_exact(n + 1).ok()?;
    l_ptr.push(0);
    let mut l_rows: Vec<usize> = Vec::new();
    // Symmetric pruning (Eisenstat and Liu): once L[j, k] and U[k, j] are both nonzero, the
    // rows of L[:, k] below j are reached through column j as well, so a search through k only
    // needs its rows up to j: `searched[k]` of them, kept first (all while not pruned).
    let mut searched = try_filled(n, usize::MAX)?;
    let mut seen = try_filled(n, usize::MAX)?;
    let mut stack: Vec<usize> = Vec::new();
    stack.try_reserve_exact(n).ok()?;
    let mut upper_rows: Vec<usize> = Vec::new();
    upper_rows.try_reserve_exact(n).ok()?;
    let mut upper = 0usize;
    for (j, &col) in col_forward.iter().enumerate() {
        upper_rows.clear();
        for &row in &row_idx[col_ptr[col]..col_ptr[col + 1]] {
            let start = row_inverse[row];
            if seen[start] == j {
                continue;
            }
            seen[start] = j;
            stack.push(start);
            while let Some(k) = stack.pop() {
                if k <= j {
                    // U[k, j] (the diagonal included); rows k < j reach further through L[:, k].
                    upper += 1;
                    if k == j {
                        continue;
                    }
                    upper_rows.push(k);
                    let end = l_ptr[k] + searched[k].min(l_ptr[k + 1] - l_ptr[k]);
                    for &next in &l_rows[l_ptr[k]..end] {
                        if seen[next] != j {
                            seen[next] = j;
                            stack.push(next);
                        }
                    }
                } else {
                    l_rows.try_reserve(1).ok()?;
                    l_rows.push(k);
                }
            }
        }
        l_ptr.push(l_rows.len());
        for &k in &upper_rows {
            if searched[k] != usize::MAX {
                continue;
            }
            let column = &mut l_rows[l_ptr[k]..l_ptr[k + 1]];
            if column.contains(&j) {
                let mut kept = 0;
                for i in 0..column.len() {
                    if column[i] <= j {
                        column.swap(i, kept);
                        kept += 1;
                    }
                }
                searched[k] = kept;
            }
        }
    }
    Some(upper + l_rows.len())
}

/// `n` copies of `value`, or `None` when they cannot be allocated.
fn try_filled(n: usize, value: usize) -> Option<Vec<usize>> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).ok()?;
    v.resize(n, value);
    Some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense boolean elimination of P A Q without pivoting: the structural count, O(n^3).
    fn dense_count(pattern: &[Vec<bool>]) -> usize {
        let n = pattern.len();
        let mut a = pattern.to_vec();
        for k in 0..n {
            for i in k + 1..n {
                if a[i][k] {
                    for j in k + 1..n {
                        if a[k][j] {
                            a[i][j] = true;
                        }
                    }
                }
            }
        }
        a.iter().flatten().filter(|&&v| v).count()
    }

    fn csc(pattern: &[Vec<bool>]) -> (Vec<usize>, Vec<usize>) {
        let n = pattern.len();
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for j in 0..n {
            for (i, row) in pattern.iter().enumerate() {
                if row[j] {
                    row_idx.push(i);
                }
            }
            col_ptr.push(row_idx.len());
        }
        (col_ptr, row_idx)
    }

    #[test]
    fn arrow_matrices_fill_as_elimination_says() {
        // Dense first row and column, diagonal: ordered first, the arrow fills everything;
        // ordered last, nothing.
        let n = 6;
        let arrow: Vec<Vec<bool>> = (0..n)
            .map(|i| (0..n).map(|j| i == j || i == 0 || j == 0).collect())
            .collect();
        let (cp, ri) = csc(&arrow);
        let identity: Vec<usize> = (0..n).collect();
        assert_eq!(
            lu_factor_nnz(n, &cp, &ri, &identity, &identity),
            Some(n * n)
        );
        let last_first: Vec<usize> = (1..n).chain([0]).collect();
        let mut inverse = vec![0; n];
        for (pos, &r) in last_first.iter().enumerate() {
            inverse[r] = pos;
        }
        assert_eq!(
            lu_factor_nnz(n, &cp, &ri, &inverse, &last_first),
            Some(3 * n - 2)
        );
    }

    #[test]
    fn random_patterns_match_dense_elimination() {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as usize
        };
        for n in [1, 2, 5, 17, 40, 90] {
            for trial in 0..12 {
                let sparsity = [3, 7, 25][trial % 3];
                let a: Vec<Vec<bool>> = (0..n)
                    .map(|i| (0..n).map(|j| i == j || next() % sparsity == 0).collect())
                    .collect();
                let mut rows: Vec<usize> = (0..n).collect();
                let mut cols: Vec<usize> = (0..n).collect();
                for k in (1..n).rev() {
                    rows.swap(k, next() % (k + 1));
                    cols.swap(k, next() % (k + 1));
                }
                let mut row_inverse = vec![0; n];
                for (pos, &r) in rows.iter().enumerate() {
                    row_inverse[r] = pos;
                }
                let permuted: Vec<Vec<bool>> = (0..n)
                    .map(|i| (0..n).map(|j| a[rows[i]][cols[j]]).collect())
                    .collect();
                let (cp, ri) = csc(&a);
                assert_eq!(
                    lu_factor_nnz(n, &cp, &ri, &row_inverse, &cols),
                    Some(dense_count(&permuted)),
                    "n = {n}"
                );
            }
        }
    }
}
