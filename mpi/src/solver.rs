//! The distributed NSGS run: the values of one solve laid over a [`Layout`], sweeps colour by
//! colour with the boundary contacts first and their reactions sent while the interior ones are
//! swept, and the stopping test on exact sums (the same bits on every rank for any partition).
//!
//! Each contact's update is the core's ([`fc3d_core::solvers::nsgs::update_contact`]: the
//! configured one-contact solver, the frictionless shortcut, relaxation) over block rows whose
//! blocks are in increasing global column id, so a contact's local q is summed in the same
//! order on any partition. Within a colour no two contacts are coupled, so the order a rank
//! visits them in does not change a bit.

use std::time::Instant;

use crate::comm::{thread_cpu_seconds, Comm, Op};
use crate::exact::ExactSum;
use crate::halo::Halo;
use crate::input::{fingerprint, LocalRows, RunSettings};
use crate::layout::{Layout, Mode};
use fc3d::{CError, CResult, FC3D_ERR_INTERNAL, FC3D_ERR_INVALID_OPTION};
use fc3d_core::contract::ErrorSchedule;
use fc3d_core::error::{try_copy, try_vec};
use fc3d_core::local::AnyLocalSolver;
use fc3d_core::math::linalg::{block_vec_add, contact_of, distance_sq_d};
use fc3d_core::matrix::BlockRows;
use fc3d_core::measure::contact_residual_sq;
use fc3d_core::solvers::nsgs::{update_contact, ContactStep, LocalStep};
use fc3d_core::{BlockSparseMatrix, LocalTolerance};

/// What one solve reports (the same on every rank).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    pub info: i32,
    pub iterations: usize,
    pub error: f64,
    pub seconds: f64,
}

/// Counters of the last set-up and solve on this rank.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Statistics {
    pub setups: u64,
    pub solves: u64,
    pub sweeps: u64,
    pub seconds_setup: f64,
    pub seconds_compute: f64,
    pub seconds_wait: f64,
    /// CPU seconds of the compute part (below its wall time when the core is shared).
    pub cpu_seconds_compute: f64,
}

/// A communicator, a sweep mode and the set-up kept from one solve to the next.
pub struct DistributedSolver {
    pub comm: Comm,
    pub mode: Mode,
    prepared: Option<(Layout, Halo)>,
    pub statistics: Statistics,
}

/// One solve's values over the known contacts.
struct Values {
    rows: BlockRows<'static>,
    q: Vec<f64>,
    mu: Vec<f64>,
    r: Vec<f64>,
    u: Vec<f64>,
    /// Each contact's step state across sweeps (1 before its first visit).
    memory: Vec<f64>,
    /// `||q||^2` over all ranks.
    q_norm_sq: f64,
}

impl DistributedSolver {
    pub fn new(comm: Comm, mode: Mode) -> Self {
        DistributedSolver {
            comm,
            mode,
            prepared: None,
            statistics: Statistics::default(),
        }
    }

    pub fn layout(&self) -> Option<(&Layout, &Halo)> {
        self.prepared.as_ref().map(|(l, h)| (l, h))
    }

