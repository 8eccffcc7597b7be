//! The conjugate projected gradient of Siconos' `fc2d_cpg` (id 402): conjugate gradient steps on
//! `min 1/2 r·W r + q·r` where each contact's step is projected on its cone, the search
//! directions projected on the faces of the statuses (open, stick, sliding either way) of the
//! previous iterate. Siconos stops when the residual `-(W r + q)` changes by less than the
//! tolerance relative to its size; fc3d then also measures the natural-map error and goes on
//! while it is above the tolerance. The run starts from `r = 0`, as Siconos' does.

use crate::contract::{IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::{try_vec, Fc3dError};
use crate::measure::natural_map_error_of;
use crate::problem::FrictionProblem;

/// Where a contact's reaction lies (Siconos' CPG status codes 0 to 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// `r = 0` (0).
    Open,
    /// `r_T = -mu r_N` (1).
    SlideBackward,
    /// `|r_T| < mu r_N` (2).
    Stick,
    /// `r_T = mu r_N` (3).
    SlideForward,
}

impl Status {
    /// Siconos' code.
    pub fn code(self) -> i32 {
        match self {
            Status::Open => 0,
            Status::SlideBackward => 1,
            Status::Stick => 2,
            Status::SlideForward => 3,
        }
    }

    /// The status of Siconos' code `code`; codes other than 0, 1, 3 read as stick, as Siconos'
    /// projections treat them.
    pub fn from_code(code: i32) -> Status {
        match code {
            0 => Status::Open,
            1 => Status::SlideBackward,
            3 => Status::SlideForward,
            _ => Status::Stick,
        }
    }
}

/// The reaction of one contact after a step to `xi`, and its status: `xi` projected on the
/// cone, except that a contact sliding before a step whose direction has no tangential part
/// (`p_T = 0`) stays on its side of the cone.
pub fn project_step(xi: [f64; 2], p_t: f64, before: Status, mu: f64) -> ([f64; 2], Status) {
    let [n, t] = xi;
    if n <= 0.0 {
        return ([0.0, 0.0], Status::Open);
    }
    if t <= -mu * n {
        ([n, -mu * n], Status::SlideBackward)
    } else if t >= mu * n {
        ([n, mu * n], Status::SlideForward)
    } else if p_t == 0.0 && before == Status::SlideBackward {
        ([n, -mu * n], Status::SlideBackward)
    } else if p_t == 0.0 && before == Status::SlideForward {
        ([n, mu * n], Status::SlideForward)
    } else {
        ([n, t], Status::Stick)
    }
}

/// A direction `y` of one contact restricted to the moves its status allows: an open contact
/// may only close (`y_N > 0`), a sliding one may not move its tangential part towards the
/// inside of its face.
pub fn project_direction(y: [f64; 2], status: Status) -> [f64; 2] {
    match status {
        Status::Open if y[0] <= 0.0 => [0.0, 0.0],
        Status::SlideForward => [y[0], y[1].min(0.0)],
        Status::SlideBackward => [y[0], y[1].max(0.0)],
        _ => y,
    }
}

fn status_of(r: [f64; 2], mu: f64) -> Status {
    // Siconos' threshold for an open contact.
    const OPEN: f64 = 1e-12;
    if r[0] <= OPEN {
        Status::Open
    } else if r[1] <= -mu * r[0] {
        Status::SlideBackward
    } else if r[1] >= mu * r[0] {
        Status::SlideForward
    } else {
        Status::Stick
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Siconos 402 on `problem`; `r` is overwritten (the run starts from 0), `u` receives `W r + q`.
pub(crate) fn cpg(
    problem: &FrictionProblem<'_, 2>,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let n = problem.size();
    let nc = problem.n_contacts();
    let (w_op, q, mu) = (problem.w(), problem.q(), problem.mu());
    // Work vectors: the residual g = -(W r + q), its previous value, the direction p, W p, the
    // projected residual and direction, the step point.
    let mut g = try_vec(n, 0.0, "the CPG residual")?;
    let mut g_old = try_vec(n, 0.0, "the CPG residual")?;
    let mut p = try_vec(n, 0.0, "the CPG direction")?;
    let mut wp = try_vec(n, 0.0, "the CPG direction")?;
    let mut g_proj = try_vec(n, 0.0, "the CPG projected residual")?;
    let mut p_proj = try_vec(n, 0.0, "the CPG projected direction")?;
    let mut status = try_vec(nc, Status::Open, "the CPG contact statuses")?;
    let mut status_before = try_vec(nc, Status::Open, "the CPG contact statuses")?;

    r.iter_mut().for_each(|v| *v = 0.0);
    let residual = |r: &[f64], g: &mut [f64]| {
        w_op.velocity(r, q, g);
        g.iter_mut().for_each(|v| *v = -*v);
    };
    residual(r, &mut g);
    for c in 0..nc {
        status[c] = status_of([r[2 * c], r[2 * c + 1]], mu[c]);
    }

    let run = limits.start();
    let tol = run.tolerance;
    for iteration in 1..=run.max_iter {
        status_before.copy_from_slice(&status);
        g_old.copy_from_slice(&g);
        if iteration == 1 {
            p.copy_from_slice(&g);
        }
        wp.iter_mut().for_each(|v| *v = 0.0);
        w_op.mul_add(&p, &mut wp);
        let p_wp = dot(&p, &wp);
        if p_wp == 0.0 || !p_wp.is_finite() {
            // No descent left along p (p = 0 when the residual vanished on the free faces).
            return Ok(SolverOutcome::stopped(iteration - 1, false));
        }
        let alpha = dot(&g, &p) / p_wp;
        for c in 0..nc {
            let xi = [
                r[2 * c] + alpha * p[2 * c],
                r[2 * c + 1] + alpha * p[2 * c + 1],
            ];
            let (rc, s) = project_step(xi, p[2 * c + 1], status_before[c], mu[c]);
            r[2 * c..2 * c + 2].copy_from_slice(&rc);
            status[c] = s;
        }
        residual(r, &mut g);
        for c in 0..nc {
            let s = status_before[c];
            let gp = project_direction([g[2 * c], g[2 * c + 1]], s);
            let pp = project_direction([p[2 * c], p[2 * c + 1]], s);
            g_proj[2 * c..2 * c + 2].copy_from_slice(&gp);
            p_proj[2 * c..2 * c + 2].copy_from_slice(&pp);
        }
        let beta = -dot(&g_proj, &wp) / p_wp;
        for k in 0..n {
            p[k] = g_proj[k] + beta * p_proj[k];
        }
        // Siconos' test: ||g - g_old|| / ||g_old||.
        let change_sq: f64 = g.iter().zip(&g_old).map(|(a, b)| (a - b) * (a - b)).sum();
        let size_sq = dot(&g_old, &g_old);
        let change = if change_sq == 0.0 {
            0.0
        } else {
            (change_sq / size_sq).sqrt()
        };
        let mut converged = false;
        let mut measured = None;
        if change <= tol {
            for (uk, gk) in u.iter_mut().zip(&g) {
                *uk = -gk;
            }
            let error = natural_map_error_of(problem, r, u);
            measured = Some(error);
            converged = error <= tol;
        }
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error: measured.unwrap_or(change),
        });
        if let Some(outcome) = run.end_of_iteration(iteration, converged) {
            return Ok(outcome.with_final_error(measured.filter(|_| !outcome.out_of_time)));
        }
    }
    Ok(run.exhausted())
}
