//! The exported matrix helpers against a hostile host (issue 13, item 4): `NM_*`, `SBM_*`,
//! `SBCM_*` and the conversions `fc3d_driver` makes, called through the C ABI with structs whose
//! numbers are arbitrary (INT_MIN..INT_MAX, negative counts, NULL arrays, counts that disagree,
//! index arrays pointing anywhere). Each must return a clean negative code (or NULL, or NaN) with
//! a message, change nothing when it fails, and never read or write outside the memory the struct
//! declares.
//!
//! How "outside" is caught without a sanitizer: read-only host arrays live in `Guarded` memory,
//! which ends exactly at an inaccessible page (one element too far is a fault, not a silent read
//! of a neighbour), and the tests that could abort or fault before the fix, or allocate without
//! bound, run in a child process under a 2 GiB address-space limit (`isolated`). Under the address
//! sanitizer the same promises are checked by the fuzz target `matrix_helpers`
//! (`cd fuzz && cargo +nightly fuzz run matrix_helpers`), whose case runner is included here:
//! the property `random_inputs_keep_the_promises` feeds it random bytes, and every input the
//! fuzzer ever failed on (fuzz/regressions/matrix_helpers/) is replayed.

#![allow(clippy::missing_safety_doc)]

include!("../../fuzz/fuzz_targets/matrix_case.rs");

use std::process::Command;

use fc3d::types::NumericsDataVersion;
use fc3d::{FC3D_ERR_INVALID_SIZE, FC3D_ERR_INVALID_STORAGE, FC3D_ERR_NULL_POINTER};
use fc3d::{FC3D_ERR_OUT_OF_MEMORY, FC3D_OK};
use proptest::prelude::*;

const NSM_TRIPLET: c_int = 1;
const NSM_CSC: c_int = 2;
const NSM_CSR: c_int = 3;

// ---------------------------------------------------------------------------------------------
// Test machinery.

/// `values` in memory that ends exactly at an inaccessible page: touching one element past the
/// end faults. An empty array points at the inaccessible page itself.
struct Guarded<T> {
    base: *mut c_void,
    total: usize,
    ptr: *mut T,
    len: usize,
}

impl<T: Copy> Guarded<T> {
    fn new(values: &[T]) -> Self {
        unsafe {
            let page = libc::sysconf(libc::_SC_PAGESIZE) as usize;
            let bytes = std::mem::size_of_val(values);
            let data_pages = bytes.div_ceil(page);
            let total = (data_pages + 1) * page;
            let base = libc::mmap(
                std::ptr::null_mut(),
                total,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            );
            assert_ne!(base, libc::MAP_FAILED);
            let guard = (base as *mut u8).add(data_pages * page);
            assert_eq!(libc::mprotect(guard.cast(), page, libc::PROT_NONE), 0);
            let ptr = guard.sub(bytes) as *mut T;
            std::ptr::copy_nonoverlapping(values.as_ptr(), ptr, values.len());
            Guarded {
                base,
                total,
                ptr,
                len: values.len(),
            }
        }
    }

    fn ptr(&self) -> *mut T {
        self.ptr
    }

    fn to_vec(&self) -> Vec<T> {
        unsafe { std::slice::from_raw_parts(self.ptr, self.len).to_vec() }
    }
}

impl<T> Drop for Guarded<T> {
    fn drop(&mut self) {
        unsafe { libc::munmap(self.base, self.total) };
    }
}

