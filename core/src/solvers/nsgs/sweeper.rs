//! One Gauss-Seidel sweep over the contacts, prepared once per problem: the block-row view of
//! W, the local solver, each contact's rho, and the sweep options (order, relaxation, freezing).

use std::time::Instant;

use crate::error::Fc3dError;
use crate::local::{AnyLocalSolver, LocalProblem, LocalSolver, LocalSolverOptions};
use crate::matrix::BlockRows;
use crate::measure::natural_map_error_by_rows;
use crate::problem::FrictionProblem;

use super::settings::{ContactOrder, NsgsOptions};
use crate::contract::ErrorEvaluation;

/// A small, portable pseudo-random generator (SplitMix64): the same seed gives the same contact
/// orders on every platform and run, which makes shuffled runs reproducible bit for bit.
#[derive(Debug, Clone)]
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (n > 0), by rejection so that no index is favoured.
    fn below(&mut self, n: usize) -> usize {
        let n = n as u64;
        let zone = u64::MAX - u64::MAX % n;
        loop {
            let x = self.next();
            if x < zone {
                return (x % n) as usize;
            }
        }
    }

    /// Fisher-Yates shuffle in place.
    fn shuffle(&mut self, v: &mut [usize]) {
        for i in (1..v.len()).rev() {
            let j = self.below(i + 1);
            v.swap(i, j);
        }
    }
}

/// What a sweep does beyond visiting every contact in index order once.
#[derive(Debug, Clone, Default)]
struct SweepPlan {
    /// Visiting order; empty means index order.
    order: Vec<usize>,
    /// Draws a new order before each sweep when set.
    reshuffle: Option<SplitMix64>,
    /// PSOR factor omega.
    relaxation: Option<f64>,
    /// (sweeps a still contact stays frozen, relative increment below which it is still).
    freezing: Option<(u32, f64)>,
    /// Sweeps left before each frozen contact is visited again (empty without freezing).
    frozen: Vec<u32>,
    /// The velocity each contact was solved with (Dumont's motion term); empty unless needed.
    u_solved: Vec<f64>,
}

/// One Gauss-Seidel sweep's state, prepared once per problem: the block-row view of W, the
/// local solver and the sweep options. Public so that benchmarks and hosts that drive their own
/// loop can sweep without re-preparing; a sweep allocates nothing.
pub struct Sweeper {
    rows: BlockRows,
    local_options: LocalSolverOptions,
    local: AnyLocalSolver,
    /// When the local solver must stop iterating (the run's deadline).
    deadline: Option<Instant>,
    /// Each contact's penalty parameters for the local solver (they depend on W_cc only).
    rho: Vec<(f64, f64)>,
    /// Each contact's local-solver state carried from sweep to sweep (553's step length).
    memory: Vec<f64>,
    plan: SweepPlan,
}

impl Sweeper {
    /// A plain sweeper: contacts in index order, no relaxation, no freezing.
    pub fn new(
        problem: &FrictionProblem<'_>,
        local: &LocalSolverOptions,
    ) -> Result<Self, Fc3dError> {
        let rows = problem.w().block_rows()?;
        let local_solver = AnyLocalSolver::new(local);
        let rho = (0..rows.n_contacts())
            .map(|c| local_solver.rho(rows.diagonal(c)))
            .collect();
        let memory = crate::error::try_vec(rows.n_contacts(), 1.0, "local solver states")?;
        Ok(Sweeper {
            rows,
            local_options: *local,
            local: local_solver,
            deadline: None,
            rho,
            memory,
            plan: SweepPlan::default(),
        })
    }

    /// A sweeper with the sweep options of `options` (order, relaxation, freezing, and the
    /// bookkeeping Dumont's criterion needs); `tolerance` is the run's, against which freezing
    /// judges a contact still. Rejects options out of range.
    pub fn with_options(
        problem: &FrictionProblem<'_>,
        options: &NsgsOptions,
        tolerance: f64,
    ) -> Result<Self, Fc3dError> {
        options.validate()?;
        let mut s = Sweeper::new(problem, &options.local)?;
        let nc = s.rows.n_contacts();
        s.plan.relaxation = options.relaxation;
        match options.order {
            ContactOrder::Natural => {}
            ContactOrder::ShuffledOnce { seed } => {
                s.plan.order = (0..nc).collect();
                SplitMix64(seed).shuffle(&mut s.plan.order);
            }
            ContactOrder::ShuffledEachSweep { seed } => {
                s.plan.order = (0..nc).collect();
                s.plan.reshuffle = Some(SplitMix64(seed));
            }
        }
        if let Some(k) = options.freezing {
            if k > 0 {
                s.plan.freezing = Some((u32::try_from(k).unwrap_or(u32::MAX), tolerance));
                s.plan.frozen = vec![0; nc];
            }
        }
        if options.error_evaluation == ErrorEvaluation::DumontCriterion {
            s.plan.u_solved = vec![0.0; 3 * nc];
        }
        Ok(s)
    }

