//! The native global entry (`fc3d_solve_global_csr`, `_coo`, `_blocks` of fc3d_native.h) as a
//! host calls it: on every global problem of `../shared/data/siconos` with the ids a host would
//! pick, `M v = q + H r` to round-off, `u = H^T v + b`, the result's error equal to an
//! independent recomputation of Siconos' global error, the three storages agreeing on a generated
//! scene; settings of every global id; hostile input refused with a negative code, a message and
//! nothing written.

use std::ffi::{c_char, c_double, c_int, c_void, CStr};
use std::ptr::{null, null_mut};

use fc3d::{
    Fc3dResult, FC3D_ERR_INVALID_SIZE, FC3D_ERR_NON_FINITE, FC3D_ERR_NULL_POINTER,
    FC3D_ERR_UNSUPPORTED_SOLVER,
};
use fc3d_core::global::{global_error, ContactLaw, GlobalProblem};
use fc3d_core::io::dat::{read_global_dat_file, GlobalDatProblem};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
use fc3d_core::CsrMatrix;

extern "C" {
    fn fc3d_settings_new(id: c_int) -> *mut c_void;
    fn fc3d_settings_free(s: *mut c_void);
    fn fc3d_settings_set_tolerance(s: *mut c_void, t: c_double) -> c_int;
    fn fc3d_settings_set_max_iter(s: *mut c_void, m: i64) -> c_int;
    fn fc3d_settings_set_local_solver(s: *mut c_void, id: c_int) -> c_int;
    fn fc3d_last_error_message() -> *const c_char;
    fn fc3d_solve_global_csr(
        ndof: i64,
        n_contacts: i64,
        m_nnz: i64,
        m_row_ptr: *const i64,
        m_col_idx: *const i64,
        m_values: *const c_double,
        h_nnz: i64,
        h_row_ptr: *const i64,
        h_col_idx: *const i64,
        h_values: *const c_double,
        q: *const c_double,
        b: *const c_double,
        mu: *const c_double,
        r: *mut c_double,
        u: *mut c_double,
        v: *mut c_double,
        settings: *const c_void,
        result: *mut Fc3dResult,
    ) -> c_int;
    fn fc3d_solve_global_coo(
        ndof: i64,
        n_contacts: i64,
        m_nnz: i64,
        m_rows: *const i64,
        m_cols: *const i64,
        m_values: *const c_double,
        h_nnz: i64,
        h_rows: *const i64,
        h_cols: *const i64,
        h_values: *const c_double,
        q: *const c_double,
        b: *const c_double,
        mu: *const c_double,
        r: *mut c_double,
        u: *mut c_double,
        v: *mut c_double,
        settings: *const c_void,
        result: *mut Fc3dResult,
    ) -> c_int;
    fn fc3d_solve_global_blocks(
        n_blocks: i64,
        block_size: i64,
        m_blocks: *const c_double,
        n_contacts: i64,
        h_nnz: i64,
        h_row_ptr: *const i64,
        h_col_idx: *const i64,
        h_values: *const c_double,
        q: *const c_double,
        b: *const c_double,
        mu: *const c_double,
        r: *mut c_double,
        u: *mut c_double,
        v: *mut c_double,
        settings: *const c_void,
        result: *mut Fc3dResult,
    ) -> c_int;
    fn fc3d_solve_dense(
        n_contacts: i64,
        w: *const c_double,
        q: *const c_double,
        mu: *const c_double,
        r: *mut c_double,
        u: *mut c_double,
        settings: *const c_void,
        result: *mut Fc3dResult,
    ) -> c_int;
}

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn message() -> String {
    unsafe { CStr::from_ptr(fc3d_last_error_message()) }
        .to_string_lossy()
        .into_owned()
}

/// Settings of `id` with a tolerance and an iteration limit, freed on drop.
struct Settings(*mut c_void);

