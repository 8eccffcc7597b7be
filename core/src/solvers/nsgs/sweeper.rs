//! One Gauss-Seidel sweep over the contacts, prepared once per problem: the block-row view of
//! W, the one-contact step, and the sweep options (order, relaxation, freezing). The sweep is
//! generic over the contact dimension `D`: the 3D NSGS (Siconos 500) drives it with the local
//! solver of its options ([`LocalStep`]), the 2D NSGS (Siconos 400) with the exact 2x2 solve.

use std::time::Instant;

use crate::error::Fc3dError;
use crate::local::{AnyLocalSolver, LocalProblem, LocalSolver, LocalSolverOptions};
use crate::math::linalg::{block_vec_add, distance_sq_d, Block};
use crate::matrix::{BlockRows, BlockSparseMatrix, Delassus};
use crate::measure::SweptProblem;
use crate::problem::FrictionProblem;

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;

use super::parallel::{
    resolve_threads, ContactGraph, PoisonOnPanic, Pool, Reactions, SharedSlice, SpinBarrier,
};
use super::settings::{ContactOrder, Decomposition, NsgsOptions};
use crate::contract::ErrorEvaluation;
use crate::error::try_vec;

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
    fn new(rows: &BlockRows, options: &LocalSolverOptions) -> Result<Self, Fc3dError> {
        let nc = rows.n_contacts();
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

    #[inline]
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
}

/// A coloured sweep's schedule: the contacts cut in units of [`UNIT`] consecutive contacts,
/// the units coloured so that no two units of a colour are coupled. Colour after colour, the
/// threads take the colour's units one at a time and sweep each in index order: a Gauss-Seidel
/// order close to index order, with each unit's contacts and reactions contiguous in memory.
/// Units and colours do not depend on the number of threads, and each unit's squared increment
/// has its own slot, summed in unit order: the sweep is the same for any number of threads.
struct ColouredPlan {
    colouring: Colouring,
    unit_sums: Vec<f64>,
    /// Next unit to take, per colour.
    next_unit: Vec<AtomicUsize>,
    barrier: SpinBarrier,
    pool: Option<Arc<Pool>>,
}

/// Consecutive contacts swept by one thread as a unit in a coloured sweep.
pub(crate) const UNIT: usize = 512;

/// The units of a coloured sweep grouped by colour: it depends on W's block pattern only (not
/// on its values nor on the number of threads), so a workspace keeps it while the pattern holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Colouring {
    /// Units grouped by colour.
    order: Vec<usize>,
    /// Where each colour's units start in `order` (one more entry than colours).
    colour_start: Vec<usize>,
}

impl Colouring {
    fn of<const D: usize>(rows: &BlockRows<D>) -> Result<Self, Fc3dError> {
        let (order, colour_start) = ContactGraph::new(rows, UNIT)?.colour()?;
        Ok(Colouring {
            order,
            colour_start,
        })
    }

    /// The colouring of the units of an island: `contacts` (in index order), closed under
    /// coupling; `position[c]` is contact c's position in `contacts`.
    pub(crate) fn of_island<const D: usize>(
        rows: &BlockRows<D>,
        contacts: &[usize],
        position: &[usize],
    ) -> Result<Self, Fc3dError> {
        let graph = ContactGraph::over(rows, Some((contacts, position)), UNIT)?;
        let (order, colour_start) = graph.colour()?;
        Ok(Colouring {
            order,
            colour_start,
        })
    }

    /// Number of units.
    pub(crate) fn n_units(&self) -> usize {
        self.order.len()
    }

    /// Number of colours.
    pub(crate) fn n_colours(&self) -> usize {
        self.colour_start.len() - 1
    }
}

impl ColouredPlan {
    /// The plan over `colouring`, which must be that of `rows`' pattern (computed when `None`).
    fn new<const D: usize>(
        rows: &BlockRows<D>,
        threads: usize,
        colouring: Option<Colouring>,
    ) -> Result<Self, Fc3dError> {
        let colouring = match colouring {
            Some(c) => c,
            None => Colouring::of(rows)?,
        };
        let n_colours = colouring.colour_start.len() - 1;
        let unit_sums = try_vec(2 * colouring.order.len(), 0.0, "sweep increments")?;
        let pool = Pool::shared(threads)?;
        let threads = pool.as_ref().map_or(1, |p| p.threads());
        Ok(ColouredPlan {
            colouring,
            unit_sums,
            next_unit: (0..n_colours).map(|_| AtomicUsize::new(0)).collect(),
            barrier: SpinBarrier::new(threads),
            pool,
        })
    }
}

