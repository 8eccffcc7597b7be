//! One Gauss-Seidel sweep over the contacts, prepared once per problem: the block-row view of
//! W, the one-contact step, and the sweep options (order, relaxation, freezing). The sweep is
//! generic over the contact dimension `D`: the 3D NSGS (Siconos 500) drives it with the local
//! solver of its options ([`LocalStep`]), the 2D NSGS (Siconos 400) with the exact 2x2 solve.

use std::time::Instant;

use super::coloured::{ColouredPlan, Colouring};
use super::parallel::{resolve_threads, Pool, SharedSlice};
use super::settings::{ContactOrder, Decomposition, NsgsOptions};
use super::step::{new_reaction, ContactStep, LocalStep};
use crate::alloc::try_collect;
use crate::contract::ErrorEvaluation;
use crate::contract::Test;
use crate::error::{try_vec, Fc3dError};
use crate::local::LocalSolverOptions;
use crate::math::linalg::norm;
use crate::math::linalg::{block_vec_add, distance_sq_d};
use crate::matrix::{BlockRows, BlockSparseMatrix, Delassus, F32Coupling, SweepRows};
use crate::measure::relative_scale;
use crate::measure::SweptProblem;
use crate::problem::FrictionProblem;

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
    fn new(
        options: &SweepOptions,
        nc: usize,
        dimension: usize,
        tolerance: f64,
    ) -> Result<Self, Fc3dError> {
        let mut plan = SweepPlan {
            relaxation: options.relaxation,
            ..SweepPlan::default()
        };
        match options.order {
            ContactOrder::Natural => {}
            ContactOrder::ShuffledOnce { seed } => {
                plan.order = try_collect(0..nc, "the contact order")?;
                SplitMix64(seed).shuffle(&mut plan.order);
            }
            ContactOrder::ShuffledEachSweep { seed } => {
                plan.order = try_collect(0..nc, "the contact order")?;
                plan.reshuffle = Some(SplitMix64(seed));
            }
        }
        if let Some(k) = options.freezing.filter(|&k| k > 0) {
            plan.freezing = Some((u32::try_from(k).unwrap_or(u32::MAX), tolerance));
            plan.frozen = try_vec(nc, 0, "the frozen contacts")?;
        }
        if options.track_solved_velocity {
            plan.u_solved = try_vec(dimension * nc, 0.0, "the solved velocities")?;
        }
        Ok(plan)
    }
}

/// One Gauss-Seidel sweep's state for contacts of dimension `D`, prepared once per problem: the
/// block-row view of W, the one-contact step `S` and the sweep options. A sweep allocates
/// nothing.
pub struct GaussSeidel<'a, const D: usize, S: ContactStep<D>> {
    rows: BlockRows<'a, D>,
    step: S,
    /// The calling thread's worker (sequential sweeps and thread 0 of a coloured one).
    worker: S::Worker,
    /// Each contact's step state carried from sweep to sweep (553's step length).
    memory: Vec<f64>,
    plan: SweepPlan,
    /// The colouring and threads of a [`Decomposition::Coloured`] sweep.
    coloured: Option<ColouredPlan>,
    /// The f32 copy of the coupling blocks of a mixed-precision run ([`NsgsOptions::f32_sweeps`]).
    f32: Option<F32State<D>>,
}

/// Where a mixed-precision run stands: the f32 copy of W's coupling blocks, swept on while
/// `active`, and the rule that ends it (see [`F32Sweeps`](super::F32Sweeps)).
struct F32State<const D: usize> {
    coupling: F32Coupling<D>,
    switch_error: f64,
    active: bool,
    /// Sweeps done on the copy.
    sweeps: usize,
    /// The last rounding floor estimate (NaN before the first), and the full tests since.
    floor: f64,
    floor_age: u32,
}

/// The floor estimate reads the whole copy (half a product): a test under the `Full` schedule
/// (every sweep) reuses it for this many full tests, unless the error comes within twice the
/// switching distance of it.
const F32_FLOOR_REUSE: u32 = 64;

/// A full test within this factor of the f32 rounding floor ends the f32 sweeps: the f32
/// iteration's fixed point has an f64 error of at most about twice the floor, so below this
/// the copy cannot be trusted to make progress.
const F32_FLOOR_FACTOR: f64 = 4.0;