impl Settings {
    fn new(id: c_int, tol: f64, max_iter: i64) -> Settings {
        let s = unsafe { fc3d_settings_new(id) };
        assert!(!s.is_null(), "settings of {id}: {}", message());
        assert_eq!(unsafe { fc3d_settings_set_tolerance(s, tol) }, 0);
        assert_eq!(unsafe { fc3d_settings_set_max_iter(s, max_iter) }, 0);
        Settings(s)
    }
}

impl Drop for Settings {
    fn drop(&mut self) {
        unsafe { fc3d_settings_free(self.0) }
    }
}

/// A matrix as the C entry takes it: compressed rows with `int64_t` indices.
struct Csr {
    ptr: Vec<i64>,
    idx: Vec<i64>,
    val: Vec<f64>,
}

fn csr(a: &CsrMatrix) -> Csr {
    Csr {
        ptr: a.row_ptr().iter().map(|&x| x as i64).collect(),
        idx: a.col_idx().iter().map(|&x| x as i64).collect(),
        val: a.values().to_vec(),
    }
}

/// The result of a solve: (code, r, u, v, result).
type Outcome = (c_int, Vec<f64>, Vec<f64>, Vec<f64>, Fc3dResult);

fn solve_csr(p: &GlobalProblem<'_>, settings: *const c_void) -> Outcome {
    let (m, h) = (csr(p.m()), csr(p.h()));
    let (n, size) = (p.ndof(), p.size());
    let (mut r, mut u, mut v) = (vec![0.0; size], vec![0.0; size], vec![0.0; n]);
    let mut res = Fc3dResult::default();
    let code = unsafe {
        fc3d_solve_global_csr(
            n as i64,
            p.n_contacts() as i64,
            m.val.len() as i64,
            m.ptr.as_ptr(),
            m.idx.as_ptr(),
            m.val.as_ptr(),
            h.val.len() as i64,
            h.ptr.as_ptr(),
            h.idx.as_ptr(),
            h.val.as_ptr(),
            p.q().as_ptr(),
            p.b().as_ptr(),
            p.mu().as_ptr(),
            r.as_mut_ptr(),
            u.as_mut_ptr(),
            v.as_mut_ptr(),
            settings,
            &mut res,
        )
    };
    (code, r, u, v, res)
}

/// `|q + H r - M v|` relative to `|q| + |H r|`, and `|u - H^T v - b|`.
fn residuals(p: &GlobalProblem<'_>, r: &[f64], u: &[f64], v: &[f64]) -> (f64, f64) {
    let (mut hr, mut mv) = (vec![0.0; p.ndof()], vec![0.0; p.ndof()]);
    p.h().mul_add(r, &mut hr);
    p.m().mul_add(v, &mut mv);
    let norm = |x: &[f64]| x.iter().map(|a| a * a).sum::<f64>().sqrt();
    let balance: Vec<f64> = (0..p.ndof()).map(|i| p.q()[i] + hr[i] - mv[i]).collect();
    let mut ht_v = p.b().to_vec();
    fc3d_core::matrix::transpose_mul_add(p.h(), v, &mut ht_v);
    let du: Vec<f64> = u.iter().zip(&ht_v).map(|(a, b)| a - b).collect();
    (
        norm(&balance) / (norm(p.q()) + norm(&hr)).max(1e-300),
        norm(&du),
    )
}

fn shared_problems() -> Vec<(String, GlobalProblem<'static>)> {
    let Ok(entries) = std::fs::read_dir(DATA) else {
        eprintln!("{DATA} missing: skipped");
        return Vec::new();
    };
    let mut names: Vec<String> = entries
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with("GFC3D_") && n.ends_with(".dat") && !n.contains("condensed"))
        .collect();
    names.sort();
    names
        .into_iter()
        .filter_map(|n| {
            match read_global_dat_file(&std::path::Path::new(DATA).join(&n))
                .unwrap()
                .problem
            {
                GlobalDatProblem::Spatial(p) => Some((n, p)),
                GlobalDatProblem::Planar(_) => None,
            }
        })
        .collect()
}

