// One fuzz case of the exported matrix helpers (`NM_*`, `SBM_*`, `SBCM_*`) and of `fc3d_driver`
// on host-built matrices, shared by the fuzz target (fuzz/fuzz_targets/matrix_helpers.rs) and
// the tests that replay saved inputs (capi/tests/matrix_hostile.rs), which include this file.
//
// The bytes build what a hostile host fills in: a NumericsMatrix in dense, sparse-block or
// CSparse (triplet, CSC, CSR) storage, a coordinate block matrix, and the arguments of the calls.
// Every array is exactly as long as the field that declares its length (fc3d cannot see a lie
// about an allocation it does not own) and bounded, so that a case runs in microseconds; every
// other number is arbitrary: sizes, counts, indices, pointers into the arrays, cumulative block
// sizes, NULL or not, INT_MIN..INT_MAX. All memory is the C heap (calloc), so that fc3d may free
// or grow what a host gives it, and the address sanitizer sees every access.
//
// Promises checked: no crash, no sanitizer report, no leak; never FC3D_ERR_INTERNAL (a caught
// panic); a call that fails leaves its outputs as they were (struct fields, triplet arrays,
// reaction, velocity, iparam[1], dparam[1]); what a call that succeeds returns agrees with the
// data (entries read back, copies equal to their source).

use std::os::raw::{c_double, c_int, c_uint, c_void};

use fc3d::types::{
    CSparseMatrix, FrictionContactProblem, NumericsMatrix, NumericsSparseMatrix, SolverOptions,
    SparseBlockCoordinateMatrix, SparseBlockStructuredMatrix, CS_INT,
};

#[allow(improper_ctypes)]
extern "C" {
    fn NM_new() -> *mut NumericsMatrix;
    fn NM_null(a: *mut NumericsMatrix);
    fn NM_create(storage: c_int, size0: c_int, size1: c_int) -> *mut NumericsMatrix;
    fn NM_create_from_data(
        storage: c_int,
        size0: c_int,
        size1: c_int,
        data: *mut c_void,
    ) -> *mut NumericsMatrix;
    fn NM_fill(
        m: *mut NumericsMatrix,
        storage: c_int,
        size0: c_int,
        size1: c_int,
        data: *mut c_void,
    );
    fn NM_new_SBM(
        size0: c_int,
        size1: c_int,
        m1: *mut SparseBlockStructuredMatrix,
    ) -> *mut NumericsMatrix;
    fn NM_clear(m: *mut NumericsMatrix);
    fn NM_free(m: *mut NumericsMatrix) -> *mut NumericsMatrix;
    fn NM_triplet_alloc(a: *mut NumericsMatrix, nzmax: CS_INT);
    fn NM_entry(m: *mut NumericsMatrix, i: c_int, j: c_int, val: c_double);
    fn NM_get_value(m: *const NumericsMatrix, i: c_int, j: c_int) -> c_double;
    fn NM_copy_to_sparse(a: *const NumericsMatrix, b: *mut NumericsMatrix, threshold: c_double);
    fn SBM_new() -> *mut SparseBlockStructuredMatrix;
    fn SBM_clear(m: *mut SparseBlockStructuredMatrix);
    fn SBCM_new_3x3(
        m: c_uint,
        n: c_uint,
        nbblocks: c_uint,
        row: *mut c_uint,
        column: *mut c_uint,
        block: *mut c_double,
    ) -> *mut SparseBlockCoordinateMatrix;
    fn SBCM_free_3x3(mc: *mut SparseBlockCoordinateMatrix);
    fn SBCM_to_SBM(mc: *mut SparseBlockCoordinateMatrix) -> *mut SparseBlockStructuredMatrix;
    fn SBM_free_from_SBCM(m: *mut SparseBlockStructuredMatrix);
    fn solver_options_create(id: c_int) -> *mut SolverOptions;
    fn solver_options_delete(o: *mut SolverOptions);
    fn fc3d_driver(
        p: *mut FrictionContactProblem,
        r: *mut c_double,
        u: *mut c_double,
        o: *mut SolverOptions,
    ) -> c_int;
    fn fc3d_last_error_code() -> c_int;
    fn fc3d_clear_last_error();
    fn calloc(n: usize, size: usize) -> *mut c_void;
    fn free(p: *mut c_void);
}

const NM_DENSE: c_int = 0;
const NM_SPARSE_BLOCK: c_int = 1;
const NM_SPARSE: c_int = 2;
const INTERNAL: c_int = -99;

/// Reads the fuzzer's bytes as a stream of decisions; 0 once they run out.
struct MatrixBytes<'a>(&'a [u8]);

