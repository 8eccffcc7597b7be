//! The codes every fc3d C function returns, and the library's version. Shared by the Siconos
//! ABI (`fc3d.h`) and the native entry (`fc3d_native.h`).

use std::os::raw::c_int;

/// Major version of the library (semantic versioning: the C ABI changes only with it).
pub const FC3D_VERSION_MAJOR: c_int = 0;
/// Minor version of the library.
pub const FC3D_VERSION_MINOR: c_int = 2;
/// Patch version of the library.
pub const FC3D_VERSION_PATCH: c_int = 0;

/// Success (and "converged" for solvers).
pub const FC3D_OK: c_int = 0;
/// A solver ran and returned its best iterate, but the error is above the tolerance.
pub const FC3D_NOT_CONVERGED: c_int = 1;
/// A solver ran until its time budget (`dparam[FC3D_DPARAM_TIME_BUDGET]`) was spent; the
/// reaction is the best iterate it measured, and its error is above the tolerance.
pub const FC3D_TIME_BUDGET_EXHAUSTED: c_int = 2;
/// A solver of a relaxed problem (SOCLCP, id 517) solved its relaxation to the tolerance, but
/// the result is not a Coulomb solution: `dparam[1]`, the Coulomb natural-map error of the
/// returned reaction, is above the tolerance (some contact slides).
pub const FC3D_RELAXED_NOT_COULOMB: c_int = 3;
/// The reaction grew without bound and the solver stopped (`info` 4): its iterates diverged,
/// or they ran along a direction d with W d = 0 into which q pushes (q·d < 0), where the relative
/// error falls as ||r|| grows although the problem has no solution. `dparam[1]` is the error of
/// the returned reaction.
pub const FC3D_UNBOUNDED: c_int = 4;
/// A required pointer argument (or a pointer inside a struct) is NULL.
pub const FC3D_ERR_NULL_POINTER: c_int = -1;
/// Sizes are negative, inconsistent, or too large.
pub const FC3D_ERR_INVALID_SIZE: c_int = -2;
/// Unknown or unsupported matrix storage, or an inconsistent sparse structure.
pub const FC3D_ERR_INVALID_STORAGE: c_int = -3;
/// NaN or infinity in W, q, mu or the initial reaction.
pub const FC3D_ERR_NON_FINITE: c_int = -4;
/// An option value out of range (iparam/dparam), or an option not implemented.
pub const FC3D_ERR_INVALID_OPTION: c_int = -5;
/// A solver id that fc3d does not implement.
pub const FC3D_ERR_UNSUPPORTED_SOLVER: c_int = -6;
/// The problem is ill-posed as given: mu < 0, a missing diagonal block, dimension != 3.
pub const FC3D_ERR_INVALID_PROBLEM: c_int = -7;
/// A malformed or truncated problem file.
pub const FC3D_ERR_PARSE: c_int = -8;
/// A file could not be opened, read or written.
pub const FC3D_ERR_IO: c_int = -9;
/// Memory for input-sized data could not be allocated (a size too large for the machine).
pub const FC3D_ERR_OUT_OF_MEMORY: c_int = -10;
/// A bug in fc3d (a caught panic). Please report it.
pub const FC3D_ERR_INTERNAL: c_int = -99;