#[test]
fn every_shared_global_problem_through_the_native_entry() {
    let problems = shared_problems();
    for (name, p) in &problems {
        for id in [600, 602, 605, 606, 607, 614] {
            let s = Settings::new(id, 1e-8, 2000);
            for coo in [false, true] {
                let what = format!("{name} with {id} (triplets: {coo})");
                let (code, r, mut u, v, res) = if coo {
                    solve_coo(p, s.0)
                } else {
                    solve_csr(p, s.0)
                };
                assert!(code >= 0, "{what}: {code} {}", message());
                assert_eq!(code, res.info, "{what}");
                let (balance, du) = residuals(p, &r, &u, &v);
                assert!(balance <= 1e-10, "{what}: M v = q + H r off by {balance:e}");
                assert!(du <= 1e-10, "{what}: u = H^T v + b off by {du:e}");
                let again = global_error(p, ContactLaw::Coulomb, &r, &mut u, &v);
                assert!(
                    (again - res.error).abs() <= 1e-12 * again.max(1.0),
                    "{what}: reported {:e}, recomputed {again:e}",
                    res.error
                );
                if res.info == 0 {
                    assert!(res.error <= 1e-8, "{what}: converged at {:e}", res.error);
                }
            }
        }
    }
    // The default (NULL settings): 600 with Siconos' defaults.
    if let Some((name, p)) = problems.iter().find(|(n, _)| n == "GFC3D_TwoRods1.dat") {
        let (code, ..) = solve_csr(p, null());
        assert_eq!(code, 0, "{name} with the default settings: {}", message());
    }
}

/// The triplets of a matrix, as the COO entry takes them.
fn triplets(a: &CsrMatrix) -> (Vec<i64>, Vec<i64>, Vec<f64>) {
    let mut rows = Vec::new();
    for i in 0..a.nrows() {
        rows.extend(std::iter::repeat_n(
            i as i64,
            a.row_ptr()[i + 1] - a.row_ptr()[i],
        ));
    }
    let cols = a.col_idx().iter().map(|&c| c as i64).collect();
    (rows, cols, a.values().to_vec())
}

fn solve_coo(p: &GlobalProblem<'_>, settings: *const c_void) -> Outcome {
    let (mr, mc, mv) = triplets(p.m());
    let (hr, hc, hv) = triplets(p.h());
    let (n, size) = (p.ndof(), p.size());
    let (mut r, mut u, mut v) = (vec![0.0; size], vec![0.0; size], vec![0.0; n]);
    let mut res = Fc3dResult::default();
    let code = unsafe {
        fc3d_solve_global_coo(
            n as i64,
            p.n_contacts() as i64,
            mv.len() as i64,
            mr.as_ptr(),
            mc.as_ptr(),
            mv.as_ptr(),
            hv.len() as i64,
            hr.as_ptr(),
            hc.as_ptr(),
            hv.as_ptr(),
            p.q().as_ptr(),
            p.b().as_ptr(),
            p.mu().as_ptr(),
            r.as_mut_ptr(),
            u.as_mut_ptr(),
            v.as_mut_ptr(),
            settings,
            &mut res,
        )
    };
    (code, r, u, v, res)
}

