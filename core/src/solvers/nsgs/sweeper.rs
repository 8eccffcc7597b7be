//! One Gauss-Seidel sweep over the contacts, prepared once per problem: the block-row view of
//! W, the one-contact step, and the sweep options (order, relaxation, freezing). The sweep is
//! generic over the contact dimension `D`: the 3D NSGS (Siconos 500) drives it with the local
//! solver of its options ([`LocalStep`]), the 2D NSGS (Siconos 400) with the exact 2x2 solve.

use std::time::Instant;

use crate::error::Fc3dError;
use crate::local::{AnyLocalSolver, LocalProblem, LocalSolver, LocalSolverOptions};
use crate::math::linalg::{block_vec_add, contact_of, distance_sq_d, Block};
use crate::matrix::BlockRows;
use crate::measure::SweptProblem;
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

/// The one-contact step a sweep applies to each contact of dimension `D`.
pub trait ContactStep<const D: usize> {
    /// The reaction of contact `c` for its local problem FC(`w`, `q`, `mu`), starting from and
    /// written into `r`. A step that cannot produce a finite answer leaves `r` as it was.
    fn solve(&mut self, c: usize, w: &Block<D>, q: &[f64; D], mu: f64, r: &mut [f64; D]);

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

/// The 3D step: the configured local solver with each contact's penalty parameters (they depend
/// on `W_cc` only, so they are computed once per problem).
pub struct LocalStep {
    options: LocalSolverOptions,
    solver: AnyLocalSolver,
    rho: Vec<(f64, f64)>,
    /// Each contact's local-solver state carried from sweep to sweep (553's step length).
    memory: Vec<f64>,
    deadline: Option<Instant>,
}

impl LocalStep {
    fn new(rows: &BlockRows, options: &LocalSolverOptions) -> Result<Self, Fc3dError> {
        let solver = AnyLocalSolver::new(options);
        let rho = (0..rows.n_contacts())
            .map(|c| solver.rho(rows.diagonal(c)))
            .collect();
        Ok(LocalStep {
            options: *options,
            solver,
            rho,
            memory: crate::error::try_vec(rows.n_contacts(), 1.0, "local solver states")?,
            deadline: None,
        })
    }
}

impl ContactStep<3> for LocalStep {
    #[inline]
    fn solve(&mut self, c: usize, w: &Block<3>, q: &[f64; 3], mu: f64, r: &mut [f64; 3]) {
        let p = LocalProblem { w, q: *q, mu };
        let old = *r;
        self.solver
            .solve_in_sweep(&p, self.rho[c], &mut self.memory[c], r);
        if !r.iter().all(|v| v.is_finite()) {
            *r = old;
        }
    }

    fn set_tolerance(&mut self, tolerance: f64) {
        if tolerance != self.options.tolerance && tolerance.is_finite() && tolerance >= 0.0 {
            self.options.tolerance = tolerance;
            self.solver = AnyLocalSolver::new(&self.options);
            self.solver.set_deadline(self.deadline);
        }
    }

    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
        self.solver.set_deadline(deadline);
    }
}

/// The sweep options shared by the 3D and 2D Gauss-Seidel families.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepOptions {
    /// PSOR factor omega in (0, 2); `None`: plain Gauss-Seidel.
    pub relaxation: Option<f64>,
    pub order: ContactOrder,
    /// Sweeps a contact that stopped moving stays frozen; `None` or `Some(0)`: never.
    pub freezing: Option<usize>,
    /// Keep the velocity each contact was solved with (Dumont's motion term).
    pub track_solved_velocity: bool,
}

