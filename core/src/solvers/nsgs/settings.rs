//! Settings of the nonsmooth Gauss-Seidel solver (NSGS, Siconos id 500) beyond the common
//! limits, with Siconos' defaults.

use crate::contract::ErrorEvaluation;
use crate::error::{require_setting, Fc3dError};
use crate::local::{LocalSolverKind, LocalSolverOptions};

/// How the local solver's tolerance is set during NSGS (Siconos iparam[2], ratio in dparam[2]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LocalTolerance {
    /// The local solver's own tolerance, fixed (Siconos' default, "given value").
    Given,
    /// After each measured sweep: `max(error / ratio, tolerance / n_contacts)` ("adaptive").
    Adaptive { ratio: f64 },
    /// After each measured sweep: `error / (ratio * n_contacts)` ("adaptive per contact").
    AdaptivePerContact { ratio: f64 },
}

/// Order in which a sweep visits the contacts (Siconos iparam[5], seed iparam[6]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactOrder {
    /// Contacts in index order (default).
    Natural,
    /// One random permutation drawn from `seed` before the first sweep.
    ShuffledOnce { seed: u64 },
    /// A new random permutation before every sweep, drawn from a generator seeded with `seed`.
    ShuffledEachSweep { seed: u64 },
}

/// How a sweep splits the contacts for threads (and islands). Every choice but
/// [`Decomposition::Sequential`] visits the contacts in another Gauss-Seidel order than Siconos',
/// so its sweep counts differ from Siconos'; the results are bitwise identical for any number of
/// threads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Decomposition {
    /// One thread, contacts in the order of [`ContactOrder`] (default; Siconos 4.4's iteration).
    #[default]
    Sequential,
    /// Block-multicoloured Gauss-Seidel: the contacts are cut in units of 512 consecutive
    /// contacts, and the units coloured greedily (index order, smallest free colour) so that no
    /// two units of a colour are coupled through W (in either direction); a sweep visits the
    /// colours in turn, the units of one colour in parallel, each unit in index order. Every
    /// contact sees the newest reactions of all its neighbours, as in any Gauss-Seidel sweep;
    /// only the order differs from index order.
    Coloured,
    /// Connected components of the contact graph (through W's off-diagonal blocks) solved as
    /// independent problems, in parallel: each island is swept in index order with its own
    /// stopping test (its residual against its share `||q|| sqrt(n_I / n)` of the tolerance)
    /// and stops being swept once converged; a contact
    /// coupled to no other is solved once and checked. The reported error is the global one.
    /// An island of 4096 contacts or more is swept by all threads together as
    /// [`Decomposition::Coloured`] sweeps a problem (its own units and colours); smaller ones
    /// are shared among the threads, one island per thread at a time.
    /// Adaptive local tolerances are not applied (the local solver's own tolerance is used).
    Islands,
}

/// Acceleration of the sweep across iterations (an fc3d option; Siconos has none).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Acceleration {
    /// Plain Gauss-Seidel (default).
    #[default]
    None,
    /// Anderson's type-II step over the last `memory` sweeps (1..=16), safeguarded: an
    /// extrapolated point is kept only while the sweep from it shrinks the residual
    /// `|G(x) - x|`; otherwise the run falls back to the plain sweep's output and restarts the
    /// history. The error is measured on sweep outputs only. Sequential order or
    /// [`Decomposition::Coloured`] only; no freezing.
    Anderson { memory: usize },
}

/// The switch error of [`F32Sweeps::default`] (measured on generated piles and shared problems,
/// docs/convergence.md, "Cheaper bytes").
pub const DEFAULT_F32_SWITCH_ERROR: f64 = 1e-5;

/// Early sweeps on an f32 copy of W's coupling blocks (issue 27 item 5; an fc3d option, Rust
/// and CLI only: no Siconos slot, not exposed through the C API). The off-diagonal blocks of
/// W's rows are rounded once to f32 (about 6e-8 relative an entry; the copy is allocated
/// fallibly, about half the bytes of the coupling) and the row products `q_c + sum_d W_cd r_d`
/// read them with f64 accumulation; the diagonal blocks and the local solves stay in f64. The
/// run sweeps on the copy until the first of: a test whose error (the one the schedule
/// measures, cheap or full) is at most `switch_error`; a full test above the tolerance within
/// 4x of the f32 rounding floor (`2^-24 || |W_off| |r| ||` over the error's scale, one pass
/// over the copy, refreshed every 64 full tests or when the error nears it); a stalled test. It then sweeps on W's f64 blocks to the tolerance. Every full error, the final one
/// included, is measured in f64 on the host's W. A W with an entry beyond f32's range is swept
/// in f64 throughout. Sequential and [`Decomposition::Coloured`] sweeps (bitwise identical for
/// any number of threads), not [`Decomposition::Islands`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct F32Sweeps {
    /// The error at or below which the sweep leaves the f32 copy (default
    /// [`DEFAULT_F32_SWITCH_ERROR`]; finite and > 0: the floor rule needs a full test, which the
    /// default cheap test makes only once its cheap error passes the tolerance).
    pub switch_error: f64,
}

impl Default for F32Sweeps {
    fn default() -> Self {
        F32Sweeps {
            switch_error: DEFAULT_F32_SWITCH_ERROR,
        }
    }
}

