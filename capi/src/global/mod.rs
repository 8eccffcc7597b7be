//! Siconos 4.4's global problems (`GlobalFrictionContactProblem.h`,
//! `GlobalRollingFrictionContactProblem.h`): the structs' life cycle, files and display
//! (through `host_problem`, shared with the local structs), their copy, and their core view.
//! The drivers are in `driver`, the solver entries in `entries`, the error, the global velocity and the
//! reformulations in `measures`, the FCLIB functions in `fclib`.
//!
//! M and H may come in any storage (dense, sparse-block of any block sizes, sparse): the core
//! view holds them in compressed rows, with the storage they had (so that a file written from a
//! host's problem, or a copy of it, keeps it). The host's M and H are never modified: every
//! function reads them, none factors or writes them.
//!
//! Ownership (as in Siconos): `globalFrictionContactProblem_free` releases `M` and `H` (storage
//! and struct), `q`, `b`, `mu` (and `mu_r`) and the struct; `env` is Siconos' solver scratch,
//! never read nor released by fc3d. Problems read from files are allocated the same way.

#![allow(non_snake_case)]

mod driver;

mod entries;

mod fclib;

mod measures;

use std::borrow::Cow;
use std::ffi::c_char;
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::alloc::{c_box, c_copy, c_free};
use super::host_problem::{self, release_array, release_matrix, HostProblem};
use super::matrix::{c_slice, nm_clear_impl, stored_from_c, stored_to_c};
use super::types::NumericsMatrix;
use super::types::{GlobalFrictionContactProblem, GlobalRollingFrictionContactProblem};
use super::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_INVALID_SIZE};
use fc3d_core::error::Fc3dError;
use fc3d_core::io::dat::{
    read_global_dat, read_global_rolling_dat, write_global_dat, write_global_rolling_dat,
    GlobalDat, GlobalDatProblem, GlobalStorage, MatrixStorage,
};
use fc3d_core::matrix::CsrMatrix;
use fc3d_core::problem::{GlobalProblem, GlobalRollingProblem};

/// A global problem of either dimension Siconos writes (3: gfc3d, 2: Siconos 4.5's gfc2d).
pub(crate) enum AnyGlobal<'a> {
    Spatial(GlobalProblem<'a, 3>),
    Planar(GlobalProblem<'a, 2>),
}

/// The core view of a C global problem and the storages of its M and H.
pub(crate) struct GlobalView<P> {
    pub problem: P,
    pub storage: GlobalStorage,
}

/// The sizes of a C global problem, checked: `(ndof, nc, dimension * nc)`.
unsafe fn global_sizes<const D: usize>(
    number_of_contacts: c_int,
    m: *mut NumericsMatrix,
) -> CResult<(usize, usize, usize)> {
    let nc = usize::try_from(number_of_contacts).map_err(|_| {
        CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("numberOfContacts = {number_of_contacts} is negative"),
        )
    })?;
    let size = nc
        .checked_mul(D)
        .filter(|&s| c_int::try_from(s).is_ok())
        .ok_or_else(|| {
            CError::new(
                FC3D_ERR_INVALID_SIZE,
                format!(
                    "numberOfContacts = {nc} is too large: H would have {D} * {nc} columns, more \
                     than a C int holds"
                ),
            )
        })?;
    let m = m.as_ref().ok_or_else(|| CError::null("problem->M"))?;
    if m.size0 < 0 || m.size0 != m.size1 {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("M is {}x{}: it must be square", m.size0, m.size1),
        ));
    }
    Ok((m.size0 as usize, nc, size))
}

