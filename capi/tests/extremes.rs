//! The extremes matrix (issue 6): every implemented solver id, through `fc3d_driver` as a C host
//! calls it, on every problem of the seeded extreme generator (`common/extremes.rs`). For each run:
//! a return code of 0, 1, 2 or 3 (never a crash or a rejection of valid input); r and u finite;
//! `dparam[1]` equal to `fc3d_compute_error` on the returned reaction and to an independent
//! recomputation; `info == 0` exactly when that error is within the tolerance; the iteration limit
//! respected; the time budget (`dparam[FC3D_DPARAM_TIME_BUDGET]`) respected within a margin; and
//! determinism: a second identical call returns the same bits.
//! The matrix (solver x problem: solved / honest failure) is printed and written to
//! `target/extremes-matrix.md`.

#[path = "../../core/tests/common/mod.rs"]
mod common;

use std::os::raw::c_int;
use std::time::Instant;

use common::extremes::extreme_problems;
use fc3d::types::{FrictionContactProblem, NumericsMatrix, SolverOptions};
use fc3d_core::FrictionProblem;

mod siconos_api;
use siconos_api::*;

const FC3D_ERR_UNSUPPORTED_SOLVER: c_int = fc3d::FC3D_ERR_UNSUPPORTED_SOLVER;
const BUDGET: f64 = 0.5;
const TOL: f64 = 1e-8;
/// Iteration cap for every solver (small problems: what does not converge in this many
/// iterations is a failure to report honestly, not to wait for).
const MAX_ITER: c_int = 2000;

/// A solver to run: a top-level id, and for NSGS the local solver id.
#[derive(Clone, Copy)]
struct Variant {
    id: c_int,
    local: Option<c_int>,
}

impl Variant {
    fn label(&self) -> String {
        match self.local {
            Some(l) => format!("{}/{}", self.id, l),
            None => format!("{}", self.id),
        }
    }

    unsafe fn options(&self) -> *mut SolverOptions {
        let o = solver_options_create(self.id);
        assert!(!o.is_null());
        if let Some(l) = self.local {
            solver_options_update_internal(o, 0, l);
        }
        *(*o).iparam = MAX_ITER;
        *(*o).dparam = TOL;
        *(*o).dparam.add(fc3d::FC3D_DPARAM_TIME_BUDGET as usize) = BUDGET;
        o
    }
}

unsafe fn release(o: *mut SolverOptions) {
    solver_options_delete(o);
    free(o.cast());
}

/// The problem as a C host builds it: a dense NumericsMatrix pointing at its own column-major copy.
struct CProblem {
    w: Vec<f64>,
    q: Vec<f64>,
    mu: Vec<f64>,
    m: Box<NumericsMatrix>,
    nc: usize,
}

impl CProblem {
    fn new(p: &FrictionProblem<'_>) -> Self {
        let n = p.size();
        let mut w = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                w[i + j * n] = p.w().get(i, j);
            }
        }
        // SAFETY: an all-zero NumericsMatrix is a valid "empty" value (NULL pointers, size 0).
        let mut m: Box<NumericsMatrix> = Box::new(unsafe { std::mem::zeroed() });
        m.storageType = 0;
        m.size0 = n as c_int;
        m.size1 = n as c_int;
        let mut c = CProblem {
            w,
            q: p.q().to_vec(),
            mu: p.mu().to_vec(),
            m,
            nc: p.n_contacts(),
        };
        c.m.matrix0 = c.w.as_mut_ptr();
        c
    }

    fn raw(&mut self) -> FrictionContactProblem {
        FrictionContactProblem {
            dimension: 3,
            numberOfContacts: self.nc as c_int,
            M: &mut *self.m,
            q: self.q.as_mut_ptr(),
            mu: self.mu.as_mut_ptr(),
        }
    }
}