    /// Solves from checked rows and settings (collective; every rank's have been agreed on):
    /// writes r and u (the host's order) only on success.
    pub fn solve(
        &mut self,
        rows: &LocalRows,
        settings: &RunSettings,
        r_out: &mut [f64],
        u_out: &mut [f64],
    ) -> CResult<Outcome> {
        let start = Instant::now();
        let comm = &self.comm;
        let print = fingerprint(settings);
        let mut range = [print, -print];
        comm.allreduce(&mut range, Op::Min)?;
        let same = range[0] == print && -range[1] == print;
        comm.agree(if same {
            Ok(())
        } else {
            Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                "the settings differ between ranks (every rank must pass the same settings)",
            ))
        })?;
        let mut reuse = [i64::from(
            self.prepared
                .as_ref()
                .is_some_and(|(l, _)| l.same_pattern(rows)),
        )];
        comm.allreduce(&mut reuse, Op::Min)?;
        if reuse[0] == 0 {
            self.prepared = None;
            let t = Instant::now();
            let layout = Layout::build(comm, rows, self.mode)?;
            let halo = comm.agree(Halo::new(&layout))?;
            self.statistics.setups += 1;
            self.statistics.seconds_setup = t.elapsed().as_secs_f64();
            self.prepared = Some((layout, halo));
        }
        let (layout, halo) = self.prepared.as_mut().expect("a layout");
        let mut values = comm.agree(values_of(layout, rows))?;
        let mut sums = [ExactSum::default()];
        for &i in &layout.known_of_host {
            for v in &values.q[3 * i..3 * i + 3] {
                sums[0].add(v * v);
            }
        }
        ExactSum::reduce_all(comm, &mut sums, &mut [])?;
        values.q_norm_sq = sums[0].value();
        halo.exchange_all(comm, layout.colours, &mut values.r)?;
        halo.take_wait();
        let mut run = Run {
            comm,
            layout,
            halo,
            values,
            compute: 0.0,
            compute_cpu: 0.0,
            wait: 0.0,
        };
        let outcome = run.iterate(settings, start)?;
        let (compute, compute_cpu) = (run.compute, run.compute_cpu);
        let wait = run.wait + run.halo.take_wait().0;
        let values = run.values;
        let seconds = comm.max_f64(start.elapsed().as_secs_f64())?;
        for (k, &i) in layout.known_of_host.iter().enumerate() {
            r_out[3 * k..3 * k + 3].copy_from_slice(&values.r[3 * i..3 * i + 3]);
            u_out[3 * k..3 * k + 3].copy_from_slice(&values.u[3 * i..3 * i + 3]);
        }
        self.statistics.solves += 1;
        self.statistics.sweeps = outcome.iterations as u64;
        self.statistics.seconds_compute = compute;
        self.statistics.seconds_wait = wait;
        self.statistics.cpu_seconds_compute = compute_cpu;
        Ok(Outcome { seconds, ..outcome })
    }
}

/// The known contacts' blocks, q, mu and warm start (ghosts: zero blocks, their r received).
fn values_of(layout: &Layout, rows: &LocalRows) -> CResult<Values> {
    let n = layout.n_known();
    // Input-sized: allocated fallibly (an out-of-memory error is agreed on by the caller).
    let mut blocks = try_vec(layout.block_source.len(), [0.0; 9], "blocks")?;
    for (block, &b) in blocks.iter_mut().zip(&layout.block_source) {
        if b != usize::MAX {
            block.copy_from_slice(&rows.blocks[9 * b..9 * b + 9]);
        }
    }
    let w = BlockSparseMatrix::new(
        n,
        n,
        try_copy(&layout.row_ptr, "row pointers")?,
        try_copy(&layout.cols, "column indices")?,
        blocks,
    )?;
    let rows_view = BlockRows::from_block_sparse(&w)?;
    let (mut q, mut mu, mut r) = (
        try_vec(3 * n, 0.0, "q")?,
        try_vec(n, 0.0, "mu")?,
        try_vec(3 * n, 0.0, "r")?,
    );
    for (k, &i) in layout.known_of_host.iter().enumerate() {
        q[3 * i..3 * i + 3].copy_from_slice(&rows.q[3 * k..3 * k + 3]);
        r[3 * i..3 * i + 3].copy_from_slice(&rows.r[3 * k..3 * k + 3]);
        mu[i] = rows.mu[k];
    }
    Ok(Values {
        rows: rows_view,
        q,
        mu,
        r,
        u: try_vec(3 * n, 0.0, "u")?,
        memory: try_vec(n, 1.0, "the contacts' step state")?,
        q_norm_sq: 0.0,
    })
}

struct Run<'s> {
    comm: &'s Comm,
    layout: &'s Layout,
    halo: &'s mut Halo,
    values: Values,
    compute: f64,
    compute_cpu: f64,
    wait: f64,
}

