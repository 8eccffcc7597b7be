//! The C ABI: a thin layer that converts Siconos-layout structs into core types, validates
//! them, calls the core and converts back. It holds no numerics.
//!
//! Contract (also in docs/c-api.md):
//! * Every `extern "C"` function runs inside [`ffi_guard`]: a Rust panic is caught and turned into
//!   [`FC3D_ERR_INTERNAL`]; nothing unwinds into C, nothing aborts or exits.
//! * Functions returning `int` return 0 on success, 1 when a solver ran but did not reach its
//!   tolerance, and a negative `FC3D_ERR_*` code for rejected input. Functions returning a pointer
//!   return NULL on failure. `void` functions leave their outputs unchanged on failure. In all
//!   cases [`fc3d_last_error_message`] returns the reason (per thread), and it is printed to
//!   stderr when `numerics_set_verbose(>0)`.
//! * Outputs (reaction, velocity, iparam[1], dparam[1], out-pointers) are written only on success.
//! * Memory that C may free (problem arrays, matrices, options arrays) is allocated with the C
//!   allocator (`malloc`), so `free` and the `_free`/`_delete` functions may be mixed as in Siconos.

// Without Siconos' names, the code only they use is left unused (not exported).
#![cfg_attr(not(feature = "siconos-abi"), allow(dead_code, unused_imports))]

pub mod types;

mod alart_curnier;
mod alloc;
mod codes;
mod driver;
mod errors;
mod fc2d;
mod fclib;
mod global;
mod host_problem;
mod lmgc;
mod matrix;
mod measures;
/// cbindgen:ignore
mod names;
mod native;
mod option_tree;
mod options;
mod params;
mod problem;
mod problem_files;
mod rolling;
mod solver_entries;
mod solver_list;
mod stream;
mod workspace;

use std::os::raw::c_int;
use std::sync::atomic::Ordering;

pub use codes::*;
pub(crate) use errors::verbose;
pub use errors::{fc3d_clear_last_error, fc3d_last_error_code, fc3d_last_error_message};
// For libraries built on this one (fc3d-mpi): the same panic boundary, errors and settings.
pub use errors::{ffi_guard, CError, CResult};
pub use native::{fc3d_version, settings_config, Fc3dProblem, Fc3dResult, Fc3dSettings};
pub use option_tree::{
    FC3D_OPTIONS_MAX_DEPTH, FC3D_OPTIONS_MAX_INTERNAL_SOLVERS, FC3D_OPTIONS_MAX_PARAM_SIZE,
};
pub use solver_list::{fc3d_solver_at, fc3d_solver_count, FC3D_AUTO};
pub use workspace::{
    Fc3dWorkspace, FC3D_CONTACT_APEX, FC3D_CONTACT_SLIDE, FC3D_CONTACT_STICK, FC3D_CONTACT_TAKE_OFF,
};