impl MatrixBytes<'_> {
    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn flag(&mut self) -> bool {
        self.byte() & 1 == 1
    }

    /// A length the harness allocates: 0..=max.
    fn len(&mut self, max: usize) -> usize {
        self.byte() as usize % (max + 1)
    }

    fn raw<const N: usize>(&mut self) -> [u8; N] {
        let mut x = [0u8; N];
        x.iter_mut().for_each(|v| *v = self.byte());
        x
    }

    /// An int a hostile host writes: usually small, often at a limit, sometimes anything.
    fn int(&mut self) -> c_int {
        const SPECIAL: [c_int; 12] = [
            c_int::MIN,
            c_int::MIN + 1,
            -1,
            -2,
            -3,
            0,
            1,
            3,
            c_int::MAX,
            c_int::MAX - 1,
            715827883,
            1 << 30,
        ];
        match self.byte() % 8 {
            0 => SPECIAL[self.byte() as usize % SPECIAL.len()],
            1 => c_int::from_le_bytes(self.raw()),
            _ => (self.byte() % 14) as c_int - 2,
        }
    }

    fn cs_int(&mut self) -> CS_INT {
        const SPECIAL: [CS_INT; 12] = [
            CS_INT::MIN,
            CS_INT::MIN + 1,
            -1,
            -2,
            -3,
            0,
            CS_INT::MAX,
            CS_INT::MAX / 2 + 1,
            1 << 62,
            c_int::MAX as CS_INT,
            c_int::MAX as CS_INT + 1,
            c_int::MIN as CS_INT,
        ];
        match self.byte() % 8 {
            0 => SPECIAL[self.byte() as usize % SPECIAL.len()],
            1 => CS_INT::from_le_bytes(self.raw()),
            _ => (self.byte() % 14) as CS_INT - 2,
        }
    }

    fn uint(&mut self) -> c_uint {
        const SPECIAL: [c_uint; 9] = [
            0,
            1,
            2,
            3,
            c_uint::MAX,
            c_uint::MAX - 1,
            0x8000_0000,
            0x5555_5556,
            715827883,
        ];
        match self.byte() % 8 {
            0 => SPECIAL[self.byte() as usize % SPECIAL.len()],
            1 => c_uint::from_le_bytes(self.raw()),
            _ => (self.byte() % 12) as c_uint,
        }
    }

    /// A block count for SBCM_new_3x3: small, or too large for 3 * count to be a C int (never
    /// the hundreds of millions in between, which are valid and cost gigabytes).
    fn block_count(&mut self) -> c_uint {
        match self.byte() % 4 {
            0 => [c_uint::MAX, 0x8000_0000, 0x5555_5556, 715827883][self.byte() as usize % 4],
            1 => c_uint::from_le_bytes(self.raw()) | 0x8000_0000,
            _ => (self.byte() % 12) as c_uint,
        }
    }

    fn size(&mut self) -> usize {
        const SPECIAL: [usize; 7] = [
            0,
            1,
            usize::MAX,
            usize::MAX - 1,
            1 << 63,
            (1 << 61) + 1,
            u32::MAX as usize + 1,
        ];
        match self.byte() % 8 {
            0 => SPECIAL[self.byte() as usize % SPECIAL.len()],
            1 => usize::from_le_bytes(self.raw()),
            _ => (self.byte() % 12) as usize,
        }
    }

    /// A size fc3d may allocate: small, negative, or so large that no allocator gives it (never
    /// the gigabytes in between, which a real allocator would hand out and a fuzzer call an
    /// out-of-memory crash).
    fn alloc_size(&mut self) -> CS_INT {
        match self.byte() % 6 {
            // 2^58 elements: 2^61 bytes, within isize::MAX but beyond any address space (57 bits).
            0 => [
                CS_INT::MIN,
                -1,
                CS_INT::MAX,
                1 << 62,
                1 << 58,
                (CS_INT::MAX / 8) + 1,
            ][self.byte() as usize % 6],
            _ => (self.byte() % 40) as CS_INT - 2,
        }
    }

    fn value(&mut self) -> f64 {
        match self.byte() % 16 {
            0 => [
                0.0,
                -0.0,
                f64::NAN,
                f64::INFINITY,
                -f64::INFINITY,
                1e300,
                -1e300,
                5e-324,
            ][self.byte() as usize % 8],
            1 => f64::from_le_bytes(self.raw()),
            _ => (self.byte() as f64 - 128.0) / 16.0,
        }
    }
}

/// A zeroed C array of `n` T (NULL when `n` is 0 and the bytes say so).
unsafe fn c_array<T>(n: usize) -> *mut T {
    calloc(n.max(1), std::mem::size_of::<T>()) as *mut T
}

unsafe fn c_fill<T: Copy>(n: usize, mut f: impl FnMut() -> T) -> *mut T {
    let p = c_array::<T>(n);
    for k in 0..n {
        *p.add(k) = f();
    }
    p
}

/// Runs `f`, asserting that it did not report a caught panic; returns the error code (0: none).
unsafe fn checked(what: &str, f: impl FnOnce()) -> c_int {
    fc3d_clear_last_error();
    f();
    let code = fc3d_last_error_code();
    assert_ne!(code, INTERNAL, "{what}: internal error");
    assert!(code <= 0, "{what}: error code {code}");
    code
}

/// What the harness allocated for a host matrix, to free it when fc3d does not.
struct HostSbm {
    /// Length of the block pointer array as allocated (fc3d may only trust `nbblocks` up to it).
    block_len: usize,
}

/// Snapshot of the fields of a matrix (pointers and numbers), to check that a failed call
/// changed nothing.
#[derive(PartialEq, Debug, Clone)]
struct Snapshot(Vec<u64>);

unsafe fn cs_snapshot(v: &mut Vec<u64>, c: *const CSparseMatrix) {
    v.push(c as u64);
    if let Some(c) = c.as_ref() {
        v.extend([
            c.nzmax as u64,
            c.m as u64,
            c.n as u64,
            c.p as u64,
            c.i as u64,
            c.x as u64,
            c.nz as u64,
        ]);
        // The entries a triplet holds (a failed NM_entry must not have written one).
        if c.nz > 0
            && c.nz <= c.nzmax
            && c.nz <= 64
            && !c.p.is_null()
            && !c.i.is_null()
            && !c.x.is_null()
        {
            for k in 0..c.nz as usize {
                v.extend([
                    *c.p.add(k) as u64,
                    *c.i.add(k) as u64,
                    (*c.x.add(k)).to_bits(),
                ]);
            }
        }
    }
}