/// The core view of the parts of a C global problem with contacts of dimension `D`: sizes and
/// pointers checked, q, b and mu borrowed, M and H converted (their storages kept beside).
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn global_from_parts<'a, const D: usize>(
    number_of_contacts: c_int,
    m: *mut NumericsMatrix,
    h: *mut NumericsMatrix,
    q: *mut c_double,
    b: *mut c_double,
    mu: *mut c_double,
) -> CResult<GlobalView<GlobalProblem<'a, D>>> {
    let (n, nc, size) = global_sizes::<D>(number_of_contacts, m)?;
    // The vectors first: cheap to check, and the matrices' conversions allocate.
    let q = c_slice(q as *const c_double, n, "problem->q")?;
    let b = c_slice(b as *const c_double, size, "problem->b")?;
    let mu = c_slice(mu as *const c_double, nc, "problem->mu")?;
    if let Some(hm) = h.as_ref() {
        if usize::try_from(hm.size0) != Ok(n) || usize::try_from(hm.size1) != Ok(size) {
            return Err(CError::new(
                FC3D_ERR_INVALID_SIZE,
                format!(
                    "H is {}x{} but M is {n}x{n} and {nc} contacts of dimension {D} need {n}x{size}",
                    hm.size0, hm.size1
                ),
            ));
        }
    }
    let (m, m_storage) = stored_from_c(&*m, "M")?;
    let (h, h_storage) = match h.as_ref() {
        Some(h) => stored_from_c(h, "H")?,
        // A problem without contacts needs no H (Siconos only reads its size).
        None if size == 0 => (CsrMatrix::from_triplets(n, 0, &[])?, MatrixStorage::Sparse),
        None => return Err(CError::null("problem->H")),
    };
    let problem =
        GlobalProblem::<D>::new(m, h, Cow::Borrowed(q), Cow::Borrowed(b), Cow::Borrowed(mu))?;
    Ok(GlobalView {
        problem,
        storage: GlobalStorage {
            m: m_storage,
            h: h_storage,
        },
    })
}

/// The core view of a C global problem of dimension `D`.
pub(crate) unsafe fn global_from_c<const D: usize>(
    p: &GlobalFrictionContactProblem,
) -> CResult<GlobalView<GlobalProblem<'_, D>>> {
    if usize::try_from(p.dimension) != Ok(D) {
        let hint = match (p.dimension, D) {
            (2, 3) => {
                " (a 2D global problem, as Siconos 4.5 writes them: Siconos 4.4 and fc3d solve \
                 dimension 3 only)"
            }
            _ => "",
        };
        return Err(CError::new(
            FC3D_ERR_INVALID_PROBLEM,
            format!(
                "global problem of dimension {} where {D} is needed{hint}",
                p.dimension
            ),
        ));
    }
    global_from_parts::<D>(p.numberOfContacts, p.M, p.H, p.q, p.b, p.mu)
}

/// The core view of a C global problem of dimension 3 or 2.
unsafe fn any_global_from_c(
    p: &GlobalFrictionContactProblem,
) -> CResult<GlobalView<AnyGlobal<'_>>> {
    Ok(if p.dimension == 2 {
        let v = global_from_c::<2>(p)?;
        GlobalView {
            problem: AnyGlobal::Planar(v.problem),
            storage: v.storage,
        }
    } else {
        let v = global_from_c::<3>(p)?;
        GlobalView {
            problem: AnyGlobal::Spatial(v.problem),
            storage: v.storage,
        }
    })
}

/// The core view of a C global rolling problem (dimension 5).
pub(crate) unsafe fn global_rolling_from_c(
    p: &GlobalRollingFrictionContactProblem,
) -> CResult<GlobalView<GlobalRollingProblem<'_>>> {
    if p.dimension != 5 {
        return Err(CError::new(
            FC3D_ERR_INVALID_PROBLEM,
            format!(
                "global rolling problem of dimension {} where 5 is needed",
                p.dimension
            ),
        ));
    }
    let v = global_from_parts::<5>(p.numberOfContacts, p.M, p.H, p.q, p.b, p.mu)?;
    let mu_r = c_slice(
        p.mu_r as *const c_double,
        v.problem.n_contacts(),
        "problem->mu_r",
    )?;
    Ok(GlobalView {
        problem: GlobalRollingProblem::new(v.problem, Cow::Borrowed(mu_r))?,
        storage: v.storage,
    })
}

