//! CSparse storage (`CSparseMatrix` as triplet, CSC or Siconos' CSR, inside a
//! `NumericsSparseMatrix`): a checked view of a host's matrix (single entries, every entry,
//! conversion to the core's `CsrMatrix`), the C-allocated CSC copy of a core matrix, empty
//! structures, release and triplet growth.
//!
//! A host fills `nzmax`, `m`, `n`, `nz`, `p`, `i` as plain integers: each is checked against the
//! others before an array is read with it. `nzmax` is the declared length of `i` and `x` (and of
//! `p` for a triplet); a compressed form's `p` holds `n + 1` (CSC) or `m + 1` (CSR) pointers.

use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::{c_slice, check_heap_len, nonneg, size_err, storage_err, CBuf};
use super::{NSM_CSC, NSM_CSR, NSM_HALF_TRIPLET, NSM_TRIPLET, NSM_UNKNOWN};
use crate::alloc::c_free;
use crate::types::*;
use crate::{CError, CResult, FC3D_ERR_OUT_OF_MEMORY};
use fc3d_core::error::try_vec;
use fc3d_core::matrix::CsrMatrix;

/// A host CSparse matrix read as a `rows x cols` matrix of the given kind, its sizes and counts
/// checked (dimensions, `nz` against the kind, `0 <= nz <= nzmax`); the index arrays are checked
/// where they are read.
pub(super) struct CsView<'a> {
    cs: &'a CSparseMatrix,
    kind: c_int,
    rows: usize,
    cols: usize,
}

impl<'a> CsView<'a> {
    pub(super) fn new(
        cs: &'a CSparseMatrix,
        kind: c_int,
        rows: usize,
        cols: usize,
    ) -> CResult<Self> {
        match kind {
            NSM_TRIPLET => {
                check_dims(cs.m, cs.n, rows, cols)?;
                if cs.nz < 0 {
                    return Err(storage_err(format!(
                        "triplet matrix has nz = {} (< 0: the form of a compressed matrix)",
                        cs.nz
                    )));
                }
            }
            NSM_CSC => {
                check_dims(cs.m, cs.n, rows, cols)?;
                if cs.nz != -1 {
                    return Err(storage_err(format!(
                        "CSC matrix must have nz = -1, got {}",
                        cs.nz
                    )));
                }
            }
            NSM_CSR => {
                // Siconos stores a CSR matrix as the CSC of its transpose: n rows, m columns.
                check_dims(cs.n, cs.m, rows, cols)?;
                if cs.nz != -2 && cs.nz != -1 {
                    return Err(storage_err(format!(
                        "CSR matrix must have nz = -2, got {}",
                        cs.nz
                    )));
                }
            }
            NSM_HALF_TRIPLET => return Err(storage_err(
                "half-triplet (symmetric half) storage is rejected: W is not symmetric in general",
            )),
            other => return Err(storage_err(format!("unknown sparse origin {other}"))),
        }
        nonneg(cs.nzmax, "sparse matrix nzmax")?;
        if cs.nz > cs.nzmax {
            return Err(storage_err(format!(
                "triplet nz = {} exceeds nzmax = {}",
                cs.nz, cs.nzmax
            )));
        }
        Ok(CsView {
            cs,
            kind,
            rows,
            cols,
        })
    }

    /// (outer dimension, inner dimension, name of a pointer, name of an index) of a compressed form.
    fn compressed(&self) -> (usize, usize, &'static str, &'static str) {
        if self.kind == NSM_CSR {
            (
                self.rows,
                self.cols,
                "CSR row pointers (p)",
                "CSR column indices (i)",
            )
        } else {
            (
                self.cols,
                self.rows,
                "CSC column pointers (p)",
                "CSC row indices (i)",
            )
        }
    }