unsafe fn snapshot(m: *const NumericsMatrix) -> Snapshot {
    let mut v = vec![m as u64];
    if let Some(m) = m.as_ref() {
        v.extend([m.storageType as u64, m.size0 as u64, m.size1 as u64]);
        v.extend([
            m.matrix0 as u64,
            m.matrix1 as u64,
            m.matrix2 as u64,
            m.internalData as u64,
        ]);
        if let Some(s) = m.matrix1.as_ref() {
            v.extend([
                s.nbblocks as u64,
                s.block as u64,
                s.blocknumber0 as u64,
                s.blocknumber1 as u64,
            ]);
            v.extend([
                s.blocksize0 as u64,
                s.blocksize1 as u64,
                s.filled1 as u64,
                s.filled2 as u64,
            ]);
            v.extend([
                s.index1_data as u64,
                s.index2_data as u64,
                s.diagonal_blocks as u64,
            ]);
        }
        if let Some(s) = m.matrix2.as_ref() {
            v.extend([
                s.origin as u64,
                s.diag_indx as u64,
                s.linearSolverParams as u64,
            ]);
            for c in [s.triplet, s.half_triplet, s.csc, s.trans_csc, s.csr] {
                cs_snapshot(&mut v, c);
            }
        }
    }
    Snapshot(v)
}

/// Builds a CSparse matrix: `p` as long as its longest use (nzmax column indices of a triplet,
/// n + 1 or m + 1 pointers of a compressed form), `i` and `x` nzmax long; values arbitrary.
unsafe fn build_cs(b: &mut MatrixBytes, rows: c_int, cols: c_int) -> *mut CSparseMatrix {
    let cs = c_array::<CSparseMatrix>(1);
    let small = |v: c_int| v.clamp(0, 12) as usize;
    // m, n: usually the NumericsMatrix's sizes (so that the rest gets checked), else anything
    // small (the pointer array is allocated for them).
    let (m, n) = if !b.byte().is_multiple_of(4) {
        (small(rows), small(cols))
    } else {
        (b.len(12), b.len(12))
    };
    let nzmax = b.len(24);
    let p_len = nzmax.max(m + 1).max(n + 1);
    let kind = b.byte() % 4;
    let nz: CS_INT = match kind {
        0 => -1,
        1 => -2,
        2 => b.len(nzmax) as CS_INT,
        _ => b.cs_int(),
    };
    // Pointers: usually a valid cumulative array, sometimes arbitrary.
    let hostile_ptr = b.byte().is_multiple_of(4);
    let mut acc: CS_INT = 0;
    let outer = if nz == -2 { m } else { n };
    let mut k = 0usize;
    let p = c_fill(p_len, || {
        let v = if nz >= 0 {
            b.len(n + 2) as CS_INT - if b.byte().is_multiple_of(16) { 3 } else { 0 }
        } else if hostile_ptr {
            b.cs_int()
        } else if k == 0 {
            0
        } else if k <= outer {
            acc = (acc + b.len(4) as CS_INT)
                .min(nzmax as CS_INT + (b.byte().is_multiple_of(8)) as CS_INT);
            acc
        } else {
            b.cs_int()
        };
        k += 1;
        v
    });
    let idx_max = if nz == -2 { n } else { m };
    let i = c_fill(nzmax, || {
        if b.byte().is_multiple_of(8) {
            b.cs_int()
        } else {
            b.len(idx_max.max(1)) as CS_INT
        }
    });
    let x = c_fill(nzmax, || b.value());
    let null = b.byte();
    *cs = CSparseMatrix {
        nzmax: if b.byte().is_multiple_of(8) {
            b.cs_int()
        } else {
            nzmax as CS_INT
        },
        // m and n declare how many pointers p holds: the real ones, or negative.
        m: if b.byte().is_multiple_of(8) {
            -(b.cs_int().unsigned_abs() as CS_INT).max(1)
        } else {
            m as CS_INT
        },
        n: if b.byte().is_multiple_of(8) {
            CS_INT::MIN + b.byte() as CS_INT
        } else {
            n as CS_INT
        },
        p,
        i,
        x,
        nz,
    };
    // A NULL array is a host's mistake fc3d must see (the harness frees what it allocated).
    let c = &mut *cs;
    if null & 0x10 != 0 {
        free(c.p.cast());
        c.p = std::ptr::null_mut();
    }
    if null & 0x20 != 0 {
        free(c.i.cast());
        c.i = std::ptr::null_mut();
    }
    if null & 0x40 != 0 {
        free(c.x.cast());
        c.x = std::ptr::null_mut();
    }
    // A declared nzmax above the real arrays is a lie fc3d cannot see: keep it only where no
    // array is read with it (a compressed form reads i, x up to p[n] <= nzmax).
    if c.nzmax > nzmax as CS_INT {
        c.nzmax = nzmax as CS_INT;
    }
    cs
}