/// Runs the calling test's body in a child process under a 2 GiB address-space limit, so that
/// what the unfixed library did (an abort, a fault, an allocation of tens of gigabytes) fails
/// this one test with its cause instead of killing or swapping the whole run. Returns `true` in
/// the parent (which has checked the child's exit) and `false` in the child (run the body).
fn isolated(name: &str) -> bool {
    if std::env::var_os("FC3D_HOSTILE_CHILD").is_some() {
        return false;
    }
    use std::os::unix::process::CommandExt;
    let mut cmd = Command::new(std::env::current_exe().unwrap());
    cmd.args([name, "--exact", "--nocapture", "--test-threads=1"])
        .env("FC3D_HOSTILE_CHILD", "1");
    unsafe {
        cmd.pre_exec(|| {
            let limit = libc::rlimit {
                rlim_cur: 2 << 30,
                rlim_max: 2 << 30,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let out = cmd.output().expect("cannot run the test binary");
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && text.contains("1 passed"),
        "{name} failed in its child process ({}):\n{text}",
        out.status
    );
    true
}

/// The error code a call leaves (0 when it succeeded).
unsafe fn code_of(f: impl FnOnce()) -> c_int {
    fc3d_clear_last_error();
    f();
    fc3d_last_error_code()
}

fn message() -> String {
    extern "C" {
        fn fc3d_last_error_message() -> *const std::ffi::c_char;
    }
    unsafe { std::ffi::CStr::from_ptr(fc3d_last_error_message()) }
        .to_string_lossy()
        .into_owned()
}

/// `a` on the heap for the rest of the test; the host changes it through the pointer only.
fn raw<T: Copy, const N: usize>(a: [T; N]) -> *mut T {
    Box::leak(Box::new(a)).as_mut_ptr()
}

/// `v` on the heap for the rest of the test, changed through the pointer only.
fn boxed<T>(v: T) -> *mut T {
    Box::into_raw(Box::new(v))
}

/// An all-NULL matrix of the given storage and sizes.
fn matrix(storage: c_int, size0: c_int, size1: c_int) -> NumericsMatrix {
    let mut m: NumericsMatrix = unsafe { std::mem::zeroed() };
    m.storageType = storage;
    m.size0 = size0;
    m.size1 = size1;
    m
}

fn empty_nsm() -> NumericsSparseMatrix {
    unsafe { std::mem::zeroed() }
}

/// A sparse-block structure over host arrays.
#[allow(clippy::too_many_arguments)]
fn sbm(
    nbblocks: c_uint,
    block: *mut *mut c_double,
    bs0: &Guarded<c_uint>,
    bs1: &Guarded<c_uint>,
    index1: &Guarded<usize>,
    index2: &Guarded<usize>,
) -> SparseBlockStructuredMatrix {
    SparseBlockStructuredMatrix {
        nbblocks,
        block,
        blocknumber0: bs0.len as c_uint,
        blocknumber1: bs1.len as c_uint,
        blocksize0: bs0.ptr(),
        blocksize1: bs1.ptr(),
        filled1: index1.len,
        filled2: index2.len,
        index1_data: index1.ptr(),
        index2_data: index2.ptr(),
        diagonal_blocks: std::ptr::null_mut(),
        version: NumericsDataVersion::default(),
    }
}

fn block9(scale: f64) -> Guarded<f64> {
    Guarded::new(&[scale, 0.0, 0.0, 0.0, scale, 0.0, 0.0, 0.0, scale])
}

/// `NM_get_value(m, i, j)` and the code it left.
unsafe fn get(m: *const NumericsMatrix, i: c_int, j: c_int) -> (f64, c_int) {
    let mut v = 0.0;
    let code = code_of(|| v = NM_get_value(m, i, j));
    (v, code)
}

/// A CSparse matrix over guarded arrays.
struct HostCs {
    p: Guarded<CS_INT>,
    i: Guarded<CS_INT>,
    x: Guarded<f64>,
    cs: CSparseMatrix,
}

impl HostCs {
    fn new(
        m: CS_INT,
        n: CS_INT,
        nz: CS_INT,
        nzmax: CS_INT,
        p: &[CS_INT],
        i: &[CS_INT],
        x: &[f64],
    ) -> Box<Self> {
        let (p, i, x) = (Guarded::new(p), Guarded::new(i), Guarded::new(x));
        let cs = CSparseMatrix {
            nzmax,
            m,
            n,
            p: p.ptr(),
            i: i.ptr(),
            x: x.ptr(),
            nz,
        };
        Box::new(HostCs { p, i, x, cs })
    }
}

// ---------------------------------------------------------------------------------------------
// NM_get_value on sparse-block storage.

/// Before: a NULL block pointer (or a NULL block array) where the index arrays say a block is
/// was dereferenced (SIGSEGV).
#[test]
fn get_value_rejects_null_blocks() {
    if isolated("get_value_rejects_null_blocks") {
        return;
    }
    let (bs0, bs1) = (Guarded::new(&[3u32]), Guarded::new(&[3u32]));
    let (index1, index2) = (Guarded::new(&[0usize, 1]), Guarded::new(&[0usize]));
    let blocks = Guarded::new(&[std::ptr::null_mut::<c_double>()]);
    let s = boxed(sbm(1, blocks.ptr(), &bs0, &bs1, &index1, &index2));
    let mut m = matrix(NM_SPARSE_BLOCK, 3, 3);
    m.matrix1 = s;
    unsafe {
        let (v, code) = get(&m, 0, 0);
        assert!(v.is_nan());
        assert_eq!(code, FC3D_ERR_NULL_POINTER, "{}", message());
        (*s).block = std::ptr::null_mut();
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_NULL_POINTER, "{}", message());
    }
}

/// Before: block-row pointers read past `filled1` and block indices past `filled2` were slice
/// index panics (FC3D_ERR_INTERNAL); `filled2` > `nbblocks` read the block array past its end.
#[test]
fn get_value_checks_block_counts() {
    if isolated("get_value_checks_block_counts") {
        return;
    }
    let (bs0, bs1) = (Guarded::new(&[3u32]), Guarded::new(&[3u32]));
    let b0 = block9(1.0);
    let blocks = Guarded::new(&[b0.ptr()]);
    unsafe {
        // filled1 = 1 for one block row: no end pointer.
        let (index1, index2) = (Guarded::new(&[0usize]), Guarded::new(&[0usize]));
        let mut s = sbm(1, blocks.ptr(), &bs0, &bs1, &index1, &index2);
        let mut m = matrix(NM_SPARSE_BLOCK, 3, 3);
        m.matrix1 = &mut s;
        assert_eq!(get(&m, 0, 0).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
        // The row ends past filled2.
        let index1 = Guarded::new(&[0usize, 5]);
        let mut s = sbm(1, blocks.ptr(), &bs0, &bs1, &index1, &index2);
        m.matrix1 = &mut s;
        assert_eq!(get(&m, 0, 0).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
        // filled2 = 2 blocks but nbblocks = 1 (and the block array holds one pointer).
        let (index1, index2) = (Guarded::new(&[0usize, 2]), Guarded::new(&[1usize, 0]));
        let mut s = sbm(1, blocks.ptr(), &bs0, &bs1, &index1, &index2);
        m.matrix1 = &mut s;
        assert_eq!(get(&m, 0, 0).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
        // A block column index past blocknumber1.
        let (index1, index2) = (Guarded::new(&[0usize, 1]), Guarded::new(&[7usize]));
        let mut s = sbm(1, blocks.ptr(), &bs0, &bs1, &index1, &index2);
        m.matrix1 = &mut s;
        assert_eq!(get(&m, 0, 0).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
    }
}

/// Before: cumulative block sizes that do not increase ([3, 0, 6]) made a 3x3 block look 6 rows
/// tall, and the lookup read past its 9 values (SIGSEGV here, garbage otherwise).
#[test]
fn get_value_rejects_non_increasing_block_sizes() {
    if isolated("get_value_rejects_non_increasing_block_sizes") {
        return;
    }
    let (bs0, bs1) = (Guarded::new(&[3u32, 0, 6]), Guarded::new(&[3u32]));
    let b0 = block9(1.0);
    let blocks = Guarded::new(&[b0.ptr()]);
    let (index1, index2) = (Guarded::new(&[0usize, 0, 0, 1]), Guarded::new(&[0usize]));
    let mut s = sbm(1, blocks.ptr(), &bs0, &bs1, &index1, &index2);
    let mut m = matrix(NM_SPARSE_BLOCK, 6, 3);
    m.matrix1 = &mut s;
    unsafe {
        assert_eq!(get(&m, 4, 2).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
    }
}

/// Before: with two blocks stored at the same place, NM_get_value returned the first one while
/// the solver (and NM_copy_to_sparse) sum them: the host read a W that is not the one solved.
#[test]
fn get_value_sums_duplicate_blocks_as_the_solver_does() {
    let (bs0, bs1) = (Guarded::new(&[3u32]), Guarded::new(&[3u32]));
    let (b0, b1) = (block9(1.0), block9(2.0));
    let blocks = Guarded::new(&[b0.ptr(), b1.ptr()]);
    let (index1, index2) = (Guarded::new(&[0usize, 2]), Guarded::new(&[0usize, 0]));
    let mut s = sbm(2, blocks.ptr(), &bs0, &bs1, &index1, &index2);
    let mut m = matrix(NM_SPARSE_BLOCK, 3, 3);
    m.matrix1 = &mut s;
    unsafe {
        assert_eq!(get(&m, 1, 1), (3.0, FC3D_OK));
        let copy = NM_new();
        assert_eq!(code_of(|| NM_copy_to_sparse(&m, copy, 0.0)), FC3D_OK);
        assert_eq!(get(copy, 1, 1), (3.0, FC3D_OK));
        NM_free(copy);
        // And the driver solves with the sum: W = 3 I, q = (-3, 0, 0) gives r = (1, 0, 0).
        let mut q = [-3.0, 0.0, 0.0];
        let mut mu = [0.5];
        let mut p = FrictionContactProblem {
            dimension: 3,
            numberOfContacts: 1,
            M: &mut m,
            q: q.as_mut_ptr(),
            mu: mu.as_mut_ptr(),
        };
        let (mut r, mut u) = ([0.0; 3], [0.0; 3]);
        let o = solver_options_create(500);
        assert_eq!(fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), o), 0);
        assert!((r[0] - 1.0).abs() < 1e-12, "{r:?}");
        solver_options_delete(o);
        free(o.cast());
    }
}

/// An empty sparse-block structure (as NM_create makes it) holds zeros; a structure whose block
/// sizes do not cover the matrix is an error, not a guess.
#[test]
fn get_value_on_empty_and_short_block_structures() {
    unsafe {
        let m = NM_create(NM_SPARSE_BLOCK, 6, 3);
        assert_eq!(get(m, 5, 2), (0.0, FC3D_OK));
        NM_free(m);
    }
    let (bs0, bs1) = (Guarded::new(&[3u32]), Guarded::new(&[3u32]));
    let (index1, index2) = (Guarded::new(&[0usize, 0]), Guarded::<usize>::new(&[]));
    let mut s = sbm(0, std::ptr::null_mut(), &bs0, &bs1, &index1, &index2);
    let mut m = matrix(NM_SPARSE_BLOCK, 6, 3);
    m.matrix1 = &mut s;
    unsafe {
        assert_eq!(get(&m, 1, 1), (0.0, FC3D_OK));
        assert_eq!(get(&m, 4, 1).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
    }
}

// ---------------------------------------------------------------------------------------------
// NM_get_value on dense and sparse storage.

/// Before: every NM_get_value on a dense matrix checked all size0 * size1 values for NaN
/// (quadratic work for a host reading W entry by entry) and failed on a finite entry when
/// another one was NaN. Now it reads the one entry it is asked for, as Siconos does.
#[test]
fn get_value_reads_one_dense_entry() {
    let mut data = [1.0, 2.0, 3.0, 4.0, 5.0, f64::NAN];
    let mut m = matrix(NM_DENSE, 2, 3);
    m.matrix0 = data.as_mut_ptr();
    unsafe {
        assert_eq!(get(&m, 1, 1), (4.0, FC3D_OK));
        let (v, code) = get(&m, 1, 2);
        assert!(v.is_nan() && code == FC3D_OK);
        for (i, j) in [
            (2, 0),
            (0, 3),
            (-1, 0),
            (0, c_int::MIN),
            (c_int::MAX, c_int::MAX),
        ] {
            let (v, code) = get(&m, i, j);
            assert!(v.is_nan() && code == FC3D_ERR_INVALID_SIZE, "({i}, {j})");
        }
        m.matrix0 = std::ptr::null_mut();
        assert_eq!(get(&m, 0, 0).1, FC3D_ERR_NULL_POINTER);
    }
}

/// Before: NM_get_value and NM_copy_to_sparse converted the whole sparse matrix to compressed
/// rows, allocating size0 + 1 row pointers: 16 GiB for a 2^31-row matrix holding one entry (an
/// abort under a memory limit). Now they cost what the matrix holds.
#[test]
fn huge_sparse_matrix_costs_its_entries_only() {
    if isolated("huge_sparse_matrix_costs_its_entries_only") {
        return;
    }
    unsafe {
        let big = c_int::MAX;
        let m = NM_create(NM_SPARSE, big, big);
        assert!(!m.is_null());
        NM_triplet_alloc(m, 4);
        assert_eq!(code_of(|| NM_entry(m, big - 1, 5, 2.5)), FC3D_OK);
        assert_eq!(code_of(|| NM_entry(m, big - 1, 5, 0.5)), FC3D_OK);
        assert_eq!(get(m, big - 1, 5), (3.0, FC3D_OK));
        assert_eq!(get(m, 0, 0), (0.0, FC3D_OK));
        let copy = NM_new();
        assert_eq!(
            code_of(|| NM_copy_to_sparse(m, copy, 0.0)),
            FC3D_OK,
            "{}",
            message()
        );
        assert_eq!(get(copy, big - 1, 5), (3.0, FC3D_OK));
        let t = &*(*(*copy).matrix2).triplet;
        assert_eq!((t.nz, t.m, t.n), (1, big as CS_INT, big as CS_INT));
        NM_free(copy);
        NM_free(m);
    }
}

/// Compressed storage: pointers and indices are checked where they are read; a value is the
/// sum of the entries stored at (i, j), as the solver sees it.
#[test]
fn get_value_on_hostile_compressed_storage() {
    unsafe {
        // 2x3 CSC: (0,0)=1, (1,0)=2, (1,2)=3, (1,2)=4 (duplicate).
        let mut h = HostCs::new(
            2,
            3,
            -1,
            4,
            &[0, 2, 2, 4],
            &[0, 1, 1, 1],
            &[1.0, 2.0, 3.0, 4.0],
        );
        let hc: *mut CSparseMatrix = &mut h.cs;
        let nsm = boxed(empty_nsm());
        (*nsm).csc = hc;
        (*nsm).origin = NSM_CSC;
        let mut m = matrix(NM_SPARSE, 2, 3);
        m.matrix2 = nsm;
        assert_eq!(get(&m, 1, 2), (7.0, FC3D_OK));
        assert_eq!(get(&m, 0, 1), (0.0, FC3D_OK));
        // p[n] beyond nzmax: the arrays are only nzmax long.
        (*hc).nzmax = 3;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
        (*hc).nzmax = 4;
        // A pointer that decreases or is negative: the column that reads it is refused, and so
        // is every conversion of the whole matrix.
        for (k, v) in [(2usize, 1 as CS_INT), (1, -7), (3, 1)] {
            let old = *h.p.ptr().add(k);
            *h.p.ptr().add(k) = v;
            assert_eq!(
                get(&m, 0, k as c_int - 1).1,
                FC3D_ERR_INVALID_STORAGE,
                "p[{k}] = {v}"
            );
            let copy = NM_new();
            assert_eq!(
                code_of(|| NM_copy_to_sparse(&m, copy, 0.0)),
                FC3D_ERR_INVALID_STORAGE
            );
            NM_free(copy);
            *h.p.ptr().add(k) = old;
        }
        *h.i.ptr().add(3) = 2;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
        *h.i.ptr().add(3) = 1;
        // nz must say CSC; the dimensions must be the matrix's.
        (*hc).nz = 0;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_STORAGE);
        (*hc).nz = -1;
        (*hc).n = 4;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_SIZE);
        (*hc).n = 3;
        // Siconos' CSR (n rows, m columns, nz = -2): the same matrix by rows.
        let mut r = HostCs::new(
            3,
            2,
            -2,
            4,
            &[0, 1, 4],
            &[0, 0, 2, 2],
            &[1.0, 2.0, 3.0, 4.0],
        );
        (*nsm).csc = std::ptr::null_mut();
        (*nsm).csr = &mut r.cs;
        (*nsm).origin = NSM_CSR;
        assert_eq!(get(&m, 1, 2), (7.0, FC3D_OK));
        assert_eq!(get(&m, 1, 0), (2.0, FC3D_OK));
        // Triplet: nz beyond nzmax, negative nz, negative indices.
        let mut t = HostCs::new(2, 3, 2, 2, &[2, 2], &[1, 1], &[3.0, 4.0]);
        let tc: *mut CSparseMatrix = &mut t.cs;
        (*nsm).csr = std::ptr::null_mut();
        (*nsm).triplet = tc;
        (*nsm).origin = NSM_TRIPLET;
        assert_eq!(get(&m, 1, 2), (7.0, FC3D_OK));
        (*tc).nz = 3;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_STORAGE);
        (*tc).nz = -3;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_STORAGE);
        (*tc).nz = 2;
        *t.i.ptr() = -1;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_STORAGE);
        (*nsm).origin = 9;
        assert_eq!(get(&m, 1, 2).1, FC3D_ERR_INVALID_STORAGE);
        drop(Box::from_raw(nsm));
        let _ = (h.x.to_vec(), r.x.to_vec(), t.p.to_vec());
    }
}

/// Before: a slice length whose byte size exceeds the address space (a triplet declaring 2^61
/// entries) and a misaligned array pointer reached `slice::from_raw_parts`, whose precondition
/// check aborts the process in debug builds (undefined behaviour in release builds).
#[test]
fn impossible_lengths_and_misaligned_arrays_are_rejected() {
    if isolated("impossible_lengths_and_misaligned_arrays_are_rejected") {
        return;
    }
    unsafe {
        let mut t = HostCs::new(3, 3, 1 << 61, 1 << 61, &[0, 1], &[0, 1], &[1.0, 2.0]);
        let mut nsm = empty_nsm();
        nsm.triplet = &mut t.cs;
        nsm.origin = NSM_TRIPLET;
        let mut m = matrix(NM_SPARSE, 3, 3);
        m.matrix2 = &mut nsm;
        assert_eq!(get(&m, 0, 0).1, FC3D_ERR_INVALID_SIZE, "{}", message());
        let copy = NM_new();
        assert_eq!(
            code_of(|| NM_copy_to_sparse(&m, copy, 0.0)),
            FC3D_ERR_INVALID_SIZE
        );
        NM_free(copy);
        let mut q = [0.0; 3];
        let mut mu = [0.0];
        let mut p = FrictionContactProblem {
            dimension: 3,
            numberOfContacts: 1,
            M: &mut m,
            q: q.as_mut_ptr(),
            mu: mu.as_mut_ptr(),
        };
        let (mut r, mut u) = ([0.0; 3], [0.0; 3]);
        let o = solver_options_create(500);
        assert_eq!(
            fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), o),
            FC3D_ERR_INVALID_SIZE
        );
        // A misaligned array.
        t.cs.nz = 2;
        t.cs.nzmax = 2;
        t.cs.i = (t.i.ptr() as *mut u8).add(1).cast();
        assert_eq!(get(&m, 0, 0).1, FC3D_ERR_INVALID_STORAGE, "{}", message());
        assert_eq!(
            fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), o),
            FC3D_ERR_INVALID_STORAGE
        );
        // A dense matrix whose values are misaligned.
        let data = [0.0f64; 10];
        let mut d = matrix(NM_DENSE, 3, 3);
        d.matrix0 = (data.as_ptr() as *mut u8).add(4).cast();
        p.M = &mut d;
        assert_eq!(
            fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), o),
            FC3D_ERR_INVALID_STORAGE
        );
        solver_options_delete(o);
        free(o.cast());
    }
}

