//! Problem files.

pub mod dat;

pub use dat::{
    parse_dat, parse_matrix, parse_matrix_prefix, parse_sbm, parse_sbm_prefix, read_dat_file,
    write_dat, write_dat_file, write_matrix, write_sbm,
};

/// FCLIB `.hdf5` problems (needs the system libhdf5: cargo feature `fclib`).
#[cfg(feature = "fclib")]
pub mod fclib;

#[cfg(feature = "fclib")]
pub use fclib::read_fclib_file;

/// Reads a problem file, choosing the reader by extension (case-insensitive): `.dat` with
/// [`read_dat_file`], `.hdf5` / `.h5` (FCLIB) with `read_fclib_file` when fc3d is built with the
/// `fclib` feature. Without it, and for any other extension, an [`Fc3dError::Unsupported`] that
/// names the file.
///
/// [`Fc3dError::Unsupported`]: crate::error::Fc3dError::Unsupported
pub fn read_problem_file(
    path: &std::path::Path,
) -> Result<crate::problem::FrictionProblem<'static>, crate::error::Fc3dError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("dat") => read_dat_file(path),
        Some("hdf5" | "h5") => read_hdf5_problem(path),
        _ => Err(crate::error::Fc3dError::Unsupported(format!(
            "{}: unknown problem file extension (expected .dat, .hdf5 or .h5)",
            path.display()
        ))),
    }
}

#[cfg(feature = "fclib")]
fn read_hdf5_problem(
    path: &std::path::Path,
) -> Result<crate::problem::FrictionProblem<'static>, crate::error::Fc3dError> {
    fclib::read_fclib_file(path)
}

#[cfg(not(feature = "fclib"))]
fn read_hdf5_problem(
    path: &std::path::Path,
) -> Result<crate::problem::FrictionProblem<'static>, crate::error::Fc3dError> {
    Err(crate::error::Fc3dError::Unsupported(format!(
        "{}: FCLIB .hdf5 problems cannot be read: fc3d was built without the `fclib` feature \
         (rebuild with `--features fclib`, which needs libhdf5-dev and pkg-config)",
        path.display()
    )))
}
