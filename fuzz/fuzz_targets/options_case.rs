// One fuzz case of `fc3d_driver` over option slots, shared by the fuzz target
// (fuzz/fuzz_targets/options.rs), the regression replay (capi/tests/fuzz_regressions.rs) and the
// slot sweep (capi/tests/option_extremes.rs), which include this file.
//
// A small valid problem, a `SolverOptions` for any solver id (every id fc3d accepts, ids it only
// names, local ids used as top-level ids, random ids), random internal solver ids, and extreme
// values (INT_MIN, INT_MAX, -1, 0, huge, NaN, +-inf, 1e308, subnormals, ...) in random
// iparam/dparam slots of the options and of their internal solvers; sometimes a broken tree (a
// cycle, a count with no array, sizes below 20). The top-level time budget dparam[19] is always
// short, so that every run ends. Asserted: the return code is 0..=4 or a negative FC3D_ERR_* code
// other than FC3D_ERR_INTERNAL; on 0..=4, r and u are finite and dparam[1] equals
// fc3d_compute_error of the returned reaction; on a negative code nothing is written.

use std::os::raw::{c_double, c_int};

use fc3d::types::{FrictionContactProblem, NumericsMatrix, SolverOptions};

extern "C" {
    fn solver_options_create(id: c_int) -> *mut SolverOptions;
    fn solver_options_delete(o: *mut SolverOptions);
    fn solver_options_copy(o: *mut SolverOptions) -> *mut SolverOptions;
    fn solver_options_update_internal(parent: *mut SolverOptions, n: usize, id: c_int);
    fn fc3d_driver(
        p: *mut FrictionContactProblem,
        r: *mut c_double,
        u: *mut c_double,
        o: *mut SolverOptions,
    ) -> c_int;
    fn fc3d_compute_error(
        p: *mut FrictionContactProblem,
        z: *mut c_double,
        w: *mut c_double,
        tol: c_double,
        o: *mut SolverOptions,
        norm: c_double,
        e: *mut c_double,
    ) -> c_int;
    fn fc3d_last_error_message() -> *const std::ffi::c_char;
    fn free(p: *mut std::ffi::c_void);
}

/// Every id `fc3d_driver` accepts as a top-level solver, the ids fc3d only names, the local ids
/// (which `fc3d_driver` must reject as top-level ids) and fc3d's Tresca sub-problem ids.
pub const OPTION_CASE_IDS: [c_int; 40] = [
    500, 502, 503, 504, 505, 506, 507, 511, 512, 513, 516, 517, 520, 522, 523, // solvers
    501, 508, 510, 563, // named only
    550, 551, 552, 553, 554, 555, 557, 558, 561, 562, 564, 565, 570, 571, 572, // local
    566, 567, // Tresca sub-problem solvers
    0, -1, 599, 400,
];

/// Extreme integers.
pub const OPTION_CASE_INTS: [c_int; 16] = [
    c_int::MIN,
    c_int::MIN + 1,
    -100,
    -2,
    -1,
    0,
    1,
    2,
    3,
    4,
    10,
    20,
    1000,
    1 << 30,
    c_int::MAX - 1,
    c_int::MAX,
];

/// Extreme doubles.
pub const OPTION_CASE_DOUBLES: [f64; 24] = [
    0.0,
    -0.0,
    f64::NAN,
    -f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e308,
    -1e308,
    f64::MAX,
    f64::MIN,
    1e300,
    -1e300,
    f64::MIN_POSITIVE,
    5e-324,
    -5e-324,
    1e-300,
    f64::EPSILON,
    1.0,
    -1.0,
    2.0,
    0.5,
    1.999999999,
    1e-3,
    1e15,
];

/// Reads the fuzzer's bytes as a stream of small decisions (0 once they run out).
pub struct OptionBytes<'a>(pub &'a [u8]);

impl OptionBytes<'_> {
    pub fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn int(&mut self) -> c_int {
        let b = self.byte();
        if b < 224 {
            OPTION_CASE_INTS[b as usize % OPTION_CASE_INTS.len()]
        } else {
            c_int::from_le_bytes([self.byte(), self.byte(), self.byte(), self.byte()])
        }
    }

    fn double(&mut self) -> f64 {
        let b = self.byte();
        if b < 224 {
            OPTION_CASE_DOUBLES[b as usize % OPTION_CASE_DOUBLES.len()]
        } else {
            let mut x = [0u8; 8];
            x.iter_mut().for_each(|v| *v = self.byte());
            f64::from_le_bytes(x)
        }
    }

    fn id(&mut self) -> c_int {
        let b = self.byte();
        if b < 240 {
            OPTION_CASE_IDS[b as usize % OPTION_CASE_IDS.len()]
        } else {
            c_int::from_le_bytes([self.byte(), self.byte(), self.byte(), self.byte()])
        }
    }
}

