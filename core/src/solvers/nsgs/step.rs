//! The one-contact step of a Gauss-Seidel sweep: the [`ContactStep`] trait, the 3D step with a
//! local solver ([`LocalStep`]), and the update of one contact against the current reactions
//! ([`new_reaction`]) that the sequential, coloured and island sweeps share.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use super::parallel::Reactions;
use crate::error::Fc3dError;
use crate::local::{AnyLocalSolver, LocalProblem, LocalSolver, LocalSolverOptions};
use crate::math::linalg::Block;
use crate::matrix::{BlockRows, SweepRows};

/// The one-contact step a sweep applies to each contact of dimension `D`. Its configuration is
/// shared by the threads of a parallel sweep; each thread solves with its own [`Self::Worker`].
pub trait ContactStep<const D: usize>: Sync {
    /// What one thread needs of its own to solve contacts (a local solver instance).
    type Worker;

    /// A worker with the current configuration (tolerance, deadline).
    fn worker(&self) -> Self::Worker;

    /// The reaction of contact `c` for its local problem FC(`w`, `q`, `mu`), starting from and
    /// written into `r`; `memory` is the contact's own state kept from sweep to sweep (1 before
    /// the first visit). A step that cannot produce a finite answer leaves `r` as it was.
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        worker: &mut Self::Worker,
        c: usize,
        w: &Block<D>,
        q: &[f64; D],
        mu: f64,
        memory: &mut f64,
        r: &mut [f64; D],
    );

    /// A new tolerance for iterative steps (adaptive local tolerance); exact steps ignore it.
    fn set_tolerance(&mut self, _tolerance: f64) {}

    /// The instant after which an iterative step stops iterating.
    fn set_deadline(&mut self, _deadline: Option<Instant>) {}

    /// Whether contact `c`'s cone is the half-line `R+ e_N` (the sweep then solves the scalar
    /// problem of the normal row itself): with the Coulomb cone, when `mu = 0`.
    fn normal_only(&self, _c: usize, mu: f64) -> bool {
        mu == 0.0
    }

    /// The point of contact `c`'s cone nearest to `r` (an over-relaxed reaction can leave it).
    fn project(&self, _c: usize, r: &[f64; D], mu: f64) -> [f64; D] {
        crate::math::cone::project_on_cone_d(r, mu)
    }
}

/// The 3D step: the configured local solver with each contact's penalty parameters. They depend
/// on `W_cc` only, so each is computed once per problem, at the contact's first update, from the
/// diagonal block the update reads anyway: preparing a solve does not visit every diagonal block
/// of W (on a host's W, one allocation each, that pass cost a fifth of a sweep at 10^5 contacts).
pub struct LocalStep {
    options: LocalSolverOptions,
    /// Per contact, the bits of `(rho_N, rho_T)`; NaN until computed. Atomics (relaxed: each
    /// contact is updated by one thread at a time, sweeps are ordered by barriers) so that the
    /// threads of a coloured sweep share the step.
    rho: Vec<[AtomicU64; 2]>,
    deadline: Option<Instant>,
}

impl LocalStep {
    /// The step of `options`' local solver for the contacts of `rows`.
    pub fn new(rows: &BlockRows, options: &LocalSolverOptions) -> Result<Self, Fc3dError> {
        Self::for_contacts(rows.n_contacts(), options)
    }

    /// The step of `options`' local solver for `nc` contacts.
    pub fn for_contacts(nc: usize, options: &LocalSolverOptions) -> Result<Self, Fc3dError> {
        let mut rho = Vec::new();
        rho.try_reserve_exact(nc)
            .map_err(|_| Fc3dError::OutOfMemory {
                what: "local penalties".into(),
                bytes: nc.saturating_mul(16),
            })?;
        rho.extend((0..nc).map(|_| {
            [
                AtomicU64::new(f64::NAN.to_bits()),
                AtomicU64::new(f64::NAN.to_bits()),
            ]
        }));
        Ok(LocalStep {
            options: *options,
            rho,
            deadline: None,
        })
    }

    /// Contact `c`'s penalty parameters for its diagonal block `w` (computed at first use).
    #[inline]
    fn rho_of(&self, solver: &AnyLocalSolver, c: usize, w: &Block<3>) -> (f64, f64) {
        let [n, t] = &self.rho[c];
        let rn = f64::from_bits(n.load(Ordering::Relaxed));
        if !rn.is_nan() {
            return (rn, f64::from_bits(t.load(Ordering::Relaxed)));
        }
        let (rn, rt) = solver.rho(w);
        n.store(rn.to_bits(), Ordering::Relaxed);
        t.store(rt.to_bits(), Ordering::Relaxed);
        (rn, rt)
    }
}

impl ContactStep<3> for LocalStep {
    type Worker = AnyLocalSolver;

    fn worker(&self) -> AnyLocalSolver {
        let mut solver = AnyLocalSolver::new(&self.options);
        solver.set_deadline(self.deadline);
        solver
    }

