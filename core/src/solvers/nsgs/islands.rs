//! NSGS by islands ([`Decomposition::Islands`]): the connected components of the contact graph
//! are independent friction problems, each with its own stopping test, its share of the error
//! (133) (see [`Island::error`]), and no longer swept once it passes; a contact coupled to no
//! other is solved once and checked. An island of fewer than [`COLOURED_ISLAND`] contacts is
//! swept in index order (Siconos' order restricted to the island, so its iterates are those of
//! a sequential NSGS on it alone) by one thread; threads take such islands, largest first, for
//! [`VISIT`] sweeps at a time, so that under a time budget every island progresses. A larger
//! island is swept by all threads together, as [`Decomposition::Coloured`] sweeps a whole
//! problem (units of consecutive contacts of the island, coloured), so that a scene with one
//! dominant pile does not run on one thread. Which islands are coloured depends on their size
//! only, never on the number of threads: results are the same for any number of threads.
//! After every round of visits the global error (133) is measured: the run stops when it passes
//! (it is the error reported), and its normalisation sets the islands' shares. Should every
//! island stop while the global error is above the tolerance, the islands run again with a
//! tolerance tightened by the missing ratio (at most [`ROUNDS`] times).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

use super::coloured::{Colouring, Units, UNIT};
use super::parallel::{resolve_threads, ContactGraph, Pool, Reactions, SharedSlice, SpinBarrier};
use super::settings::{Decomposition, NsgsOptions};
use super::step::{new_reaction, ContactStep};
use super::sweeper::Sweeper;
use crate::alloc::{reserve, try_push};
use crate::contract::SolverOutcome;
use crate::contract::{deadline_passed, ErrorSchedule, IterationEvent, Limits, Observer};
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::{block_vec_add, distance_sq_d};
use crate::matrix::BlockRows;
use crate::measure::{contact_residual_sq_d, natural_map_error_by_rows, relative_scale};
use crate::problem::FrictionProblem;

/// Rounds of island solves at most (the first, and tightened ones).
const ROUNDS: usize = 4;

/// Sweeps an island gets per visit: islands take turns, so that under a time budget every
/// island progresses (the results do not depend on it).
const VISIT: usize = 16;

/// Islands of at least this many contacts (8 units of the coloured sweep) are swept by all
/// threads together with the coloured scheme; smaller ones by one thread each, in index order.
/// Below it a coloured island has too few units per colour to share among threads, and the
/// sweep order of the small Capsules and RockPile problems stays Siconos' order.
pub(crate) const COLOURED_ISLAND: usize = 8 * UNIT;

/// A large island's coloured schedule and its per-unit sums.
struct ColouredIsland {
    colouring: Colouring,
    next_unit: Vec<AtomicUsize>,
    unit_sums: Vec<f64>,
}

/// An island's run: its stopping test and where it stands.
struct IslandRun {
    schedule: ErrorSchedule,
    /// Sweeps counted by `schedule` (since the last tightening).
    tested: usize,
    /// Sweeps done in all.
    sweeps: usize,
    done: bool,
}

impl IslandRun {
    /// Records one sweep of `island` with squared increment `increment_sq` and squared
    /// reaction norm `r_sq`, and runs the island's test; true when the island stops being
    /// swept for now (converged, stalled, out of sweeps, or the deadline passed, then flagged
    /// in `timed_out`).
    fn after_sweep(
        &mut self,
        island: &Island<'_>,
        reactions: &SharedSlice<'_>,
        (increment_sq, r_sq): (f64, f64),
        limits: (usize, Option<std::time::Instant>),
        timed_out: &AtomicBool,
    ) -> bool {
        let (max_iter, deadline) = limits;
        self.sweeps += 1;
        self.tested += 1;
        // A lone contact was solved exactly: go straight to the full test.
        let light = if island.contacts.len() == 1 {
            0.0
        } else if r_sq > 0.0 {
            (increment_sq / r_sq).sqrt()
        } else {
            increment_sq.sqrt()
        };
        let test = self
            .schedule
            .test_light(self.tested, light, |_| island.error(reactions));
        if test.converged || test.stalled || self.sweeps >= max_iter {
            self.done = true;
            return true;
        }
        if deadline_passed(deadline) {
            timed_out.store(true, Ordering::Relaxed);
            return true;
        }
        false
    }
}

