//! The schedule of a coloured sweep: the contacts cut in units of [`UNIT`] consecutive
//! contacts, the units coloured by the coupling of W's block pattern ([`Colouring`]), and the
//! sweep of the units colour after colour on a pool of threads ([`Units`]).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use super::parallel::{ContactGraph, Coupling, PoisonOnPanic, Pool, SharedSlice, SpinBarrier};
use super::step::{new_reaction, ContactStep};
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::distance_sq_d;
use crate::matrix::SweepRows;

/// A coloured sweep's schedule: the contacts cut in units of [`UNIT`] consecutive contacts,
/// the units coloured so that no two units of a colour are coupled. Colour after colour, the
/// threads take the colour's units one at a time and sweep each in index order: a Gauss-Seidel
/// order close to index order, with each unit's contacts and reactions contiguous in memory.
/// Units and colours do not depend on the number of threads, and each unit's squared increment
/// has its own slot, summed in unit order: the sweep is the same for any number of threads.
pub(super) struct ColouredPlan {
    pub(super) colouring: Colouring,
    pub(super) unit_sums: Vec<f64>,
    /// Next unit to take, per colour.
    pub(super) next_unit: Vec<AtomicUsize>,
    pub(super) barrier: SpinBarrier,
    pub(super) pool: Option<Arc<Pool>>,
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
    pub(crate) fn of(rows: &impl Coupling) -> Result<Self, Fc3dError> {
        let (order, colour_start) = ContactGraph::new(rows, UNIT)?.colour()?;
        Ok(Colouring {
            order,
            colour_start,
        })
    }

    /// The colouring of the units of an island: `contacts` (in index order), closed under
    /// coupling; `position[c]` is contact c's position in `contacts`.
    pub(crate) fn of_island(
        rows: &impl Coupling,
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
    pub(super) fn new(
        rows: &impl Coupling,
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

impl ColouredPlan {
    /// The schedule of a sweep over all contacts, and the slots of its units' sums.
    pub(super) fn units(&mut self) -> (Units<'_>, &mut [f64]) {
        let ColouredPlan {
            colouring,
            unit_sums,
            next_unit,
            barrier,
            pool,
        } = self;
        let units = Units {
            contacts: None,
            colouring,
            next_unit,
            barrier,
            pool: pool.as_deref(),
        };
        (units, unit_sums)
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
    /// One NSGS sweep of `rows`' contacts (see [`Units::run`]): each contact's update
    /// ([`new_reaction`]) written into `reactions` and `memory`.
    #[allow(clippy::too_many_arguments)]
    pub fn sweep<const D: usize, P: SweepRows<D>, S: ContactStep<D>>(
        &self,
        rows: &P,
        step: &S,
        relaxation: Option<f64>,
        q: &[f64],
        mu: &[f64],
        reactions: &SharedSlice<'_>,
        memory: &SharedSlice<'_>,
        unit_sums: &mut [f64],
    ) -> (f64, f64) {
        let update = |worker: &mut S::Worker, c: usize| {
            let mut m = memory.get(c);
            let (rc, old, _) = new_reaction(
                rows, step, worker, relaxation, c, q, mu, reactions, &mut m, false,
            );
            // SAFETY: contact c belongs to the unit being swept, by one thread only, and no
            // unit of its colour reads another's contacts; the barrier between colours orders
            // these writes before the next colour's reads.
            unsafe {
                reactions.set_contact(c, &rc);
                memory.set(c, m);
            }
            (distance_sq_d(&rc, &old), distance_sq_d(&rc, &[0.0; D]))
        };
        self.run(rows.n_contacts(), || step.worker(), update, unit_sums)
    }

    /// One sweep of `update` over the positions: colour after colour, the threads take the
    /// colour's units and update each unit's contacts in position order (`update(worker, c)`
    /// returns contact c's squared increment and squared reaction norm, and may write only
    /// what belongs to c and to the contacts it is coupled with). `unit_sums` (two slots per
    /// unit) receives each unit's sums; returns their totals, taken in unit order, so that the
    /// result does not depend on the number of threads. `n_contacts` counts the positions
    /// when `contacts` is `None`.
    pub fn run<W>(
        &self,
        n_contacts: usize,
        worker: impl Fn() -> W + Sync,
        update: impl Fn(&mut W, usize) -> (f64, f64) + Sync,
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
        let n_positions = self.contacts.map_or(n_contacts, |c| c.len());
        let (contacts, next_unit, barrier) = (self.contacts, self.next_unit, self.barrier);
        let sums = SharedSlice::new(unit_sums);
        let job = |_thread: usize| {
            let _poison = PoisonOnPanic(barrier);
            let mut worker = worker();
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
                        let (i, n) = update(&mut worker, c);
                        increment += i;
                        norm += n;
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