/// The schedule of one coloured sweep over a set of contacts: the positions of `contacts`
/// (every contact in index order when `None`) cut in units of [`UNIT`] consecutive positions,
/// coloured by `colouring`. Used for the whole problem ([`Decomposition::Coloured`]) and for each
/// large island ([`Decomposition::Islands`]).
pub(crate) struct Units<'s> {
    pub contacts: Option<&'s [usize]>,
    pub colouring: &'s Colouring,
    /// Next unit to take, per colour (reset by every sweep).
    pub next_unit: &'s [AtomicUsize],
    /// For the threads of `pool` (one thread without it).
    pub barrier: &'s SpinBarrier,
    pub pool: Option<&'s Pool>,
}

impl Units<'_> {
    /// One sweep: colour after colour, the threads take the colour's units and sweep each in
    /// position order. `unit_sums` (two slots per unit) receives each unit's squared increment
    /// and squared reaction norm; returns their sums, taken in unit order, so that the result
    /// does not depend on the number of threads.
    #[allow(clippy::too_many_arguments)]
    pub fn sweep<const D: usize, S: ContactStep<D>>(
        &self,
        rows: &BlockRows<D>,
        step: &S,
        relaxation: Option<f64>,
        q: &[f64],
        mu: &[f64],
        reactions: &SharedSlice<'_>,
        memory: &SharedSlice<'_>,
        unit_sums: &mut [f64],
    ) -> (f64, f64) {
        for next in self.next_unit {
            next.store(0, Ordering::Relaxed);
        }
        let Colouring {
            order,
            colour_start,
        } = self.colouring;
        let n_colours = colour_start.len() - 1;
        let n_positions = self.contacts.map_or(rows.n_contacts(), |c| c.len());
        let (contacts, next_unit, barrier) = (self.contacts, self.next_unit, self.barrier);
        let sums = SharedSlice::new(unit_sums);
        let job = |_thread: usize| {
            let _poison = PoisonOnPanic(barrier);
            let mut worker = step.worker();
            for k in 0..n_colours {
                let units = &order[colour_start[k]..colour_start[k + 1]];
                loop {
                    let taken = next_unit[k].fetch_add(1, Ordering::Relaxed);
                    let Some(&unit) = units.get(taken) else {
                        break;
                    };
                    let (mut increment, mut norm) = (0.0, 0.0);
                    for position in unit * UNIT..((unit + 1) * UNIT).min(n_positions) {
                        let c = contacts.map_or(position, |contacts| contacts[position]);
                        let mut m = memory.get(c);
                        let (rc, old, _) = new_reaction(
                            rows,
                            step,
                            &mut worker,
                            relaxation,
                            c,
                            q,
                            mu,
                            reactions,
                            &mut m,
                            false,
                        );
                        increment += distance_sq_d(&rc, &old);
                        norm += distance_sq_d(&rc, &[0.0; D]);
                        // SAFETY: contact c belongs to this unit, swept by this thread only,
                        // and no unit of this colour reads another's contacts; the barrier
                        // below orders these writes before the next colour's reads.
                        unsafe {
                            reactions.set_contact(c, &rc);
                            memory.set(c, m);
                        }
                    }
                    // SAFETY: unit taken by this thread only.
                    unsafe {
                        sums.set(2 * unit, increment);
                        sums.set(2 * unit + 1, norm);
                    }
                }
                barrier.wait();
            }
        };
        match self.pool {
            Some(pool) => pool.broadcast(&job),
            None => job(0),
        }
        (0..sums.len() / 2).fold((0.0, 0.0), |(i, n), unit| {
            (i + sums.get(2 * unit), n + sums.get(2 * unit + 1))
        })
    }
}

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
        if options.decomposition == Decomposition::Coloured {
            sweeper.colour(resolve_threads(options.threads), colouring)?;
        }
        Ok(sweeper)
    }
}

