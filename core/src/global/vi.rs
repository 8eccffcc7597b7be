//! Siconos' `GFC3D_VI_FPP` (610) and `GFC3D_VI_EG` (611): the local VI solvers' fixed point
//! and extragradient (`solvers::vi`, the same implementation) on the global problem as a VI in
//! `x = (v, r)`:
//!
//! `F(x) = [ M v - q - H r ;  u + g(u) ]`, `u = H^T v + b`, `g(u)_c = (mu_c ||u_{T,c}||, 0, 0)`,
//!
//! with v free and each `r_c` in its Coulomb cone. They stop on the VI error
//! `||x - P_X(x - F(x))|| / ||q||` as Siconos' do; the solve then reports the global error of
//! the triple `(r, u, v)` with `v = M^-1 (q + H r)`.

use crate::contract::{Limits, Observer, SolverOutcome};
use crate::error::{require_setting, try_vec, Fc3dError};
use crate::math::linalg::norm;
use crate::matrix::{transpose_mul_add, HForm};
use crate::problem::GlobalProblem;
use crate::solvers::vi::{
    de_saxce_map, project_step, project_step_in_place, run_projection, Lineage, ViMap, ViOptions,
    ViSolver,
};

/// The global problem as a VI in `(v, r)`.
struct GlobalVi<'p, 'a> {
    problem: &'p GlobalProblem<'a>,
    norm_q: f64,
}

impl GlobalVi<'_, '_> {
    fn split<'x>(&self, x: &'x [f64]) -> (&'x [f64], &'x [f64]) {
        x.split_at(self.problem.ndof())
    }
}

impl ViMap for GlobalVi<'_, '_> {
    fn size(&self) -> usize {
        self.problem.ndof() + self.problem.size()
    }
    fn velocity_size(&self) -> usize {
        self.problem.size()
    }
    fn evaluate(&self, x: &[f64], u: &mut [f64], f: &mut [f64]) {
        let p = self.problem;
        let (v, r) = self.split(x);
        let (f_v, f_r) = f.split_at_mut(p.ndof());
        // M v - q - H r, as -(q - M v + H r) without a work vector.
        for (fi, qi) in f_v.iter_mut().zip(p.q()) {
            *fi = -qi;
        }
        p.m().mul_add(v, f_v);
        for fi in f_v.iter_mut() {
            *fi = -*fi;
        }
        p.h().mul_add(r, f_v);
        for fi in f_v.iter_mut() {
            *fi = -*fi;
        }
        u.copy_from_slice(p.b());
        transpose_mul_add(p.h(), v, u);
        de_saxce_map(p.mu(), u, f_r);
    }
    fn project_step(&self, base: &[f64], f: &[f64], rho: f64, out: &mut [f64]) {
        let n = self.problem.ndof();
        for ((o, b), fi) in out[..n].iter_mut().zip(&base[..n]).zip(&f[..n]) {
            *o = b - rho * fi;
        }
        project_step(self.problem.mu(), &base[n..], &f[n..], rho, &mut out[n..]);
    }
    fn project_step_in_place(&self, x: &mut [f64], f: &[f64], rho: f64) {
        let n = self.problem.ndof();
        for (xi, fi) in x[..n].iter_mut().zip(&f[..n]) {
            *xi -= rho * fi;
        }
        project_step_in_place(self.problem.mu(), &mut x[n..], &f[n..], rho);
    }
    fn stopping_error(&self, _lineage: Lineage, x: &[f64], _u: &[f64], f: &[f64]) -> f64 {
        // ||x - P_X(x - F(x))||: F's v part itself, the cone part per contact.
        let n = self.problem.ndof();
        let mut s: f64 = f[..n].iter().map(|v| v * v).sum();
        let r = &x[n..];
        for (c, &mu) in self.problem.mu().iter().enumerate() {
            let k = 3 * c;
            let fc = &f[n + k..n + k + 3];
            let p = crate::math::cone::project_on_cone(
                &[r[k] - fc[0], r[k + 1] - fc[1], r[k + 2] - fc[2]],
                mu,
            );
            s += (0..3).map(|i| (r[k + i] - p[i]).powi(2)).sum::<f64>();
        }
        if self.norm_q > f64::EPSILON {
            s.sqrt() / self.norm_q
        } else {
            s.sqrt()
        }
    }
    fn reaction<'x>(&self, x: &'x [f64]) -> &'x [f64] {
        &x[self.problem.ndof()..]
    }
}

/// Only Siconos' generic VI solvers have a global id.
pub(super) fn validate(options: &ViOptions) -> Result<(), Fc3dError> {
    require_setting(
        matches!(
            options.solver,
            ViSolver::ViFixedPointProjection | ViSolver::ViExtraGradient
        ),
        "global_vi.solver",
        options.solver.short_name(),
        "VI-FPP (610) or VI-EG (611)",
    )?;
    options.validate()
}

/// Runs the VI solver from the reaction in `r` (and `v = M^-1 (q + H r)`); returns the
/// outcome and the VI error it tested last.
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &ViOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<(SolverOutcome, f64), Fc3dError> {
    let n = problem.ndof();
    let map = GlobalVi {
        problem,
        norm_q: norm(problem.q()),
    };
    let mut x = try_vec(n + problem.size(), 0.0, "the global VI iterate")?;
    operator.global_velocity(problem.q(), r, v);
    x[..n].copy_from_slice(v);
    x[n..].copy_from_slice(r);
    let mut last_error = f64::INFINITY;
    let outcome = run_projection(&map, options, limits, &mut x, u, &mut |event| {
        last_error = event.error;
        observer(event);
    })?;
    v.copy_from_slice(&x[..n]);
    r.copy_from_slice(&x[n..]);
    // The VI error is not the global one: the solve measures that on the returned triple.
    Ok((outcome.with_final_error(None), last_error))
}