// ---------------------------------------------------------------------------------------------
// NM_entry and NM_triplet_alloc.

/// A triplet over malloc'd arrays (NM_entry may grow them), with any nz and nzmax.
unsafe fn c_triplet(len: usize, nz: CS_INT, nzmax: CS_INT) -> *mut CSparseMatrix {
    let t = c_array::<CSparseMatrix>(1);
    *t = CSparseMatrix {
        nzmax,
        m: 3,
        n: 3,
        p: c_fill(len, || 1),
        i: c_fill(len, || 2),
        x: c_fill(len, || 0.5),
        nz,
    };
    t
}

/// A sparse NumericsMatrix (3x3) owning `t` as its triplet; release with NM_free.
unsafe fn sparse_matrix(t: *mut CSparseMatrix, origin: c_int) -> *mut NumericsMatrix {
    let nsm = c_array::<NumericsSparseMatrix>(1);
    (*nsm).triplet = t;
    (*nsm).origin = origin;
    let m = c_array::<NumericsMatrix>(1);
    *m = matrix(NM_SPARSE, 3, 3);
    (*m).matrix2 = nsm;
    m
}

/// Before: a triplet with a negative nz (a compressed matrix in the triplet slot) was written
/// at index nz as usize (SIGSEGV); nz > nzmax grew the arrays to 2 nzmax and wrote past them;
/// a negative nzmax was taken for a capacity; nzmax = nz = 2^63 - 1 overflowed 2 nzmax (a panic,
/// FC3D_ERR_INTERNAL, in debug builds; a wrapped realloc size and a heap overflow in release
/// builds); nz = nzmax = 1000 over arrays of 2 was grown by copying what lay past them.
#[test]
fn entry_checks_the_triplet_it_appends_to() {
    if isolated("entry_checks_the_triplet_it_appends_to") {
        return;
    }
    unsafe {
        for (len, nz, nzmax, want) in [
            (2, -1, 2, FC3D_ERR_INVALID_STORAGE),
            (2, 5, 2, FC3D_ERR_INVALID_STORAGE),
            (2, 0, -4, FC3D_ERR_INVALID_SIZE),
            (2, CS_INT::MAX, CS_INT::MAX, FC3D_ERR_INVALID_SIZE),
            (2, 1000, 1000, FC3D_ERR_INVALID_STORAGE),
        ] {
            let t = c_triplet(len, nz, nzmax);
            let m = sparse_matrix(t, NSM_TRIPLET);
            let before = snapshot(m);
            assert_eq!(
                code_of(|| NM_entry(m, 0, 0, 1.0)),
                want,
                "nz {nz} nzmax {nzmax}: {}",
                message()
            );
            assert_eq!(
                before,
                snapshot(m),
                "nz {nz} nzmax {nzmax}: changed on failure"
            );
            // Made consistent, the matrix is released normally.
            (*t).nz = 0;
            (*t).nzmax = len as CS_INT;
            NM_free(m);
        }
        // A full triplet grows: the entries it held are kept, in order.
        let t = c_triplet(2, 2, 2);
        let m = sparse_matrix(t, NSM_TRIPLET);
        assert_eq!(code_of(|| NM_entry(m, 0, 0, 4.0)), FC3D_OK);
        let t = (*(*m).matrix2).triplet;
        assert_eq!(((*t).nz, (*t).nzmax), (3, 4));
        assert_eq!(get(m, 2, 1), (1.0, FC3D_OK));
        assert_eq!(get(m, 0, 0), (4.0, FC3D_OK));
        // Arrays of the capacity declared but NULL: refused.
        let t = c_triplet(2, 0, 2);
        free((*t).x.cast());
        (*t).x = std::ptr::null_mut();
        let m2 = sparse_matrix(t, NSM_TRIPLET);
        assert_eq!(code_of(|| NM_entry(m2, 0, 0, 1.0)), FC3D_ERR_NULL_POINTER);
        NM_free(m2);
        NM_free(m);
    }
}

