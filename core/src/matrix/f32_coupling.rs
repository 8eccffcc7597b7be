//! An f32 copy of the coupling (off-diagonal) blocks of W's block rows, for the mixed-precision
//! Gauss-Seidel sweep (issue 27 item 5): each stored off-diagonal block rounded once to f32
//! (relative rounding 2^-24 ~ 6e-8 an entry), read with f64 accumulation, the diagonal blocks
//! kept in f64 (the local solver needs them exact). A coupling block then costs 36 bytes and a
//! 4-byte column instead of 72 and 8: a sweep reads about half the bytes of W.
//!
//! The diagonal blocks are copied too (f64, row-major, one after the other): read from W's
//! arrays, each would be a cache miss of its own once the sweep no longer streams through
//! them (measured: the f32 sweep on 10^5 sphere contacts was 1.2x slower than the f64 one).
//!
//! The rows a Gauss-Seidel update reads are abstracted by [`SweepRows`]: W's own
//! [`BlockRows`], or the [`F32Coupling`].

use super::BlockRows;
use crate::alloc::{reserve, try_push};
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::{contact_of, Block};

/// What a Gauss-Seidel update reads of W: each contact's diagonal block and the product of its
/// coupling blocks with the other contacts' reactions, `q_c + sum_{b != c} W_cb r_b`.
pub trait SweepRows<const D: usize>: Sync {
    fn n_contacts(&self) -> usize;
    /// Contact `c`'s diagonal block (row-major, f64).
    fn diagonal(&self, c: usize) -> Block<D>;
    /// `q_c + sum_{b != c} W_cb r_b`, each contact's reaction read through `r_of`.
    fn local_q_by(&self, c: usize, q: &[f64], r_of: impl Fn(usize) -> [f64; D]) -> [f64; D];
    /// The normal component of [`SweepRows::local_q_by`], the reaction read entry by entry.
    fn local_q_normal_by(&self, c: usize, q: &[f64], r_at: impl Fn(usize) -> f64) -> f64;
    /// [`SweepRows::local_q_by`] on a plain reaction vector.
    #[inline]
    fn local_q(&self, c: usize, q: &[f64], r: &[f64]) -> [f64; D] {
        let contacts = r.as_chunks::<D>().0;
        self.local_q_by(c, q, |b| contacts[b])
    }
    /// [`SweepRows::local_q_normal_by`] on a plain reaction vector.
    #[inline]
    fn local_q_normal(&self, c: usize, q: &[f64], r: &[f64]) -> f64 {
        self.local_q_normal_by(c, q, |i| r[i])
    }
}

impl<const D: usize> SweepRows<D> for BlockRows<'_, D> {
    #[inline]
    fn n_contacts(&self) -> usize {
        BlockRows::n_contacts(self)
    }
    #[inline]
    fn diagonal(&self, c: usize) -> Block<D> {
        BlockRows::diagonal(self, c)
    }
    #[inline]
    fn local_q_by(&self, c: usize, q: &[f64], r_of: impl Fn(usize) -> [f64; D]) -> [f64; D] {
        BlockRows::local_q_by(self, c, q, r_of)
    }
    #[inline]
    fn local_q_normal_by(&self, c: usize, q: &[f64], r_at: impl Fn(usize) -> f64) -> f64 {
        BlockRows::local_q_normal_by(self, c, q, r_at)
    }
    #[inline]
    fn local_q(&self, c: usize, q: &[f64], r: &[f64]) -> [f64; D] {
        BlockRows::local_q(self, c, q, r)
    }
    #[inline]
    fn local_q_normal(&self, c: usize, q: &[f64], r: &[f64]) -> f64 {
        BlockRows::local_q_normal(self, c, q, r)
    }
}

/// The coupling blocks of W's block rows in f32: per contact, the columns (u32) and the
/// `D * D` column-major values of its stored off-diagonal blocks (diagonal ones left out), and
/// each contact's diagonal block in f64.
#[derive(Debug, Clone)]
pub struct F32Coupling<const D: usize = 3> {
    diagonal: Vec<Block<D>>,
    row_ptr: Vec<usize>,
    cols: Vec<u32>,
    values: Vec<f32>,
}

