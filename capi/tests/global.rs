//! The global family through the C ABI (issue 26) on every global problem of
//! `../shared/data/siconos`: `gfc3d_driver` with every id it runs returns finite `(r, u, v)` with
//! `M v = q + H r` to round-off and `u = H^T v + b`, leaves the caller's M, H, q, b and mu
//! unchanged byte for byte, writes `iparam[1]` and a `dparam[1]` equal to an independent
//! recomputation of `gfc3d_compute_error`; hostile inputs are refused with a negative code and
//! nothing written; the LMGC and global rolling drivers. Files, copies and reformulations:
//! `global_files.rs`.

use std::ffi::{c_char, c_double, c_int, c_uint};
use std::ptr::{null, null_mut};

use fc3d::types::{
    GlobalFrictionContactProblem, GlobalRollingFrictionContactProblem, NumericsMatrix,
};
use fc3d::{
    FC3D_ERR_INVALID_OPTION, FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_INVALID_SIZE, FC3D_ERR_NON_FINITE,
    FC3D_ERR_NULL_POINTER, FC3D_ERR_UNSUPPORTED_SOLVER,
};
use fc3d_core::matrix::CsrMatrix;
use fc3d_core::problem::GlobalProblem;

mod siconos_api;

mod global_api;
use global_api::*;

#[test]
fn every_id_solves_every_global_file_honestly() {
    if !available() {
        return;
    }
    for &name in GLOBAL_FILES {
        let core = core_problem(name);
        let (n, m) = (core.ndof(), core.size());
        for id in IDS {
            let p = CProblem::read(name);
            let before = unsafe { problem_bytes(p.get()) };
            let o = Options::new(id, 1e-5, 10000);
            o.set_iparam(1, -7);
            let (mut r, mut u, mut v) = (vec![0.0; m], vec![0.0; m], vec![0.0; n]);
            let info =
                unsafe { gfc3d_driver(p.0, r.as_mut_ptr(), u.as_mut_ptr(), v.as_mut_ptr(), o.0) };
            let what = format!("{name} with {id}");
            assert!(info >= 0, "{what}: {info} {}", last_message());
            assert!(o.iparam(1) >= 0, "{what}: iparam[1] not written");
            for x in r.iter().chain(&u).chain(&v) {
                assert!(x.is_finite(), "{what}: non-finite result");
            }
            // The caller's problem is untouched.
            assert!(
                before == unsafe { problem_bytes(p.get()) },
                "{what}: problem modified"
            );
            // M v = q + H r to round-off, u = H^T v + b.
            let mut mv = vec![0.0; n];
            core.m().mul_add(&v, &mut mv);
            let mut hr = vec![0.0; n];
            core.h().mul_add(&r, &mut hr);
            let residual: Vec<f64> = (0..n).map(|i| core.q()[i] + hr[i] - mv[i]).collect();
            let scale = norm(core.q()).max(norm(&mv)).max(norm(&hr)).max(1.0);
            assert!(
                norm(&residual) <= 1e-12 * scale,
                "{what}: ||q + H r - M v|| = {:e}",
                norm(&residual)
            );
            let mut ht_v = core.b().to_vec();
            fc3d_core::matrix::transpose_mul_add(core.h(), &v, &mut ht_v);
            for (a, b) in u.iter().zip(&ht_v) {
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
                    "{what}: u != H^T v + b"
                );
            }
            // dparam[1] is gfc3d_compute_error of the returned triple, recomputed.
            let (mut u2, mut e) = (vec![0.0; m], f64::NAN);
            let code = unsafe {
                gfc3d_compute_error(
                    p.0,
                    r.as_mut_ptr(),
                    u2.as_mut_ptr(),
                    v.as_mut_ptr(),
                    1e-5,
                    null_mut(),
                    norm(core.q()),
                    0.0,
                    &mut e,
                )
            };
            assert!(code >= 0, "{what}: {}", last_message());
            assert_eq!(o.dparam(1), e, "{what}: dparam[1] vs gfc3d_compute_error");
            let core_error = fc3d_core::measure::global_error(
                &core,
                fc3d_core::measure::ContactLaw::Coulomb,
                &r,
                &mut u2,
                &v,
            );
            assert!((core_error - e).abs() <= 1e-14 * (1.0 + e), "{what}");
            if info == 0 {
                assert!(e <= 1e-5, "{what}: info 0 with error {e:e}");
            }
        }
    }
}

