//! `FrictionContactProblem` functions: the conversion to and from the core problem type,
//! creation, copy, rescaling and release (files, streams and display: `problem_files.rs`).
//!
//! Ownership (as in Siconos): `frictionContactProblem_new_with_data` keeps the given pointers
//! (no copy); `frictionContactProblem_free` releases `M` (with `NM_free`), `q`, `mu` (with `free`)
//! and the struct. Problems read from files are allocated the same way.

#![allow(non_snake_case)]

use std::borrow::Cow;
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::alloc::{c_box, c_copy, c_free};
use super::host_problem;
use super::matrix::{
    c_slice, delassus_from_c_blocks, matrix_to_c, nm_clear_impl, nm_duplicate, nm_scale_in_place,
};
use super::types::{FrictionContactProblem, NumericsMatrix};
use super::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_INVALID_SIZE};
use fc3d_core::matrix::{Delassus, DenseMatrix};
use fc3d_core::problem::{FrictionProblem, FrictionProblem2d};

/// A C problem of either dimension.
pub(crate) enum AnyProblem<'a> {
    Spatial(FrictionProblem<'a>),
    Planar(FrictionProblem2d<'a>),
}

/// The core view of a C problem of dimension 2 or 3.
pub(crate) unsafe fn any_problem_from_c<'a>(
    p: &'a FrictionContactProblem,
) -> CResult<AnyProblem<'a>> {
    if p.dimension == 2 {
        planar_problem_from_c(p).map(AnyProblem::Planar)
    } else {
        problem_from_c(p).map(AnyProblem::Spatial)
    }
}

/// The core view of a 3D C problem; dense W, q and mu are borrowed, not copied; every value of
/// W is checked finite.
pub(crate) unsafe fn problem_from_c<'a>(
    p: &'a FrictionContactProblem,
) -> CResult<FrictionProblem<'a>> {
    let view = problem_view_from_c(p)?;
    view.w().check_finite()?;
    Ok(view)
}

/// [`problem_from_c`] for a solve: a sparse-block W is a view of the host's blocks (nothing
/// copied, see `delassus_view_from_c`) whose values are not read up front; the solve looks for
/// non-finite ones when its error comes out non-finite (`fc3d_core::solve`), so that a call
/// costs no extra pass over W.
pub(crate) unsafe fn problem_view_from_c<'a>(
    p: &'a FrictionContactProblem,
) -> CResult<FrictionProblem<'a>> {
    problem_from_c_d::<3>(p)
}

/// The core view of a 2D C problem (`fc2d_driver`); a sparse-block W (2x2 blocks) is copied
/// into a general sparse matrix, a dense or sparse one is borrowed or converted as in 3D.
pub(crate) unsafe fn planar_problem_from_c<'a>(
    p: &'a FrictionContactProblem,
) -> CResult<FrictionProblem2d<'a>> {
    problem_from_c_d::<2>(p)
}

unsafe fn problem_from_c_d<'a, const D: usize>(
    p: &'a FrictionContactProblem,
) -> CResult<FrictionProblem<'a, D>> {
    if usize::try_from(p.dimension) != Ok(D) {
        let hint = match (p.dimension, D) {
            (2, 3) => " (a 2D problem: solve it with fc2d_driver)",
            (3, 2) => " (a 3D problem: solve it with fc3d_driver)",
            _ => "",
        };
        return Err(CError::new(
            FC3D_ERR_INVALID_PROBLEM,
            format!("dimension {} where {D} is needed{hint}", p.dimension),
        ));
    }
    let (w, q, mu) = parts_from_c::<D>(p.numberOfContacts, p.M, p.q, p.mu)?;
    Ok(FrictionProblem::<D>::from_parts(
        w,
        Cow::Borrowed(q),
        Cow::Borrowed(mu),
    )?)
}

/// W, q and mu of a C problem with `nc` contacts of dimension `D`, checked (sizes, pointers);
/// dense W, q and mu are borrowed.
pub(crate) unsafe fn parts_from_c<'a, const D: usize>(
    number_of_contacts: c_int,
    m: *mut NumericsMatrix,
    q: *mut c_double,
    mu: *mut c_double,
) -> CResult<(Delassus<'a>, &'a [f64], &'a [f64])> {
    let nc = usize::try_from(number_of_contacts).map_err(|_| {
        CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("numberOfContacts = {number_of_contacts} is negative"),
        )
    })?;
    // M's sizes are C ints: D * numberOfContacts must be one (checked, never truncated).
    let n = nc
        .checked_mul(D)
        .filter(|&n| c_int::try_from(n).is_ok())
        .ok_or_else(|| {
            CError::new(
                FC3D_ERR_INVALID_SIZE,
                format!(
                    "numberOfContacts = {nc} is too large: M would have {D} * {nc} rows, more \
                     than a C int holds ({})",
                    c_int::MAX
                ),
            )
        })?;
    // q and mu first: they are cheap to check, and a W conversion may allocate.
    let q = c_slice(q as *const c_double, n, "problem->q")?;
    let mu = c_slice(mu as *const c_double, nc, "problem->mu")?;
    let w = if m.is_null() {
        if nc > 0 {
            return Err(CError::null("problem->M"));
        }
        Delassus::Dense(DenseMatrix::new(0, 0, Vec::new())?)
    } else {
        let m = &*m;
        let is_n = |size: c_int| usize::try_from(size) == Ok(n);
        if !is_n(m.size0) || !is_n(m.size1) {
            return Err(CError::new(
                FC3D_ERR_INVALID_SIZE,
                format!(
                    "M is {}x{} but {nc} contacts need {n}x{n}",
                    m.size0, m.size1
                ),
            ));
        }
        delassus_from_c_blocks(m, D)?
    };
    Ok((w, q, mu))
}