#[test]
fn the_three_storages_agree_on_a_generated_scene() {
    let scene = GeneratedScene {
        pile: PileSpec {
            contacts: 120,
            piles: 2,
            seed: 5,
        },
        shape: PileShape::Boxes,
    };
    let p = scene.generate_global().unwrap();
    let s = Settings::new(606, 1e-10, 200);
    let by_csr = solve_csr(&p, s.0);
    let by_coo = solve_coo(&p, s.0);
    // M as 6x6 diagonal blocks, column-major.
    let bodies = p.ndof() / 6;
    let mut blocks = vec![0.0; 36 * bodies];
    let m = p.m();
    for i in 0..p.ndof() {
        for k in m.row_ptr()[i]..m.row_ptr()[i + 1] {
            let j = m.col_idx()[k];
            assert_eq!(i / 6, j / 6, "M is block diagonal");
            blocks[36 * (i / 6) + 6 * (j % 6) + i % 6] = m.values()[k];
        }
    }
    let h = csr(p.h());
    let (mut r, mut u, mut v) = (
        vec![0.0; p.size()],
        vec![0.0; p.size()],
        vec![0.0; p.ndof()],
    );
    let mut res = Fc3dResult::default();
    let code = unsafe {
        fc3d_solve_global_blocks(
            bodies as i64,
            6,
            blocks.as_ptr(),
            p.n_contacts() as i64,
            h.val.len() as i64,
            h.ptr.as_ptr(),
            h.idx.as_ptr(),
            h.val.as_ptr(),
            p.q().as_ptr(),
            p.b().as_ptr(),
            p.mu().as_ptr(),
            r.as_mut_ptr(),
            u.as_mut_ptr(),
            v.as_mut_ptr(),
            s.0,
            &mut res,
        )
    };
    assert_eq!(by_csr.0, 0, "{}", message());
    assert!(by_csr.4.error <= 1e-10);
    assert_eq!((by_coo.0, code), (0, 0), "{}", message());
    assert_eq!(by_csr.1, by_coo.1, "CSR and COO give the same reaction");
    assert_eq!(by_csr.3, by_coo.3, "and the same v");
    for (a, b) in by_csr.1.iter().zip(&r) {
        assert!(
            (a - b).abs() <= 1e-9 * (1.0 + a.abs()),
            "blocks: {a} vs {b}"
        );
    }
    let (balance, du) = residuals(&p, &r, &u, &v);
    assert!(balance <= 1e-10 && du <= 1e-10);
}

#[test]
fn settings_of_every_global_id() {
    for id in 600..=615 {
        let s = unsafe { fc3d_settings_new(id) };
        match id {
            601 | 608 | 609 => {
                assert!(s.is_null(), "{id} is refused");
                assert!(message().contains(&id.to_string()), "{}", message());
            }
            _ => {
                assert!(!s.is_null(), "{id}: {}", message());
                unsafe { fc3d_settings_free(s) };
            }
        }
    }
    let rolling = unsafe { fc3d_settings_new(5000) };
    assert!(!rolling.is_null(), "5000: {}", message());
    unsafe { fc3d_settings_free(rolling) };
    // A _WR id takes its local solver's local solver.
    let s = Settings::new(600, 1e-8, 100);
    assert_eq!(
        unsafe { fc3d_settings_set_local_solver(s.0, 552) },
        0,
        "{}",
        message()
    );
    // Global settings on a local solve, and local ones on a global solve: refused.
    let (mut r, mut u) = ([0.0; 3], [0.0; 3]);
    let mut res = Fc3dResult::default();
    let w = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let code = unsafe {
        fc3d_solve_dense(
            1,
            w.as_ptr(),
            [-1.0, 0.0, 0.0].as_ptr(),
            [0.5].as_ptr(),
            r.as_mut_ptr(),
            u.as_mut_ptr(),
            s.0,
            &mut res,
        )
    };
    assert!(code < 0, "a global id on a local solve");
    let local = Settings::new(500, 1e-8, 100);
    let p = one_contact();
    let (code, r, ..) = solve_csr(&p, local.0);
    assert_eq!(code, FC3D_ERR_UNSUPPORTED_SOLVER);
    assert!(message().contains("not a global solver"), "{}", message());
    assert_eq!(r, [0.0; 3], "nothing written");
}

/// M = 2 I, H = I, q = (-2, 4, 0), b = 0, mu = 0.5.
fn one_contact() -> GlobalProblem<'static> {
    let eye = |x: f64| CsrMatrix::from_triplets(3, 3, &[(0, 0, x), (1, 1, x), (2, 2, x)]).unwrap();
    GlobalProblem::new(
        eye(2.0),
        eye(1.0),
        vec![-2.0, 4.0, 0.0],
        vec![0.0; 3],
        vec![0.5],
    )
    .unwrap()
}