/// The C-allocated M, H, q, b and mu of `p` in `storage`: all of them or nothing.
type CParts = (
    *mut NumericsMatrix,
    *mut NumericsMatrix,
    *mut c_double,
    *mut c_double,
    *mut c_double,
);

fn parts_to_c<const D: usize>(
    p: &GlobalProblem<'_, D>,
    storage: &GlobalStorage,
) -> CResult<CParts> {
    let m = stored_to_c(p.m(), &storage.m)?;
    let mut matrices = vec![m];
    let mut arrays: Vec<*mut c_double> = Vec::new();
    let release = |matrices: &[*mut NumericsMatrix], arrays: &[*mut c_double]| unsafe {
        for &a in arrays {
            c_free(a);
        }
        for &m in matrices {
            nm_clear_impl(m);
            c_free(m);
        }
    };
    let h = stored_to_c(p.h(), &storage.h).inspect_err(|_| release(&matrices, &arrays))?;
    matrices.push(h);
    for v in [p.q(), p.b(), p.mu()] {
        arrays.push(c_copy(v).inspect_err(|_| release(&matrices, &arrays))?);
    }
    Ok((m, h, arrays[0], arrays[1], arrays[2]))
}

/// A C-allocated global problem holding a copy of `p`, M and H in `storage`.
pub(crate) fn global_to_c<const D: usize>(
    p: &GlobalProblem<'_, D>,
    storage: &GlobalStorage,
) -> CResult<*mut GlobalFrictionContactProblem> {
    let nc = c_int::try_from(p.n_contacts())
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, "too many contacts for a C int"))?;
    let (m, h, q, b, mu) = parts_to_c(p, storage)?;
    let mut out = GlobalFrictionContactProblem {
        dimension: D as c_int,
        numberOfContacts: nc,
        M: m,
        H: h,
        q,
        norm_q: 0.0,
        b,
        norm_b: 0.0,
        mu,
        env: null_mut(),
    };
    c_box(GlobalFrictionContactProblem { ..out }).inspect_err(|_| unsafe { out.release() })
}

/// A C-allocated global rolling problem holding a copy of `p`, M and H in `storage`.
fn global_rolling_to_c(
    p: &GlobalRollingProblem<'_>,
    storage: &GlobalStorage,
) -> CResult<*mut GlobalRollingFrictionContactProblem> {
    let base = p.base();
    let nc = c_int::try_from(base.n_contacts())
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, "too many contacts for a C int"))?;
    let (m, h, q, b, mu) = parts_to_c(base, storage)?;
    let mut out = GlobalRollingFrictionContactProblem {
        dimension: 5,
        numberOfContacts: nc,
        M: m,
        H: h,
        q,
        b,
        mu,
        mu_r: null_mut(),
    };
    out.mu_r = c_copy(p.mu_r()).inspect_err(|_| unsafe { out.release() })?;
    c_box(GlobalRollingFrictionContactProblem { ..out }).inspect_err(|_| unsafe { out.release() })
}

fn display_global<const D: usize>(name: &str, p: &GlobalProblem<'_, D>, s: &GlobalStorage) {
    let norm = fc3d_core::math::linalg::norm;
    println!(
        "{name}: dimension {D}, {} contacts, M {n}x{n} ({}), H {n}x{} ({}), ||q|| = {:e}, \
         ||b|| = {:e}",
        p.n_contacts(),
        s.m.name(),
        p.size(),
        s.h.name(),
        norm(p.q()),
        norm(p.b()),
        n = p.ndof(),
    );
    println!("  mu = {:?}", p.mu());
    println!("  q = {:?}", p.q());
    println!("  b = {:?}", p.b());
}