impl<const D: usize> F32Coupling<D> {
    /// The f32 copy of `rows`' coupling blocks, allocated fallibly (one pass over W). `None`
    /// when f32 cannot hold it: more than `u32::MAX` contacts, or a finite entry beyond f32's
    /// range (it would round to an infinity); the sweep then stays in f64.
    pub fn from_rows(rows: &BlockRows<'_, D>) -> Result<Option<Self>, Fc3dError> {
        let nc = rows.n_contacts();
        if u32::try_from(nc).is_err() {
            return Ok(None);
        }
        let what = "the f32 copy of W's coupling blocks";
        let mut diagonal = try_vec(nc, [[0.0; D]; D], what)?;
        for (c, d) in diagonal.iter_mut().enumerate() {
            *d = rows.diagonal(c);
        }
        let mut row_ptr = try_vec(nc + 1, 0usize, what)?;
        let n_blocks = rows.n_off_diagonal();
        let mut cols: Vec<u32> = Vec::new();
        reserve(&mut cols, n_blocks, what)?;
        let mut values: Vec<f32> = Vec::new();
        reserve(&mut values, n_blocks.saturating_mul(D * D), what)?;
        // Exactly `n_off_diagonal` blocks are visited: the pushes below stay within the room
        // reserved (try_push only guards the count).
        let mut pushed = Ok(());
        let mut representable = true;
        for c in 0..nc {
            rows.for_each_coupling_block(c, |b, m| {
                if pushed.is_err() {
                    return;
                }
                pushed = try_push(&mut cols, b as u32, what);
                for &v in &m[..D * D] {
                    let x = v as f32;
                    representable &= x.is_finite() || !v.is_finite();
                    if pushed.is_ok() {
                        pushed = try_push(&mut values, x, what);
                    }
                }
            });
            pushed.clone()?;
            if !representable {
                return Ok(None);
            }
            row_ptr[c + 1] = cols.len();
        }
        Ok(Some(F32Coupling {
            diagonal,
            row_ptr,
            cols,
            values,
        }))
    }

    /// Bytes of the copy (what a sweep reads of it: diagonal blocks, coupling values, columns
    /// and row pointers).
    pub fn bytes(&self) -> usize {
        let diagonal = std::mem::size_of::<Block<D>>() * self.diagonal.len();
        diagonal + 4 * self.values.len() + 4 * self.cols.len() + 8 * self.row_ptr.len()
    }

    /// `q_c + sum_{b != c} W32_cb r_b`, accumulated in f64 in the order of
    /// [`BlockRows::local_q_by`].
    #[inline]
    pub fn local_q_by(&self, c: usize, q: &[f64], r_of: impl Fn(usize) -> [f64; D]) -> [f64; D] {
        let range = self.row_ptr[c]..self.row_ptr[c + 1];
        let cols = &self.cols[range.clone()];
        let values = &self.values[D * D * range.start..D * D * range.end];
        let mut acc = contact_of(q, c);
        for (m, &b) in values.chunks_exact(D * D).zip(cols) {
            let rb: [f64; D] = r_of(b as usize);
            let m = &m[..D * D];
            for (i, a) in acc.iter_mut().enumerate() {
                for (j, x) in rb.iter().enumerate() {
                    *a += f64::from(m[i + D * j]) * x;
                }
            }
        }
        acc
    }

    /// The normal component of [`F32Coupling::local_q_by`].
    #[inline]
    pub fn local_q_normal_by(&self, c: usize, q: &[f64], r_at: impl Fn(usize) -> f64) -> f64 {
        let range = self.row_ptr[c]..self.row_ptr[c + 1];
        let cols = &self.cols[range.clone()];
        let values = &self.values[D * D * range.start..D * D * range.end];
        let mut acc = q[D * c];
        for (m, &b) in values.chunks_exact(D * D).zip(cols) {
            let b = b as usize;
            let mut s = f64::from(m[0]) * r_at(D * b);
            for j in 1..D {
                s += f64::from(m[D * j]) * r_at(D * b + j);
            }
            acc += s;
        }
        acc
    }