#[test]
fn hostile_input_is_refused_and_nothing_is_written() {
    let p = one_contact();
    let (m, h) = (csr(p.m()), csr(p.h()));
    let nan_q = [f64::NAN, 0.0, 0.0];
    let singular = [0.0; 3];
    let bad_ptr = [0i64, 1, 2, 4];
    let bad_idx = [0i64, 1, 7];
    struct Case<'a> {
        what: &'a str,
        ndof: i64,
        nc: i64,
        m_ptr: *const i64,
        m_idx: *const i64,
        m_val: *const f64,
        q: *const f64,
        result: bool,
        code: c_int,
    }
    let good = Case {
        what: "",
        ndof: 3,
        nc: 1,
        m_ptr: m.ptr.as_ptr(),
        m_idx: m.idx.as_ptr(),
        m_val: m.val.as_ptr(),
        q: p.q().as_ptr(),
        result: true,
        code: 0,
    };
    let cases = [
        Case {
            what: "negative ndof",
            ndof: -3,
            code: FC3D_ERR_INVALID_SIZE,
            ..good
        },
        Case {
            what: "negative contacts",
            nc: -1,
            code: FC3D_ERR_INVALID_SIZE,
            ..good
        },
        Case {
            what: "NULL row_ptr",
            m_ptr: null(),
            code: FC3D_ERR_NULL_POINTER,
            ..good
        },
        Case {
            what: "NULL result",
            result: false,
            code: FC3D_ERR_NULL_POINTER,
            ..good
        },
        Case {
            what: "NaN in q",
            q: nan_q.as_ptr(),
            code: FC3D_ERR_NON_FINITE,
            ..good
        },
        Case {
            what: "singular M",
            m_val: singular.as_ptr(),
            code: 0, // the factorization's refusal, "M is singular"
            ..good
        },
        Case {
            what: "row_ptr[n] != nnz",
            m_ptr: bad_ptr.as_ptr(),
            code: FC3D_ERR_INVALID_SIZE,
            ..good
        },
        Case {
            what: "column out of range",
            m_idx: bad_idx.as_ptr(),
            code: 0, // any negative code: the storage's or the size's
            ..good
        },
    ];
    for c in cases {
        let (mut r, mut u, mut v) = ([7.0; 3], [7.0; 3], [7.0; 3]);
        let mut res = Fc3dResult {
            info: 42,
            ..Default::default()
        };
        let code = unsafe {
            fc3d_solve_global_csr(
                c.ndof,
                c.nc,
                3,
                c.m_ptr,
                c.m_idx,
                c.m_val,
                3,
                h.ptr.as_ptr(),
                h.idx.as_ptr(),
                h.val.as_ptr(),
                c.q,
                p.b().as_ptr(),
                p.mu().as_ptr(),
                r.as_mut_ptr(),
                u.as_mut_ptr(),
                v.as_mut_ptr(),
                null(),
                if c.result { &mut res } else { null_mut() },
            )
        };
        assert!(code < 0, "{}: {code}", c.what);
        if c.code != 0 {
            assert_eq!(code, c.code, "{}: {}", c.what, message());
        }
        assert!(!message().is_empty(), "{}", c.what);
        if c.what == "singular M" {
            assert!(message().contains("singular"), "{}", message());
        }
        assert_eq!(
            (r, u, v, res.info),
            ([7.0; 3], [7.0; 3], [7.0; 3], 42),
            "{}",
            c.what
        );
    }
    // A block size that overflows, and NULL blocks.
    let mut res = Fc3dResult::default();
    let (mut r, mut u, mut v) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for (nb, bs, blocks) in [(i64::MAX, 3, singular.as_ptr()), (1, 3, null())] {
        let code = unsafe {
            fc3d_solve_global_blocks(
                nb,
                bs,
                blocks,
                1,
                3,
                h.ptr.as_ptr(),
                h.idx.as_ptr(),
                h.val.as_ptr(),
                p.q().as_ptr(),
                p.b().as_ptr(),
                p.mu().as_ptr(),
                r.as_mut_ptr(),
                u.as_mut_ptr(),
                v.as_mut_ptr(),
                null(),
                &mut res,
            )
        };
        assert!(code < 0, "blocks {nb} x {bs}");
    }
}