/// The 3D sweep with a local solver (public so that benchmarks and hosts that drive their own
/// loop can sweep without re-preparing).
pub type Sweeper<'a> = GaussSeidel<'a, 3, LocalStep>;

impl<'a> Sweeper<'a> {
    /// A plain sweeper: contacts in index order, no relaxation, no freezing.
    pub fn new(
        problem: &FrictionProblem<'a>,
        local: &LocalSolverOptions,
    ) -> Result<Self, Fc3dError> {
        let rows = problem.w().block_rows()?;
        let step = LocalStep::new(&rows, local)?;
        GaussSeidel::from_parts(
            rows,
            step,
            &SweepOptions {
                relaxation: None,
                order: ContactOrder::Natural,
                freezing: None,
                track_solved_velocity: false,
            },
            0.0,
        )
    }

    /// A sweeper with the sweep options of `options` (order, relaxation, freezing, the
    /// bookkeeping Dumont's criterion needs, a coloured decomposition); `tolerance` is the
    /// run's, against which freezing judges a contact still. Rejects options out of range.
    pub fn with_options(
        problem: &FrictionProblem<'a>,
        options: &NsgsOptions,
        tolerance: f64,
    ) -> Result<Self, Fc3dError> {
        options.validate()?;
        let rows = problem.w().block_rows()?;
        Self::with_rows(rows, options, tolerance, None)
    }

    /// [`Sweeper::with_options`] over block rows prepared earlier (a workspace keeps them from
    /// one time step to the next) and, for a coloured sweep, the colouring of their pattern
    /// when it is known; `options` must have been validated.
    pub(crate) fn with_rows(
        rows: BlockRows<'a>,
        options: &NsgsOptions,
        tolerance: f64,
        colouring: Option<Colouring>,
    ) -> Result<Self, Fc3dError> {
        let step = LocalStep::new(&rows, &options.local)?;
        let mut sweeper = GaussSeidel::from_parts(rows, step, &options.into(), tolerance)?;
        if let Some(f) = options.f32_sweeps {
            sweeper.f32 = F32Coupling::from_rows(&sweeper.rows)?.map(|coupling| F32State {
                coupling,
                switch_error: f.switch_error,
                active: true,
                sweeps: 0,
                floor: f64::NAN,
                floor_age: 0,
            });
        }
        if options.decomposition == Decomposition::Coloured {
            sweeper.colour(resolve_threads(options.threads), colouring)?;
        }
        Ok(sweeper)
    }
}

impl<'a, const D: usize, S: ContactStep<D>> GaussSeidel<'a, D, S> {
    /// A sweeper over the block rows `rows` with the one-contact step `step`; `tolerance` is the
    /// run's, against which freezing judges a contact still.
    pub fn from_parts(
        rows: BlockRows<'a, D>,
        step: S,
        options: &SweepOptions,
        tolerance: f64,
    ) -> Result<Self, Fc3dError> {
        let plan = SweepPlan::new(options, rows.n_contacts(), D, tolerance)?;
        let memory = try_vec(rows.n_contacts(), 1.0, "local solver states")?;
        Ok(GaussSeidel {
            worker: step.worker(),
            rows,
            step,
            memory,
            plan,
            coloured: None,
            f32: None,
        })
    }

    /// Switches to multicoloured sweeps on `threads` threads (see [`Decomposition::Coloured`]).
    /// `colouring`, when given, is that of the rows' pattern (kept from an earlier sweeper).
    pub(crate) fn colour(
        &mut self,
        threads: usize,
        colouring: Option<Colouring>,
    ) -> Result<(), Fc3dError> {
        self.coloured = Some(ColouredPlan::new(&self.rows, threads, colouring)?);
        Ok(())
    }

    /// What an island sweep needs: the block rows, the step, each contact's step state and
    /// the relaxation factor.
    pub(crate) fn island_parts(&mut self) -> (&BlockRows<'a, D>, &S, &mut [f64], Option<f64>) {
        (
            &self.rows,
            &self.step,
            &mut self.memory,
            self.plan.relaxation,
        )
    }