impl HostProblem for GlobalFrictionContactProblem {
    type View<'a> = GlobalView<AnyGlobal<'a>>;
    type Read = GlobalDat<GlobalDatProblem>;

    fn empty() -> Self {
        GlobalFrictionContactProblem {
            dimension: 0,
            numberOfContacts: 0,
            M: null_mut(),
            H: null_mut(),
            q: null_mut(),
            norm_q: 0.0,
            b: null_mut(),
            norm_b: 0.0,
            mu: null_mut(),
            env: null_mut(),
        }
    }

    unsafe fn release(&mut self) {
        release_matrix(&mut self.M);
        release_matrix(&mut self.H);
        release_array(&mut self.q);
        release_array(&mut self.b);
        release_array(&mut self.mu);
    }

    unsafe fn view(&self) -> CResult<Self::View<'_>> {
        any_global_from_c(self)
    }

    fn write(view: &Self::View<'_>, mut out: &mut dyn std::io::Write) -> std::io::Result<()> {
        match &view.problem {
            AnyGlobal::Spatial(p) => write_global_dat(p, &view.storage, &mut out),
            AnyGlobal::Planar(p) => write_global_dat(p, &view.storage, &mut out),
        }
    }

    fn display(view: &Self::View<'_>) {
        let name = "GlobalFrictionContactProblem";
        match &view.problem {
            AnyGlobal::Spatial(p) => display_global(name, p, &view.storage),
            AnyGlobal::Planar(p) => display_global(name, p, &view.storage),
        }
    }

    fn read(
        stream: &mut dyn std::io::Read,
        len: Option<u64>,
        label: &str,
    ) -> Result<(Self::Read, u64), Fc3dError> {
        read_global_dat(stream, len, label)
    }

    fn to_c(read: Self::Read) -> CResult<*mut Self> {
        match &read.problem {
            GlobalDatProblem::Spatial(p) => global_to_c(p, &read.storage),
            GlobalDatProblem::Planar(p) => global_to_c(p, &read.storage),
        }
    }

    /// A `.dat` file, or an FCLIB file (HDF5 signature, or named `.hdf5` / `.h5`) as
    /// `globalFrictionContact_fclib_read` reads it.
    fn read_file(path: &str) -> CResult<*mut Self> {
        if super::fclib::is_fclib_file(path) {
            return fclib::read_global_fclib(path);
        }
        host_problem::read_dat_file(path)
    }
}

impl HostProblem for GlobalRollingFrictionContactProblem {
    type View<'a> = GlobalView<GlobalRollingProblem<'a>>;
    type Read = GlobalDat<GlobalRollingProblem<'static>>;

    fn empty() -> Self {
        GlobalRollingFrictionContactProblem {
            dimension: 0,
            numberOfContacts: 0,
            M: null_mut(),
            H: null_mut(),
            q: null_mut(),
            b: null_mut(),
            mu: null_mut(),
            mu_r: null_mut(),
        }
    }

    unsafe fn release(&mut self) {
        release_matrix(&mut self.M);
        release_matrix(&mut self.H);
        release_array(&mut self.q);
        release_array(&mut self.b);
        release_array(&mut self.mu);
        release_array(&mut self.mu_r);
    }

    unsafe fn view(&self) -> CResult<Self::View<'_>> {
        global_rolling_from_c(self)
    }

    fn write(view: &Self::View<'_>, mut out: &mut dyn std::io::Write) -> std::io::Result<()> {
        write_global_rolling_dat(&view.problem, &view.storage, &mut out)
    }

    fn display(view: &Self::View<'_>) {
        display_global(
            "GlobalRollingFrictionContactProblem",
            view.problem.base(),
            &view.storage,
        );
        println!("  mu_r = {:?}", view.problem.mu_r());
    }

    fn read(
        stream: &mut dyn std::io::Read,
        len: Option<u64>,
        label: &str,
    ) -> Result<(Self::Read, u64), Fc3dError> {
        read_global_rolling_dat(stream, len, label)
    }

    fn to_c(read: Self::Read) -> CResult<*mut Self> {
        global_rolling_to_c(&read.problem, &read.storage)
    }
}