/// A small well-posed problem as a C host builds it (dense W = B B^T + I, column-major).
pub struct OptionCaseProblem {
    pub w: Vec<f64>,
    pub q: Vec<f64>,
    pub mu: Vec<f64>,
    pub m: Box<NumericsMatrix>,
    pub nc: usize,
}

impl OptionCaseProblem {
    /// `nc` contacts (1..=3), entries from `seed`.
    pub fn new(nc: usize, seed: u8) -> Self {
        let n = 3 * nc;
        let mut state = (seed as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let b: Vec<f64> = (0..n * n).map(|_| next()).collect();
        let mut w = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                let mut s = if i == j { 1.0 } else { 0.0 };
                for k in 0..n {
                    s += b[i * n + k] * b[j * n + k];
                }
                w[i + j * n] = s;
            }
        }
        let q: Vec<f64> = (0..n)
            .map(|i| {
                if i % 3 == 0 {
                    -1.0 + 0.5 * next()
                } else {
                    next()
                }
            })
            .collect();
        let mu: Vec<f64> = (0..nc).map(|_| 0.3 + 0.3 * next()).collect();
        // SAFETY: an all-zero NumericsMatrix is a valid empty value (NULL pointers).
        let mut m: Box<NumericsMatrix> = Box::new(unsafe { std::mem::zeroed() });
        m.storageType = 0;
        m.size0 = n as c_int;
        m.size1 = n as c_int;
        let mut p = OptionCaseProblem { w, q, mu, m, nc };
        p.m.matrix0 = p.w.as_mut_ptr();
        p
    }

    pub fn raw(&mut self) -> FrictionContactProblem {
        FrictionContactProblem {
            dimension: 3,
            numberOfContacts: self.nc as c_int,
            M: &mut *self.m,
            q: self.q.as_mut_ptr(),
            mu: self.mu.as_mut_ptr(),
        }
    }
}

/// The options node at `path` below `o` (internal solver 0 at each step), if it exists.
pub unsafe fn option_case_node(o: *mut SolverOptions, depth: usize) -> *mut SolverOptions {
    let mut node = o;
    for _ in 0..depth {
        if node.is_null()
            || (*node).numberOfInternalSolvers == 0
            || (*node).internalSolvers.is_null()
        {
            return std::ptr::null_mut();
        }
        node = *(*node).internalSolvers;
    }
    node
}

/// Runs `fc3d_driver` on `problem` with `o` and checks the C contract; returns the code.
pub unsafe fn option_case_check(problem: &mut OptionCaseProblem, o: *mut SolverOptions) -> c_int {
    let n = 3 * problem.nc;
    let mut p = problem.raw();
    let (iparam, dparam) = ((*o).iparam, (*o).dparam);
    let outputs = !iparam.is_null() && !dparam.is_null() && (*o).iSize >= 20 && (*o).dSize >= 20;
    if outputs {
        *iparam.add(1) = -12345;
        *dparam.add(1) = -12345.0;
    }
    let sentinel = 7.25;
    let mut r = vec![sentinel; n];
    let mut u = vec![sentinel; n];
    let rc = fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), o);
    let message = || {
        let m = fc3d_last_error_message();
        if m.is_null() {
            String::new()
        } else {
            std::ffi::CStr::from_ptr(m).to_string_lossy().into_owned()
        }
    };
    assert_ne!(rc, fc3d::FC3D_ERR_INTERNAL, "internal error: {}", message());
    // 0 converged, 1 iteration limit, 2 time budget, 3 relaxed not Coulomb, 4 unbounded.
    assert!(rc <= 4, "return code {rc}");
    if rc >= 0 {
        assert!(outputs, "solved with unusable parameter arrays");
        assert!(
            r.iter().chain(&u).all(|x| x.is_finite()),
            "non-finite output: rc {rc} r {r:?} u {u:?}"
        );
        let mut e = f64::NAN;
        let mut w2 = vec![0.0; n];
        let qn = problem.q.iter().fold(0.0f64, |a, &x| a.hypot(x));
        let ec = fc3d_compute_error(
            &mut p,
            r.as_mut_ptr(),
            w2.as_mut_ptr(),
            1e-4,
            std::ptr::null_mut(),
            qn,
            &mut e,
        );
        assert!(ec >= 0, "compute_error rejected what the driver accepted");
        let reported = *dparam.add(1);
        assert!(
            reported == e || (reported - e).abs() <= 1e-14 * reported.abs().max(e.abs()),
            "dparam[1] {reported} vs recomputed {e}"
        );
        assert!(*iparam.add(1) >= 0, "iterations {}", *iparam.add(1));
    } else {
        assert!(
            r.iter().chain(&u).all(|&x| x == sentinel),
            "outputs written on failure"
        );
        if outputs {
            assert_eq!(*iparam.add(1), -12345);
            assert_eq!(*dparam.add(1), -12345.0);
        }
        let m = message();
        assert!(!m.is_empty(), "rejected without a message");
        if rc == fc3d::FC3D_ERR_INVALID_OPTION {
            // The message names what was wrong: a slot, a size, the tree.
            assert!(
                m.contains("param[")
                    || m.contains("Size")
                    || m.contains("internal")
                    || m.contains("NULL"),
                "message names no slot: {m}"
            );
        }
    }
    rc
}