    #[inline(always)]
    fn solve(
        &self,
        solver: &mut AnyLocalSolver,
        c: usize,
        w: &Block<3>,
        q: &[f64; 3],
        mu: f64,
        memory: &mut f64,
        r: &mut [f64; 3],
    ) {
        let p = LocalProblem { w, q: *q, mu };
        let old = *r;
        let rho = self.rho_of(solver, c, w);
        solver.solve_in_sweep(&p, rho, memory, r);
        if !r.iter().all(|v| v.is_finite()) {
            *r = old;
        }
    }

    fn set_tolerance(&mut self, tolerance: f64) {
        if tolerance.is_finite() && tolerance >= 0.0 {
            self.options.tolerance = tolerance;
        }
    }

    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
    }
}

/// The new reaction of contact `c` of `rows` against the reactions `r` (not written): the
/// one-contact update of every Gauss-Seidel sweep (frictionless shortcut, local solve,
/// relaxation), for sweeps driven outside the core (fc3d-mpi's distributed sweep). `memory` is
/// the contact's step state (1 before its first visit).
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn update_contact<const D: usize, S: ContactStep<D>>(
    rows: &BlockRows<D>,
    step: &S,
    worker: &mut S::Worker,
    relaxation: Option<f64>,
    c: usize,
    q: &[f64],
    mu: &[f64],
    r: &[f64],
    memory: &mut f64,
) -> [f64; D] {
    new_reaction(rows, step, worker, relaxation, c, q, mu, r, memory, false).0
}

/// The new reaction of contact `c` against the reactions `r` (not written), its old reaction,
/// and its local q when `keep_local_q` (or when computed anyway).
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn new_reaction<
    const D: usize,
    P: SweepRows<D>,
    S: ContactStep<D>,
    R: Reactions<D> + ?Sized,
>(
    rows: &P,
    step: &S,
    worker: &mut S::Worker,
    relaxation: Option<f64>,
    c: usize,
    q: &[f64],
    mu: &[f64],
    r: &R,
    memory: &mut f64,
    keep_local_q: bool,
) -> ([f64; D], [f64; D], Option<[f64; D]>) {
    let old: [f64; D] = r.contact(c);
    let (rc, local_q) = solve_contact(
        step,
        worker,
        relaxation,
        c,
        &rows.diagonal(c),
        mu[c],
        &old,
        || r.local_q(rows, c, q),
        || r.local_q_normal(rows, c, q),
        memory,
        keep_local_q,
    );
    (rc, old, local_q)
}

/// The one-contact update of every Gauss-Seidel sweep, whatever holds the coupling (W's block
/// rows, or the H form's velocity): contact `c` with diagonal block `w`, friction `mu` and
/// reaction `old`, whose local q (`q_c + sum_{b != c} W_cb r_b`) `local_q` computes (and its
/// normal component `local_q_normal`, all a frictionless contact needs). Frictionless shortcut,
/// local solve, relaxation; returns the new reaction and the local q when `keep_local_q` (or
/// when computed anyway).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn solve_contact<const D: usize, S: ContactStep<D>>(
    step: &S,
    worker: &mut S::Worker,
    relaxation: Option<f64>,
    c: usize,
    w: &Block<D>,
    mu: f64,
    old: &[f64; D],
    local_q: impl FnOnce() -> [f64; D],
    local_q_normal: impl FnOnce() -> f64,
    memory: &mut f64,
    keep_local_q: bool,
) -> ([f64; D], Option<[f64; D]>) {
    let wnn = w[0][0];
    let frictionless = step.normal_only(c, mu) && wnn > 0.0 && wnn.is_finite();
    let need_local_q = !frictionless || keep_local_q;
    let mut compute = Some(local_q);
    let mut local_q = if need_local_q {
        compute.take().map(|f| f())
    } else {
        None
    };
    // The cone is the half-line R+ e_N: only the normal row of the coupling matters. A
    // quotient that overflows (a subnormal W_NN) is left to the one-contact step.
    let scalar = if frictionless {
        let qn = match local_q {
            Some(lq) => lq[0],
            None => local_q_normal(),
        };
        Some((-qn / wnn).max(0.0)).filter(|rn| rn.is_finite())
    } else {
        None
    };
    let mut rc = match scalar {
        Some(rn) => {
            let mut rc = [0.0; D];
            rc[0] = rn;
            rc
        }
        None => {
            // Without a local q only when a frictionless quotient overflowed: computed now.
            let lq = *local_q.get_or_insert_with(|| compute.take().map_or([0.0; D], |f| f()));
            let mut rc = *old;
            step.solve(worker, c, w, &lq, mu, memory, &mut rc);
            rc
        }
    };
    if let Some(omega) = relaxation {
        for (x, o) in rc.iter_mut().zip(old) {
            *x = omega * *x + (1.0 - omega) * o;
        }
        if omega > 1.0 {
            // Over-relaxation can leave the cone; the iterate must stay admissible.
            rc = step.project(c, &rc, mu);
        }
    }
    (rc, local_q)
}
