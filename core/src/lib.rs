//! fc3d: solvers for the discrete 3D frictional contact problem FC(W, q, mu) in Delassus form,
//!
//! find `r, u` in R^{3 nc} with `u = W r + q` and, for every contact `c`,
//! `K*_c ∋ u_c + mu_c ||u_{T,c}|| e_N ⟂ r_c ∈ K_c` (Signorini contact with exact Coulomb friction),
//! where `K_c = { r : ||r_T|| <= mu_c r_N }` is the Coulomb cone.
//!
//! The crate is a pure-Rust core (this module tree, no FFI types) plus a thin C layer in [`capi`]
//! that reproduces the fc3d part of the Siconos Numerics 4.4 ABI.
//!
//! Entry points: build a [`FrictionProblem`] from a [`Delassus`] operator, `q` and `mu`, pick a
//! [`SolverConfig`], call [`solve`]. Every [`SolveReport`] carries the error measured on the returned
//! `(r, u)` with [`natural_map_error`], never the tolerance that was asked for.

pub mod admm;
pub mod cone;
pub mod error;
pub mod io;
pub mod linalg;
pub mod local;
pub mod matrix;
pub mod measure;
pub mod nsgs;
pub mod nsn;
pub mod options;
pub mod pfp;
pub mod problem;
pub mod prox;
pub mod report;
pub mod scaling;
pub mod scenes;
pub mod soclcp;
pub mod solver;
pub mod tresca;
pub mod vi;

pub use admm::{AdmmAcceleration, AdmmInitialRho, AdmmOptions, AdmmRhoStrategy};
pub use error::Fc3dError;
pub use matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
pub use measure::natural_map_error;
pub use nsgs::Sweeper;
pub use nsn::{NsnFormulation, NsnLineSearch, NsnOptions};
pub use options::{
    ContactOrder, ErrorEvaluation, LocalSolverKind, LocalSolverOptions, LocalTolerance,
    NsgsOptions, RhoRule,
};
pub use problem::FrictionProblem;
pub use prox::{ProxInternal, ProxOptions};
pub use report::{SolveReport, SolveStatus};
pub use scaling::{solve_rescaled, Rescaling};
pub use solver::{solve, solve_with_observer, IterationEvent, SolverConfig};
pub use vi::{SelfAdaptiveStep, StepRatio, StepSize, ViOptions, ViSolver};

/// The README's Rust examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
struct ReadmeDoctests;