/// Releases options made by `solver_options_create`.
pub unsafe fn option_case_release(o: *mut SolverOptions) {
    solver_options_delete(o);
    free(o.cast());
}

/// Runs one input; panics (assert) on any broken promise of the C contract.
pub fn run_options_case(data: &[u8]) {
    let mut b = OptionBytes(data);
    let flags = b.byte();
    let mut problem = OptionCaseProblem::new(1 + (flags % 3) as usize, b.byte());
    let id = b.id();
    unsafe {
        // An id fc3d cannot create: options of another id with the solverId overwritten.
        let mut o = solver_options_create(id);
        if o.is_null() {
            o = solver_options_create(500);
            (*o).solverId = id;
        }
        // Internal solvers by id (replaced through the API, or their solverId overwritten).
        for depth in 0..2 {
            let parent = option_case_node(o, depth);
            if parent.is_null() || (*parent).numberOfInternalSolvers == 0 {
                break;
            }
            match b.byte() % 4 {
                1 => solver_options_update_internal(parent, 0, b.id()),
                2 => {
                    let i = *(*parent).internalSolvers;
                    if !i.is_null() {
                        (*i).solverId = b.id();
                    }
                }
                _ => {}
            }
        }
        // Extreme values in random slots of the options and of their internal solvers.
        for _ in 0..(b.byte() % 8) {
            let sel = b.byte();
            let node = option_case_node(o, (sel % 3) as usize);
            if node.is_null() {
                continue;
            }
            let k = (b.byte() % 20) as usize;
            if sel & 4 == 0 {
                *(*node).iparam.add(k) = b.int();
            } else {
                *(*node).dparam.add(k) = b.double();
            }
        }
        // A short budget, so that every run ends (iteration counts may be INT_MAX).
        *(*o).dparam.add(19) = [1e-3, 2e-3, 5e-3, 5e-324][(flags >> 2) as usize % 4];

        // Broken trees and sizes; undone before the options are released.
        let saved_count = (*o).numberOfInternalSolvers;
        let saved_array = (*o).internalSolvers;
        let saved_sizes = ((*o).iSize, (*o).dSize);
        let mut cycle_at: *mut SolverOptions = std::ptr::null_mut();
        let mut cycle_saved: *mut SolverOptions = std::ptr::null_mut();
        match (flags >> 4) % 8 {
            1 => {
                // An options struct that is its own internal solver, directly or deeper.
                let at = option_case_node(o, (b.byte() % 3) as usize);
                if !at.is_null()
                    && (*at).numberOfInternalSolvers > 0
                    && !(*at).internalSolvers.is_null()
                {
                    cycle_at = at;
                    cycle_saved = *(*at).internalSolvers;
                    *(*at).internalSolvers = o;
                }
            }
            2 => {
                (*o).numberOfInternalSolvers = [1usize, 2, 1000, usize::MAX][b.byte() as usize % 4];
                (*o).internalSolvers = std::ptr::null_mut();
            }
            3 => {
                let s = [c_int::MIN, -1, 0, 1, 19, 20][b.byte() as usize % 6];
                if b.byte() % 2 == 0 {
                    (*o).iSize = s;
                } else {
                    (*o).dSize = s;
                }
            }
            _ => {}
        }
        option_case_check(&mut problem, o);
        // A copy of what the driver saw (refused when the tree is broken) solves the same way.
        if flags & 0x80 != 0 {
            let c = solver_options_copy(o);
            if !c.is_null() {
                option_case_check(&mut problem, c);
                option_case_release(c);
            }
        }
        if !cycle_at.is_null() {
            *(*cycle_at).internalSolvers = cycle_saved;
        }
        (*o).numberOfInternalSolvers = saved_count;
        (*o).internalSolvers = saved_array;
        ((*o).iSize, (*o).dSize) = saved_sizes;
        option_case_release(o);
    }
}