/// Sentinel arrays for a refused call: nothing may be written.
struct Outputs {
    r: Vec<f64>,
    u: Vec<f64>,
    v: Vec<f64>,
}

impl Outputs {
    fn new(m: usize, n: usize) -> Self {
        Outputs {
            r: vec![0.25; m],
            u: vec![7.0; m],
            v: vec![-3.0; n],
        }
    }
    fn untouched(&self) -> bool {
        self.r.iter().all(|&x| x == 0.25)
            && self.u.iter().all(|&x| x == 7.0)
            && self.v.iter().all(|&x| x == -3.0)
    }
}

/// A problem whose data the test owns: dense M (`n x n`), dense H (`n x 3nc`).
struct Owned {
    m: Vec<f64>,
    h: Vec<f64>,
    q: Vec<f64>,
    b: Vec<f64>,
    mu: Vec<f64>,
    nm: NumericsMatrix,
    nh: NumericsMatrix,
    problem: GlobalFrictionContactProblem,
}

impl Owned {
    /// Two bodies of 3 unknowns, M = diag(2), H = I (6 x 6), 2 contacts pushed in.
    fn new() -> Box<Self> {
        let n = 6;
        let mut m = vec![0.0; n * n];
        let mut h = vec![0.0; n * n];
        for i in 0..n {
            m[i + n * i] = 2.0;
            h[i + n * i] = 1.0;
        }
        let mut o = Box::new(Owned {
            m,
            h,
            q: vec![-1.0, 0.2, 0.0, -0.5, 0.0, 0.1],
            b: vec![0.0; n],
            mu: vec![0.5, 0.3],
            nm: unsafe { std::mem::zeroed() },
            nh: unsafe { std::mem::zeroed() },
            problem: unsafe { std::mem::zeroed() },
        });
        o.nm.storageType = 0;
        o.nm.size0 = n as c_int;
        o.nm.size1 = n as c_int;
        o.nm.matrix0 = o.m.as_mut_ptr();
        o.nh.storageType = 0;
        o.nh.size0 = n as c_int;
        o.nh.size1 = n as c_int;
        o.nh.matrix0 = o.h.as_mut_ptr();
        o.problem.dimension = 3;
        o.problem.numberOfContacts = 2;
        o.problem.M = &mut o.nm;
        o.problem.H = &mut o.nh;
        o.problem.q = o.q.as_mut_ptr();
        o.problem.b = o.b.as_mut_ptr();
        o.problem.mu = o.mu.as_mut_ptr();
        o
    }

    fn solve(&mut self, options: &Options) -> (c_int, Outputs) {
        let mut out = Outputs::new(6, 6);
        let info = unsafe {
            gfc3d_driver(
                &mut self.problem,
                out.r.as_mut_ptr(),
                out.u.as_mut_ptr(),
                out.v.as_mut_ptr(),
                options.0,
            )
        };
        (info, out)
    }
}