/// Index in `dparam` of fc3d's wall-clock budget in seconds (0, the default: no budget). An index
/// Siconos' fc3d solvers leave unused.
pub const FC3D_DPARAM_TIME_BUDGET: c_int = 19;
/// Index in `dparam` where NSGS writes Dumont's criterion (37) at its last test when it ran with
/// `iparam[7] = FC3D_ERROR_EVALUATION_DUMONT` (output; untouched otherwise). Unused by Siconos.
pub const FC3D_DPARAM_DUMONT_CRITERION: c_int = 18;
/// Value of NSGS's `iparam[7]` (error evaluation) selecting Dumont's criterion (37) as the
/// stopping test, beside Siconos' 0 (full), 1 (light) and 2 (light with full final). The
/// reported error `dparam[1]` stays the natural-map error.
pub const FC3D_ERROR_EVALUATION_DUMONT: c_int = 20;
/// Index in a local solver's `iparam` (NSGS's internal solver 0) choosing the variant of the
/// one-contact solvers 550, 551, 565 and 553: `FC3D_VARIANT_SICONOS` (0, the default of
/// `solver_options_create`) runs Siconos 4.4's iteration step for step,
/// `FC3D_VARIANT_FC3D` fc3d's refinements (relative stop test before each Newton step, a
/// failed line search keeps its best decrease, 565 keeps the best point of all rounds, 553
/// restarts from `rho = 1 / W_NN` and stops on the relative residual). Unused by Siconos.
pub const FC3D_IPARAM_VARIANT: c_int = 19;
/// `iparam[FC3D_IPARAM_VARIANT]`: Siconos 4.4's one-contact iteration (default).
pub const FC3D_VARIANT_SICONOS: c_int = 0;
/// `iparam[FC3D_IPARAM_VARIANT]`: fc3d's refined one-contact iteration.
pub const FC3D_VARIANT_FC3D: c_int = 1;
/// Index in NSGS's (500) `iparam` choosing how sweeps split the contacts for threads, an index
/// Siconos' NSGS leaves unused: `FC3D_NSGS_SEQUENTIAL` (0, default: Siconos 4.4's order and
/// sweep counts), `FC3D_NSGS_COLOURED` (multicoloured Gauss-Seidel, contacts of one colour
/// solved in parallel) or `FC3D_NSGS_ISLANDS` (connected components solved independently, in
/// parallel, each with its own stopping test). Results are bitwise identical for any number of
/// threads; the sweep order, and so the sweep counts, differ from Siconos'.
pub const FC3D_IPARAM_NSGS_DECOMPOSITION: c_int = 15;
/// Index in NSGS's (500) `iparam` of the threads of a coloured or islands run: 0 (default) takes
/// the environment variable `FC3D_NUM_THREADS`, else the machine's available parallelism.
pub const FC3D_IPARAM_NSGS_THREADS: c_int = 16;
/// `iparam[FC3D_IPARAM_NSGS_DECOMPOSITION]`: one thread, Siconos' order (default).
pub const FC3D_NSGS_SEQUENTIAL: c_int = 0;
/// `iparam[FC3D_IPARAM_NSGS_DECOMPOSITION]`: multicoloured parallel sweeps.
pub const FC3D_NSGS_COLOURED: c_int = 1;
/// `iparam[FC3D_IPARAM_NSGS_DECOMPOSITION]`: islands solved independently, in parallel.
pub const FC3D_NSGS_ISLANDS: c_int = 2;
/// Length of iparam and dparam (Siconos' OPTIONS_PARAM_SIZE).
pub const OPTIONS_PARAM_SIZE: c_int = 20;
/// fc3d's value of a local solver's `iparam[9]` (rho strategy) for Dumont's rule
/// `rho_N = rho_T = alpha / W_NN`, with alpha in `dparam[3]` (Siconos 4.4 uses 0..=4). Default
/// of the local solvers `FC3D_ONECONTACT_EBP` and `FC3D_ONECONTACT_EAL` (alpha = 1).
pub const FC3D_RHO_STRATEGY_DUMONT: c_int = 10;
/// fc3d's one-contact solver ids are in 568..=599, a range Siconos 4.4 leaves free (its
/// one-contact solvers use 550..=567). FP-VI-UPK of Acary-Brémond-Huber's Table 3 on one contact:
/// projection steps with the self-adaptive rho rule (98), started from rho strategy iparam[9]
/// (default 1, spectral norm). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_FP_VI_UPK: c_int = 570;
/// Dumont's EBP (2021): Newton on the bipotential fixed point `r = P_K(r - rho ũ)` with the
/// condensed 3x3 system (32); rho by iparam[9] (default `FC3D_RHO_STRATEGY_DUMONT`, alpha =
/// dparam[3] = 1). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_EBP: c_int = 571;
/// Dumont's EAL (2021): Newton on the augmented-Lagrangian fixed point; the same function as
/// the Alart-Curnier Newton 550, with Dumont's rho (`FC3D_RHO_STRATEGY_DUMONT`) by default.
pub const FC3D_ONECONTACT_EAL: c_int = 572;
/// Output index in AUTO's `iparam`: the stages it took, one decimal digit each, first stage
/// most significant (1 NSGS, 2 NSN-AC, 3 PROX, 4 ADMM, 5 TFP, 6 EG, 7 TFP-APGD; 12 = NSGS then
/// NSN-AC).
pub const FC3D_IPARAM_AUTO_STAGES: c_int = 18;

/// Siconos' verbosity switch: > 0 prints rejected calls and solver summaries to stderr.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
#[allow(non_snake_case)]
pub extern "C" fn numerics_set_verbose(newVerboseMode: c_int) {
    errors::VERBOSE.store(newVerboseMode, Ordering::Relaxed);
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc3d_core::LocalSolverKind;

    /// The C names of fc3d's one-contact ids are the core's ids.
    #[test]
    fn one_contact_ids_are_the_cores() {
        for (id, kind) in [
            (FC3D_ONECONTACT_FP_VI_UPK, LocalSolverKind::FpViUpk),
            (FC3D_ONECONTACT_EBP, LocalSolverKind::EnhancedBipotential),
            (
                FC3D_ONECONTACT_EAL,
                LocalSolverKind::EnhancedAugmentedLagrangian,
            ),
        ] {
            assert_eq!(id, kind.siconos_id());
        }
    }
}