/// Before: NM_entry on a matrix stored in compressed columns (origin CSC, no triplet) made an
/// empty triplet, put the entry in it and switched the origin to it: the host's entries vanished
/// from W without an error. Now it inserts as Siconos 4.4 does (through a triplet, compressed
/// again, origin kept): the entries stay. Compressed rows are refused (Siconos has no such case),
/// and so is a CSC whose structure or arrays disagree with its counts, with W unchanged.
#[test]
fn entry_into_compressed_columns_keeps_the_entries() {
    unsafe {
        // 3x3 CSC holding (0,0) = 2, over heap arrays (NM_entry replaces and frees them).
        let csc = c_array::<CSparseMatrix>(1);
        *csc = CSparseMatrix {
            nzmax: 1,
            m: 3,
            n: 3,
            p: c_fill(4, || 1),
            i: c_fill(1, || 0),
            x: c_fill(1, || 2.0),
            nz: -1,
        };
        *(*csc).p = 0;
        let nsm = c_array::<NumericsSparseMatrix>(1);
        (*nsm).csc = csc;
        (*nsm).origin = NSM_CSC;
        let m = c_array::<NumericsMatrix>(1);
        *m = matrix(NM_SPARSE, 3, 3);
        (*m).matrix2 = nsm;
        assert_eq!(code_of(|| NM_entry(m, 2, 1, 5.0)), FC3D_OK, "{}", message());
        assert_eq!(code_of(|| NM_entry(m, 0, 0, 1.0)), FC3D_OK, "{}", message());
        assert_eq!(get(m, 0, 0), (3.0, FC3D_OK));
        assert_eq!(get(m, 2, 1), (5.0, FC3D_OK));
        assert_eq!(((*nsm).origin, (*csc).nz, (*csc).nzmax), (NSM_CSC, -1, 3));
        // Column 0 holds two entries, column 1 one: p = [0, 2, 3, 3]. A pointer that decreases
        // is refused, nothing changed.
        assert_eq!(std::slice::from_raw_parts((*csc).p, 4), &[0, 2, 3, 3]);
        *(*csc).p.add(2) = 1;
        let before = snapshot(m);
        assert_eq!(code_of(|| NM_entry(m, 1, 1, 1.0)), FC3D_ERR_INVALID_STORAGE);
        assert_eq!(before, snapshot(m));
        *(*csc).p.add(2) = 3;
        // Counts above the heap arrays (nzmax and the pointers say 300 entries, the arrays hold 3).
        let last = *(*csc).p.add(3);
        *(*csc).p.add(3) = 300;
        (*csc).nzmax = 300;
        let before = snapshot(m);
        assert_eq!(
            code_of(|| NM_entry(m, 1, 1, 1.0)),
            FC3D_ERR_INVALID_STORAGE,
            "{}",
            message()
        );
        assert_eq!(before, snapshot(m));
        *(*csc).p.add(3) = last;
        (*csc).nzmax = 3;
        // Compressed rows: refused.
        (*nsm).csr = (*nsm).csc;
        (*nsm).csc = std::ptr::null_mut();
        (*nsm).origin = NSM_CSR;
        (*csc).nz = -2;
        let before = snapshot(m);
        assert_eq!(code_of(|| NM_entry(m, 1, 1, 1.0)), FC3D_ERR_INVALID_STORAGE);
        assert_eq!(before, snapshot(m));
        NM_free(m);
    }
}