unsafe fn build_nsm(b: &mut MatrixBytes, rows: c_int, cols: c_int) -> *mut NumericsSparseMatrix {
    let s = c_array::<NumericsSparseMatrix>(1);
    let which = b.byte();
    if which & 1 != 0 {
        (*s).triplet = build_cs(b, rows, cols);
    }
    if which & 2 != 0 {
        (*s).csc = build_cs(b, rows, cols);
    }
    if which & 4 != 0 {
        (*s).csr = build_cs(b, rows, cols);
    }
    if which & 8 != 0 {
        (*s).half_triplet = build_cs(b, rows, cols);
    }
    (*s).origin = if which & 0x30 == 0x30 {
        b.int()
    } else {
        (b.byte() % 5) as c_int
    };
    s
}

/// A sparse-block matrix with arrays as long as their declared lengths, each block as large as
/// the largest block the cumulative sizes can describe (so any block a lookup picks is readable),
/// and everything else arbitrary.
unsafe fn build_sbm(b: &mut MatrixBytes, host: &mut HostSbm) -> *mut SparseBlockStructuredMatrix {
    let s = c_array::<SparseBlockStructuredMatrix>(1);
    let nbr = b.len(5);
    let nbc = b.len(5);
    let regular = b.flag();
    let sizes = |b: &mut MatrixBytes, len: usize| -> *mut c_uint {
        let mut cum = 0u32;
        let p = c_array::<c_uint>(len);
        for k in 0..len {
            *p.add(k) = if regular {
                3 * (k as c_uint + 1)
            } else if b.byte().is_multiple_of(4) {
                b.len(16) as c_uint
            } else {
                cum += b.len(4) as c_uint;
                cum.min(16)
            };
        }
        p
    };
    let bs0 = sizes(b, nbr);
    let bs1 = sizes(b, nbc);
    let nb = b.len(8);
    let filled1 = if !b.byte().is_multiple_of(4) {
        nbr + 1
    } else {
        b.len(7)
    };
    let mut acc = 0usize;
    let hostile_ptr = b.byte().is_multiple_of(4);
    let index1 = c_fill(filled1, || {
        if hostile_ptr {
            b.size()
        } else {
            let v = acc;
            acc = (acc + b.len(3)).min(nb + (b.byte().is_multiple_of(8)) as usize);
            v
        }
    });
    let filled2 = if !b.byte().is_multiple_of(4) {
        nb
    } else {
        b.len(8)
    };
    let index2 = c_fill(filled2, || {
        if b.byte().is_multiple_of(8) {
            b.size()
        } else {
            b.len(nbc)
        }
    });
    // The block array: as long as filled2 and nbblocks both say, so that a reader trusting either
    // stays inside it; blocks of 16x16 doubles (the largest the cumulative sizes above describe).
    // Pointers past nbblocks stay NULL (fc3d frees nbblocks blocks: the count stays exact).
    let block_len = nb.max(filled2);
    let null_blocks = b.byte();
    let block = c_fill(block_len, std::ptr::null_mut::<c_double>);
    for k in 0..nb {
        if null_blocks & 0x80 == 0 || !b.byte().is_multiple_of(4) {
            *block.add(k) = c_fill(16 * 16, || b.value());
        }
    }
    host.block_len = block_len;
    *s = SparseBlockStructuredMatrix {
        nbblocks: nb as c_uint,
        block,
        blocknumber0: nbr as c_uint,
        blocknumber1: nbc as c_uint,
        blocksize0: bs0,
        blocksize1: bs1,
        filled1,
        filled2,
        index1_data: index1,
        index2_data: index2,
        diagonal_blocks: std::ptr::null_mut(),
        version: Default::default(),
    };
    let c = &mut *s;
    let null = b.byte();
    if null & 0x01 != 0 && null & 0x80 != 0 {
        for k in 0..block_len {
            free((*c.block.add(k)).cast());
        }
        free(c.block.cast());
        c.block = std::ptr::null_mut();
        host.block_len = 0;
    }
    if null & 0x02 != 0 && null & 0x80 != 0 {
        free(c.blocksize0.cast());
        c.blocksize0 = std::ptr::null_mut();
    }
    if null & 0x04 != 0 && null & 0x80 != 0 {
        free(c.index1_data.cast());
        c.index1_data = std::ptr::null_mut();
    }
    if null & 0x08 != 0 && null & 0x80 != 0 {
        free(c.index2_data.cast());
        c.index2_data = std::ptr::null_mut();
    }
    s
}

/// Frees what the harness built for `m` when fc3d did not (its fields as they are now).
unsafe fn host_free(m: *mut NumericsMatrix, host: &HostSbm) {
    let mm = &mut *m;
    free(mm.matrix0.cast());
    if let Some(s) = mm.matrix1.as_mut() {
        if !s.block.is_null() {
            for k in 0..host.block_len {
                free((*s.block.add(k)).cast());
            }
        }
        for p in [
            s.block.cast::<c_void>(),
            s.blocksize0.cast(),
            s.blocksize1.cast(),
        ] {
            free(p);
        }
        for p in [
            s.index1_data.cast::<c_void>(),
            s.index2_data.cast(),
            s.diagonal_blocks.cast(),
        ] {
            free(p);
        }
        free(mm.matrix1.cast());
    }
    if let Some(s) = mm.matrix2.as_mut() {
        for c in [s.triplet, s.half_triplet, s.csc, s.trans_csc, s.csr] {
            if let Some(cs) = c.as_mut() {
                free(cs.p.cast());
                free(cs.i.cast());
                free(cs.x.cast());
                free(c.cast());
            }
        }
        free(s.diag_indx.cast());
        free(mm.matrix2.cast());
    }
    free(m.cast());
}