    /// `||  |W32_off| |r|  ||^2`: the squared norm of the entrywise absolute coupling product,
    /// which bounds (times 2^-24) what rounding W's coupling blocks to f32 moves `W r`.
    pub fn abs_product_norm_sq(&self, r: &[f64]) -> f64 {
        let contacts = r.as_chunks::<D>().0;
        let mut total = 0.0;
        for c in 0..self.row_ptr.len() - 1 {
            let range = self.row_ptr[c]..self.row_ptr[c + 1];
            let values = &self.values[D * D * range.start..D * D * range.end];
            let mut acc = [0.0f64; D];
            for (m, &b) in values.chunks_exact(D * D).zip(&self.cols[range]) {
                let rb = contacts[b as usize];
                for (i, a) in acc.iter_mut().enumerate() {
                    for (j, x) in rb.iter().enumerate() {
                        *a += f64::from(m[i + D * j]).abs() * x.abs();
                    }
                }
            }
            total += acc.iter().map(|a| a * a).sum::<f64>();
        }
        total
    }
}

/// The rows of a mixed-precision sweep: W's f64 diagonal blocks and the f32 coupling blocks.
impl<const D: usize> SweepRows<D> for F32Coupling<D> {
    #[inline]
    fn n_contacts(&self) -> usize {
        self.diagonal.len()
    }
    #[inline]
    fn diagonal(&self, c: usize) -> Block<D> {
        self.diagonal[c]
    }
    #[inline]
    fn local_q_by(&self, c: usize, q: &[f64], r_of: impl Fn(usize) -> [f64; D]) -> [f64; D] {
        F32Coupling::local_q_by(self, c, q, r_of)
    }
    #[inline]
    fn local_q_normal_by(&self, c: usize, q: &[f64], r_at: impl Fn(usize) -> f64) -> f64 {
        F32Coupling::local_q_normal_by(self, c, q, r_at)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix::BlockSparseMatrix;

    #[test]
    fn the_f32_product_is_the_f64_one_to_f32_rounding() {
        // A chain of 3 contacts, block (0, 1) stored twice (summed by every reader).
        let b = |s: f64| -> [f64; 9] { std::array::from_fn(|k| (s + k as f64) / 3.0) };
        let s = BlockSparseMatrix::new(
            3,
            3,
            vec![0, 3, 6, 8],
            vec![0, 1, 1, 0, 1, 2, 1, 2],
            vec![
                b(10.0),
                b(1.0),
                b(0.5),
                b(2.0),
                b(20.0),
                b(3.0),
                b(4.0),
                b(30.0),
            ],
        )
        .unwrap();
        let rows = BlockRows::<3>::from_block_sparse(&s).unwrap();
        let low = F32Coupling::from_rows(&rows).unwrap().unwrap();
        let mixed = &low;
        let q: Vec<f64> = (0..9).map(|k| 0.1 * k as f64 - 0.3).collect();
        let r: Vec<f64> = (0..9).map(|k| 1.0 + 0.25 * k as f64).collect();
        let bound = low.abs_product_norm_sq(&r).sqrt() * f64::from(f32::EPSILON);
        for c in 0..3 {
            assert_eq!(mixed.diagonal(c), rows.diagonal(c));
            let (a, e) = (mixed.local_q(c, &q, &r), rows.local_q(c, &q, &r));
            for i in 0..3 {
                assert!((a[i] - e[i]).abs() <= bound, "{c} {i}: {} {}", a[i], e[i]);
            }
            let (an, en) = (
                mixed.local_q_normal(c, &q, &r),
                rows.local_q_normal(c, &q, &r),
            );
            assert!((an - en).abs() <= bound);
            assert_eq!(an, a[0]);
        }
    }

    #[test]
    fn an_entry_beyond_f32_range_keeps_the_sweep_in_f64() {
        let mut blocks = vec![[1.0; 9]; 3];
        blocks[1][4] = 1e300;
        let s = BlockSparseMatrix::new(2, 2, vec![0, 2, 3], vec![0, 1, 1], blocks).unwrap();
        let rows = BlockRows::<3>::from_block_sparse(&s).unwrap();
        assert!(F32Coupling::from_rows(&rows).unwrap().is_none());
    }
}