    /// One sweep over all contacts, updating `r` in place; returns
    /// `sum_c ||r_c^new - r_c^old||^2`.
    pub fn sweep(&mut self, q: &[f64], mu: &[f64], r: &mut [f64]) -> f64 {
        let GaussSeidel {
            rows,
            step,
            worker,
            memory,
            plan,
            coloured,
            f32,
        } = self;
        let low = match f32 {
            Some(state) if state.active => {
                state.sweeps += 1;
                Some(&state.coupling)
            }
            _ => None,
        };
        if let Some(coloured) = coloured.as_mut() {
            let relaxation = plan.relaxation;
            return match low {
                Some(coupling) => {
                    coloured_sweep(coupling, step, memory, relaxation, coloured, q, mu, r)
                }
                None => coloured_sweep(&*rows, step, memory, relaxation, coloured, q, mu, r),
            };
        }
        if let Some(rng) = plan.reshuffle.as_mut() {
            rng.shuffle(&mut plan.order);
        }
        match low {
            Some(coupling) => sequential_sweep(coupling, step, worker, memory, plan, q, mu, r),
            None => sequential_sweep(&*rows, step, worker, memory, plan, q, mu, r),
        }
    }

    /// After a tested sweep of a mixed-precision run (see [`F32Sweeps`](super::F32Sweeps)): whether the f32
    /// sweeps end here (the next sweeps read W's f64 blocks). `u` holds `W r + q` after a full
    /// test. Always false without the f32 copy, or once it was left.
    pub(crate) fn f32_switch(
        &mut self,
        test: &Test,
        tolerance: f64,
        q: &[f64],
        r: &[f64],
        u: &[f64],
    ) -> bool {
        let Some(state) = self.f32.as_mut().filter(|s| s.active) else {
            return false;
        };
        let mut switch = test.error <= state.switch_error || test.stalled;
        if !switch && test.full && test.error > tolerance {
            let near = test.error <= 2.0 * F32_FLOOR_FACTOR * state.floor;
            if state.floor.is_nan() || state.floor_age >= F32_FLOOR_REUSE || near {
                let scale = relative_scale(norm(q), r, u);
                let bound = state.coupling.abs_product_norm_sq(r).sqrt();
                state.floor = f64::from(f32::EPSILON) * bound / scale;
                state.floor_age = 0;
            } else {
                state.floor_age += 1;
            }
            switch = test.error <= F32_FLOOR_FACTOR * state.floor;
        }
        if switch {
            state.active = false;
        }
        switch
    }

    /// Sweeps done on the f32 copy of the coupling blocks (`None` without it).
    pub(crate) fn f32_sweeps(&self) -> Option<usize> {
        self.f32.as_ref().map(|s| s.sweeps)
    }

    /// Gives the block rows and the colouring of their pattern back (to be kept for the next
    /// problem with the same pattern).
    pub(crate) fn into_prepared(self) -> (BlockRows<'a, D>, Option<Colouring>) {
        (self.rows, self.coloured.map(|c| c.colouring))
    }

    /// Whether the sweep is a coloured one ([`Decomposition::Coloured`]).
    pub(crate) fn is_coloured(&self) -> bool {
        self.coloured.is_some()
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
        self.worker = self.step.worker();
    }

    /// The instant after which the local solves stop iterating, so that one sweep ends soon
    /// after the budget whatever the local iteration limits.
    pub fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.step.set_deadline(deadline);
        self.worker = self.step.worker();
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