/// The natural-map error recomputed here from its definition (no fc3d code).
fn independent_error(w: &[f64], q: &[f64], mu: &[f64], r: &[f64]) -> f64 {
    let n = q.len();
    let mut u = q.to_vec();
    for j in 0..n {
        for i in 0..n {
            u[i] += w[i + j * n] * r[j];
        }
    }
    let mut s = 0.0;
    for (c, &m) in mu.iter().enumerate() {
        let (rn, rt1, rt2) = (r[3 * c], r[3 * c + 1], r[3 * c + 2]);
        let (un, ut1, ut2) = (u[3 * c], u[3 * c + 1], u[3 * c + 2]);
        let x = [
            rn - (un + m * (ut1 * ut1 + ut2 * ut2).sqrt()),
            rt1 - ut1,
            rt2 - ut2,
        ];
        let t = (x[1] * x[1] + x[2] * x[2]).sqrt();
        let p = if t <= m * x[0] {
            x
        } else if m * t <= -x[0] {
            [0.0; 3]
        } else {
            let a = (x[0] + m * t) / (1.0 + m * m);
            if t > 0.0 {
                [a, m * a * x[1] / t, m * a * x[2] / t]
            } else {
                [a, 0.0, 0.0]
            }
        };
        s += (rn - p[0]).powi(2) + (rt1 - p[1]).powi(2) + (rt2 - p[2]).powi(2);
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let scale = norm(q).max(norm(r)).max(norm(&u));
    s.sqrt() / if scale > 0.0 { scale } else { 1.0 }
}

/// Every solver variant fc3d implements: top-level ids that `fc3d_driver` accepts, and NSGS with
/// every local solver id it accepts (probed on a small problem; an id is implemented when the
/// driver does not answer FC3D_ERR_UNSUPPORTED_SOLVER).
fn implemented_variants(probe: &mut CProblem) -> Vec<Variant> {
    let mut out = Vec::new();
    let n = 3 * probe.nc;
    let accepts = |v: Variant, probe: &mut CProblem| unsafe {
        if solver_options_create(v.id).is_null() {
            return false;
        }
        let o = v.options();
        let mut r = vec![0.0; n];
        let mut u = vec![0.0; n];
        let mut p = probe.raw();
        let rc = fc3d_driver(&mut p, r.as_mut_ptr(), u.as_mut_ptr(), o);
        release(o);
        rc != FC3D_ERR_UNSUPPORTED_SOLVER
    };
    for id in (500..600).chain(600..700) {
        // Leak-free probe of the id's existence (options are released in `accepts`).
        let o = unsafe { solver_options_create(id) };
        if o.is_null() {
            continue;
        }
        unsafe { release(o) };
        let top = Variant { id, local: None };
        if accepts(top, probe) {
            out.push(top);
            continue;
        }
        let local = Variant {
            id: 500,
            local: Some(id),
        };
        if accepts(local, probe) {
            out.push(local);
        }
    }
    out
}

#[test]
fn every_solver_on_every_extreme_problem_is_finite_and_honest() {
    let problems = extreme_problems(20261122);
    let mut probe = CProblem::new(&problems[2].1);
    let variants = implemented_variants(&mut probe);
    assert!(
        variants.len() >= 7,
        "only {} variants found",
        variants.len()
    );

    let mut table = vec![format!(
        "| solver | {} |",
        problems
            .iter()
            .map(|(n, _)| n.as_str())
            .collect::<Vec<_>>()
            .join(" | ")
    )];
    table.push(format!("| --- |{}", " --- |".repeat(problems.len())));
    let mut failures = Vec::new();
    for v in &variants {
        let mut row = vec![v.label()];
        for (name, p) in &problems {
            let mut cp = CProblem::new(p);
            let n = p.size();
            let mut r = vec![0.0; n];
            let mut u = vec![0.0; n];
            let t = Instant::now();
            let (rc, iters, reported) = unsafe {
                let o = v.options();
                let mut raw = cp.raw();
                let rc = fc3d_driver(&mut raw, r.as_mut_ptr(), u.as_mut_ptr(), o);
                let out = (rc, *(*o).iparam.add(1), *(*o).dparam.add(1));
                release(o);
                out
            };
            let elapsed = t.elapsed().as_secs_f64();
            let what = format!("{} on {name}", v.label());
            // Determinism: the same call again gives the same bits (unless the wall clock
            // decided, i.e. the time budget ran out).
            if rc != 2 {
                let mut r2 = vec![0.0; n];
                let mut u2 = vec![0.0; n];
                let again = unsafe {
                    let o = v.options();
                    let mut raw = cp.raw();
                    let rc2 = fc3d_driver(&mut raw, r2.as_mut_ptr(), u2.as_mut_ptr(), o);
                    let out = (rc2, *(*o).iparam.add(1), (*(*o).dparam.add(1)).to_bits());
                    release(o);
                    out
                };
                let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                // A second call cut by the wall clock (loaded machine) is not a repeat.
                let cut_by_clock = again.0 == 2;
                if !cut_by_clock
                    && (again != (rc, iters, reported.to_bits())
                        || bits(&r) != bits(&r2)
                        || bits(&u) != bits(&u2))
                {
                    failures.push(format!(
                        "{what}: a second identical call gave different bits"
                    ));
                }
            }
            // 0 converged, 1 iteration limit, 2 time budget, 3 (SOCLCP) relaxed solution that is
            // not a Coulomb solution, 4 a reaction that grew without bound.
            if !(0..=4).contains(&rc) {
                failures.push(format!("{what}: returned {rc}"));
                row.push(format!("ERR {rc}"));
                continue;
            }
            if !r.iter().chain(&u).all(|x| x.is_finite()) {
                failures.push(format!("{what}: non-finite r or u"));
            }
            let mut api = f64::NAN;
            let mut w2 = vec![0.0; n];
            let qn = p.q().iter().map(|x| x * x).sum::<f64>().sqrt();
            unsafe {
                let mut raw = cp.raw();
                let o = v.options();
                fc3d_compute_error(
                    &mut raw,
                    r.as_mut_ptr(),
                    w2.as_mut_ptr(),
                    TOL,
                    o,
                    qn,
                    &mut api,
                );
                release(o);
            }
            if reported != api {
                failures.push(format!(
                    "{what}: dparam[1] = {reported:e} but fc3d_compute_error = {api:e}"
                ));
            }
            let indep = independent_error(&cp.w, p.q(), p.mu(), &r);
            if (reported - indep).abs() > 1e-9 * indep.max(1e-300) + 1e-14 {
                failures.push(format!(
                    "{what}: dparam[1] = {reported:e}, recomputed {indep:e}"
                ));
            }
            // Info 0 exactly when the error is within the tolerance, except a reaction that grew
            // without bound (4), whose error may be small without solving anything.
            if (rc == 0) != (reported <= TOL && rc != 4) {
                failures.push(format!("{what}: info {rc} with error {reported:e}"));
            }
            if iters > MAX_ITER {
                failures.push(format!("{what}: {iters} iterations > {MAX_ITER}"));
            }
            if elapsed > BUDGET + 1.0 {
                failures.push(format!("{what}: {elapsed:.2} s for a {BUDGET} s budget"));
            }
            row.push(match rc {
                0 => format!("ok {iters}"),
                2 => format!("budget {reported:.0e}"),
                3 => format!("relaxed {reported:.0e}"),
                4 => format!("unbounded {reported:.0e}"),
                _ => format!("fail {reported:.0e}"),
            });
        }
        table.push(format!("| {} |", row.join(" | ")));
    }
    let text = table.join("\n");
    println!("{text}");
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/extremes-matrix.md");
    let _ = std::fs::write(out, format!("{text}\n"));
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_generator_is_reproducible() {
    let a = extreme_problems(7);
    let b = extreme_problems(7);
    assert_eq!(a.len(), b.len());
    for ((na, pa), (nb, pb)) in a.iter().zip(&b) {
        assert_eq!(na, nb);
        assert_eq!(pa, pb);
    }
}