/// The sums one sweep reduces: squared increment and squared norm of r.
struct SweepSums {
    increment: ExactSum,
    norm: ExactSum,
    panicked: bool,
}

impl Run<'_> {
    /// The main loop: sweep, reduce, test (Siconos' error-evaluation schedule), until
    /// convergence, the sweep limit or the time budget (agreed on: any rank past the deadline
    /// stops all of them).
    fn iterate(&mut self, settings: &RunSettings, start: Instant) -> CResult<Outcome> {
        let limits = settings.limits;
        let nsgs = &settings.nsgs;
        let mut step = LocalStep::new(&self.values.rows, &nsgs.local)?;
        let deadline = limits.time_budget.and_then(|b| start.checked_add(b));
        step.set_deadline(deadline);
        let mut worker = step.worker();
        let mut memory = std::mem::take(&mut self.values.memory);
        let mut schedule = ErrorSchedule::new(
            nsgs.error_evaluation,
            limits.tolerance,
            nsgs.evaluation_frequency,
            limits.max_iter,
        );
        let nc = self.layout.total_contacts.max(1) as f64;
        let mut info = 1;
        let mut iterations = 0;
        let mut final_error = None;
        for iteration in 1..=limits.max_iter {
            let (t, cpu) = (Instant::now(), thread_cpu_seconds());
            let sums = self.sweep(&step, &mut worker, &mut memory, nsgs.relaxation)?;
            let (waited, waited_cpu) = self.halo.take_wait();
            self.compute += t.elapsed().as_secs_f64() - waited;
            self.compute_cpu += thread_cpu_seconds() - cpu - waited_cpu;
            self.wait += waited;
            iterations = iteration;
            let out_of_time = deadline.is_some_and(|d| Instant::now() >= d);
            let mut reduced = [sums.increment, sums.norm];
            let mut flags = [i64::from(out_of_time), i64::from(sums.panicked)];
            let t = Instant::now();
            ExactSum::reduce_all(self.comm, &mut reduced, &mut flags)?;
            self.wait += t.elapsed().as_secs_f64();
            if flags[1] > 0 {
                return Err(CError::new(
                    FC3D_ERR_INTERNAL,
                    "internal error: a one-contact solve panicked on a rank",
                ));
            }
            let (increment, norm) = (reduced[0].value().sqrt(), reduced[1].value().sqrt());
            let light = if norm > 0.0 {
                increment / norm
            } else {
                increment
            };
            let mut failure = None;
            let test = schedule.test_light(iteration, light, |_| match self.measure() {
                Ok(e) => e,
                Err(e) => {
                    failure = Some(e);
                    f64::NAN
                }
            });
            if let Some(e) = failure {
                return Err(e);
            }
            final_error = test.full.then_some(test.error);
            if test.tested {
                let tolerance = match nsgs.local_tolerance {
                    LocalTolerance::Given => None,
                    LocalTolerance::Adaptive { ratio } => {
                        Some((test.error / ratio).max(limits.tolerance / nc))
                    }
                    LocalTolerance::AdaptivePerContact { ratio } => Some(test.error / (ratio * nc)),
                };
                if let Some(t) = tolerance {
                    step.set_tolerance(t);
                    worker = step.worker();
                }
            }
            if test.converged {
                info = 0;
                break;
            }
            if test.stalled {
                break;
            }
            if flags[0] > 0 {
                info = 2;
                break;
            }
        }
        let error = match final_error {
            Some(e) => e,
            None => self.measure()?,
        };
        if iterations == 0 && error <= limits.tolerance {
            info = 0;
        }
        Ok(Outcome {
            info,
            iterations,
            error,
            seconds: 0.0,
        })
    }

    /// One sweep, colour by colour: wait for the previous colour's ghosts, update the boundary
    /// contacts and send them, update the interior ones while the messages travel.
    fn sweep(
        &mut self,
        step: &LocalStep,
        worker: &mut AnyLocalSolver,
        memory: &mut [f64],
        relaxation: Option<f64>,
    ) -> CResult<SweepSums> {
        let mut sums = SweepSums {
            increment: ExactSum::default(),
            norm: ExactSum::default(),
            panicked: false,
        };
        let colours = self.layout.colours;
        self.halo.post_receives(self.comm)?;
        for k in 0..colours {
            if k > 0 {
                self.halo.wait_colour(k - 1, &mut self.values.r)?;
            }
            let colour = &self.layout.steps[k];
            self.update(
                &colour.boundary,
                step,
                worker,
                memory,
                relaxation,
                &mut sums,
            );
            self.halo.send_colour(self.comm, k, &self.values.r)?;
            self.update(
                &colour.interior,
                step,
                worker,
                memory,
                relaxation,
                &mut sums,
            );
        }
        if colours > 0 {
            self.halo.wait_colour(colours - 1, &mut self.values.r)?;
        }
        self.halo.wait_sends()?;
        Ok(sums)
    }

    /// Updates `contacts` (known indices) in turn. A panic is caught and reported through the
    /// sweep's sums, so that this rank still sends and receives what the others wait for.
    fn update(
        &mut self,
        contacts: &[usize],
        step: &LocalStep,
        worker: &mut AnyLocalSolver,
        memory: &mut [f64],
        relaxation: Option<f64>,
        sums: &mut SweepSums,
    ) {
        let v = &mut self.values;
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            for &c in contacts {
                let rc: [f64; 3] = update_contact(
                    &v.rows,
                    step,
                    worker,
                    relaxation,
                    c,
                    &v.q,
                    &v.mu,
                    &v.r,
                    &mut memory[c],
                );
                let old: [f64; 3] = contact_of(&v.r, c);
                sums.increment.add(distance_sq_d(&rc, &old));
                sums.norm.add(rc[0] * rc[0] + rc[1] * rc[1] + rc[2] * rc[2]);
                v.r[3 * c..3 * c + 3].copy_from_slice(&rc);
            }
        }));
        if result.is_err() {
            sums.panicked = true;
        }
    }

    /// The relative natural-map error of the current r over all ranks (collective), with
    /// `u = W r + q` left in `values.u` for this rank's contacts.
    fn measure(&mut self) -> CResult<f64> {
        let (t, cpu) = (Instant::now(), thread_cpu_seconds());
        let v = &mut self.values;
        let mut sums = [
            ExactSum::default(),
            ExactSum::default(),
            ExactSum::default(),
        ];
        for &c in &self.layout.known_of_host {
            let rc: [f64; 3] = contact_of(&v.r, c);
            let uc = block_vec_add(&v.rows.diagonal(c), &rc, &v.rows.local_q(c, &v.q, &v.r));
            v.u[3 * c..3 * c + 3].copy_from_slice(&uc);
            sums[0].add(contact_residual_sq(&rc, &uc, v.mu[c]));
            sums[1].add(rc[0] * rc[0] + rc[1] * rc[1] + rc[2] * rc[2]);
            sums[2].add(uc[0] * uc[0] + uc[1] * uc[1] + uc[2] * uc[2]);
        }
        let computed = Instant::now();
        self.compute += (computed - t).as_secs_f64();
        self.compute_cpu += thread_cpu_seconds() - cpu;
        ExactSum::reduce_all(self.comm, &mut sums, &mut [])?;
        self.wait += computed.elapsed().as_secs_f64();
        let scale = v
            .q_norm_sq
            .sqrt()
            .max(sums[1].value().sqrt())
            .max(sums[2].value().sqrt());
        let residual = sums[0].value().sqrt();
        Ok(if scale > 0.0 {
            residual / scale
        } else {
            residual
        })
    }
}

/// The layout's kind of sweep.
impl Mode {
    pub fn code(self) -> i32 {
        match self {
            Mode::Reproducible => 0,
            Mode::Fast => 1,
        }
    }
}
