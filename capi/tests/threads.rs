//! Stack and threads (issue 13, item 7): hosts call fc3d from worker threads with small stacks,
//! several at a time. The file readers (`frictionContact_new_from_filename`,
//! `frictionContact_newFromFile` on a `FILE*`, the native `fc3d_problem_read`) and `fc3d_driver`
//! with solvers of every family (NSGS with three local solvers, the three nonsmooth Newton
//! solvers, PROX with NSN_AC and with NSGS, ADMM, which factorize; TFP, PFP, ACLMFP, SOCLCP and
//! the VI family) run on shared Siconos problems:
//! * once on a thread with an 8 MiB stack: the reference;
//! * on a thread with a 256 KiB stack (`std::thread::Builder::stack_size`);
//! * on 4 threads with 256 KiB stacks at the same time, each in another order.
//!
//! Every run must give the reference bit for bit (reaction, velocity, return code, `iparam[1]`,
//! `dparam[1]`, and the problem data read), and a rejected call reports its own message on its
//! own thread (`fc3d_last_error_message` is per thread). No time budget is set (it would make
//! results depend on the machine's load): iteration limits bound every run.

use std::ffi::{c_char, c_void, CStr, CString};
use std::os::raw::{c_double, c_int};
use std::path::PathBuf;

use fc3d::types::FrictionContactProblem;
use fc3d::{Fc3dResult, FC3D_ERR_INVALID_OPTION};

mod siconos_api;
use siconos_api::*;

extern "C" {
    fn frictionContact_newFromFile(file: *mut c_void) -> *mut FrictionContactProblem;
    fn fc3d_problem_read(path: *const c_char) -> *mut c_void;
    fn fc3d_problem_free(p: *mut c_void);
    fn fc3d_problem_contacts(p: *const c_void) -> i64;
    fn fc3d_problem_nnz(p: *const c_void) -> i64;
    fn fc3d_problem_get(
        p: *const c_void,
        row_ptr: *mut i64,
        col_idx: *mut i64,
        values: *mut c_double,
        q: *mut c_double,
        mu: *mut c_double,
    ) -> c_int;
    fn fc3d_problem_solve(
        p: *const c_void,
        r: *mut c_double,
        u: *mut c_double,
        s: *const c_void,
        res: *mut Fc3dResult,
    ) -> c_int;
    fn fc3d_settings_new(id: c_int) -> *mut c_void;
    fn fc3d_settings_free(s: *mut c_void);
    fn fc3d_settings_set_max_iter(s: *mut c_void, m: i64) -> c_int;
    fn fc3d_settings_set_tolerance(s: *mut c_void, t: c_double) -> c_int;
    fn fopen(path: *const c_char, mode: *const c_char) -> *mut c_void;
    fn fclose(f: *mut c_void) -> c_int;
}

const SMALL_STACK: usize = 256 << 10;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/siconos")
        .join(name)
}

/// Small and medium problems in dense and sparse-block storage (solved), and two large ones (read
/// and solved by a few iterations: the readers' and the factorizations' memory is sized by them).
const PROBLEMS: [(&str, c_int); 5] = [
    ("Rover1039.dat", 200),
    ("FC3D_Example1_SBM.dat", 200),
    ("NESpheres_10_1.dat", 100),
    ("Capsules-i101-404.dat", 5),
    ("RockPile_tob1.dat", 2),
];

/// Solver id and internal solver id (NSGS's local solver, PROX's internal solver).
const SOLVERS: [(c_int, Option<c_int>); 18] = [
    (500, None),
    (500, Some(551)),
    (500, Some(553)),
    (504, None),
    (513, None),
    (520, None),
    (502, None),
    (502, Some(500)),
    (523, None),
    (503, None),
    (522, None),
    (516, None),
    (517, None),
    (505, None),
    (506, None),
    (507, None),
    (511, None),
    (512, None),
];

/// One result, as bits.
#[derive(Debug, Clone, PartialEq)]
struct Record {
    label: String,
    bits: Vec<u64>,
}