/// A C-allocated problem holding a copy of `p` (W in the same storage; a 2D problem's W, held as
/// dense or general sparse, in that storage).
pub(crate) fn problem_to_c<const D: usize>(
    p: &FrictionProblem<'_, D>,
) -> CResult<*mut FrictionContactProblem> {
    let nc = c_int::try_from(p.n_contacts())
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, "too many contacts for a C int"))?;
    let m = matrix_to_c(p.w())?;
    // On a failure below, release what was made (the problem struct owns nothing yet).
    let release = |ptrs: &[*mut c_double]| unsafe {
        for &x in ptrs {
            c_free(x);
        }
        super::matrix::nm_clear_impl(m);
        c_free(m);
    };
    let q = c_copy(p.q()).inspect_err(|_| release(&[]))?;
    let mu = c_copy(p.mu()).inspect_err(|_| release(&[q]))?;
    c_box(FrictionContactProblem {
        dimension: D as c_int,
        numberOfContacts: nc,
        M: m,
        q,
        mu,
    })
    .inspect_err(|_| release(&[q, mu]))
}

/// Siconos' deep copy of a problem: a new problem with the same dimension and contacts, `M`
/// copied in its storage and layout (`NM_copy`: the dense values, the sparse-block structure and
/// blocks, or the sparse origin form), `q` and `mu` copied. The source is checked first as the
/// solvers check it; NULL and the reason in `fc3d_last_error_message` when it is refused.
/// Release with `frictionContactProblem_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_copy(
    problem: *mut FrictionContactProblem,
) -> *mut FrictionContactProblem {
    ffi_guard(
        "frictionContact_copy",
        |_| null_mut(),
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            let src = &*problem;
            let p = problem_from_c(src)?;
            let m = nm_duplicate(&*src.M)?;
            let release = |ptrs: &[*mut c_double]| {
                for &x in ptrs {
                    c_free(x);
                }
                nm_clear_impl(m);
                c_free(m);
            };
            let q = c_copy(p.q()).inspect_err(|_| release(&[]))?;
            let mu = c_copy(p.mu()).inspect_err(|_| release(&[q]))?;
            c_box(FrictionContactProblem {
                dimension: src.dimension,
                numberOfContacts: src.numberOfContacts,
                M: m,
                q,
                mu,
            })
            .inspect_err(|_| release(&[q, mu]))
        },
    )
}

/// Siconos' rescaling of a problem in place: `M <- alpha gamma^2 M` (as Siconos' `NM_scal`: a
/// sparse M is scaled in its CSC form, which becomes its origin, the other forms released) and
/// `q <- alpha gamma q`. The problem is checked first as the solvers check it, and a non-finite
/// `alpha` or `gamma` is refused; nothing is changed then (the reason in
/// `fc3d_last_error_message`).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_rescaling(
    problem: *mut FrictionContactProblem,
    alpha: c_double,
    gamma: c_double,
) {
    ffi_guard(
        "frictionContact_rescaling",
        |_| (),
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            if !(alpha.is_finite() && gamma.is_finite()) {
                return Err(CError::new(
                    super::FC3D_ERR_NON_FINITE,
                    format!("alpha = {alpha}, gamma = {gamma}"),
                ));
            }
            let n = problem_from_c(&*problem)?.size();
            let src = &mut *problem;
            nm_scale_in_place(&mut *src.M, alpha * gamma * gamma)?;
            for v in std::slice::from_raw_parts_mut(src.q, n) {
                *v *= alpha * gamma;
            }
            Ok(())
        },
    )
}

/// An empty problem (dimension 0, no data). Release with `frictionContactProblem_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn frictionContactProblem_new() -> *mut FrictionContactProblem {
    ffi_guard(
        "frictionContactProblem_new",
        |_| null_mut(),
        host_problem::new::<FrictionContactProblem>,
    )
}

/// A problem that takes `M`, `q` and `mu` as they are (no copy): they then belong to the
/// problem and are released by `frictionContactProblem_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn frictionContactProblem_new_with_data(
    dim: c_int,
    nc: c_int,
    M: *mut NumericsMatrix,
    q: *mut c_double,
    mu: *mut c_double,
) -> *mut FrictionContactProblem {
    ffi_guard(
        "frictionContactProblem_new_with_data",
        |_| null_mut(),
        || {
            c_box(FrictionContactProblem {
                dimension: dim,
                numberOfContacts: nc,
                M,
                q,
                mu,
            })
        },
    )
}

/// Releases `M` (storage and struct), `q`, `mu` and the problem struct. NULL is a no-op.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContactProblem_free(problem: *mut FrictionContactProblem) {
    ffi_guard(
        "frictionContactProblem_free",
        |_| (),
        || host_problem::free(problem),
    )
}