/// Entries (i, j) to try: in range, at the edges, and anything.
fn probe(b: &mut MatrixBytes, m: &NumericsMatrix) -> (c_int, c_int) {
    let pick = |b: &mut MatrixBytes, size: c_int| -> c_int {
        match b.byte() % 4 {
            0 => b.int(),
            1 => size,
            _ if size > 0 => (b.byte() as c_int) % size.min(64),
            _ => 0,
        }
    };
    (pick(b, m.size0), pick(b, m.size1))
}

/// Every entry of `a` that can be read equals the same entry of `b`.
unsafe fn same_values(a: *const NumericsMatrix, b: *const NumericsMatrix, what: &str) {
    let (r, c) = ((*a).size0.clamp(0, 16), (*a).size1.clamp(0, 16));
    for i in 0..r {
        for j in 0..c {
            let mut va = 0.0;
            let mut vb = 0.0;
            if checked("NM_get_value", || va = NM_get_value(a, i, j)) == 0 {
                let code = checked("NM_get_value", || vb = NM_get_value(b, i, j));
                assert_eq!(code, 0, "{what}: ({i}, {j}) unreadable in the copy");
                assert!(
                    va == vb || (va - vb).abs() <= 1e-12 * va.abs().max(vb.abs()),
                    "{what}: ({i}, {j}) is {va} but {vb} in the copy"
                );
            }
        }
    }
}

/// `fc3d_driver` on FC(M, q, mu): never an internal error; outputs untouched on rejection.
unsafe fn drive(b: &mut MatrixBytes, m: *mut NumericsMatrix) {
    let nc = if b.byte().is_multiple_of(8) {
        b.int()
    } else {
        (*m).size0 / 3
    };
    let n = if (0..=16).contains(&nc) {
        3 * nc as usize
    } else {
        0
    };
    if n == 0 && nc > 0 && 3 * nc as i64 == (*m).size0 as i64 && (*m).size0 == (*m).size1 {
        // Millions of contacts without q: valid sizes whose W the driver may convert (gigabytes)
        // before it sees that q is missing.
        return;
    }
    let mut q: Vec<f64> = (0..n).map(|_| b.value()).collect();
    let mut mu: Vec<f64> = (0..n / 3).map(|_| (b.byte() % 10) as f64 / 10.0).collect();
    let mut r = vec![7.25; n];
    let mut u = vec![7.25; n];
    let mut p = FrictionContactProblem {
        dimension: 3,
        numberOfContacts: nc,
        M: m,
        q: if n > 0 {
            q.as_mut_ptr()
        } else {
            std::ptr::null_mut()
        },
        mu: if n > 0 {
            mu.as_mut_ptr()
        } else {
            std::ptr::null_mut()
        },
    };
    let o = solver_options_create(500);
    assert!(!o.is_null());
    *(*o).iparam = 20;
    *(*o).dparam.add(fc3d::FC3D_DPARAM_TIME_BUDGET as usize) = 0.002;
    *(*o).iparam.add(1) = -12345;
    *(*o).dparam.add(1) = -12345.0;
    let before = snapshot(m);
    let rp = if n > 0 {
        r.as_mut_ptr()
    } else {
        std::ptr::null_mut()
    };
    let up = if n > 0 {
        u.as_mut_ptr()
    } else {
        std::ptr::null_mut()
    };
    let mut rc = 0;
    checked("fc3d_driver", || rc = fc3d_driver(&mut p, rp, up, o));
    // (The positive codes, solver outcomes, are the driver target's business.)
    assert_ne!(rc, INTERNAL, "fc3d_driver: internal error");
    assert_eq!(before, snapshot(m), "fc3d_driver changed the matrix");
    if rc < 0 {
        assert!(
            r.iter().chain(&u).all(|&v| v == 7.25),
            "outputs written on failure"
        );
        assert_eq!(*(*o).iparam.add(1), -12345);
        assert_eq!(*(*o).dparam.add(1), -12345.0);
    } else {
        assert!(
            r.iter().chain(&u).all(|v| v.is_finite()),
            "non-finite output"
        );
    }
    solver_options_delete(o);
    free(o.cast());
}

