//! Problem files.

pub mod dat;

pub use dat::{parse_dat, read_dat_file, write_dat, write_dat_file};