impl From<&NsgsOptions> for SweepOptions {
    fn from(o: &NsgsOptions) -> Self {
        SweepOptions {
            relaxation: o.relaxation,
            order: o.order,
            freezing: o.freezing,
            track_solved_velocity: o.error_evaluation == ErrorEvaluation::DumontCriterion,
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

impl SweepPlan {
    fn new(options: &SweepOptions, nc: usize, dimension: usize, tolerance: f64) -> Self {
        let mut plan = SweepPlan {
            relaxation: options.relaxation,
            ..SweepPlan::default()
        };
        match options.order {
            ContactOrder::Natural => {}
            ContactOrder::ShuffledOnce { seed } => {
                plan.order = (0..nc).collect();
                SplitMix64(seed).shuffle(&mut plan.order);
            }
            ContactOrder::ShuffledEachSweep { seed } => {
                plan.order = (0..nc).collect();
                plan.reshuffle = Some(SplitMix64(seed));
            }
        }
        if let Some(k) = options.freezing.filter(|&k| k > 0) {
            plan.freezing = Some((u32::try_from(k).unwrap_or(u32::MAX), tolerance));
            plan.frozen = vec![0; nc];
        }
        if options.track_solved_velocity {
            plan.u_solved = vec![0.0; dimension * nc];
        }
        plan
    }
}

/// One Gauss-Seidel sweep's state for contacts of dimension `D`, prepared once per problem: the
/// block-row view of W, the one-contact step `S` and the sweep options. A sweep allocates
/// nothing.
pub struct GaussSeidel<const D: usize, S> {
    rows: BlockRows<D>,
    step: S,
    plan: SweepPlan,
}

/// The 3D sweep with a local solver (public so that benchmarks and hosts that drive their own
/// loop can sweep without re-preparing).
pub type Sweeper = GaussSeidel<3, LocalStep>;

impl Sweeper {
    /// A plain sweeper: contacts in index order, no relaxation, no freezing.
    pub fn new(
        problem: &FrictionProblem<'_>,
        local: &LocalSolverOptions,
    ) -> Result<Self, Fc3dError> {
        let rows = problem.w().block_rows()?;
        let step = LocalStep::new(&rows, local)?;
        Ok(GaussSeidel::from_parts(
            rows,
            step,
            &SweepOptions {
                relaxation: None,
                order: ContactOrder::Natural,
                freezing: None,
                track_solved_velocity: false,
            },
            0.0,
        ))
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
        let rows = problem.w().block_rows()?;
        Self::with_rows(rows, options, tolerance)
    }

    /// [`Sweeper::with_options`] over block rows prepared earlier (a workspace keeps them from
    /// one time step to the next); `options` must have been validated.
    pub(crate) fn with_rows(
        rows: BlockRows,
        options: &NsgsOptions,
        tolerance: f64,
    ) -> Result<Self, Fc3dError> {
        let step = LocalStep::new(&rows, &options.local)?;
        Ok(GaussSeidel::from_parts(
            rows,
            step,
            &options.into(),
            tolerance,
        ))
    }
}

impl<const D: usize, S: ContactStep<D>> GaussSeidel<D, S> {
    /// A sweeper over the block rows `rows` with the one-contact step `step`; `tolerance` is the
    /// run's, against which freezing judges a contact still.
    pub fn from_parts(rows: BlockRows<D>, step: S, options: &SweepOptions, tolerance: f64) -> Self {
        let plan = SweepPlan::new(options, rows.n_contacts(), D, tolerance);
        GaussSeidel { rows, step, plan }
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
        let old: [f64; D] = contact_of(r, c);
        let wnn = w[0][0];
        let frictionless = self.step.normal_only(c, mu[c]) && wnn > 0.0 && wnn.is_finite();
        let need_local_q = !frictionless || !self.plan.u_solved.is_empty();
        let local_q = need_local_q.then(|| self.rows.local_q(c, q, r));
        // The cone is the half-line R+ e_N: only the normal row of the coupling matters. A
        // quotient that overflows (a subnormal W_NN) is left to the one-contact step.
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
            Some(rn) => {
                let mut rc = [0.0; D];
                rc[0] = rn;
                rc
            }
            None => {
                let lq = local_q.unwrap_or_else(|| self.rows.local_q(c, q, r));
                let mut rc = old;
                self.step.solve(c, w, &lq, mu[c], &mut rc);
                rc
            }
        };
        if let Some(omega) = self.plan.relaxation {
            for (x, o) in rc.iter_mut().zip(&old) {
                *x = omega * *x + (1.0 - omega) * o;
            }
            if omega > 1.0 {
                // Over-relaxation can leave the cone; the iterate must stay admissible.
                rc = self.step.project(c, &rc, mu[c]);
            }
        }
        let d_sq = distance_sq_d(&rc, &old);
        if let Some((sweeps, tol)) = self.plan.freezing {
            let r_sq = distance_sq_d(&rc, &[0.0; D]);
            if d_sq <= tol * tol * r_sq {
                self.plan.frozen[c] = sweeps;
            }
        }
        r[D * c..D * c + D].copy_from_slice(&rc);
        if let Some(lq) = local_q.filter(|_| !self.plan.u_solved.is_empty()) {
            let uc = block_vec_add(w, &rc, &lq);
            self.plan.u_solved[D * c..D * c + D].copy_from_slice(&uc);
        }
        d_sq
    }

    /// Gives the block rows back (to be kept for the next problem with the same pattern).
    pub(crate) fn into_rows(self) -> BlockRows<D> {
        self.rows
    }

    pub(crate) fn any_frozen(&self) -> bool {
        self.plan.frozen.iter().any(|&f| f > 0)
    }

    /// Unfreezes every contact.
    pub(crate) fn thaw(&mut self) {
        self.plan.frozen.iter_mut().for_each(|f| *f = 0);
    }

    /// Sets the one-contact step's tolerance (adaptive local tolerance strategies).
    pub(crate) fn set_local_tolerance(&mut self, tolerance: f64) {
        self.step.set_tolerance(tolerance);
    }

    /// The instant after which the local solves stop iterating, so that one sweep ends soon
    /// after the budget whatever the local iteration limits.
    pub fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.step.set_deadline(deadline);
    }

    /// The relative natural-map error of `r`, with `u = W r + q` computed through the prepared
    /// blocks (cheaper than the host's storage when W is dense but sparsely coupled).
    pub fn natural_map_error<P: SweptProblem<D>>(
        &self,
        problem: &P,
        r: &[f64],
        u: &mut [f64],
    ) -> f64 {
        problem.error_by_rows(&self.rows, r, u)
    }

    /// Dumont's criterion (37) after the last sweep (`u` receives `W r + q`).
    pub(crate) fn dumont_criterion<P: SweptProblem<D>>(
        &self,
        problem: &P,
        r: &[f64],
        u: &mut [f64],
    ) -> f64 {
        problem.dumont_by_rows(&self.rows, r, u, &self.plan.u_solved)
    }
}