/// The operations on one host matrix `m` (which the harness owns until `NM_free` succeeds).
unsafe fn operate(b: &mut MatrixBytes, m: *mut NumericsMatrix) {
    for _ in 0..(1 + b.byte() % 6) {
        match b.byte() % 8 {
            0 | 1 => {
                let (i, j) = probe(b, &*m);
                let before = snapshot(m);
                let mut v = 0.0;
                let code = checked("NM_get_value", || v = NM_get_value(m, i, j));
                assert_eq!(before, snapshot(m), "NM_get_value changed the matrix");
                if code == 0 && (*m).storageType == NM_DENSE {
                    let d = *(*m)
                        .matrix0
                        .add(i as usize + j as usize * (*m).size0 as usize);
                    assert!(
                        v.to_bits() == d.to_bits(),
                        "NM_get_value({i}, {j}) = {v}, stored {d}"
                    );
                }
            }
            2 | 3 => {
                let (i, j) = probe(b, &*m);
                let val = b.value();
                let mut old = 0.0;
                let readable = checked("NM_get_value", || old = NM_get_value(m, i, j)) == 0;
                let before = snapshot(m);
                let code = checked("NM_entry", || NM_entry(m, i, j, val));
                if code != 0 {
                    assert_eq!(
                        before,
                        snapshot(m),
                        "NM_entry failed ({code}) but changed the matrix"
                    );
                } else if readable && val.is_finite() && old.is_finite() {
                    // Dense: overwritten; triplet: appended, summed with what was there.
                    let mut now = 0.0;
                    if checked("NM_get_value", || now = NM_get_value(m, i, j)) == 0 {
                        let want = if (*m).storageType == NM_DENSE {
                            val
                        } else {
                            old + val
                        };
                        assert!(
                            now == want || (now - want).abs() <= 1e-12 * now.abs().max(want.abs()),
                            "NM_entry({i}, {j}, {val}) then NM_get_value = {now}, expected {want}"
                        );
                    }
                }
            }
            4 => {
                let into = NM_new();
                let threshold = if b.flag() { -1.0 } else { b.value() };
                let code = checked("NM_copy_to_sparse", || {
                    NM_copy_to_sparse(m, into, threshold)
                });
                if code == 0 && threshold < 0.0 {
                    same_values(m, into, "NM_copy_to_sparse");
                }
                assert_eq!(
                    checked("NM_free", || {
                        NM_free(into);
                    }),
                    0
                );
            }
            5 => drive(b, m),
            6 => {
                let nzmax = b.alloc_size();
                let before = snapshot(m);
                let code = checked("NM_triplet_alloc", || NM_triplet_alloc(m, nzmax));
                if code != 0 {
                    assert_eq!(
                        before,
                        snapshot(m),
                        "NM_triplet_alloc failed but changed the matrix"
                    );
                }
            }
            _ => {
                // Aliasing: A and B the same matrix (its storage replaced by its own copy).
                let before = snapshot(m);
                let code = checked("NM_copy_to_sparse", || NM_copy_to_sparse(m, m, -1.0));
                if code != 0 {
                    assert_eq!(
                        before,
                        snapshot(m),
                        "NM_copy_to_sparse failed but changed B"
                    );
                }
            }
        }
    }
}

/// A host-filled NumericsMatrix of any storage, then the operations, then `NM_free`.
unsafe fn host_matrix_case(b: &mut MatrixBytes) {
    let m = c_array::<NumericsMatrix>(1);
    let mut host = HostSbm { block_len: 0 };
    let storage = match b.byte() % 8 {
        0 => b.int(),
        k => [NM_DENSE, NM_SPARSE_BLOCK, NM_SPARSE][k as usize % 3],
    };
    let (size0, size1) = if b.byte().is_multiple_of(4) {
        (b.int(), b.int())
    } else {
        (b.len(12) as c_int, b.len(12) as c_int)
    };
    (*m).storageType = storage;
    (*m).size0 = size0;
    (*m).size1 = size1;
    match storage {
        // matrix0 holds size0 * size1 values when the sizes say so; NULL when they are negative
        // or too large to allocate (a lie about its length is not testable).
        NM_DENSE
            if (0..=12).contains(&size0)
                && (0..=12).contains(&size1)
                && !b.byte().is_multiple_of(8) =>
        {
            (*m).matrix0 = c_fill((size0 * size1) as usize, || b.value());
        }
        NM_SPARSE_BLOCK if !b.byte().is_multiple_of(8) => (*m).matrix1 = build_sbm(b, &mut host),
        NM_SPARSE if !b.byte().is_multiple_of(8) => (*m).matrix2 = build_nsm(b, size0, size1),
        _ => {}
    }
    operate(b, m);
    // The release: after the operations, nbblocks may be made to overstate the block array
    // (fc3d must then refuse to free rather than read past it).
    if let Some(s) = (*m).matrix1.as_mut() {
        if b.byte().is_multiple_of(4) {
            s.nbblocks = b.uint();
        }
        if (s.nbblocks as usize) < host.block_len {
            // fc3d frees nbblocks blocks: the harness keeps the rest.
            for k in s.nbblocks as usize..host.block_len {
                if !s.block.is_null() {
                    free((*s.block.add(k)).cast());
                    *s.block.add(k) = std::ptr::null_mut();
                }
            }
            host.block_len = s.nbblocks as usize;
        }
    }
    let clear_only = b.flag();
    let code = checked("NM_free", || {
        if clear_only {
            NM_clear(m);
        } else {
            NM_free(m);
        }
    });
    if code != 0 {
        host_free(m, &host);
    } else if clear_only {
        let mm = &*m;
        assert!(
            mm.matrix0.is_null() && mm.matrix1.is_null() && mm.matrix2.is_null(),
            "NM_clear left storage"
        );
        free(m.cast());
    }
}

