//! fc3d-core: solvers for the discrete 3D frictional contact problem FC(W, q, mu) in Delassus
//! form: find `r, u` in R^{3 nc} with `u = W r + q` and, for every contact `c`,
//! `K*_c ∋ u_c + mu_c ||u_{T,c}|| e_N ⟂ r_c ∈ K_c` (Signorini contact with exact Coulomb friction),
//! where `K_c = { r : ||r_T|| <= mu_c r_N }` is the Coulomb cone.
//!
//! This crate is the pure-Rust core: no FFI types, no CLI dependencies. The C ABI (Siconos
//! Numerics 4.4 compatible) is the `fc3d` crate; the `fc3d` command is `fc3d-cli`.
//!
//! Entry points: build a [`FrictionProblem`] from a [`Delassus`] operator, `q` and `mu`, pick a
//! [`SolverConfig`] (limits plus a [`Method`]), call [`solve`]. Every [`SolveReport`] carries the
//! error measured on the returned `(r, u)` with [`natural_map_error`], never the tolerance that
//! was asked for.
//!
//! Layers, bottom to top (no module imports one above it; `tests/architecture.rs` checks it):
//! `error`, `math` → `matrix` → `problem` → `measure` → `contract` → `local` → `solvers` →
//! `config` → `solve` → `workspace`; `io` and `scenes` build problems, `diagnostics` sits beside
//! `measure`. See `docs/architecture.md`.

mod alloc;
pub mod config;
pub mod contract;
pub mod diagnostics;
pub mod error;
pub mod global;
pub mod io;
pub mod local;
pub mod math;
pub mod matrix;
pub mod measure;
pub mod problem;
pub mod scenes;
pub mod solve;
pub mod solvers;
pub mod workspace;

pub use config::{
    Method, MethodChoice, MethodConfig, PlanarConfig, Rescaling, RollingConfig, SolverConfig,
};
pub use contract::Fill;
pub use contract::{
    ErrorEvaluation, InnerTolerance, IterationEvent, Limits, Observer, SolveReport, SolveStatus,
};
pub use contract::{Stage, StageEnd, StageKind, StageLog};
pub use diagnostics::{diagnose, ContactDiagnostic, ContactStatus, DiagnosticOptions, Diagnostics};
pub use error::Fc3dError;
pub use local::rolling::RollingProjectionIteration;
pub use local::{
    AlgorithmVariant, LocalSolverKind, LocalSolverOptions, NewtonFormulation, RhoRule,
};
pub use matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
pub use measure::natural_map_error;
pub use problem::{FrictionProblem, FrictionProblem2d, RollingProblem, RollingProblem2d};
pub use solve::{
    check_w_before_solving_in_place, solve, solve_planar, solve_planar_with_observer,
    solve_rolling, solve_rolling_with_observer, solve_with_observer,
};
pub use solvers::accelerated::{ApgdSettings, SpgSettings};
pub use solvers::aclm::{AclmInnerSolver, AclmOptions};
pub use solvers::admm::{AdmmAcceleration, AdmmInitialRho, AdmmOptions, AdmmRhoStrategy};
pub use solvers::auto::{AutoChoice, AutoOptions, PlannedStage, ProblemFeatures};
pub use solvers::nsgs::{
    Acceleration, ContactOrder, Decomposition, F32Sweeps, LocalTolerance, NsgsOptions, Sweeper,
    DEFAULT_F32_SWITCH_ERROR, NUM_THREADS_ENV,
};
pub use solvers::nsn::{NsnFormulation, NsnLineSearch, NsnOptions};
pub use solvers::pfp::PfpOptions;
pub use solvers::planar::{PlanarMethod, PlanarNsgsOptions};
pub use solvers::prox::{ProxInternal, ProxOptions};
pub use solvers::rolling::{RollingLocalSolver, RollingMethod, RollingNsgsOptions};
pub use solvers::soclcp::SoclcpOptions;
pub use solvers::tresca::{TrescaInnerSolver, TrescaOptions};
pub use solvers::vi::{
    ExtraGradientCorrection, HyperplaneSearch, SelfAdaptiveStep, StepRatio, StepSize, TrialStart,
    ViIteration, ViOptions, ViSolver,
};
pub use workspace::{WarmStart, Workspace, WorkspaceStats};

/// The README's Rust examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
struct ReadmeDoctests;

/// And those of the docs pages that hold Rust code.
#[cfg(doctest)]
#[doc = include_str!("../../docs/time-stepping.md")]
struct TimeSteppingDoctests;
