//! A workspace for a sequence of solves (one per time step of a host's simulation): what a solve
//! learns about the contacts and about W is kept for the next one.
//!
//! * **Warm start by contact id.** The host names its contacts with ids of its own (any `i64`,
//!   unique within a step). Each solve starts contact `c` from the reaction the contact with id
//!   `ids[c]` had at the end of the previous solve; a contact that was not there (it appeared)
//!   starts from `r_c = 0`; a contact of the previous step that is absent now (it vanished) is
//!   forgotten.
//! * **Active set.** Whether each contact ended the last solve pushing (`r_N > 0`), by id.
//! * **Prepared W.** The structures a family builds from W before iterating — NSGS's block rows
//!   and the colouring of a coloured sweep, NSN's Newton matrix pattern with its symbolic LU
//!   factorization — are kept and refilled with the new values when the new W has the same block
//!   pattern. A W that is a view of a host's blocks (the C API's sparse-block W) is read in place
//!   on every call, never converted: the kept rows hold their own copy of its index arrays to
//!   compare patterns, not its blocks. The check is part of the refill: one pass over the stored
//!   blocks, no allocation for the block rows; when the pattern changed, the structure is
//!   rebuilt (and counted in [`WorkspaceStats`]).
//! * **AUTO's last choice** ([`Workspace::auto_choice`]): while the tolerance and the budget are
//!   unchanged, AUTO starts from the stage of its plan that reached the tolerance in the
//!   previous solve. On the same W block pattern it skips its feature pass; on another one
//!   (contacts appeared or vanished) it measures the features and resumes only if they give the
//!   same rule. Its NSGS and Newton stages use the kept structures.
//!
//! A workspace solve is the ordinary [`crate::solve`] (same checks, rescaling, post-processing
//! and reported error) started from the warm iterate: its result equals a cold [`crate::solve`]
//! started from [`Workspace::initial_guess`]'s iterate.

use std::collections::HashMap;

use crate::config::{Method, SolverConfig};
use crate::contract::{Observer, SolveReport, SolverOutcome};
use crate::error::Fc3dError;
use crate::matrix::{BlockRows, Delassus};
use crate::problem::FrictionProblem;
use crate::solve::solve_with_runner;
use crate::solvers::auto::{auto_with, AutoCarry, AutoChoice};
use crate::solvers::nsgs::{nsgs_on_rows, Decomposition, PreparedSweep};
use crate::solvers::nsn::{nsn_on, NewtonSolver};

/// What a workspace remembers of one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ContactMemory {
    reaction: [f64; 3],
    active: bool,
}

/// Counters of what a workspace reused (cumulative since [`Workspace::new`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WorkspaceStats {
    /// Solves run through the workspace.
    pub solves: usize,
    /// Contacts started from their previous reaction.
    pub warm_contacts: usize,
    /// Contacts started from zero (they appeared).
    pub cold_contacts: usize,
    /// Solves whose prepared W structure (block rows or Newton matrix) was refilled in place.
    pub structure_reused: usize,
    /// Solves that had to build it (first solve, pattern change, other family).
    pub structure_built: usize,
    /// Coloured NSGS solves that took the colouring kept from an earlier solve.
    pub colouring_reused: usize,
    /// AUTO solves that resumed from the last choice (no feature pass).
    pub auto_resumed: usize,
}

/// How many contacts [`Workspace::initial_guess`] started warm and cold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WarmStart {
    pub warm: usize,
    pub cold: usize,
}

/// Keeps what one solve learned for the next one; see the module documentation.
///
/// ```
/// use fc3d_core::{scenes::sequences, solve, NsgsOptions, SolverConfig, Workspace};
/// let config = SolverConfig::new(NsgsOptions::default()).with_tolerance(1e-8);
/// // A short simulation, stepped with cold solves, gives the problems of each step.
/// let mut cold = |p: &fc3d_core::FrictionProblem<'_>| {
///     let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
///     solve(p, &config, &mut r, &mut u).unwrap();
///     r
/// };
/// let sequence = sequences::box_slide(20, &mut cold);
/// let mut ws = Workspace::new();
/// for step in sequence.steps {
///     let n = step.problem.size();
///     let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
///     let report = ws.solve(&step.problem, &config, &step.ids, &mut r, &mut u).unwrap();
///     assert!(report.converged());
/// }
/// assert!(ws.stats().warm_contacts > 0);
/// ```
#[derive(Default)]
pub struct Workspace {
    memory: HashMap<i64, ContactMemory>,
    /// The map being built for the current solve (kept to reuse its allocation).
    next_memory: HashMap<i64, ContactMemory>,
    /// Kept detached ([`BlockRows::into_detached`]): a host's borrowed blocks are not kept
    /// past its call.
    sweep: Option<PreparedSweep<'static>>,
    newton: Option<NewtonSolver>,
    auto_choice: Option<AutoChoice>,
    stats: WorkspaceStats,
}

