//! Problem files by kind: the choice between `.dat` and FCLIB by extension, and the FCLIB entry
//! points that exist in every build. Without the `fclib` feature the FCLIB ones return an
//! [`Fc3dError::Unsupported`] that names the file and the feature, so that callers (the C ABI,
//! the command line) compile and link the same way in both builds.

use std::path::Path;

use super::dat::{read_dat_file, write_dat_file};
use super::info::FclibInfo;
use crate::error::Fc3dError;
use crate::problem::{FrictionProblem, GlobalProblem, GlobalRollingProblem};

/// Whether this build reads and writes FCLIB `.hdf5` files (the `fclib` cargo feature).
pub const FCLIB_AVAILABLE: bool = cfg!(feature = "fclib");

/// The 8 bytes every HDF5 file starts with (when it has no user block).
const HDF5_SIGNATURE: [u8; 8] = [0x89, b'H', b'D', b'F', b'\r', b'\n', 0x1a, b'\n'];

/// Whether `path` names an FCLIB file by its extension: `.hdf5` or `.h5`, in any case
/// (`x.hdf5.dat` is a `.dat` file).
pub fn has_fclib_extension(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("hdf5") || e.eq_ignore_ascii_case("h5"))
}

/// Whether the file at `path` starts with the HDF5 signature (false when it cannot be read).
pub fn is_hdf5_file(path: &Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 8];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok_and(|()| head == HDF5_SIGNATURE)
}

/// Reads a problem file, choosing the reader by extension (case-insensitive): `.dat` with
/// [`read_dat_file`], `.hdf5` / `.h5` (FCLIB) with [`read_fclib_file`]. Any other extension is an
/// [`Fc3dError::Unsupported`] that names the file.
pub fn read_problem_file(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("dat") => read_dat_file(path),
        _ if has_fclib_extension(path) => read_fclib_file(path),
        _ => Err(Fc3dError::Unsupported(format!(
            "{}: unknown problem file extension (expected .dat, .hdf5 or .h5)",
            path.display()
        ))),
    }
}

/// Writes a problem file, choosing the format by extension as [`read_problem_file`] does:
/// `.dat` with [`write_dat_file`] (`info` is not used), `.hdf5` / `.h5` with
/// [`write_fclib_file`]. Reading the file back gives an equal problem, bit for bit, in the same
/// storage.
pub fn write_problem_file(
    problem: &FrictionProblem<'_>,
    path: &Path,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("dat") => write_dat_file(problem, path),
        _ if has_fclib_extension(path) => write_fclib_file(problem, path, info),
        _ => Err(Fc3dError::Unsupported(format!(
            "{}: unknown problem file extension (expected .dat, .hdf5 or .h5)",
            path.display()
        ))),
    }
}

/// Reads an FCLIB file whatever its name: `/fclib_local`, else `/fclib_global` reduced to the
/// local form (see `io::fclib` with the `fclib` feature). Without the feature, an
/// [`Fc3dError::Unsupported`] naming the file and the feature.
pub fn read_fclib_file(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    #[cfg(feature = "fclib")]
    return super::fclib::read_fclib_file(path);
    #[cfg(not(feature = "fclib"))]
    Err(without_fclib(path, "read"))
}

/// Writes `problem` as an FCLIB local problem (`/fclib_local`, W in compressed rows, the info
/// group from `info`), replacing the file; see `io::fclib::write_fclib_file` with the `fclib`
/// feature. Without the feature, an [`Fc3dError::Unsupported`] naming the file and the feature,
/// and nothing is written.
pub fn write_fclib_file(
    problem: &FrictionProblem<'_>,
    path: &Path,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    #[cfg(feature = "fclib")]
    return super::fclib::write_fclib_file(problem, path, info);
    #[cfg(not(feature = "fclib"))]
    {
        let _ = (problem, info);
        Err(without_fclib(path, "written"))
    }
}

/// Reads the global problem (`/fclib_global`) of an FCLIB file; see
/// `io::fclib::read_fclib_global_file` with the `fclib` feature. Without the feature, an
/// [`Fc3dError::Unsupported`] naming the file and the feature.
pub fn read_fclib_global_file(path: &Path) -> Result<GlobalProblem<'static>, Fc3dError> {
    #[cfg(feature = "fclib")]
    return super::fclib::read_fclib_global_file(path);
    #[cfg(not(feature = "fclib"))]
    Err(without_fclib(path, "read"))
}

/// Writes `problem` as an FCLIB global problem (`/fclib_global`, M and H as triplets, as
/// Siconos' `globalFrictionContact_fclib_write`), replacing the file; see
/// `io::fclib::write_fclib_global_file` with the `fclib` feature. Without the feature, an
/// [`Fc3dError::Unsupported`] naming the file and the feature, and nothing is written.
pub fn write_fclib_global_file(
    problem: &GlobalProblem<'_>,
    path: &Path,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    #[cfg(feature = "fclib")]
    return super::fclib::write_fclib_global_file(problem, path, info);
    #[cfg(not(feature = "fclib"))]
    {
        let _ = (problem, info);
        Err(without_fclib(path, "written"))
    }
}

/// Writes `problem` as an FCLIB global rolling problem (`/fclib_global_rolling`, as FCLIB's
/// `fclib_write_global_rolling`), replacing the file; see
/// `io::fclib::write_fclib_global_rolling_file` with the `fclib` feature. Without the feature, an
/// [`Fc3dError::Unsupported`] naming the file and the feature, and nothing is written.
pub fn write_fclib_global_rolling_file(
    problem: &GlobalRollingProblem<'_>,
    path: &Path,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    #[cfg(feature = "fclib")]
    return super::fclib::write_fclib_global_rolling_file(problem, path, info);
    #[cfg(not(feature = "fclib"))]
    {
        let _ = (problem, info);
        Err(without_fclib(path, "written"))
    }
}

/// The info group of an FCLIB file (that of `/fclib_local`, else of `/fclib_global`; all
/// `None` when there is none). Without the `fclib` feature, an [`Fc3dError::Unsupported`].
pub fn read_fclib_info(path: &Path) -> Result<FclibInfo, Fc3dError> {
    #[cfg(feature = "fclib")]
    return super::fclib::read_fclib_info(path);
    #[cfg(not(feature = "fclib"))]
    Err(without_fclib(path, "read"))
}

#[cfg(not(feature = "fclib"))]
fn without_fclib(path: &Path, done: &str) -> Fc3dError {
    Fc3dError::Unsupported(format!(
        "{}: FCLIB .hdf5 problems cannot be {done}: fc3d was built without the `fclib` feature \
         (rebuild with `--features fclib`, which needs libhdf5-dev and pkg-config)",
        path.display()
    ))
}