/// Before: NM_triplet_alloc wrote a new sparse structure into A before its allocations could
/// fail (A changed on failure, and the arrays allocated before the failing one leaked), and
/// accepted negative sizes as the triplet's dimensions.
#[test]
fn triplet_alloc_is_all_or_nothing() {
    if isolated("triplet_alloc_is_all_or_nothing") {
        return;
    }
    unsafe {
        let m = NM_new();
        let before = snapshot(m);
        for nzmax in [-1, CS_INT::MIN, CS_INT::MAX, 1 << 60, 1 << 28] {
            let code = code_of(|| NM_triplet_alloc(m, nzmax));
            assert!(
                [FC3D_ERR_INVALID_SIZE, FC3D_ERR_OUT_OF_MEMORY].contains(&code),
                "nzmax {nzmax}: {code} {}",
                message()
            );
            assert_eq!(before, snapshot(m), "nzmax {nzmax}: changed on failure");
        }
        (*m).size0 = -5;
        assert_eq!(code_of(|| NM_triplet_alloc(m, 4)), FC3D_ERR_INVALID_SIZE);
        (*m).size0 = 3;
        (*m).size1 = 3;
        assert_eq!(code_of(|| NM_triplet_alloc(m, 0)), FC3D_OK);
        assert_eq!(code_of(|| NM_entry(m, 2, 2, 1.5)), FC3D_OK);
        assert_eq!(get(m, 2, 2), (1.5, FC3D_OK));
        assert!(code_of(|| NM_triplet_alloc(std::ptr::null_mut(), 4)) == FC3D_ERR_NULL_POINTER);
        NM_free(m);
    }
}

