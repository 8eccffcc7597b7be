// One fuzz case of `fc3d_driver`, shared by the fuzz target (fuzz/fuzz_targets/driver.rs) and the
// regression test over saved crashes (tests/fuzz_regressions.rs), which include this file.

use std::os::raw::{c_double, c_int};

use fc3d::types::{FrictionContactProblem, NumericsMatrix, SolverOptions};

extern "C" {
    fn solver_options_create(id: c_int) -> *mut SolverOptions;
    fn solver_options_delete(o: *mut SolverOptions);
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
    fn free(p: *mut std::ffi::c_void);
}

/// Reads the fuzzer's bytes as a stream of small decisions.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    /// A value that is usually ordinary and sometimes extreme.
    fn value(&mut self) -> f64 {
        const SPECIAL: [f64; 10] = [
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e300,
            1e-300,
            f64::MIN_POSITIVE / 4.0,
            f64::EPSILON,
        ];
        let b = self.byte();
        match b % 16 {
            0 => SPECIAL[(self.byte() % 10) as usize],
            1 => {
                let mut x = [0u8; 8];
                x.iter_mut().for_each(|v| *v = self.byte());
                f64::from_le_bytes(x)
            }
            _ => (self.byte() as f64 - 128.0) / 16.0,
        }
    }
}

const IDS: [c_int; 16] = [500, 501, 502, 503, 504, 505, 506, 507, 511, 512, 513, 516, 517, 520, 522, 523];

/// Runs one input; panics (assert) on any broken promise of the C contract.
pub fn run_driver_case(data: &[u8]) {
    let mut b = Bytes(data);
    let flags = b.byte();
    let nc = (b.byte() % 5) as usize;
    let n = 3 * nc;
    let mut w = vec![0.0; n * n];
    if flags & 1 == 0 {
        // A well-posed W: B B^T + I with B from the bytes (solvers get to iterate).
        let bm: Vec<f64> = (0..n * n).map(|_| (b.byte() as f64 - 128.0) / 64.0).collect();
        for i in 0..n {
            for j in 0..n {
                let mut s = if i == j { 1.0 } else { 0.0 };
                for k in 0..n {
                    s += bm[i * n + k] * bm[j * n + k];
                }
                w[i + j * n] = s;
            }
        }
        if flags & 2 != 0 && n > 0 {
            let k = b.byte() as usize % (n * n);
            w[k] = b.value();
        }
    } else {
        w.iter_mut().for_each(|x| *x = b.value());
    }
    let mut q: Vec<f64> = (0..n).map(|_| b.value()).collect();
    let mut mu: Vec<f64> = (0..nc)
        .map(|_| if flags & 4 == 0 { (b.byte() % 20) as f64 / 10.0 } else { b.value() })
        .collect();
    let id = IDS[(b.byte() as usize) % IDS.len()];
    let local = 550 + (b.byte() % 20) as c_int;

    // SAFETY: an all-zero NumericsMatrix is a valid empty value (NULL pointers).
    let mut m: NumericsMatrix = unsafe { std::mem::zeroed() };
    m.storageType = if flags & 8 != 0 { (b.byte() % 5) as c_int } else { 0 };
    m.size0 = n as c_int;
    m.size1 = n as c_int;
    if flags & 16 != 0 {
        m.size0 += (b.byte() % 3) as c_int - 1;
    }
    m.matrix0 = w.as_mut_ptr();
    let mut problem = FrictionContactProblem {
        dimension: if flags & 32 != 0 { (b.byte() % 4) as c_int } else { 3 },
        numberOfContacts: nc as c_int,
        M: &mut m,
        q: q.as_mut_ptr(),
        mu: mu.as_mut_ptr(),
    };
    unsafe {
        let o = solver_options_create(id);
        if o.is_null() {
            return;
        }
        if id == 500 && flags & 64 != 0 {
            solver_options_update_internal(o, 0, local);
        }
        for _ in 0..(b.byte() % 4) {
            let k = (b.byte() % 20) as usize;
            *(*o).iparam.add(k) = b.byte() as i8 as c_int;
        }
        for _ in 0..(b.byte() % 4) {
            let k = (b.byte() % 20) as usize;
            *(*o).dparam.add(k) = b.value();
        }
        // Bounded work per input: at most 50 iterations and 5 ms (millions of inputs must run).
        let it = (*o).iparam;
        *it = (*it).clamp(0, 50);
        *(*o).dparam.add(fc3d::FC3D_DPARAM_TIME_BUDGET as usize) = 0.005;
        *(*o).iparam.add(1) = -12345;
        *(*o).dparam.add(1) = -12345.0;
        let sentinel = 7.25;
        let mut r = vec![sentinel; n];
        let mut u = vec![sentinel; n];
        let rc = fc3d_driver(&mut problem, r.as_mut_ptr(), u.as_mut_ptr(), o);
        if rc >= 0 {
            assert!(rc <= 4, "return code {rc}");
            assert!(r.iter().chain(&u).all(|x| x.is_finite()), "non-finite output: rc {rc} r {r:?} u {u:?}");
            let mut e = f64::NAN;
            let mut w2 = vec![0.0; n];
            // ||q|| without overflow (q may hold 1e300): a naive sum of squares gives inf, and
            // fc3d_compute_error then divides by it (the first crash this target found was
            // that harness bug, kept in fuzz/regressions/driver).
            let qn = q.iter().fold(0.0f64, |a, &x| a.hypot(x));
            let ec = fc3d_compute_error(&mut problem, r.as_mut_ptr(), w2.as_mut_ptr(), 1e-4, o, qn, &mut e);
            assert!(ec >= 0, "compute_error rejected what the driver accepted");
            let reported = *(*o).dparam.add(1);
            // Equal up to the rounding of ||q||: the host computes the norm it passes to
            // fc3d_compute_error its own way (the second saved crash: 1 ulp apart).
            assert!(
                reported == e || (reported - e).abs() <= 1e-14 * reported.abs().max(e.abs()),
                "dparam[1] {reported} vs recomputed {e}"
            );
        } else {
            assert!(r.iter().chain(&u).all(|&x| x == sentinel), "outputs written on failure");
            assert_eq!(*(*o).iparam.add(1), -12345);
            assert_eq!(*(*o).dparam.add(1), -12345.0);
        }
        solver_options_delete(o);
        free(o.cast());
    }
}
