//! Problem files.

pub mod dat;
mod files;
mod info;

pub use dat::{
    parse_dat, parse_matrix, parse_matrix_prefix, parse_sbm, parse_sbm_prefix, read_dat,
    read_dat_file, read_matrix, read_matrix_file, read_sbm, write_dat, write_dat_file,
    write_matrix, write_sbm,
};
pub use files::{
    has_fclib_extension, is_hdf5_file, read_fclib_file, read_fclib_global_file, read_fclib_info,
    read_problem_file, write_fclib_file, write_fclib_global_file, write_fclib_global_rolling_file,
    write_problem_file, FCLIB_AVAILABLE,
};
pub use info::FclibInfo;

/// FCLIB `.hdf5` problems, read and written through the system libhdf5 (cargo feature `fclib`).
/// The functions of the same names above exist in every build.
#[cfg(feature = "fclib")]
pub mod fclib;