fn bits(v: &[f64]) -> impl Iterator<Item = u64> + '_ {
    v.iter().map(|x| x.to_bits())
}

unsafe fn problem_bits(p: *mut FrictionContactProblem) -> Vec<u64> {
    let n = 3 * (*p).numberOfContacts as usize;
    let q = std::slice::from_raw_parts((*p).q, n);
    let mu = std::slice::from_raw_parts((*p).mu, n / 3);
    bits(q).chain(bits(mu)).collect()
}

/// `fc3d_driver` with `solver` on `p` from r = 0, `max_iter` iterations, tolerance 1e-12.
unsafe fn drive(
    p: *mut FrictionContactProblem,
    solver: (c_int, Option<c_int>),
    max_iter: c_int,
) -> Vec<u64> {
    let n = 3 * (*p).numberOfContacts as usize;
    let o = solver_options_create(solver.0);
    assert!(!o.is_null());
    if let Some(i) = solver.1 {
        solver_options_update_internal(o, 0, i);
    }
    *(*o).iparam = max_iter;
    *(*o).dparam = 1e-12;
    // Bounded inner solves (TFP, PFP, PROX).
    if (*o).numberOfInternalSolvers > 0 && solver.0 != 500 {
        let i = *(*o).internalSolvers;
        *(*i).iparam = (*(*i).iparam).min(20);
    }
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let rc = fc3d_driver(p, r.as_mut_ptr(), u.as_mut_ptr(), o);
    assert!(rc >= 0, "{solver:?}: {rc}");
    let mut out = vec![
        rc as u64,
        *(*o).iparam.add(1) as u64,
        (*(*o).dparam.add(1)).to_bits(),
    ];
    out.extend(bits(&r).chain(bits(&u)));
    solver_options_delete(o);
    free(o.cast());
    out
}

/// A rejected call on this thread: the message is this call's (`tag` is in it).
unsafe fn own_message(p: *mut FrictionContactProblem, tag: f64) {
    let n = 3 * (*p).numberOfContacts as usize;
    let o = solver_options_create(500);
    *(*o).dparam = -tag;
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    assert_eq!(
        fc3d_driver(p, r.as_mut_ptr(), u.as_mut_ptr(), o),
        FC3D_ERR_INVALID_OPTION
    );
    let m = CStr::from_ptr(fc3d_last_error_message())
        .to_string_lossy()
        .into_owned();
    assert!(
        m.contains(&format!("{}", -tag)),
        "another thread's message: {m}"
    );
    solver_options_delete(o);
    free(o.cast());
}