/// Settings of the nonsmooth Gauss-Seidel solver (NSGS, Siconos id 500). Its limits default to
/// 1000 sweeps and a tolerance of 1e-4. Under a time budget NSGS stops after the sweep that
/// spends it and returns the best iterate it measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NsgsOptions {
    /// Error evaluation strategy (default [`ErrorEvaluation::LightWithFullFinal`]).
    pub error_evaluation: ErrorEvaluation,
    /// The stopping test runs every `evaluation_frequency` sweeps (default 1; Siconos iparam[8],
    /// where 0 also means every sweep). The last allowed sweep is always tested.
    pub evaluation_frequency: usize,
    /// The one-contact solver and its options (default [`LocalSolverKind::NewtonHybrid`]).
    pub local: LocalSolverOptions,
    /// How the local tolerance evolves (default [`LocalTolerance::Given`]).
    pub local_tolerance: LocalTolerance,
    /// Over-relaxation (PSOR): each contact takes `omega r_new + (1 - omega) r_old`, projected on
    /// its cone when `omega > 1` would leave it. `None` (default) is plain Gauss-Seidel. `omega`
    /// must lie in (0, 2).
    pub relaxation: Option<f64>,
    /// Contact visiting order (default [`ContactOrder::Natural`]).
    pub order: ContactOrder,
    /// Freezing: a contact whose reaction moved by less than `tolerance * ||r_c||` in a sweep is
    /// skipped for this many following sweeps (default `None`: never frozen). Convergence is
    /// always confirmed on all contacts.
    pub freezing: Option<usize>,
    /// How contacts are split for threads (default [`Decomposition::Sequential`]).
    /// [`Decomposition::Coloured`] and [`Decomposition::Islands`] take the natural order and no
    /// freezing, and do not run Dumont's criterion.
    pub decomposition: Decomposition,
    /// Threads of a [`Decomposition::Coloured`] or [`Decomposition::Islands`] run (ignored by
    /// [`Decomposition::Sequential`]): 0 (default) takes the environment variable
    /// `FC3D_NUM_THREADS` when it holds a positive integer, else the machine's available
    /// parallelism. The results do not depend on it.
    pub threads: usize,
    /// Acceleration across sweeps (default [`Acceleration::None`]).
    pub acceleration: Acceleration,
    /// Early sweeps on an f32 copy of W's coupling blocks (default `None`: f64 throughout).
    pub f32_sweeps: Option<F32Sweeps>,
}

impl Default for NsgsOptions {
    fn default() -> Self {
        NsgsOptions {
            error_evaluation: ErrorEvaluation::LightWithFullFinal,
            evaluation_frequency: 1,
            local: LocalSolverOptions::default(),
            local_tolerance: LocalTolerance::Given,
            relaxation: None,
            order: ContactOrder::Natural,
            freezing: None,
            decomposition: Decomposition::Sequential,
            threads: 0,
            acceleration: Acceleration::None,
            f32_sweeps: None,
        }
    }
}

impl NsgsOptions {
    /// Default options with another local solver.
    pub fn with_local(kind: LocalSolverKind) -> Self {
        NsgsOptions {
            local: LocalSolverOptions::new(kind),
            ..Default::default()
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        self.local.validate()?;
        if let Some(omega) = self.relaxation {
            require_setting(
                omega > 0.0 && omega < 2.0,
                "nsgs.relaxation",
                omega,
                "in (0, 2)",
            )?;
        }
        if self.decomposition != Decomposition::Sequential {
            let name = "nsgs.decomposition";
            let value = format!("{:?}", self.decomposition);
            let why = "sequential with a shuffled order, freezing or Dumont's criterion";
            let supported = self.order == ContactOrder::Natural
                && self.freezing.is_none_or(|k| k == 0)
                && self.error_evaluation != ErrorEvaluation::DumontCriterion;
            require_setting(supported, name, value, why)?;
        }
        if let Acceleration::Anderson { memory } = self.acceleration {
            require_setting(
                (1..=super::anderson::MAX_MEMORY).contains(&memory),
                "nsgs.acceleration.memory",
                memory,
                "in 1..=16",
            )?;
            let supported = self.decomposition != Decomposition::Islands
                && self.freezing.is_none_or(|k| k == 0)
                && self.error_evaluation != ErrorEvaluation::DumontCriterion;
            let why = "the sequential or coloured sweep without freezing or Dumont's criterion";
            require_setting(supported, "nsgs.acceleration", "Anderson", why)?;
        }
        if let Some(f) = self.f32_sweeps {
            let e = f.switch_error;
            let name = "nsgs.f32_sweeps.switch_error";
            require_setting(e > 0.0 && e.is_finite(), name, e, "finite and > 0")?;
            let why = "the sequential or coloured sweep";
            let supported = self.decomposition != Decomposition::Islands;
            require_setting(supported, "nsgs.f32_sweeps", "islands", why)?;
        }
        match self.local_tolerance {
            LocalTolerance::Given => Ok(()),
            LocalTolerance::Adaptive { ratio } | LocalTolerance::AdaptivePerContact { ratio } => {
                require_setting(
                    ratio > 0.0 && ratio.is_finite(),
                    "nsgs.local_tolerance.ratio",
                    ratio,
                    "finite and > 0",
                )
            }
        }
    }
}