/// A hostile input: what it is, how it spoils a valid problem, the code it must get.
type Spoiled = (&'static str, Box<dyn Fn(&mut Owned)>, c_int);

#[test]
fn a_small_problem_solves_and_hostile_inputs_are_refused_writing_nothing() {
    let o = Options::new(600, 1e-10, 1000);
    let mut p = Owned::new();
    let (info, out) = p.solve(&o);
    assert_eq!(info, 0, "{}", last_message());
    assert!(o.dparam(1) <= 1e-10);
    // Contact 0 pushed in with q_T inside the cone: sticks with u = 0.
    assert!(out.u[..3].iter().all(|x| x.abs() < 1e-9), "{:?}", out.u);

    let cases: Vec<Spoiled> = vec![
        (
            "NaN in q",
            Box::new(|p| p.q[1] = f64::NAN),
            FC3D_ERR_NON_FINITE,
        ),
        (
            "inf in M",
            Box::new(|p| p.m[7] = f64::INFINITY),
            FC3D_ERR_NON_FINITE,
        ),
        (
            "negative mu",
            Box::new(|p| p.mu[1] = -0.1),
            FC3D_ERR_INVALID_PROBLEM,
        ),
        (
            "non-square M",
            Box::new(|p| p.nm.size1 = 5),
            FC3D_ERR_INVALID_SIZE,
        ),
        (
            "H rows != M size",
            Box::new(|p| p.nh.size0 = 5),
            FC3D_ERR_INVALID_SIZE,
        ),
        (
            "negative contacts",
            Box::new(|p| p.problem.numberOfContacts = -1),
            FC3D_ERR_INVALID_SIZE,
        ),
        (
            "H columns != 3 nc",
            Box::new(|p| p.problem.numberOfContacts = 3),
            FC3D_ERR_INVALID_SIZE,
        ),
        (
            "NULL q",
            Box::new(|p| p.problem.q = null_mut()),
            FC3D_ERR_NULL_POINTER,
        ),
        (
            "NULL H",
            Box::new(|p| p.problem.H = null_mut()),
            FC3D_ERR_NULL_POINTER,
        ),
        (
            "dimension 2",
            Box::new(|p| p.problem.dimension = 2),
            FC3D_ERR_INVALID_PROBLEM,
        ),
        (
            "unknown storage",
            Box::new(|p| p.nm.storageType = 9),
            fc3d::FC3D_ERR_INVALID_STORAGE,
        ),
    ];
    for (what, spoil, code) in cases {
        let mut p = Owned::new();
        spoil(&mut p);
        let (info, out) = p.solve(&o);
        assert_eq!(info, code, "{what}: {}", last_message());
        assert!(out.untouched(), "{what}: outputs written");
    }
    // A singular M: refused (a negative code), nothing written.
    let mut p = Owned::new();
    p.m[0] = 0.0;
    let (info, out) = p.solve(&o);
    assert!(info < 0, "singular M: {info}");
    assert!(last_message().contains("singular"), "{}", last_message());
    assert!(out.untouched());
    // NULL arrays and options.
    let mut p = Owned::new();
    let mut out = Outputs::new(6, 6);
    for (r, u, v, options) in [
        (null_mut(), out.u.as_mut_ptr(), out.v.as_mut_ptr(), o.0),
        (out.r.as_mut_ptr(), null_mut(), out.v.as_mut_ptr(), o.0),
        (out.r.as_mut_ptr(), out.u.as_mut_ptr(), null_mut(), o.0),
        (
            out.r.as_mut_ptr(),
            out.u.as_mut_ptr(),
            out.v.as_mut_ptr(),
            null_mut(),
        ),
    ] {
        let info = unsafe { gfc3d_driver(&mut p.problem, r, u, v, options) };
        assert_eq!(info, FC3D_ERR_NULL_POINTER);
    }
    assert!(out.untouched());
    let info = unsafe {
        gfc3d_driver(
            null_mut(),
            out.r.as_mut_ptr(),
            out.u.as_mut_ptr(),
            out.v.as_mut_ptr(),
            o.0,
        )
    };
    assert_eq!(info, FC3D_ERR_NULL_POINTER);
    // No contacts (H with no columns): v = M^-1 q, as Siconos.
    let mut p = Owned::new();
    p.problem.numberOfContacts = 0;
    p.nh.size1 = 0;
    let (info, out) = p.solve(&o);
    assert_eq!(info, 0, "{}", last_message());
    for (v, q) in out.v.iter().zip(&p.q) {
        assert_eq!(*v, q / 2.0);
    }
    // A NaN initial reaction.
    let mut p = Owned::new();
    let mut out = Outputs::new(6, 6);
    out.r[2] = f64::NAN;
    let info = unsafe {
        gfc3d_driver(
            &mut p.problem,
            out.r.as_mut_ptr(),
            out.u.as_mut_ptr(),
            out.v.as_mut_ptr(),
            o.0,
        )
    };
    assert_eq!(info, FC3D_ERR_NON_FINITE, "{}", last_message());
    assert!(out.u.iter().all(|&x| x == 7.0));
}

#[test]
fn ids_fc3d_does_not_run_are_refused_with_the_reason() {
    let mut p = Owned::new();
    for (id, says) in [
        (601, "exits"),
        (608, "GAMS"),
        (609, "GAMS"),
        (5000, "g_rolling_fc3d_driver"),
        (500, "not a global friction solver"),
    ] {
        let o = Options::new(id, 1e-5, 100);
        o.set_iparam(1, -7);
        let (info, out) = p.solve(&o);
        assert_eq!(info, FC3D_ERR_UNSUPPORTED_SOLVER, "{id}");
        assert!(last_message().contains(says), "{id}: {}", last_message());
        assert!(out.untouched());
        assert_eq!(o.iparam(1), -7, "{id}: iparam[1] written on a refusal");
    }
    // A solver entry with options of another id.
    let o = Options::new(602, 1e-5, 100);
    let mut out = Outputs::new(6, 6);
    let mut info = 99;
    unsafe {
        gfc3d_nsgs_wr(
            &mut p.problem,
            out.r.as_mut_ptr(),
            out.u.as_mut_ptr(),
            out.v.as_mut_ptr(),
            &mut info,
            o.0,
        )
    };
    assert_eq!(info, FC3D_ERR_INVALID_OPTION);
    // A _WR id whose local rescaling Siconos would not apply.
    let o = Options::new(600, 1e-5, 100);
    o.set_iparam(3, 1);
    let (info, _) = p.solve(&o);
    assert_eq!(info, FC3D_ERR_INVALID_OPTION, "{}", last_message());
}

/// A problem as LMGC90 hands it over: M and H in 1-based coordinates, q, b, mu; its options.
struct Lmgc {
    m: (Vec<c_double>, Vec<c_uint>, Vec<c_uint>),
    h: (Vec<c_double>, Vec<c_uint>, Vec<c_uint>),
    q: Vec<f64>,
    b: Vec<f64>,
    mu: Vec<f64>,
    iparam: [c_int; 20],
    dparam: [c_double; 20],
}

/// The entries of a matrix in 1-based coordinates, as LMGC90 gives them.
fn coordinates(m: &CsrMatrix) -> (Vec<c_double>, Vec<c_uint>, Vec<c_uint>) {
    let (mut x, mut r, mut c) = (Vec::new(), Vec::new(), Vec::new());
    m.for_each_entry(|i, j, v| {
        x.push(v);
        r.push(i as c_uint + 1);
        c.push(j as c_uint + 1);
    });
    (x, r, c)
}

impl Lmgc {
    fn of(p: &GlobalProblem<'_>) -> Self {
        Lmgc {
            m: coordinates(p.m()),
            h: coordinates(p.h()),
            q: p.q().to_vec(),
            b: p.b().to_vec(),
            mu: p.mu().to_vec(),
            iparam: [0; 20],
            dparam: [0.0; 20],
        }
    }

    /// `gfc3d_LmgcDriver` with solver 600 into `r`, `u`, `v`.
    fn solve(&mut self, r: &mut [f64], u: &mut [f64], v: &mut [f64]) -> c_int {
        let (n, nc) = (self.q.len(), self.mu.len());
        unsafe {
            gfc3d_LmgcDriver(
                r.as_mut_ptr(),
                u.as_mut_ptr(),
                v.as_mut_ptr(),
                self.q.as_mut_ptr(),
                self.b.as_mut_ptr(),
                self.mu.as_mut_ptr(),
                self.m.0.as_mut_ptr(),
                self.m.0.len() as c_uint,
                self.m.1.as_mut_ptr(),
                self.m.2.as_mut_ptr(),
                self.h.0.as_mut_ptr(),
                self.h.0.len() as c_uint,
                self.h.1.as_mut_ptr(),
                self.h.2.as_mut_ptr(),
                n as c_uint,
                nc as c_uint,
                600,
                20,
                self.iparam.as_mut_ptr(),
                20,
                self.dparam.as_mut_ptr(),
                0,
                0,
                0,
            )
        }
    }
}

#[test]
fn lmgc_driver_gives_gfc3d_drivers_answer() {
    if !available() {
        return;
    }
    let name = "GFC3D_TwoRods1.dat";
    let core = core_problem(name);
    let (n, m) = (core.ndof(), core.size());
    let mut lmgc = Lmgc::of(&core);
    lmgc.dparam[0] = 1e-8;
    lmgc.iparam[0] = 5000;
    let (mut r, mut u, mut v) = (vec![0.0; m], vec![0.0; m], vec![0.0; n]);
    let info = lmgc.solve(&mut r, &mut u, &mut v);
    assert_eq!(info, 0, "{}", last_message());
    assert!(lmgc.iparam[1] > 0);
    assert_eq!(lmgc.dparam[0], 1e-8);
    assert!(lmgc.dparam[1] <= 1e-8);
    // gfc3d_driver on the file's problem with the same options.
    let p = CProblem::read(name);
    let o = Options::new(600, 1e-8, 5000);
    let (mut r2, mut u2, mut v2) = (vec![0.0; m], vec![0.0; m], vec![0.0; n]);
    let info = unsafe { gfc3d_driver(p.0, r2.as_mut_ptr(), u2.as_mut_ptr(), v2.as_mut_ptr(), o.0) };
    assert_eq!(info, 0);
    assert_eq!((&r, &v, o.iparam(1)), (&r2, &v2, lmgc.iparam[1]));
    // An index outside the matrix is refused, nothing written.
    lmgc.m.1[0] = n as c_uint + 1;
    let mut r3 = vec![0.5; m];
    assert_eq!(lmgc.solve(&mut r3, &mut u, &mut v), FC3D_ERR_INVALID_SIZE);
    assert!(r3.iter().all(|&x| x == 0.5));
}

#[test]
fn the_global_rolling_driver_solves_with_5000() {
    // Two bodies of 5 unknowns, M = diag(1, 2, ...), H = I, 2 rolling contacts pushed in.
    let n = 10;
    let mut mdata = vec![0.0; n * n];
    let mut hdata = vec![0.0; n * n];
    for i in 0..n {
        mdata[i + n * i] = 1.0 + i as f64;
        hdata[i + n * i] = 1.0;
    }
    let mut q: Vec<f64> = (0..n)
        .map(|i| if i % 5 == 0 { -1.0 } else { 0.1 })
        .collect();
    let mut b = vec![0.0; n];
    let (mut mu, mut mu_r) = (vec![0.5, 0.4], vec![0.05, 0.1]);
    let mut nm: NumericsMatrix = unsafe { std::mem::zeroed() };
    nm.size0 = n as c_int;
    nm.size1 = n as c_int;
    nm.matrix0 = mdata.as_mut_ptr();
    let mut nh: NumericsMatrix = unsafe { std::mem::zeroed() };
    nh.size0 = n as c_int;
    nh.size1 = n as c_int;
    nh.matrix0 = hdata.as_mut_ptr();
    let mut p = GlobalRollingFrictionContactProblem {
        dimension: 5,
        numberOfContacts: 2,
        M: &mut nm,
        H: &mut nh,
        q: q.as_mut_ptr(),
        b: b.as_mut_ptr(),
        mu: mu.as_mut_ptr(),
        mu_r: mu_r.as_mut_ptr(),
    };
    let o = Options::new(5000, 1e-10, 1000);
    let (mut r, mut u, mut v) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let info = unsafe {
        g_rolling_fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), v.as_mut_ptr(), o.0)
    };
    assert_eq!(info, 0, "{}", last_message());
    assert!(o.dparam(1) <= 1e-10);
    for i in 0..n {
        // M v = q + r (H = I).
        assert!((mdata[i + n * i] * v[i] - q[i] - r[i]).abs() < 1e-12);
        assert_eq!(u[i], v[i]);
    }
    // Options of the plain global solver are refused.
    let o = Options::new(600, 1e-10, 1000);
    let info = unsafe {
        g_rolling_fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), v.as_mut_ptr(), o.0)
    };
    assert_eq!(info, FC3D_ERR_UNSUPPORTED_SOLVER);
    let _ = null::<c_char>();
}