    /// One sweep over all contacts, updating `r` in place; returns
    /// `sum_c ||r_c^new - r_c^old||^2`.
    pub fn sweep(&mut self, q: &[f64], mu: &[f64], r: &mut [f64]) -> f64 {
        if let Some(rng) = self.plan.reshuffle.as_mut() {
            rng.shuffle(&mut self.plan.order);
        }
        let nc = self.rows.n_contacts();
        let mut increment_sq = 0.0;
        for k in 0..nc {
            let c = if self.plan.order.is_empty() {
                k
            } else {
                self.plan.order[k]
            };
            increment_sq += self.update_contact(c, q, mu, r);
        }
        increment_sq
    }

    /// Solves contact `c` against the current reactions of the others and writes its new
    /// reaction into `r`; returns the squared increment.
    #[inline]
    fn update_contact(&mut self, c: usize, q: &[f64], mu: &[f64], r: &mut [f64]) -> f64 {
        if let Some(left) = self.plan.frozen.get_mut(c) {
            if *left > 0 {
                *left -= 1;
                return 0.0;
            }
        }
        let w = self.rows.diagonal(c);
        let old = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
        let wnn = w[0][0];
        let frictionless = mu[c] == 0.0 && wnn > 0.0 && wnn.is_finite();
        let need_local_q = !frictionless || !self.plan.u_solved.is_empty();
        let local_q = need_local_q.then(|| self.rows.local_q(c, q, r));
        // The cone is the half-line R+ e_N: only the normal row of the coupling matters. A
        // quotient that overflows (a subnormal W_NN) is left to the 3D local solver.
        let scalar = if frictionless {
            let qn = match local_q {
                Some(lq) => lq[0],
                None => self.rows.local_q_normal(c, q, r),
            };
            Some((-qn / wnn).max(0.0)).filter(|rn| rn.is_finite())
        } else {
            None
        };
        let mut rc = match scalar {
            Some(rn) => [rn, 0.0, 0.0],
            None => {
                let lq = local_q.unwrap_or_else(|| self.rows.local_q(c, q, r));
                let p = LocalProblem {
                    w,
                    q: lq,
                    mu: mu[c],
                };
                let mut rc = old;
                self.local
                    .solve_in_sweep(&p, self.rho[c], &mut self.memory[c], &mut rc);
                if rc.iter().all(|v| v.is_finite()) {
                    rc
                } else {
                    old
                }
            }
        };
        if let Some(omega) = self.plan.relaxation {
            rc = [
                omega * rc[0] + (1.0 - omega) * old[0],
                omega * rc[1] + (1.0 - omega) * old[1],
                omega * rc[2] + (1.0 - omega) * old[2],
            ];
            if omega > 1.0 {
                // Over-relaxation can leave the cone; the iterate must stay admissible.
                rc = crate::math::cone::project_on_cone(&rc, mu[c]);
            }
        }
        let d = [rc[0] - old[0], rc[1] - old[1], rc[2] - old[2]];
        let d_sq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if let Some((sweeps, tol)) = self.plan.freezing {
            let r_sq = rc[0] * rc[0] + rc[1] * rc[1] + rc[2] * rc[2];
            if d_sq <= tol * tol * r_sq {
                self.plan.frozen[c] = sweeps;
            }
        }
        r[3 * c..3 * c + 3].copy_from_slice(&rc);
        if let Some(lq) = local_q.filter(|_| !self.plan.u_solved.is_empty()) {
            let uc = crate::math::linalg::mat3_vec_add(w, &rc, &lq);
            self.plan.u_solved[3 * c..3 * c + 3].copy_from_slice(&uc);
        }
        d_sq
    }

    pub(super) fn any_frozen(&self) -> bool {
        self.plan.frozen.iter().any(|&f| f > 0)
    }

    /// Unfreezes every contact.
    pub(super) fn thaw(&mut self) {
        self.plan.frozen.iter_mut().for_each(|f| *f = 0);
    }

    /// Sets the local solver's tolerance (adaptive local tolerance strategies).
    pub(super) fn set_local_tolerance(&mut self, tolerance: f64) {
        if tolerance != self.local_options.tolerance && tolerance.is_finite() && tolerance >= 0.0 {
            self.local_options.tolerance = tolerance;
            self.local = AnyLocalSolver::new(&self.local_options);
            self.local.set_deadline(self.deadline);
        }
    }

    /// The instant after which the local solves stop iterating, so that one sweep ends soon
    /// after the budget whatever the local iteration limits.
    pub fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
        self.local.set_deadline(deadline);
    }

    /// The relative natural-map error of `r`, with `u = W r + q` computed through the prepared
    /// blocks (cheaper than the host's storage when W is dense but sparsely coupled).
    pub fn natural_map_error(
        &self,
        problem: &FrictionProblem<'_>,
        r: &[f64],
        u: &mut [f64],
    ) -> f64 {
        natural_map_error_by_rows(problem, &self.rows, r, u)
    }

    /// Dumont's criterion (37) after the last sweep (`u` receives `W r + q`).
    pub(super) fn dumont_criterion(
        &self,
        problem: &FrictionProblem<'_>,
        r: &[f64],
        u: &mut [f64],
    ) -> f64 {
        self.rows.velocity(problem.q(), r, u);
        crate::measure::dumont_criterion(r, u, &self.plan.u_solved, problem.mu())
    }
}