pub(crate) fn run_islands(
    problem: &FrictionProblem<'_>,
    sweeper: &mut Sweeper,
    options: &NsgsOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    debug_assert_eq!(options.decomposition, Decomposition::Islands);
    let run = limits.start();
    sweeper.set_deadline(run.deadline());
    let (order, start) = ContactGraph::new(sweeper.island_parts().0, 1)?.islands()?;
    let n_islands = start.len() - 1;
    // Islands come largest first: the coloured ones are the first n_coloured.
    let n_coloured = (0..n_islands)
        .take_while(|&i| start[i + 1] - start[i] >= COLOURED_ISLAND)
        .count();
    let mut coloured = Vec::new();
    if n_coloured > 0 {
        let nc = problem.n_contacts();
        let mut position = try_vec(nc, 0usize, "island positions")?;
        for i in 0..n_coloured {
            for (p, &c) in order[start[i]..start[i + 1]].iter().enumerate() {
                position[c] = p;
            }
        }
        for i in 0..n_coloured {
            let contacts = &order[start[i]..start[i + 1]];
            let colouring = Colouring::of_island(sweeper.island_parts().0, contacts, &position)?;
            let unit_sums = try_vec(2 * colouring.n_units(), 0.0, "sweep increments")?;
            let next_unit = (0..colouring.n_colours())
                .map(|_| AtomicUsize::new(0))
                .collect();
            let island = ColouredIsland {
                colouring,
                next_unit,
                unit_sums,
            };
            try_push(&mut coloured, island, "the coloured islands")?;
        }
    }
    let threads = match n_coloured {
        0 => resolve_threads(options.threads).min(n_islands.max(1)),
        _ => resolve_threads(options.threads),
    };
    let pool = Pool::shared(threads)?;
    let barrier = SpinBarrier::new(pool.as_ref().map_or(1, |p| p.threads()));
    let (q, mu) = (problem.q(), problem.mu());
    let tol = run.tolerance;
    let nc = problem.n_contacts().max(1) as f64;
    let norm_q = match crate::math::linalg::norm(q) {
        n if n > 0.0 && n.is_finite() => n,
        _ => 1.0,
    };
    // Normalisation of the error (133) at the last global measurement (||q|| before the first).
    let mut scale = norm_q;
    let new_run = |island_tol: f64, sweeps: usize| IslandRun {
        schedule: ErrorSchedule::new(
            options.error_evaluation,
            island_tol,
            options.evaluation_frequency,
            run.max_iter - sweeps,
        ),
        tested: 0,
        sweeps,
        done: sweeps >= run.max_iter,
    };
    let mut islands: Vec<Mutex<IslandRun>> = Vec::new();
    reserve(&mut islands, n_islands, "the island runs")?;
    islands.extend((0..n_islands).map(|_| Mutex::new(new_run(tol, 0))));
    let mut island_tol = tol;
    let mut rounds = 1;
    let timed_out = AtomicBool::new(false);
    let error = loop {
        let next = AtomicUsize::new(n_coloured);
        let (rows, step, memory, relaxation) = sweeper.island_parts();
        {
            let reactions = SharedSlice::new(r);
            let memory = SharedSlice::new(memory);
            let island_of = |i: usize| {
                let contacts = &order[start[i]..start[i + 1]];
                Island {
                    contacts,
                    scale: scale * (contacts.len() as f64 / nc).sqrt(),
                    rows,
                    q,
                    mu,
                }
            };
            let limits = (run.max_iter, run.deadline());
            // The large islands one after the other, each swept by all threads.
            for (i, plan) in coloured.iter_mut().enumerate() {
                if timed_out.load(Ordering::Relaxed) {
                    break;
                }
                let mut state = islands[i].lock().unwrap_or_else(|e| e.into_inner());
                if state.done {
                    continue;
                }
                let ColouredIsland {
                    colouring,
                    next_unit,
                    unit_sums,
                } = plan;
                let island = island_of(i);
                let units = Units {
                    contacts: Some(island.contacts),
                    colouring,
                    next_unit,
                    barrier: &barrier,
                    pool: pool.as_deref(),
                };
                for _ in 0..VISIT {
                    let sums = units.sweep(
                        rows, step, relaxation, q, mu, &reactions, &memory, unit_sums,
                    );
                    if state.after_sweep(&island, &reactions, sums, limits, &timed_out) {
                        break;
                    }
                }
            }
            // The small islands shared among the threads, one thread per island.
            let job = |_thread: usize| {
                let mut worker = step.worker();
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= n_islands || timed_out.load(Ordering::Relaxed) {
                        break;
                    }
                    let mut state = islands[i].lock().unwrap_or_else(|e| e.into_inner());
                    if state.done {
                        continue;
                    }
                    let island = island_of(i);
                    for _ in 0..VISIT {
                        let sums = island.sweep(step, &mut worker, relaxation, &reactions, &memory);
                        if state.after_sweep(&island, &reactions, sums, limits, &timed_out) {
                            break;
                        }
                    }
                }
            };
            if n_coloured < n_islands && !timed_out.load(Ordering::Relaxed) {
                match &pool {
                    Some(pool) => pool.broadcast(&job),
                    None => job(0),
                }
            }
        }
        // The global error after every round of visits: the run stops on it, and its
        // normalisation sets the islands' shares for the next round.
        let error = natural_map_error_by_rows(problem, rows, r, u);
        scale = relative_scale(norm_q, r, u);
        if timed_out.load(Ordering::Relaxed) || error <= tol || !error.is_finite() {
            break error;
        }
        let (mut all_done, mut exhausted) = (true, true);
        for state in &islands {
            let state = state.lock().unwrap_or_else(|e| e.into_inner());
            all_done &= state.done;
            exhausted &= state.sweeps >= run.max_iter;
        }
        if exhausted || (all_done && rounds == ROUNDS) {
            break error;
        }
        if all_done {
            // Every island passed its test yet the whole did not: ask the islands for the
            // missing ratio (with a margin) and go on from where they are.
            rounds += 1;
            island_tol *= 0.5 * tol / error;
            for state in &islands {
                let mut state = state.lock().unwrap_or_else(|e| e.into_inner());
                *state = new_run(island_tol, state.sweeps);
            }
        }
    };
    let iterations = islands
        .iter()
        .map(|s| s.lock().unwrap_or_else(|e| e.into_inner()).sweeps)
        .max()
        .unwrap_or(0);
    observer(&IterationEvent {
        iteration: iterations,
        reaction: r,
        error,
    });
    Ok(SolverOutcome::stopped(
        iterations,
        timed_out.load(Ordering::Relaxed),
    ))
}