impl std::fmt::Debug for Workspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Workspace")
            .field("contacts", &self.memory.len())
            .field("has_block_rows", &self.sweep.is_some())
            .field("has_newton_matrix", &self.newton.is_some())
            .field("auto_choice", &self.auto_choice)
            .field("stats", &self.stats)
            .finish()
    }
}

impl Workspace {
    /// An empty workspace: the first solve is a cold one.
    pub fn new() -> Self {
        Self::default()
    }

    /// Writes into `r` the warm start for contacts named `ids` (previous reaction of each known
    /// id, zero for a new one). Fails, leaving `r` untouched, when `r` does not hold 3 entries
    /// per id or an id repeats.
    pub fn initial_guess(&self, ids: &[i64], r: &mut [f64]) -> Result<WarmStart, Fc3dError> {
        if r.len() != 3 * ids.len() {
            return Err(Fc3dError::dims("reaction", 3 * ids.len(), r.len()));
        }
        check_unique(ids)?;
        let mut start = WarmStart { warm: 0, cold: 0 };
        for (rc, id) in r.chunks_exact_mut(3).zip(ids) {
            match self.memory.get(id) {
                Some(m) => {
                    rc.copy_from_slice(&m.reaction);
                    start.warm += 1;
                }
                None => {
                    rc.iter_mut().for_each(|v| *v = 0.0);
                    start.cold += 1;
                }
            }
        }
        Ok(start)
    }

    /// Solves `problem`, whose contact `c` the host names `ids[c]`, from the warm start of
    /// [`Workspace::initial_guess`] (whatever `r` holds on entry), and remembers the result.
    /// On success `r`, `u` and the report are those of [`crate::solve`]; on `Err`, `r`, `u` and
    /// the remembered reactions are unchanged.
    pub fn solve(
        &mut self,
        problem: &FrictionProblem<'_>,
        config: &SolverConfig,
        ids: &[i64],
        r: &mut [f64],
        u: &mut [f64],
    ) -> Result<SolveReport, Fc3dError> {
        self.solve_with_observer(problem, config, ids, r, u, &mut |_| {})
    }