/// `NM_create`, `NM_create_from_data`, `NM_fill`, `NM_new_SBM`, `NM_null` with arbitrary
/// arguments; what they return is then used and released.
unsafe fn constructors_case(b: &mut MatrixBytes) {
    let storage = if b.flag() {
        b.int()
    } else {
        (b.byte() % 4) as c_int
    };
    let (size0, size1) = match b.byte() % 4 {
        0 => (b.int(), b.int()),
        // Sizes no allocator gives (8 size0 size1 bytes exceed any address space, 2^57).
        1 => (
            [c_int::MAX, 1 << 30][b.byte() as usize % 2],
            [c_int::MAX, 1 << 30][b.byte() as usize % 2],
        ),
        _ => (b.len(9) as c_int, b.len(9) as c_int),
    };
    // Small, refused, or impossible everywhere; never the gigabytes to terabytes that a machine
    // may give (and the matrix would then be walked entry by entry).
    let product = (size0 as i64) * (size1 as i64);
    let allocatable = size0 < 0 || size1 < 0 || product <= 1 << 12 || product >= 1 << 56;
    match b.byte() % 4 {
        0 if allocatable => {
            let mut m = std::ptr::null_mut();
            let code = checked("NM_create", || m = NM_create(storage, size0, size1));
            assert_eq!(code != 0, m.is_null(), "NM_create: NULL exactly on failure");
            if !m.is_null() {
                operate(b, m);
                assert_eq!(
                    checked("NM_free", || {
                        NM_free(m);
                    }),
                    0
                );
            }
        }
        1 => {
            // Data that matches the storage; fc3d owns it once the call succeeds.
            let mut host = HostSbm { block_len: 0 };
            let data: *mut c_void = match storage {
                NM_DENSE if (0..=12).contains(&size0) && (0..=12).contains(&size1) => {
                    c_fill((size0 * size1) as usize, || b.value()).cast()
                }
                NM_SPARSE_BLOCK if b.flag() => build_sbm(b, &mut host).cast(),
                NM_SPARSE_BLOCK => SBM_new().cast(),
                NM_SPARSE => build_nsm(b, size0, size1).cast(),
                _ => std::ptr::null_mut(),
            };
            let mut m = std::ptr::null_mut();
            let code = if storage == NM_SPARSE_BLOCK && b.flag() {
                checked("NM_new_SBM", || m = NM_new_SBM(size0, size1, data.cast()))
            } else {
                checked("NM_create_from_data", || {
                    m = NM_create_from_data(storage, size0, size1, data)
                })
            };
            assert_eq!(code != 0, m.is_null());
            if m.is_null() {
                // Rejected: the data is still the harness's.
                let holder = c_array::<NumericsMatrix>(1);
                (*holder).storageType = storage;
                match storage {
                    NM_DENSE => (*holder).matrix0 = data.cast(),
                    NM_SPARSE_BLOCK => (*holder).matrix1 = data.cast(),
                    NM_SPARSE => (*holder).matrix2 = data.cast(),
                    _ => {}
                }
                host_free(holder, &host);
            } else {
                operate(b, m);
                if checked("NM_free", || {
                    NM_free(m);
                }) != 0
                {
                    host_free(m, &host);
                }
            }
        }
        2 => {
            let m = NM_new();
            let dense =
                (0..=12).contains(&size0) && (0..=12).contains(&size1) && storage == NM_DENSE;
            let data: *mut c_void = if dense {
                c_fill((size0 * size1) as usize, || b.value()).cast()
            } else {
                std::ptr::null_mut()
            };
            let before = snapshot(m);
            let code = checked("NM_fill", || NM_fill(m, storage, size0, size1, data));
            if code != 0 {
                assert_eq!(before, snapshot(m), "NM_fill failed but changed M");
                free(data);
            } else {
                operate(b, m);
            }
            assert_eq!(
                checked("NM_free", || {
                    NM_free(m);
                }),
                0
            );
        }
        _ => {
            let m = NM_new();
            assert_eq!(checked("NM_null", || NM_null(m)), 0);
            operate(b, m);
            assert_eq!(
                checked("NM_free", || {
                    NM_free(m);
                }),
                0
            );
            assert!(checked("NM_null", || NM_null(std::ptr::null_mut())) < 0);
        }
    }
}