// ---------------------------------------------------------------------------------------------
// GlobalFrictionContactProblem.h

/// An empty global problem (dimension 0, no data). Release with
/// `globalFrictionContact_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn globalFrictionContactProblem_new() -> *mut GlobalFrictionContactProblem {
    ffi_guard(
        "globalFrictionContactProblem_new",
        |_| null_mut(),
        host_problem::new::<GlobalFrictionContactProblem>,
    )
}

/// Prints a summary of the problem (sizes, storages of M and H, mu, q, b) to stdout.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_display(problem: *mut GlobalFrictionContactProblem) {
    ffi_guard(
        "globalFrictionContact_display",
        |_| (),
        || host_problem::display(problem),
    )
}

/// Writes `problem` to an open stream in Siconos' global .dat format (dimension, contacts, M,
/// H, q, b, mu), M and H in the storages they have, values in their shortest exactly
/// round-tripping form. Returns 0 on success, a negative code otherwise (nothing written).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_printInFile(
    problem: *mut GlobalFrictionContactProblem,
    file: *mut libc::FILE,
) -> c_int {
    ffi_guard(
        "globalFrictionContact_printInFile",
        |c| c,
        || host_problem::print_in_file(problem, file),
    )
}

/// Writes `problem` to the file `filename` (created or truncated), as
/// `globalFrictionContact_printInFile`. Returns 0 on success.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_printInFileName(
    problem: *mut GlobalFrictionContactProblem,
    filename: *const c_char,
) -> c_int {
    ffi_guard(
        "globalFrictionContact_printInFileName",
        |c| c,
        || host_problem::print_in_filename(problem, filename),
    )
}

/// Reads a global problem in Siconos' .dat format from an open stream, up to its last friction
/// coefficient (a stream that can seek is left at the next token, or put back where it was on
/// failure). M and H keep the storage of the file (a sparse-block one with its block sizes).
/// Dimensions 3 and 2 are read. NULL on failure (see `fc3d_last_error_message`; Siconos returns
/// NULL on a read failure too, and reads what fc3d refuses: a non-square M, an H of the wrong
/// size, negative or non-finite values).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_newFromFile(
    file: *mut libc::FILE,
) -> *mut GlobalFrictionContactProblem {
    ffi_guard(
        "globalFrictionContact_newFromFile",
        |_| null_mut(),
        || host_problem::new_from_file(file),
    )
}

/// Reads a global problem from a .dat file, or from an FCLIB file (HDF5 signature, or named
/// `.hdf5` / `.h5`) as `globalFrictionContact_fclib_read` does. NULL on failure.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_new_from_filename(
    filename: *const c_char,
) -> *mut GlobalFrictionContactProblem {
    ffi_guard(
        "globalFrictionContact_new_from_filename",
        |_| null_mut(),
        || host_problem::new_from_filename(filename),
    )
}

/// Releases `M` and `H` (storage and struct), `q`, `b`, `mu` and the problem struct; `env` is
/// left alone (Siconos asserts it is NULL). NULL is a no-op.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_free(problem: *mut GlobalFrictionContactProblem) {
    ffi_guard(
        "globalFrictionContact_free",
        |_| (),
        || host_problem::free(problem),
    )
}

/// A deep copy: M and H in the storages they have (a sparse-block one with its block sizes;
/// a sparse one as a triplet), q, b and mu copied, `norm_q`, `norm_b` copied, `env` NULL. The
/// source is checked first as the drivers check it; NULL and the reason in
/// `fc3d_last_error_message` when it is refused. Release with `globalFrictionContact_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_copy(
    problem: *mut GlobalFrictionContactProblem,
) -> *mut GlobalFrictionContactProblem {
    ffi_guard(
        "globalFrictionContact_copy",
        |_| null_mut(),
        || {
            let src = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let view = any_global_from_c(src)?;
            let copy = match &view.problem {
                AnyGlobal::Spatial(p) => global_to_c(p, &view.storage)?,
                AnyGlobal::Planar(p) => global_to_c(p, &view.storage)?,
            };
            (*copy).norm_q = src.norm_q;
            (*copy).norm_b = src.norm_b;
            Ok(copy)
        },
    )
}