    /// [`Workspace::solve`] with an observer called after every iteration.
    pub fn solve_with_observer(
        &mut self,
        problem: &FrictionProblem<'_>,
        config: &SolverConfig,
        ids: &[i64],
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolveReport, Fc3dError> {
        if ids.len() != problem.n_contacts() {
            return Err(Fc3dError::dims(
                "contact ids",
                problem.n_contacts(),
                ids.len(),
            ));
        }
        if r.len() != problem.size() {
            return Err(Fc3dError::dims("reaction", problem.size(), r.len()));
        }
        if u.len() != problem.size() {
            return Err(Fc3dError::dims("velocity", problem.size(), u.len()));
        }
        // The warm iterate goes to a copy: r stays untouched if the solve fails.
        let mut start = crate::error::try_vec(problem.size(), 0.0, "warm start")?;
        let counts = self.initial_guess(ids, &mut start)?;
        // Room to remember this step's contacts, reserved before anything changes.
        self.next_memory.clear();
        self.next_memory
            .try_reserve(ids.len())
            .map_err(|_| Fc3dError::OutOfMemory {
                what: "workspace contact memory".into(),
                bytes: ids.len() * std::mem::size_of::<(i64, ContactMemory)>(),
            })?;
        let (sweep, newton, stats) = (&mut self.sweep, &mut self.newton, &mut self.stats);
        // Only an AUTO solve that follows an AUTO solve resumes.
        let mut last_choice = self.auto_choice.take();
        let auto_choice = &mut self.auto_choice;
        let mut runner = |p: &FrictionProblem<'_>,
                          cfg: &SolverConfig,
                          r: &mut [f64],
                          u: &mut [f64],
                          obs: &mut Observer<'_>|
         -> Result<SolverOutcome, Fc3dError> {
            let limits = cfg.limits();
            match &cfg.method {
                Method::Nsgs(options) => {
                    let (prepared, _) = prepared_sweep(sweep.take(), p.w(), stats)?;
                    if options.decomposition == Decomposition::Coloured
                        && prepared.colouring.is_some()
                    {
                        stats.colouring_reused += 1;
                    }
                    let (outcome, back) = nsgs_on_rows(p, options, &limits, prepared, r, u, obs);
                    *sweep = back.and_then(detached);
                    outcome
                }
                Method::Auto(options) => {
                    let (prepared, same_pattern) = prepared_sweep(sweep.take(), p.w(), stats)?;
                    let mut carry = AutoCarry {
                        sweep: Some(prepared),
                        newton: newton.take(),
                        resume: last_choice.take(),
                        same_pattern,
                        choice: None,
                        resumed: false,
                    };
                    let outcome = auto_with(p, options, &limits, r, u, obs, &mut carry);
                    if outcome.is_ok() && carry.resumed {
                        stats.auto_resumed += 1;
                    }
                    *sweep = carry.sweep.and_then(detached);
                    *newton = carry.newton;
                    *auto_choice = carry.choice;
                    outcome
                }
                Method::Nsn(options) => {
                    let (mut solver, reused) = NewtonSolver::reusing(p, options, newton.take())?;
                    if reused {
                        stats.structure_reused += 1;
                    } else {
                        stats.structure_built += 1;
                    }
                    let outcome = nsn_on(&mut solver, p, &limits.start(), r, u, obs);
                    *newton = Some(solver);
                    Ok(outcome)
                }
                other => other.family().run(p, &limits, r, u, obs),
            }
        };
        let mut u_out = crate::error::try_vec(problem.size(), 0.0, "velocity")?;
        // Room to remember this solve's contacts, taken before anything is written.
        self.next_memory.clear();
        self.next_memory
            .try_reserve(ids.len())
            .map_err(|_| Fc3dError::OutOfMemory {
                what: "the workspace's memory of the contacts".into(),
                bytes: ids
                    .len()
                    .saturating_mul(std::mem::size_of::<(i64, ContactMemory)>()),
            })?;
        let report = solve_with_runner(
            problem,
            config,
            &mut start,
            &mut u_out,
            observer,
            &mut runner,
        )?;
        r.copy_from_slice(&start);
        u.copy_from_slice(&u_out);
        self.remember(ids, r);
        self.stats.solves += 1;
        self.stats.warm_contacts += counts.warm;
        self.stats.cold_contacts += counts.cold;
        Ok(report)
    }

    /// Replaces the remembered contacts by those of this solve (room reserved before the solve).
    fn remember(&mut self, ids: &[i64], r: &[f64]) {
        self.next_memory.clear();
        for (rc, &id) in r.chunks_exact(3).zip(ids) {
            self.next_memory.insert(
                id,
                ContactMemory {
                    reaction: [rc[0], rc[1], rc[2]],
                    active: rc[0] > 0.0,
                },
            );
        }
        std::mem::swap(&mut self.memory, &mut self.next_memory);
    }

    /// The reaction contact `id` ended the last solve with, if it was part of it.
    pub fn last_reaction(&self, id: i64) -> Option<[f64; 3]> {
        self.memory.get(&id).map(|m| m.reaction)
    }

    /// Whether contact `id` ended the last solve pushing (`r_N > 0`), if it was part of it.
    pub fn was_active(&self, id: i64) -> Option<bool> {
        self.memory.get(&id).map(|m| m.active)
    }

    /// Number of contacts remembered (those of the last solve).
    pub fn n_remembered(&self) -> usize {
        self.memory.len()
    }

    /// Where AUTO's last solve through this workspace ended (rule, plan, the stage that reached
    /// the tolerance); `None` before, after a solve with another method, one that failed or one
    /// that did not reach its tolerance (an anytime solve keeps the stage its budget ended in).
    pub fn auto_choice(&self) -> Option<&AutoChoice> {
        self.auto_choice.as_ref()
    }

    pub fn stats(&self) -> &WorkspaceStats {
        &self.stats
    }

    /// Forgets everything (reactions, prepared structures, counters): the next solve is cold.
    pub fn clear(&mut self) {
        *self = Workspace::default();
    }
}

/// A prepared sweep that may outlive the call whose W it was built on (see
/// [`BlockRows::into_detached`]); `None` when its index arrays cannot be copied.
fn detached(prepared: PreparedSweep<'_>) -> Option<PreparedSweep<'static>> {
    Some(PreparedSweep {
        rows: prepared.rows.into_detached()?,
        colouring: prepared.colouring,
    })
}

/// The block rows of `w`: `kept` refilled in place (with its colouring) when `w` has its
/// pattern, else built anew (without colouring); the flag tells whether the pattern held.
fn prepared_sweep<'a>(
    kept: Option<PreparedSweep<'static>>,
    w: &Delassus<'a>,
    stats: &mut WorkspaceStats,
) -> Result<(PreparedSweep<'a>, bool), Fc3dError> {
    if let Some(kept) = kept {
        let mut prepared: PreparedSweep<'a> = kept;
        if prepared.rows.refill_from(w) {
            stats.structure_reused += 1;
            return Ok((prepared, true));
        }
    }
    stats.structure_built += 1;
    let rows: BlockRows<'a> = w.block_rows()?;
    Ok((
        PreparedSweep {
            rows,
            colouring: None,
        },
        false,
    ))
}

fn check_unique(ids: &[i64]) -> Result<(), Fc3dError> {
    let mut seen = std::collections::HashSet::new();
    seen.try_reserve(ids.len())
        .map_err(|_| Fc3dError::OutOfMemory {
            what: "contact id check".into(),
            bytes: std::mem::size_of_val(ids),
        })?;
    for (c, id) in ids.iter().enumerate() {
        if !seen.insert(*id) {
            return Err(Fc3dError::InvalidOption(format!(
                "contact id {id} is given twice (second time for contact {c}): ids must be unique within a solve"
            )));
        }
    }
    Ok(())
}