    /// The natural-map error a convergence test measures: the problem's own, `u = W r + q` on
    /// W's storage (the bits an independent measurement such as `fc3d_compute_error` finds),
    /// with the product shared out among a coloured sweep's threads when W is sparse-block (the
    /// product is most of a test's cost: on one thread it would cost a 2-thread sweep's time at
    /// 10^5 contacts).
    pub(crate) fn tested_error<P: SweptProblem<D>>(
        &self,
        problem: &P,
        r: &[f64],
        u: &mut [f64],
    ) -> f64 {
        let pool = self.coloured.as_ref().and_then(|c| c.pool.as_deref());
        match (pool, problem.w()) {
            (Some(pool), Delassus::SparseBlock(w)) => {
                velocity_on_threads(w, pool, problem.q(), r, u);
                problem.error_of(r, u)
            }
            _ => problem.error(r, u),
        }
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

/// `u <- W r + q` on a sparse-block W's storage, its block rows cut in one contiguous range per
/// thread of `pool`. Each entry gets the terms of [`Delassus::velocity`] in the same order, so
/// `u` has the bits of the single-threaded product for any number of threads.
fn velocity_on_threads(
    w: &BlockSparseMatrix<'_>,
    pool: &Pool,
    q: &[f64],
    r: &[f64],
    u: &mut [f64],
) {
    let u = SharedSlice::new(u);
    pool.broadcast(&|thread| {
        let rows = crate::matrix::part_of(w.n_block_rows(), thread, pool.threads());
        // SAFETY: these entries belong to this thread's rows only; r and q are only read.
        let part = unsafe { u.range_mut(3 * rows.start..3 * rows.end) };
        part.copy_from_slice(&q[3 * rows.start..3 * rows.end]);
        w.mul_add_block_rows(r, part, rows);
    });
}

/// One sequential sweep over `rows` (in the plan's order): each contact solved against the
/// current reactions of the others and written into `r`; returns the squared increment.
#[allow(clippy::too_many_arguments)]
fn sequential_sweep<const D: usize, P: SweepRows<D>, S: ContactStep<D>>(
    rows: &P,
    step: &S,
    worker: &mut S::Worker,
    memory: &mut [f64],
    plan: &mut SweepPlan,
    q: &[f64],
    mu: &[f64],
    r: &mut [f64],
) -> f64 {
    let nc = rows.n_contacts();
    let mut increment_sq = 0.0;
    for k in 0..nc {
        let c = if plan.order.is_empty() {
            k
        } else {
            plan.order[k]
        };
        increment_sq += update_contact(rows, step, worker, memory, plan, c, q, mu, r);
    }
    increment_sq
}

/// Solves contact `c` against the current reactions of the others and writes its new
/// reaction into `r`; returns the squared increment.
#[allow(clippy::too_many_arguments)]
#[inline]
fn update_contact<const D: usize, P: SweepRows<D>, S: ContactStep<D>>(
    rows: &P,
    step: &S,
    worker: &mut S::Worker,
    memory: &mut [f64],
    plan: &mut SweepPlan,
    c: usize,
    q: &[f64],
    mu: &[f64],
    r: &mut [f64],
) -> f64 {
    if let Some(left) = plan.frozen.get_mut(c) {
        if *left > 0 {
            *left -= 1;
            return 0.0;
        }
    }
    let track = !plan.u_solved.is_empty();
    let (rc, old, local_q) = new_reaction(
        rows,
        step,
        worker,
        plan.relaxation,
        c,
        q,
        mu,
        &*r,
        &mut memory[c],
        track,
    );
    let d_sq = distance_sq_d(&rc, &old);
    if let Some((sweeps, tol)) = plan.freezing {
        let r_sq = distance_sq_d(&rc, &[0.0; D]);
        if d_sq <= tol * tol * r_sq {
            plan.frozen[c] = sweeps;
        }
    }
    r[D * c..D * c + D].copy_from_slice(&rc);
    if let Some(lq) = local_q.filter(|_| track) {
        let uc = block_vec_add(&rows.diagonal(c), &rc, &lq);
        plan.u_solved[D * c..D * c + D].copy_from_slice(&uc);
    }
    d_sq
}

/// A multicoloured sweep (see [`ColouredPlan`]). Every unit's update depends only on `r` at
/// the start of its colour and on its own contacts, so the result is the same for any number
/// of threads.
#[allow(clippy::too_many_arguments)]
fn coloured_sweep<const D: usize, P: SweepRows<D>, S: ContactStep<D>>(
    rows: &P,
    step: &S,
    memory: &mut [f64],
    relaxation: Option<f64>,
    coloured: &mut ColouredPlan,
    q: &[f64],
    mu: &[f64],
    r: &mut [f64],
) -> f64 {
    let (units, unit_sums) = coloured.units();
    let (increment_sq, _) = units.sweep(
        rows,
        step,
        relaxation,
        q,
        mu,
        &SharedSlice::new(r),
        &SharedSlice::new(memory),
        unit_sums,
    );
    increment_sq
}