// ---------------------------------------------------------------------------------------------
// GlobalRollingFrictionContactProblem.h

/// An empty global rolling problem (dimension 0, no data). Release with
/// `globalRollingFrictionContactProblem_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn globalRollingFrictionContactProblem_new(
) -> *mut GlobalRollingFrictionContactProblem {
    ffi_guard(
        "globalRollingFrictionContactProblem_new",
        |_| null_mut(),
        host_problem::new::<GlobalRollingFrictionContactProblem>,
    )
}

/// A global rolling problem that takes `M`, `q`, `mu` and `mu_r` as they are (no copy: they
/// then belong to the problem); `H` and `b` are NULL (Siconos leaves them uninitialised): set
/// them before solving.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn globalRollingFrictionContactProblem_new_with_data(
    dim: c_int,
    nc: c_int,
    M: *mut NumericsMatrix,
    q: *mut c_double,
    mu: *mut c_double,
    mu_r: *mut c_double,
) -> *mut GlobalRollingFrictionContactProblem {
    ffi_guard(
        "globalRollingFrictionContactProblem_new_with_data",
        |_| null_mut(),
        || {
            c_box(GlobalRollingFrictionContactProblem {
                dimension: dim,
                numberOfContacts: nc,
                M,
                H: null_mut(),
                q,
                b: null_mut(),
                mu,
                mu_r,
            })
        },
    )
}

/// Releases `M` and `H` (storage and struct), `q`, `b`, `mu`, `mu_r` and the struct. NULL is a
/// no-op.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContactProblem_free(
    problem: *mut GlobalRollingFrictionContactProblem,
) {
    ffi_guard(
        "globalRollingFrictionContactProblem_free",
        |_| (),
        || host_problem::free(problem),
    )
}

/// Prints a summary of the problem to stdout.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_display(
    problem: *mut GlobalRollingFrictionContactProblem,
) {
    ffi_guard(
        "globalRollingFrictionContact_display",
        |_| (),
        || host_problem::display(problem),
    )
}

/// Writes `problem` to an open stream in the global rolling .dat format (the global format,
/// then mu_r). Returns 0 on success.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_printInFile(
    problem: *mut GlobalRollingFrictionContactProblem,
    file: *mut libc::FILE,
) -> c_int {
    ffi_guard(
        "globalRollingFrictionContact_printInFile",
        |c| c,
        || host_problem::print_in_file(problem, file),
    )
}

/// Writes `problem` to the file `filename` (created or truncated). Returns 0 on success.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_printInFilename(
    problem: *mut GlobalRollingFrictionContactProblem,
    filename: *mut c_char,
) -> c_int {
    ffi_guard(
        "globalRollingFrictionContact_printInFilename",
        |c| c,
        || host_problem::print_in_filename(problem, filename),
    )
}

/// Reads a global rolling problem (dimension 5) from an open stream. NULL on failure.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_newFromFile(
    file: *mut libc::FILE,
) -> *mut GlobalRollingFrictionContactProblem {
    ffi_guard(
        "globalRollingFrictionContact_newFromFile",
        |_| null_mut(),
        || host_problem::new_from_file(file),
    )
}

/// Reads a global rolling problem from a .dat file. NULL on failure.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_new_from_filename(
    filename: *const c_char,
) -> *mut GlobalRollingFrictionContactProblem {
    ffi_guard(
        "globalRollingFrictionContact_new_from_filename",
        |_| null_mut(),
        || host_problem::new_from_filename(filename),
    )
}