    /// The pointer array of a compressed form (`outer + 1` entries).
    unsafe fn pointers(&self) -> CResult<&'a [CS_INT]> {
        let (outer, _, what, _) = self.compressed();
        c_slice(self.cs.p, outer + 1, what)
    }

    /// The entries of line `o` (a column of a CSC, a row of a CSR) as (inner indices, values),
    /// its two pointers and the end of the pointer array checked against `nzmax`.
    unsafe fn line(&self, o: usize) -> CResult<(&'a [CS_INT], &'a [f64])> {
        let (outer, _, what, index) = self.compressed();
        let p = self.pointers()?;
        let (a, b) = (p[o], p[o + 1]);
        if a < 0 || b < a || b > self.cs.nzmax || p[outer] > self.cs.nzmax {
            return Err(storage_err(format!(
                "{what}: line {o} spans entries {a}..{b}, the last ends at {} (nzmax {})",
                p[outer], self.cs.nzmax
            )));
        }
        let (a, b) = (a as usize, b as usize);
        let idx = c_slice(self.cs.i, b, index)?;
        let x = c_slice(self.cs.x, b, "sparse values (x)")?;
        Ok((&idx[a..], &x[a..]))
    }

    /// An inner index checked against its dimension.
    fn inner(&self, v: CS_INT, bound: usize, what: &str) -> CResult<usize> {
        match usize::try_from(v) {
            Ok(u) if u < bound => Ok(u),
            _ => Err(storage_err(format!(
                "{what} {v} is outside 0..{bound} ({}x{} matrix)",
                self.rows, self.cols
            ))),
        }
    }

    /// Triplet arrays (row indices, column indices, values) of `nz` entries.
    unsafe fn triplet(&self) -> CResult<(&'a [CS_INT], &'a [CS_INT], &'a [f64])> {
        let nz = self.cs.nz as usize;
        Ok((
            c_slice(self.cs.i, nz, "triplet row indices (i)")?,
            c_slice(self.cs.p, nz, "triplet column indices (p)")?,
            c_slice(self.cs.x, nz, "triplet values (x)")?,
        ))
    }

    /// Entry (i, j), `i < rows` and `j < cols`: the sum of the values stored there (0 if none).
    /// Reads one line of a compressed form, every entry of a triplet, and checks what it reads.
    pub(super) unsafe fn get(&self, i: usize, j: usize) -> CResult<f64> {
        let mut v = 0.0;
        match self.kind {
            NSM_TRIPLET => {
                let (ri, cj, x) = self.triplet()?;
                for k in 0..ri.len() {
                    let r = self.inner(ri[k], self.rows, "triplet row index")?;
                    let c = self.inner(cj[k], self.cols, "triplet column index")?;
                    if (r, c) == (i, j) {
                        v += x[k];
                    }
                }
            }
            _ => {
                let (o, want) = if self.kind == NSM_CSR { (i, j) } else { (j, i) };
                let (_, inner_dim, _, what) = self.compressed();
                let (idx, x) = self.line(o)?;
                for (k, &e) in idx.iter().enumerate() {
                    if self.inner(e, inner_dim, what)? == want {
                        v += x[k];
                    }
                }
            }
        }
        Ok(v)
    }

    /// Calls `f(i, j, value)` on every stored entry in storage order, after checking the whole
    /// structure: pointers from 0, never decreasing, ending within `nzmax`; every index in range.
    pub(super) unsafe fn for_each(
        &self,
        mut f: impl FnMut(usize, usize, f64) -> CResult<()>,
    ) -> CResult<()> {
        match self.kind {
            NSM_TRIPLET => {
                let (ri, cj, x) = self.triplet()?;
                for k in 0..ri.len() {
                    let r = self.inner(ri[k], self.rows, "triplet row index")?;
                    let c = self.inner(cj[k], self.cols, "triplet column index")?;
                    f(r, c, x[k])?;
                }
            }
            _ => {
                let (outer, inner_dim, what, index) = self.compressed();
                let p = self.pointers()?;
                if p[0] != 0 || p.windows(2).any(|w| w[1] < w[0]) {
                    return Err(storage_err(format!(
                        "{what} must start at 0 and never decrease"
                    )));
                }
                let nnz = p[outer];
                if nnz > self.cs.nzmax {
                    return Err(storage_err(format!(
                        "{what} end at {nnz} but nzmax = {}",
                        self.cs.nzmax
                    )));
                }
                let nnz = nnz as usize;
                let idx = c_slice(self.cs.i, nnz, index)?;
                let x = c_slice(self.cs.x, nnz, "sparse values (x)")?;
                for o in 0..outer {
                    for k in p[o] as usize..p[o + 1] as usize {
                        let e = self.inner(idx[k], inner_dim, index)?;
                        if self.kind == NSM_CSR {
                            f(o, e, x[k])?;
                        } else {
                            f(e, o, x[k])?;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The number of stored entries (an upper bound when the structure is invalid), the arrays
    /// that hold them checked as one object each (length, alignment) before anything is sized
    /// by it.
    unsafe fn stored(&self) -> CResult<usize> {
        if self.kind == NSM_TRIPLET {
            return Ok(self.triplet()?.0.len());
        }
        let (outer, _, _, index) = self.compressed();
        let nnz = self.pointers()?[outer].clamp(0, self.cs.nzmax) as usize;
        c_slice(self.cs.i, nnz, index)?;
        c_slice(self.cs.x, nnz, "sparse values (x)")?;
        Ok(nnz)
    }

    /// Every stored entry as `(i, j, value)` in storage order (fallible allocation).
    pub(super) unsafe fn triplets(&self) -> CResult<Vec<(usize, usize, f64)>> {
        let mut t = Vec::new();
        t.try_reserve_exact(self.stored()?)
            .map_err(|_| CError::new(FC3D_ERR_OUT_OF_MEMORY, "cannot allocate the entries of W"))?;
        self.for_each(|i, j, v| {
            t.push((i, j, v));
            Ok(())
        })?;
        Ok(t)
    }
}

/// Validated core copy of a host CSparse matrix (checked as `CsView::for_each` does).
pub(super) unsafe fn csr_from_cs(
    cs: &CSparseMatrix,
    kind: c_int,
    rows: usize,
    cols: usize,
) -> CResult<CsrMatrix> {
    let view = CsView::new(cs, kind, rows, cols)?;
    let t = view.triplets()?;
    Ok(CsrMatrix::from_triplets(rows, cols, &t)?)
}

fn check_dims(m: CS_INT, n: CS_INT, rows: usize, cols: usize) -> CResult<()> {
    if m != rows as CS_INT || n != cols as CS_INT {
        return Err(size_err(format!(
            "sparse matrix is {m}x{n} but the NumericsMatrix says {rows}x{cols}"
        )));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Building C matrices.

/// A C-allocated CSparse compressed-column copy (nothing left allocated on failure).
pub(crate) fn csc_to_c(m: &CsrMatrix) -> CResult<*mut CSparseMatrix> {
    // Transpose the CSR structure into CSC.
    let (rows, cols, nnz) = (m.nrows(), m.ncols(), m.nnz());
    let mut count = try_vec(cols + 1, 0usize, "CSC column counts")?;
    for &j in m.col_idx() {
        count[j + 1] += 1;
    }
    for j in 0..cols {
        count[j + 1] += count[j];
    }
    let mut p = CBuf::<CS_INT>::zeroed(cols + 1, "CSC column pointers")?;
    for (d, &c) in p.as_mut_slice().iter_mut().zip(&count) {
        *d = c as CS_INT;
    }
    let mut ri = CBuf::<CS_INT>::zeroed(nnz, "CSC row indices")?;
    let mut x = CBuf::<c_double>::zeroed(nnz, "CSC values")?;
    let (ris, xs) = (ri.as_mut_slice(), x.as_mut_slice());
    for i in 0..rows {
        for k in m.row_ptr()[i]..m.row_ptr()[i + 1] {
            let j = m.col_idx()[k];
            ris[count[j]] = i as CS_INT;
            xs[count[j]] = m.values()[k];
            count[j] += 1;
        }
    }
    let out = CBuf::<CSparseMatrix>::zeroed(1, "CSC matrix")?.into_raw();
    let cs = CSparseMatrix {
        nzmax: nnz as CS_INT,
        m: rows as CS_INT,
        n: cols as CS_INT,
        p: p.into_raw(),
        i: ri.into_raw(),
        x: x.into_raw(),
        nz: -1,
    };
    // SAFETY: out is a fresh allocation for one CSparseMatrix.
    unsafe { out.write(cs) };
    Ok(out)
}

/// A C-allocated empty triplet of capacity `cap` for an `m x n` matrix (all or nothing).
pub(super) fn triplet_new(m: CS_INT, n: CS_INT, cap: usize) -> CResult<*mut CSparseMatrix> {
    let p = CBuf::<CS_INT>::zeroed(cap, "triplet column indices")?;
    let i = CBuf::<CS_INT>::zeroed(cap, "triplet row indices")?;
    let x = CBuf::<c_double>::zeroed(cap, "triplet values")?;
    let out = CBuf::<CSparseMatrix>::zeroed(1, "triplet")?.into_raw();
    let t = CSparseMatrix {
        nzmax: cap as CS_INT,
        m,
        n,
        p: p.into_raw(),
        i: i.into_raw(),
        x: x.into_raw(),
        nz: 0,
    };
    // SAFETY: out is a fresh allocation for one CSparseMatrix.
    unsafe { out.write(t) };
    Ok(out)
}

pub(super) fn empty_nsm() -> NumericsSparseMatrix {
    NumericsSparseMatrix {
        triplet: null_mut(),
        half_triplet: null_mut(),
        csc: null_mut(),
        trans_csc: null_mut(),
        csr: null_mut(),
        diag_indx: null_mut(),
        origin: NSM_UNKNOWN,
        linearSolverParams: null_mut(),
        versions: [NumericsDataVersion::default(); 5],
    }
}

// ---------------------------------------------------------------------------------------------
// Releasing.

pub(super) unsafe fn cs_free(cs: *mut CSparseMatrix) {
    if cs.is_null() {
        return;
    }
    c_free((*cs).p);
    c_free((*cs).i);
    c_free((*cs).x);
    c_free(cs);
}

pub(super) unsafe fn nsm_clear(s: *mut NumericsSparseMatrix) {
    if s.is_null() {
        return;
    }
    let s = &mut *s;
    for cs in [
        &mut s.triplet,
        &mut s.half_triplet,
        &mut s.csc,
        &mut s.trans_csc,
        &mut s.csr,
    ] {
        cs_free(*cs);
        *cs = null_mut();
    }
    c_free(s.diag_indx);
    s.diag_indx = null_mut();
    c_free(s.linearSolverParams);
    s.linearSolverParams = null_mut();
    s.origin = NSM_UNKNOWN;
}

// ---------------------------------------------------------------------------------------------
// Adding an entry to compressed columns.

/// Adds (i, j, v) to a host CSC matrix (`i < rows`, `j < cols`) as Siconos 4.4's `NM_entry`
/// does (through a triplet, compressed again, origin kept): the entries stay, the new one ends
/// column j (summed with an entry already at (i, j) by every reader). The whole structure is
/// checked first (`CsView::for_each`), and the old arrays, which are replaced and freed (they
/// must be heap blocks, as in Siconos), must hold what the counts say. All or nothing.
pub(super) unsafe fn csc_insert(
    cs: &mut CSparseMatrix,
    rows: usize,
    cols: usize,
    i: usize,
    j: usize,
    v: f64,
) -> CResult<()> {
    let view = CsView::new(cs, NSM_CSC, rows, cols)?;
    // The heap blocks first: they must hold what the counts say before anything is read by them.
    check_heap_len(cs.p as *const CS_INT, cols + 1, "CSC column pointers (p)")?;
    let old_p = view.pointers()?;
    let nnz = old_p[cols].clamp(0, cs.nzmax) as usize;
    check_heap_len(cs.i as *const CS_INT, nnz, "CSC row indices (i)")?;
    check_heap_len(cs.x as *const c_double, nnz, "CSC values (x)")?;
    view.for_each(|_, _, _| Ok(()))?;
    let (old_i, old_x) = (
        c_slice(cs.i, nnz, "CSC row indices (i)")?,
        c_slice(cs.x, nnz, "CSC values (x)")?,
    );
    let mut p = CBuf::<CS_INT>::zeroed(cols + 1, "CSC column pointers")?;
    let mut ri = CBuf::<CS_INT>::zeroed(nnz + 1, "CSC row indices")?;
    let mut x = CBuf::<c_double>::zeroed(nnz + 1, "CSC values")?;
    let (ps, ris, xs) = (p.as_mut_slice(), ri.as_mut_slice(), x.as_mut_slice());
    let mut k = 0;
    for c in 0..cols {
        ps[c] = k as CS_INT;
        for e in old_p[c] as usize..old_p[c + 1] as usize {
            ris[k] = old_i[e];
            xs[k] = old_x[e];
            k += 1;
        }
        if c == j {
            ris[k] = i as CS_INT;
            xs[k] = v;
            k += 1;
        }
    }
    ps[cols] = k as CS_INT;
    c_free(cs.p);
    c_free(cs.i);
    c_free(cs.x);
    cs.p = p.into_raw();
    cs.i = ri.into_raw();
    cs.x = x.into_raw();
    cs.nzmax = k as CS_INT;
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Growing a triplet.

/// Appends (i, j, v) to a host triplet as CSparse's `cs_entry` does (doubling a full triplet's
/// capacity, widening `m`, `n` to hold the entry). All or nothing: `nzmax < 0`, `nz < 0` (a
/// compressed matrix), `nz > nzmax`, NULL arrays behind a declared capacity, a capacity whose
/// double overflows, and arrays whose heap blocks hold fewer than `nz` entries (when they must be
/// grown, hence be heap blocks) are refused before anything is written.
pub(super) unsafe fn triplet_push(
    t: &mut CSparseMatrix,
    i: usize,
    j: usize,
    v: f64,
) -> CResult<()> {
    let nzmax = nonneg(t.nzmax, "triplet nzmax")?;
    if t.nz < 0 {
        return Err(storage_err(format!(
            "the triplet has nz = {} (< 0: the form of a compressed matrix); NM_entry appends to triplets only",
            t.nz
        )));
    }
    let nz = t.nz as usize;
    if nz > nzmax {
        return Err(storage_err(format!(
            "triplet nz = {nz} exceeds nzmax = {nzmax}"
        )));
    }
    if nz == nzmax {
        let cap = nzmax
            .checked_mul(2)
            .map(|c| c.max(1))
            .filter(|&c| c as u64 <= CS_INT::MAX as u64 && super::byte_size::<CS_INT>(c).is_some())
            .ok_or_else(|| size_err(format!("a triplet of nzmax = {nzmax} cannot grow")))?;
        if nz > 0 && (t.p.is_null() || t.i.is_null() || t.x.is_null()) {
            return Err(CError::null("an array of the triplet (p, i or x)"));
        }
        check_heap_len(t.p as *const CS_INT, nz, "triplet column indices (p)")?;
        check_heap_len(t.i as *const CS_INT, nz, "triplet row indices (i)")?;
        check_heap_len(t.x as *const c_double, nz, "triplet values (x)")?;
        let mut p = CBuf::<CS_INT>::zeroed(cap, "triplet column indices")?;
        let mut ii = CBuf::<CS_INT>::zeroed(cap, "triplet row indices")?;
        let mut x = CBuf::<c_double>::zeroed(cap, "triplet values")?;
        if nz > 0 {
            p.as_mut_slice()[..nz].copy_from_slice(std::slice::from_raw_parts(t.p, nz));
            ii.as_mut_slice()[..nz].copy_from_slice(std::slice::from_raw_parts(t.i, nz));
            x.as_mut_slice()[..nz].copy_from_slice(std::slice::from_raw_parts(t.x, nz));
        }
        c_free(t.p);
        c_free(t.i);
        c_free(t.x);
        t.p = p.into_raw();
        t.i = ii.into_raw();
        t.x = x.into_raw();
        t.nzmax = cap as CS_INT;
    } else {
        for (ptr, what) in [
            (t.p as *const u8, "triplet column indices (p)"),
            (t.i as *const u8, "triplet row indices (i)"),
            (t.x as *const u8, "triplet values (x)"),
        ] {
            if ptr.is_null() {
                return Err(CError::null(what));
            }
        }
        super::check_extent(t.p as *const CS_INT, nzmax, "triplet column indices (p)")?;
        super::check_extent(t.i as *const CS_INT, nzmax, "triplet row indices (i)")?;
        super::check_extent(t.x as *const c_double, nzmax, "triplet values (x)")?;
    }
    *t.i.add(nz) = i as CS_INT;
    *t.p.add(nz) = j as CS_INT;
    *t.x.add(nz) = v;
    t.nz += 1;
    t.m = t.m.max(i as CS_INT + 1);
    t.n = t.n.max(j as CS_INT + 1);
    Ok(())
}

/// A C-allocated copy of the host CSparse matrix `cs` of form `kind`, checked as a `rows x cols`
/// matrix (the whole structure, as `CsView::for_each` does): the same form, sizes and entries in
/// the same order; `nzmax` becomes the number of entries stored (at least 1, as CSparse
/// allocates). Nothing is left allocated on failure.
pub(super) unsafe fn cs_duplicate(
    cs: &CSparseMatrix,
    kind: c_int,
    rows: usize,
    cols: usize,
) -> CResult<*mut CSparseMatrix> {
    let view = CsView::new(cs, kind, rows, cols)?;
    view.for_each(|_, _, _| Ok(()))?;
    let (p, i, x): (&[CS_INT], &[CS_INT], &[f64]) = if kind == NSM_TRIPLET {
        let (ri, cj, x) = view.triplet()?;
        (cj, ri, x)
    } else {
        let (outer, _, what, index) = view.compressed();
        let p = c_slice(cs.p, outer + 1, what)?;
        let used = p[outer] as usize;
        (
            p,
            c_slice(cs.i, used, index)?,
            c_slice(cs.x, used, "sparse values (x)")?,
        )
    };
    let used = x.len();
    // A triplet's p holds a column index per entry: allocate nzmax of them like i and x.
    let copy_padded = |v: &[CS_INT], len: usize, what: &str| -> CResult<CBuf<CS_INT>> {
        let mut b = CBuf::<CS_INT>::zeroed(len, what)?;
        b.as_mut_slice()[..v.len()].copy_from_slice(v);
        Ok(b)
    };
    let nzmax = used.max(1);
    let p_len = if kind == NSM_TRIPLET { nzmax } else { p.len() };
    let p_copy = copy_padded(p, p_len, "sparse copy p")?;
    let i_copy = copy_padded(i, nzmax, "sparse copy i")?;
    let mut x_copy = CBuf::<c_double>::zeroed(nzmax, "sparse copy x")?;
    x_copy.as_mut_slice()[..used].copy_from_slice(x);
    let nzmax = CS_INT::try_from(nzmax).map_err(|_| size_err("too many sparse entries"))?;
    let out = CBuf::<CSparseMatrix>::zeroed(1, "sparse copy")?.into_raw();
    out.write(CSparseMatrix {
        nzmax,
        m: cs.m,
        n: cs.n,
        p: p_copy.into_raw(),
        i: i_copy.into_raw(),
        x: x_copy.into_raw(),
        nz: cs.nz,
    });
    Ok(out)
}

/// Scales the CSC form of a host sparse matrix in place by `factor`, as Siconos' `NM_scal`: the
/// existing CSC form when there is one (it is checked first), else a CSC built from the origin
/// form; the CSC becomes the origin and the triplet, half-triplet, transposed-CSC and CSR forms
/// are released. Returns nothing changed on failure.
pub(super) unsafe fn nsm_scale_to_csc(
    s: &mut NumericsSparseMatrix,
    rows: usize,
    cols: usize,
    factor: f64,
) -> CResult<()> {
    let csc = if s.csc.is_null() {
        let (cs, kind) = match super::sparse_origin(s)? {
            Some((cs, kind)) => (&*cs, kind),
            None => return Err(CError::null("the sparse matrix's origin form")),
        };
        csc_to_c(&csr_from_cs(cs, kind, rows, cols)?)?
    } else {
        let view = CsView::new(&*s.csc, NSM_CSC, rows, cols)?;
        view.for_each(|_, _, _| Ok(()))?;
        s.csc
    };
    let (_, _, what, _) = CsView::new(&*csc, NSM_CSC, rows, cols)?.compressed();
    let p = c_slice((*csc).p, cols + 1, what)?;
    let used = p[cols] as usize;
    if used > 0 {
        for v in std::slice::from_raw_parts_mut((*csc).x, used) {
            *v *= factor;
        }
    }
    for cs in [
        &mut s.triplet,
        &mut s.half_triplet,
        &mut s.trans_csc,
        &mut s.csr,
    ] {
        cs_free(*cs);
        *cs = null_mut();
    }
    s.csc = csc;
    s.origin = NSM_CSC;
    let newest = s.versions.iter().map(|v| v.number).max().unwrap_or(0);
    s.versions[NSM_CSC as usize].number = newest.saturating_add(1);
    Ok(())
}