/// Everything, in an order that depends on `rotation`; the records sorted by label.
fn run_all(rotation: usize, tag: f64) -> Vec<Record> {
    let mut out = Vec::new();
    let mut problems: Vec<_> = PROBLEMS.to_vec();
    problems.rotate_left(rotation % PROBLEMS.len());
    for (name, max_iter) in problems {
        let path = CString::new(data(name).to_str().unwrap()).unwrap();
        unsafe {
            // By name.
            let p = frictionContact_new_from_filename(path.as_ptr());
            assert!(!p.is_null(), "{name}");
            out.push(Record {
                label: format!("{name} read by name"),
                bits: problem_bits(p),
            });
            own_message(p, tag);
            let mut solvers = SOLVERS.to_vec();
            solvers.rotate_left(rotation % SOLVERS.len());
            for s in solvers {
                out.push(Record {
                    label: format!("{name} {s:?}"),
                    bits: drive(p, s, max_iter),
                });
            }
            frictionContactProblem_free(p);
            // From a FILE*.
            let f = fopen(path.as_ptr(), c"r".as_ptr());
            assert!(!f.is_null());
            let p = frictionContact_newFromFile(f);
            fclose(f);
            assert!(!p.is_null(), "{name}");
            out.push(Record {
                label: format!("{name} read from FILE"),
                bits: problem_bits(p),
            });
            out.push(Record {
                label: format!("{name} from FILE, NSGS"),
                bits: drive(p, (500, None), max_iter),
            });
            frictionContactProblem_free(p);
            // Native reader and solve.
            let np = fc3d_problem_read(path.as_ptr());
            assert!(!np.is_null(), "{name}");
            let nc = fc3d_problem_contacts(np) as usize;
            let nnz = fc3d_problem_nnz(np) as usize;
            let (mut rp, mut ci, mut v) = (vec![0i64; 3 * nc + 1], vec![0i64; nnz], vec![0.0; nnz]);
            let (mut q, mut mu) = (vec![0.0; 3 * nc], vec![0.0; nc]);
            assert_eq!(
                fc3d_problem_get(
                    np,
                    rp.as_mut_ptr(),
                    ci.as_mut_ptr(),
                    v.as_mut_ptr(),
                    q.as_mut_ptr(),
                    mu.as_mut_ptr()
                ),
                0
            );
            out.push(Record {
                label: format!("{name} native read"),
                bits: rp
                    .iter()
                    .chain(&ci)
                    .map(|&x| x as u64)
                    .chain(bits(&v))
                    .chain(bits(&q))
                    .chain(bits(&mu))
                    .collect(),
            });
            for id in [500, 504, 523] {
                let s = fc3d_settings_new(id);
                assert!(!s.is_null());
                assert_eq!(fc3d_settings_set_max_iter(s, max_iter as i64), 0);
                assert_eq!(fc3d_settings_set_tolerance(s, 1e-12), 0);
                let (mut r, mut u) = (vec![0.0; 3 * nc], vec![0.0; 3 * nc]);
                let mut res = Fc3dResult::default();
                let rc = fc3d_problem_solve(np, r.as_mut_ptr(), u.as_mut_ptr(), s, &mut res);
                assert!(rc >= 0);
                out.push(Record {
                    label: format!("{name} native {id}"),
                    bits: [
                        rc as u64,
                        res.info as u64,
                        res.iterations as u64,
                        res.error.to_bits(),
                    ]
                    .into_iter()
                    .chain(bits(&r))
                    .chain(bits(&u))
                    .collect(),
                });
                fc3d_settings_free(s);
            }
            fc3d_problem_free(np);
        }
    }
    out.sort_by(|a, b| a.label.cmp(&b.label));
    out
}

fn on_thread(stack: usize, rotation: usize, tag: f64) -> std::thread::JoinHandle<Vec<Record>> {
    std::thread::Builder::new()
        .stack_size(stack)
        .spawn(move || run_all(rotation, tag))
        .unwrap()
}

fn assert_same(reference: &[Record], got: &[Record], what: &str) {
    assert_eq!(reference.len(), got.len(), "{what}");
    for (a, b) in reference.iter().zip(got) {
        assert_eq!(a.label, b.label, "{what}");
        assert!(
            a.bits == b.bits,
            "{what}: {} differs from the reference",
            a.label
        );
    }
}

/// The reference on a large stack; then a 256 KiB stack; then 4 such threads at once.
#[test]
fn readers_and_solvers_on_small_stacks_and_concurrently_give_the_same_bits() {
    let reference = on_thread(8 << 20, 0, 1.0).join().unwrap();
    assert!(reference.len() > PROBLEMS.len() * SOLVERS.len());
    let iterations: u64 = reference
        .iter()
        .filter(|r| r.label.contains('(') && r.bits.len() > 3)
        .map(|r| r.bits[1])
        .sum();
    eprintln!(
        "{} results, {iterations} iterations of fc3d_driver in all",
        reference.len()
    );
    assert!(iterations > 1000);
    let small = on_thread(SMALL_STACK, 1, 2.0)
        .join()
        .expect("a 256 KiB stack is enough");
    assert_same(&reference, &small, "256 KiB stack");
    let handles: Vec<_> = (0..4)
        .map(|k| on_thread(SMALL_STACK, k + 2, 3.0 + k as f64))
        .collect();
    for (k, h) in handles.into_iter().enumerate() {
        let got = h.join().expect("a 256 KiB stack is enough");
        assert_same(&reference, &got, &format!("concurrent thread {k}"));
    }
}