/// One island: its contacts (index order) and what their local problems need.
struct Island<'a> {
    contacts: &'a [usize],
    /// `s_I` of [`Island::error`] (1 when q = 0).
    scale: f64,
    rows: &'a BlockRows<'a>,
    q: &'a [f64],
    mu: &'a [f64],
}

impl Island<'_> {
    /// One Gauss-Seidel sweep over the island; returns (squared increment, ||r_island||^2).
    fn sweep<S: ContactStep<3>>(
        &self,
        step: &S,
        worker: &mut S::Worker,
        relaxation: Option<f64>,
        reactions: &SharedSlice<'_>,
        memory: &SharedSlice<'_>,
    ) -> (f64, f64) {
        let (mut increment_sq, mut r_sq) = (0.0, 0.0);
        for &c in self.contacts {
            let mut m = memory.get(c);
            let (rc, old, _) = new_reaction(
                self.rows, step, worker, relaxation, c, self.q, self.mu, reactions, &mut m, false,
            );
            increment_sq += distance_sq_d(&rc, &old);
            r_sq += distance_sq_d(&rc, &[0.0; 3]);
            // SAFETY: islands share no contact and each is swept by one thread at a time.
            unsafe {
                reactions.set_contact(c, &rc);
                memory.set(c, m);
            }
        }
        (increment_sq, r_sq)
    }

    /// The island's share of the error (133): its natural-map residual over
    /// `s_I = S sqrt(n_I / n)`, with `S = max(||q||, ||r||, ||u||)` of the whole problem at the
    /// last global measurement, so that `sum_I s_I^2 = S^2`: when every island's share is below
    /// the tolerance, so is the global error (up to the change of S). An island with small
    /// forces is not asked for a relative accuracy the global error does not need (its own
    /// relative error (133) would: on the Capsules problems that took 10-100 times the sweeps);
    /// splitting by load instead measured no better.
    fn error(&self, reactions: &SharedSlice<'_>) -> f64 {
        let mut res = 0.0;
        for &c in self.contacts {
            let rc: [f64; 3] = reactions.contact(c);
            let lq = Reactions::<3>::local_q(reactions, self.rows, c, self.q);
            let uc = block_vec_add(&self.rows.diagonal(c), &rc, &lq);
            res += contact_residual_sq_d(&rc, &uc, self.mu[c]);
        }
        res.sqrt() / self.scale
    }
}