/// The new reaction of contact `c` against the reactions `r` (not written), its old reaction,
/// and its local q when `keep_local_q` (or when computed anyway).
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn new_reaction<const D: usize, S: ContactStep<D>, R: Reactions<D> + ?Sized>(
    rows: &BlockRows<D>,
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
    let w = rows.diagonal(c);
    let old: [f64; D] = r.contact(c);
    let wnn = w[0][0];
    let frictionless = step.normal_only(c, mu[c]) && wnn > 0.0 && wnn.is_finite();
    let need_local_q = !frictionless || keep_local_q;
    let local_q = need_local_q.then(|| r.local_q(rows, c, q));
    // The cone is the half-line R+ e_N: only the normal row of the coupling matters. A
    // quotient that overflows (a subnormal W_NN) is left to the one-contact step.
    let scalar = if frictionless {
        let qn = match local_q {
            Some(lq) => lq[0],
            None => r.local_q_normal(rows, c, q),
        };
        Some((-qn / wnn).max(0.0)).filter(|rn| rn.is_finite())
    } else {
        None
    };
    let mut local_q = local_q;
    let mut rc = match scalar {
        Some(rn) => {
            let mut rc = [0.0; D];
            rc[0] = rn;
            rc
        }
        None => {
            let lq = *local_q.get_or_insert_with(|| r.local_q(rows, c, q));
            let mut rc = old;
            step.solve(worker, c, &w, &lq, mu[c], memory, &mut rc);
            rc
        }
    };
    if let Some(omega) = relaxation {
        for (x, o) in rc.iter_mut().zip(&old) {
            *x = omega * *x + (1.0 - omega) * o;
        }
        if omega > 1.0 {
            // Over-relaxation can leave the cone; the iterate must stay admissible.
            rc = step.project(c, &rc, mu[c]);
        }
    }
    (rc, old, local_q)
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
        let plan = SweepPlan::new(options, rows.n_contacts(), D, tolerance);
        let memory = try_vec(rows.n_contacts(), 1.0, "local solver states")?;
        Ok(GaussSeidel {
            worker: step.worker(),
            rows,
            step,
            memory,
            plan,
            coloured: None,
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
        if self.coloured.is_some() {
            return self.coloured_sweep(q, mu, r);
        }
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
        let track = !self.plan.u_solved.is_empty();
        let (rc, old, local_q) = new_reaction(
            &self.rows,
            &self.step,
            &mut self.worker,
            self.plan.relaxation,
            c,
            q,
            mu,
            &*r,
            &mut self.memory[c],
            track,
        );
        let d_sq = distance_sq_d(&rc, &old);
        if let Some((sweeps, tol)) = self.plan.freezing {
            let r_sq = distance_sq_d(&rc, &[0.0; D]);
            if d_sq <= tol * tol * r_sq {
                self.plan.frozen[c] = sweeps;
            }
        }
        r[D * c..D * c + D].copy_from_slice(&rc);
        if let Some(lq) = local_q.filter(|_| track) {
            let uc = block_vec_add(&self.rows.diagonal(c), &rc, &lq);
            self.plan.u_solved[D * c..D * c + D].copy_from_slice(&uc);
        }
        d_sq
    }

    /// Gives the block rows and the colouring of their pattern back (to be kept for the next
    /// problem with the same pattern).
    pub(crate) fn into_prepared(self) -> (BlockRows<'a, D>, Option<Colouring>) {
        (self.rows, self.coloured.map(|c| c.colouring))
    }

    /// A multicoloured sweep (see [`ColouredPlan`]). Every unit's update depends only on `r` at
    /// the start of its colour and on its own contacts, so the result is the same for any
    /// number of threads.
    fn coloured_sweep(&mut self, q: &[f64], mu: &[f64], r: &mut [f64]) -> f64 {
        let GaussSeidel {
            rows,
            step,
            memory,
            plan,
            coloured,
            ..
        } = self;
        let coloured = coloured.as_mut().expect("a coloured plan");
        let ColouredPlan {
            colouring,
            unit_sums,
            next_unit,
            barrier,
            pool,
        } = &mut *coloured;
        let units = Units {
            contacts: None,
            colouring,
            next_unit,
            barrier,
            pool: pool.as_deref(),
        };
        let (increment_sq, _) = units.sweep(
            rows,
            &*step,
            plan.relaxation,
            q,
            mu,
            &SharedSlice::new(r),
            &SharedSlice::new(memory),
            unit_sums,
        );
        increment_sq
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