/// `SBCM_new_3x3`, `SBCM_to_SBM` (on what it returns, or on a coordinate matrix filled by the
/// host), the sparse-block matrix used and solved, then released.
unsafe fn coordinate_case(b: &mut MatrixBytes) {
    let nb = b.len(6);
    let m = if b.byte().is_multiple_of(4) {
        b.block_count()
    } else {
        b.len(5) as c_uint
    };
    let n = if b.byte().is_multiple_of(4) {
        b.block_count()
    } else {
        b.len(5) as c_uint
    };
    let mut row: Vec<c_uint> = (0..nb)
        .map(|_| {
            if b.byte().is_multiple_of(8) {
                b.uint()
            } else {
                b.len(m.min(6) as usize + 1) as c_uint
            }
        })
        .collect();
    let mut col: Vec<c_uint> = (0..nb)
        .map(|_| {
            if b.byte().is_multiple_of(8) {
                b.uint()
            } else {
                b.len(n.min(6) as usize + 1) as c_uint
            }
        })
        .collect();
    let mut values: Vec<f64> = (0..9 * nb).map(|_| b.value()).collect();
    let nulls = b.byte();
    let rp = if nulls & 1 != 0 && nulls & 0x80 != 0 {
        std::ptr::null_mut()
    } else {
        row.as_mut_ptr()
    };
    let cp = if nulls & 2 != 0 && nulls & 0x80 != 0 {
        std::ptr::null_mut()
    } else {
        col.as_mut_ptr()
    };
    let vp = if nulls & 4 != 0 && nulls & 0x80 != 0 {
        std::ptr::null_mut()
    } else {
        values.as_mut_ptr()
    };
    let mut coo = std::ptr::null_mut();
    let code = checked("SBCM_new_3x3", || {
        coo = SBCM_new_3x3(m, n, nb as c_uint, rp, cp, vp)
    });
    assert_eq!(code != 0, coo.is_null());
    // A coordinate matrix filled by the host instead (arrays as long as declared).
    let mut host_coo = None;
    if coo.is_null() || b.byte().is_multiple_of(4) {
        let nbr = b.len(5);
        let nbc = b.len(5);
        // Cumulative sizes of 3x3 blocks (the blocks are 9 doubles), or entries that break the
        // strict increase (a zero, a repeat, a step back) which fc3d must reject.
        let sizes = |b: &mut MatrixBytes, len: usize| -> Vec<c_uint> {
            let mut v: Vec<c_uint> = Vec::new();
            for k in 0..len {
                let prev = v.last().copied().unwrap_or(0);
                v.push(match b.byte() % 8 {
                    0 => 0,
                    1 => prev,
                    2 => prev.saturating_sub(1 + b.len(3) as c_uint),
                    _ => 3 * (k as c_uint + 1),
                });
            }
            v
        };
        let mut bs0 = sizes(b, nbr);
        let mut bs1 = sizes(b, nbc);
        let mut ptrs: Vec<*mut c_double> = (0..nb)
            .map(|k| {
                if b.byte().is_multiple_of(8) {
                    std::ptr::null_mut()
                } else {
                    values.as_mut_ptr().add(9 * k)
                }
            })
            .collect();
        let mc = Box::new(SparseBlockCoordinateMatrix {
            nbblocks: nb as c_uint,
            blocknumber0: nbr as c_uint,
            blocknumber1: nbc as c_uint,
            block: ptrs.as_mut_ptr(),
            blocksize0: if b.byte().is_multiple_of(8) {
                std::ptr::null_mut()
            } else {
                bs0.as_mut_ptr()
            },
            blocksize1: bs1.as_mut_ptr(),
            row: rp,
            column: cp,
        });
        host_coo = Some((mc, bs0, bs1, ptrs));
    }
    let source = match &mut host_coo {
        Some((mc, ..)) => &mut **mc as *mut SparseBlockCoordinateMatrix,
        None => coo,
    };
    let mut sbm = std::ptr::null_mut();
    let code = checked("SBCM_to_SBM", || sbm = SBCM_to_SBM(source));
    assert_eq!(code != 0, sbm.is_null());
    if !sbm.is_null() {
        let size = |k: c_uint, bs: *const c_uint| {
            if k == 0 {
                0
            } else {
                *bs.add(k as usize - 1) as c_int
            }
        };
        let (s0, s1) = if b.flag() {
            (
                size((*sbm).blocknumber0, (*sbm).blocksize0),
                size((*sbm).blocknumber1, (*sbm).blocksize1),
            )
        } else {
            (b.int(), b.int())
        };
        let mut mat = std::ptr::null_mut();
        checked("NM_new_SBM", || mat = NM_new_SBM(s0, s1, sbm));
        if !mat.is_null() {
            // Read only: the blocks belong to the coordinate matrix.
            for _ in 0..(b.byte() % 4) {
                let (i, j) = probe(b, &*mat);
                checked("NM_get_value", || {
                    NM_get_value(mat, i, j);
                });
            }
            if b.flag() {
                drive(b, mat);
            }
            let into = NM_new();
            let code = checked("NM_copy_to_sparse", || NM_copy_to_sparse(mat, into, -1.0));
            if code == 0 {
                same_values(mat, into, "NM_copy_to_sparse of an SBM");
            }
            NM_free(into);
            (*mat).matrix1 = std::ptr::null_mut();
            assert_eq!(
                checked("NM_free", || {
                    NM_free(mat);
                }),
                0
            );
        }
        assert_eq!(checked("SBM_free_from_SBCM", || SBM_free_from_SBCM(sbm)), 0);
    }
    assert_eq!(checked("SBCM_free_3x3", || SBCM_free_3x3(coo)), 0);
    // As in Siconos, SBCM_free_3x3 frees the arrays, not the struct.
    free(coo.cast());
    drop(host_coo);
    // An empty sparse-block structure, cleared twice.
    let s = SBM_new();
    assert!(!s.is_null());
    assert_eq!(checked("SBM_clear", || SBM_clear(s)), 0);
    assert_eq!(checked("SBM_clear", || SBM_clear(s)), 0);
    free(s.cast());
    // A host SBM cleared with an overstated block count: refused, or freed exactly.
    let mut host = HostSbm { block_len: 0 };
    let s = build_sbm(b, &mut host);
    if b.flag() {
        (*s).nbblocks = b.uint();
    }
    if ((*s).nbblocks as usize) < host.block_len && !(*s).block.is_null() {
        for k in (*s).nbblocks as usize..host.block_len {
            free((*(*s).block.add(k)).cast());
            *(*s).block.add(k) = std::ptr::null_mut();
        }
    }
    if checked("SBM_clear", || SBM_clear(s)) != 0 {
        let holder = c_array::<NumericsMatrix>(1);
        (*holder).matrix1 = s;
        host_free(holder, &host);
    } else {
        free(s.cast());
    }
}

/// Runs one input; panics (assert) on any broken promise.
pub fn run_matrix_case(data: &[u8]) {
    let mut b = MatrixBytes(data);
    unsafe {
        match b.byte() % 4 {
            0 | 1 => host_matrix_case(&mut b),
            2 => constructors_case(&mut b),
            _ => coordinate_case(&mut b),
        }
    }
}