/// Sizes no allocator gives: an error code, never an abort.
#[test]
fn create_with_impossible_sizes() {
    if isolated("create_with_impossible_sizes") {
        return;
    }
    unsafe {
        for (s0, s1) in [
            (c_int::MAX, c_int::MAX),
            (1 << 30, 1 << 30),
            (c_int::MAX, 1 << 20),
        ] {
            let mut m = std::ptr::null_mut();
            let code = code_of(|| m = NM_create(NM_DENSE, s0, s1));
            assert!(m.is_null());
            assert!(
                [FC3D_ERR_INVALID_SIZE, FC3D_ERR_OUT_OF_MEMORY].contains(&code),
                "{code}"
            );
        }
        for (storage, s0, s1, want) in [
            (NM_DENSE, -1, 3, FC3D_ERR_INVALID_SIZE),
            (NM_SPARSE, 3, c_int::MIN, FC3D_ERR_INVALID_SIZE),
            (7, 3, 3, FC3D_ERR_INVALID_STORAGE),
            (c_int::MIN, 3, 3, FC3D_ERR_INVALID_STORAGE),
        ] {
            assert!(NM_create(storage, s0, s1).is_null());
            assert_eq!(fc3d_last_error_code(), want);
            assert!(NM_create_from_data(storage, s0, s1, std::ptr::null_mut()).is_null());
            assert_eq!(fc3d_last_error_code(), want);
            let f = NM_new();
            let before = snapshot(f);
            assert_eq!(
                code_of(|| NM_fill(f, storage, s0, s1, std::ptr::null_mut())),
                want
            );
            assert_eq!(before, snapshot(f));
            NM_free(f);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// SBCM_new_3x3, SBCM_to_SBM, SBM_clear, NM_free.

/// Before: SBCM_new_3x3 built its cumulative sizes 3, 6, ..., 3m in a Vec of m entries without
/// a bound: m = 2^32 - 1 asked for 16 GiB (an abort under a memory limit) and 3 m overflowed
/// (a panic in debug builds, wrapped sizes in release builds).
#[test]
fn sbcm_new_3x3_rejects_block_counts_no_matrix_can_have() {
    if isolated("sbcm_new_3x3_rejects_block_counts_no_matrix_can_have") {
        return;
    }
    unsafe {
        let (mut row, mut col, mut blk) = ([1u32], [1u32], [1.0f64; 9]);
        for (m, n) in [
            (c_uint::MAX, 1),
            (1, 0x5555_5556),
            (715827883, 1),
            (0x8000_0000, 0x8000_0000),
        ] {
            let mut coo = std::ptr::null_mut();
            let code = code_of(|| {
                coo = SBCM_new_3x3(
                    m,
                    n,
                    1,
                    row.as_mut_ptr(),
                    col.as_mut_ptr(),
                    blk.as_mut_ptr(),
                )
            });
            assert!(coo.is_null());
            assert_eq!(code, FC3D_ERR_INVALID_SIZE, "{m}x{n}: {}", message());
        }
        // Large block counts a C int can describe are accepted (715827882 is the largest; this
        // child process has 2 GiB of address space).
        let coo = SBCM_new_3x3(
            1,
            50_000_000,
            1,
            row.as_mut_ptr(),
            col.as_mut_ptr(),
            blk.as_mut_ptr(),
        );
        assert!(!coo.is_null(), "{}", message());
        SBCM_free_3x3(coo);
        // NULL arrays for blocks that are declared.
        for k in 0..3 {
            let (r, c, b) = (
                if k == 0 {
                    std::ptr::null_mut()
                } else {
                    row.as_mut_ptr()
                },
                if k == 1 {
                    std::ptr::null_mut()
                } else {
                    col.as_mut_ptr()
                },
                if k == 2 {
                    std::ptr::null_mut()
                } else {
                    blk.as_mut_ptr()
                },
            );
            assert!(SBCM_new_3x3(1, 1, 1, r, c, b).is_null());
            assert_eq!(fc3d_last_error_code(), FC3D_ERR_NULL_POINTER);
        }
    }
}

/// Before: SBCM_to_SBM subtracted 1 from a column index of 0 (a panic in debug builds, block
/// column 2^64 - 1 in release builds), accepted columns past blocknumber1, NULL block pointers
/// and cumulative sizes that do not increase, and allocated blocknumber0 + 1 row pointers (32 GiB
/// for 2^32 - 1 block rows) before looking at the arrays that declare them. (The coordinates of
/// a SparseBlockCoordinateMatrix are 0-based, as SBCM_new_3x3 stores them in Siconos.)
#[test]
fn sbcm_to_sbm_checks_what_the_host_filled() {
    if isolated("sbcm_to_sbm_checks_what_the_host_filled") {
        return;
    }
    unsafe {
        let row = raw([0u32, 1]);
        let col = raw([0u32, 1]);
        let values = raw([1.0f64; 18]);
        let ptrs = raw([values, values.add(9)]);
        let bs = raw([3u32, 6]);
        let mc = boxed(SparseBlockCoordinateMatrix {
            nbblocks: 2,
            blocknumber0: 2,
            blocknumber1: 2,
            block: ptrs,
            blocksize0: bs,
            blocksize1: bs,
            row,
            column: col,
        });
        let s = SBCM_to_SBM(mc);
        assert!(!s.is_null(), "{}", message());
        SBM_free_from_SBCM(s);
        let expect = move |want: c_int, what: &str| {
            let mut s = std::ptr::null_mut();
            let code = code_of(|| s = SBCM_to_SBM(mc));
            assert!(s.is_null(), "{what}: accepted");
            assert_eq!(code, want, "{what}: {}", message());
        };
        *col.add(1) = c_uint::MAX;
        expect(
            FC3D_ERR_INVALID_SIZE,
            "column 2^32 - 1 (a 1-based 0 made 0-based)",
        );
        *col.add(1) = 2;
        expect(FC3D_ERR_INVALID_SIZE, "column past blocknumber1");
        *col.add(1) = 1;
        *row = 2;
        expect(FC3D_ERR_INVALID_SIZE, "row past blocknumber0");
        *row = 0;
        *ptrs.add(1) = std::ptr::null_mut();
        expect(FC3D_ERR_NULL_POINTER, "NULL block");
        *ptrs.add(1) = values.add(9);
        *bs.add(1) = 3;
        expect(FC3D_ERR_INVALID_STORAGE, "sizes that repeat");
        *bs = 0;
        expect(FC3D_ERR_INVALID_STORAGE, "a block of size 0");
        *bs = 3;
        *bs.add(1) = 6;
        (*mc).blocknumber0 = c_uint::MAX;
        (*mc).blocksize0 = std::ptr::null_mut();
        expect(FC3D_ERR_NULL_POINTER, "2^32 - 1 block rows without sizes");
        (*mc).blocknumber0 = 2;
        (*mc).blocksize0 = bs;
        (*mc).block = std::ptr::null_mut();
        expect(FC3D_ERR_NULL_POINTER, "no block array");
        assert!(SBCM_to_SBM(std::ptr::null_mut()).is_null());
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_NULL_POINTER);
    }
}

/// Before: SBM_clear and NM_free read nbblocks block pointers from the block array whatever its
/// size, and freed what they found past its end (heap corruption, an abort in free()). Now a
/// block count beyond the heap block holding the array is refused and nothing is freed.
#[test]
fn release_refuses_a_block_count_beyond_the_block_array() {
    if isolated("release_refuses_a_block_count_beyond_the_block_array") {
        return;
    }
    unsafe {
        for through_nm_free in [false, true] {
            let s = SBM_new();
            (*s).block = c_array::<*mut c_double>(1);
            *(*s).block = c_fill(9, || 1.0);
            (*s).nbblocks = 100_000;
            let code = if through_nm_free {
                let m = c_array::<NumericsMatrix>(1);
                *m = matrix(NM_SPARSE_BLOCK, 3, 3);
                (*m).matrix1 = s;
                let before = snapshot(m);
                let mut back = m;
                let code = code_of(|| back = NM_free(m));
                assert!(back.is_null());
                assert_eq!(before, snapshot(m), "NM_free changed what it refused");
                free(m.cast());
                code
            } else {
                code_of(|| SBM_clear(s))
            };
            assert_eq!(code, FC3D_ERR_INVALID_STORAGE, "{}", message());
            assert!(
                (*s).nbblocks == 100_000 && !(*s).block.is_null(),
                "changed on failure"
            );
            (*s).nbblocks = 1;
            assert_eq!(code_of(|| SBM_clear(s)), FC3D_OK);
            assert!((*s).block.is_null() && (*s).nbblocks == 0);
            free(s.cast());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Properties.

/// Cumulative sizes that may be anything (a strategy for blocksize arrays).
fn hostile_uint() -> impl Strategy<Value = c_uint> {
    prop_oneof![
        4 => 0u32..20,
        1 => Just(c_uint::MAX),
        1 => Just(0x8000_0000u32),
        1 => any::<c_uint>(),
    ]
}

fn hostile_int() -> impl Strategy<Value = c_int> {
    prop_oneof![
        4 => -3i32..12,
        1 => Just(c_int::MIN),
        1 => Just(c_int::MAX),
        1 => any::<c_int>(),
    ]
}

/// The reference value of entry (i, j) of a coordinate list of 3x3 blocks (1-based, summed).
fn reference(rows: &[c_uint], cols: &[c_uint], values: &[f64], i: usize, j: usize) -> f64 {
    let mut v = 0.0;
    for k in 0..rows.len() {
        if rows[k] as usize == i / 3 + 1 && cols[k] as usize == j / 3 + 1 {
            v += values[9 * k + i % 3 + 3 * (j % 3)];
        }
    }
    v
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

    /// The fuzz case runner on random bytes: the same promises as under the sanitizer.
    #[test]
    fn random_inputs_keep_the_promises(data in proptest::collection::vec(any::<u8>(), 0..600)) {
        run_matrix_case(&data);
    }

    /// Dense: any (i, j) reads or writes exactly entry i + j size0, or is refused; nothing else
    /// of the array changes (the array ends at an inaccessible page).
    #[test]
    fn dense_entries_stay_inside(
        size0 in 0i32..6, size1 in 0i32..6,
        lie0 in hostile_int(), lie1 in hostile_int(), use_lie in 0u8..4,
        ops in proptest::collection::vec((hostile_int(), hostile_int(), -9.0f64..9.0), 1..20),
    ) {
        let n = (size0 * size1) as usize;
        let data = Guarded::new(&(0..n).map(|k| k as f64).collect::<Vec<_>>());
        let mut m = matrix(NM_DENSE, size0, size1);
        // A negative declared size (never a larger one: the array is only size0 * size1 long).
        if use_lie == 0 && lie0 < 0 { m.size0 = lie0; }
        if use_lie == 1 && lie1 < 0 { m.size1 = lie1; }
        m.matrix0 = data.ptr();
        let mut shadow = data.to_vec();
        for (i, j, v) in ops {
            unsafe {
                let inside = i >= 0 && j >= 0 && i < m.size0 && j < m.size1;
                let code = code_of(|| NM_entry(&mut m, i, j, v));
                if inside {
                    prop_assert_eq!(code, FC3D_OK);
                    shadow[i as usize + j as usize * size0 as usize] = v;
                    prop_assert_eq!(get(&m, i, j), (v, FC3D_OK));
                } else {
                    prop_assert_eq!(code, FC3D_ERR_INVALID_SIZE);
                    prop_assert!(get(&m, i, j).0.is_nan());
                }
                prop_assert_eq!(&data.to_vec(), &shadow);
            }
        }
    }

    /// Coordinate blocks with any coordinates and block counts: SBCM_to_SBM accepts exactly the
    /// lists inside the declared block grid, and then NM_get_value, NM_copy_to_sparse and the
    /// driver see the sum of the blocks at each place.
    #[test]
    fn coordinate_blocks_are_checked_and_summed(
        m in prop_oneof![4 => 0u32..4, 1 => Just(c_uint::MAX), 1 => Just(0x5555_5556u32)],
        n in prop_oneof![4 => 0u32..4, 1 => Just(715827883u32)],
        coords in proptest::collection::vec((hostile_uint(), hostile_uint()), 0..6),
        scale in -4.0f64..4.0,
        i in hostile_int(), j in hostile_int(),
    ) {
        let nb = coords.len();
        let mut rows: Vec<c_uint> = coords.iter().map(|c| c.0 % 6).collect();
        let mut cols: Vec<c_uint> = coords.iter().map(|c| if c.1 > 100 { c.1 } else { c.1 % 6 }).collect();
        let values = Guarded::new(&(0..9 * nb).map(|k| scale * k as f64).collect::<Vec<_>>());
        let (rg, cg) = (Guarded::new(&rows), Guarded::new(&cols));
        unsafe {
            let mut coo = std::ptr::null_mut();
            let code = code_of(|| coo = SBCM_new_3x3(m, n, nb as c_uint, rg.ptr(), cg.ptr(), values.ptr()));
            let grid_ok = (m as u64) * 3 <= c_int::MAX as u64 && (n as u64) * 3 <= c_int::MAX as u64;
            let coords_ok = rows.iter().all(|&r| r >= 1 && r <= m) && cols.iter().all(|&c| c >= 1 && c <= n);
            prop_assert_eq!(coo.is_null(), !(grid_ok && coords_ok), "code {}", code);
            if coo.is_null() {
                prop_assert!(code < 0 && code != -99);
                return Ok(());
            }
            let s = SBCM_to_SBM(coo);
            prop_assert!(!s.is_null(), "{}", message());
            let mat = NM_new_SBM(3 * m as c_int, 3 * n as c_int, s);
            let (v, code) = get(mat, i, j);
            if i >= 0 && j >= 0 && i < 3 * m as c_int && j < 3 * n as c_int {
                prop_assert_eq!(code, FC3D_OK, "{}", message());
                rows = rg.to_vec();
                cols = cg.to_vec();
                let want = reference(&rows, &cols, &values.to_vec(), i as usize, j as usize);
                prop_assert!((v - want).abs() <= 1e-12 * want.abs().max(1.0), "{} vs {}", v, want);
            } else {
                prop_assert!(v.is_nan() && code == FC3D_ERR_INVALID_SIZE);
            }
            let copy = NM_new();
            prop_assert_eq!(code_of(|| NM_copy_to_sparse(mat, copy, -1.0)), FC3D_OK, "{}", message());
            same_values(mat, copy, "copy of a coordinate SBM");
            NM_free(copy);
            (*mat).matrix1 = std::ptr::null_mut();
            NM_free(mat);
            SBM_free_from_SBCM(s);
            SBCM_free_3x3(coo);
        }
    }

    /// Compressed columns with arbitrary pointers, indices, nz and nzmax (never above the arrays
    /// allocated): every call is either refused with a code or agrees with a reference reading
    /// of the same arrays, and nothing is read past them.
    #[test]
    fn compressed_columns_with_arbitrary_structure(
        rows in 0i64..5, cols in 0i64..5,
        ptr in proptest::collection::vec(prop_oneof![6 => 0i64..8, 1 => any::<i64>()], 6),
        idx in proptest::collection::vec(prop_oneof![6 => 0i64..5, 1 => any::<i64>()], 0..8),
        nzmax_lie in prop_oneof![3 => Just(0i64), 1 => -3i64..0, 1 => Just(i64::MIN)],
        nz in prop_oneof![4 => Just(-1i64), 1 => any::<i64>()],
        i in hostile_int(), j in hostile_int(),
    ) {
        let nnz = idx.len();
        let p = &ptr[..cols as usize + 1];
        let x: Vec<f64> = (0..nnz).map(|k| k as f64 + 0.5).collect();
        let mut h = HostCs::new(rows, cols, nz, nnz as i64 + nzmax_lie, p, &idx, &x);
        let mut nsm = empty_nsm();
        nsm.csc = &mut h.cs;
        nsm.origin = NSM_CSC;
        let mut m = matrix(NM_SPARSE, rows as c_int, cols as c_int);
        m.matrix2 = &mut nsm;
        // The reference: valid when nz = -1, nzmax >= 0, p starts at 0, increases, ends <= nzmax,
        // and every row index is in range.
        let nzmax = nnz as i64 + nzmax_lie;
        let valid = nz == -1 && nzmax >= 0 && p[0] == 0 && p.windows(2).all(|w| w[0] <= w[1])
            && p[cols as usize] <= nzmax && idx[..p[cols as usize].max(0) as usize].iter().all(|&r| r >= 0 && r < rows);
        unsafe {
            let (v, code) = get(&m, i, j);
            prop_assert!(code != -99);
            let inside = i >= 0 && j >= 0 && (i as i64) < rows && (j as i64) < cols;
            if valid && inside {
                prop_assert_eq!(code, FC3D_OK, "{}", message());
                let j = j as usize;
                let want: f64 = (p[j] as usize..p[j + 1] as usize).filter(|&k| idx[k] == i as i64).map(|k| x[k]).sum();
                prop_assert_eq!(v, want);
            } else if !inside {
                prop_assert_eq!(code, FC3D_ERR_INVALID_SIZE);
            }
            let copy = NM_new();
            let code = code_of(|| NM_copy_to_sparse(&m, copy, -1.0));
            prop_assert_eq!(code == FC3D_OK, valid, "code {} {}", code, message());
            if valid {
                same_values(&m, copy, "copy of a CSC");
            }
            NM_free(copy);
        }
    }

    /// A sparse-block structure with arbitrary counts and indices (arrays as long as declared,
    /// 3x3 blocks): the driver and the copy accept exactly the consistent ones.
    #[test]
    fn block_structures_with_arbitrary_counts(
        nbr in 0usize..4,
        index1 in proptest::collection::vec(prop_oneof![6 => 0usize..5, 1 => any::<usize>()], 0..6),
        index2 in proptest::collection::vec(prop_oneof![6 => 0usize..4, 1 => any::<usize>()], 0..6),
        nbblocks in prop_oneof![3 => 0u32..6, 1 => any::<c_uint>()],
        null_block in proptest::option::of(0usize..6),
    ) {
        let bs: Vec<c_uint> = (1..=nbr as c_uint).map(|k| 3 * k).collect();
        let (bs0, bs1) = (Guarded::new(&bs), Guarded::new(&bs));
        let (g1, g2) = (Guarded::new(&index1), Guarded::new(&index2));
        // The block array is as long as both counts say (nbblocks only when it is small).
        let len = index2.len().max(if nbblocks < 6 { nbblocks as usize } else { 0 });
        let store: Vec<Guarded<f64>> = (0..len).map(|k| block9(k as f64 + 1.0)).collect();
        let ptrs: Vec<*mut c_double> = (0..len).map(|k| if Some(k) == null_block { std::ptr::null_mut() } else { store[k].ptr() }).collect();
        let blocks = Guarded::new(&ptrs);
        let nbblocks = if nbblocks < 6 || len == 0 { nbblocks.min(len as c_uint) } else { nbblocks };
        let mut s = sbm(nbblocks, blocks.ptr(), &bs0, &bs1, &g1, &g2);
        let mut m = matrix(NM_SPARSE_BLOCK, 3 * nbr as c_int, 3 * nbr as c_int);
        m.matrix1 = &mut s;
        let nb = index2.len();
        // Siconos' filled1 may stop before blocknumber0 + 1 (SBCM_to_SBM sets it one past the
        // last row holding a block): the rows past it are empty, and index1_data[filled1 - 1]
        // must count every block.
        let given = index1.len().min(nbr + 1);
        let counts_agree = !(index1.len() > nbr + 1 && nbr > 0 || given == 0 && nbblocks != 0);
        let last = if given == 0 { 0 } else { index1[given - 1] };
        let mut ptr = index1[..given].to_vec();
        ptr.resize(nbr + 1, last);
        let valid = counts_agree && last == nb && ptr[0] == 0 && ptr.windows(2).all(|w| w[0] <= w[1])
            && ptr[nbr] == nb && nbblocks as usize == nb && index2.iter().all(|&c| c < nbr)
            && null_block.is_none_or(|k| k >= nb);
        unsafe {
            let copy = NM_new();
            let code = code_of(|| NM_copy_to_sparse(&m, copy, -1.0));
            prop_assert_eq!(code == FC3D_OK, valid, "code {} {}", code, message());
            prop_assert!(code != -99);
            if valid {
                same_values(&m, copy, "copy of an SBM");
            }
            NM_free(copy);
            for i in 0..3 * nbr as c_int {
                let (_, code) = get(&m, i, i);
                prop_assert!(code != -99);
            }
        }
    }
}

/// Every input the fuzz target `matrix_helpers` failed on, replayed (in a child process under a
/// 2 GiB address-space limit: some of them asked for tens of gigabytes before the fix).
#[test]
fn saved_fuzz_inputs() {
    if isolated("saved_fuzz_inputs") {
        return;
    }
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/regressions/matrix_helpers");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("fuzz/regressions/matrix_helpers")
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for f in files {
        eprintln!("{}", f.display());
        run_matrix_case(&std::fs::read(&f).unwrap());
    }
}
