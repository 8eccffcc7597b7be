//! What the global C API tests share (each test file is a crate of its own: it takes this module
//! with `mod global_api;`): the global functions of libfc3d they call, the shared data files,
//! a problem read through the C ABI, options, and a byte image of a problem.

#![allow(dead_code)] // each test file uses a part of them

use std::ffi::{c_char, c_double, c_int, c_uint, CString};
use std::path::{Path, PathBuf};

use fc3d::types::{
    FrictionContactProblem, GlobalFrictionContactProblem, GlobalRollingFrictionContactProblem,
    NumericsMatrix, SolverOptions,
};
use fc3d_core::io::dat::{read_global_dat_file, GlobalDatProblem};
use fc3d_core::problem::GlobalProblem;

use super::siconos_api::*;

extern "C" {
    pub fn globalFrictionContact_new_from_filename(
        path: *const c_char,
    ) -> *mut GlobalFrictionContactProblem;
    pub fn globalFrictionContact_free(problem: *mut GlobalFrictionContactProblem);
    pub fn globalFrictionContact_copy(
        problem: *mut GlobalFrictionContactProblem,
    ) -> *mut GlobalFrictionContactProblem;
    pub fn globalFrictionContact_printInFileName(
        problem: *mut GlobalFrictionContactProblem,
        filename: *const c_char,
    ) -> c_int;
    pub fn gfc3d_driver(
        problem: *mut GlobalFrictionContactProblem,
        reaction: *mut c_double,
        velocity: *mut c_double,
        global_velocity: *mut c_double,
        options: *mut SolverOptions,
    ) -> c_int;
    pub fn gfc3d_compute_error(
        problem: *mut GlobalFrictionContactProblem,
        reaction: *mut c_double,
        velocity: *mut c_double,
        global_velocity: *mut c_double,
        tolerance: c_double,
        options: *mut SolverOptions,
        norm_q: c_double,
        norm_b: c_double,
        error: *mut c_double,
    ) -> c_int;
    pub fn globalFrictionContact_computeGlobalVelocity(
        problem: *mut GlobalFrictionContactProblem,
        reaction: *mut c_double,
        global_velocity: *mut c_double,
    ) -> c_int;
    pub fn globalFrictionContact_reformulation_FrictionContact(
        problem: *mut GlobalFrictionContactProblem,
    ) -> *mut FrictionContactProblem;
    pub fn fc3d_reformulation_global_problem(
        problem: *mut FrictionContactProblem,
    ) -> *mut GlobalFrictionContactProblem;
    pub fn gfc3d_nsgs_wr(
        problem: *mut GlobalFrictionContactProblem,
        reaction: *mut c_double,
        velocity: *mut c_double,
        global_velocity: *mut c_double,
        info: *mut c_int,
        options: *mut SolverOptions,
    );
    #[allow(clippy::too_many_arguments)]
    pub fn gfc3d_LmgcDriver(
        reaction: *mut c_double,
        velocity: *mut c_double,
        global_velocity: *mut c_double,
        q: *mut c_double,
        b: *mut c_double,
        mu: *mut c_double,
        m_data: *mut c_double,
        nz_m: c_uint,
        row_m: *mut c_uint,
        col_m: *mut c_uint,
        h_data: *mut c_double,
        nz_h: c_uint,
        row_h: *mut c_uint,
        col_h: *mut c_uint,
        n: c_uint,
        nc: c_uint,
        solver_id: c_int,
        isize: c_int,
        iparam: *mut c_int,
        dsize: c_int,
        dparam: *mut c_double,
        verbose: c_int,
        output_file: c_int,
        freq_output: c_int,
    ) -> c_int;
    pub fn g_rolling_fc3d_driver(
        problem: *mut GlobalRollingFrictionContactProblem,
        reaction: *mut c_double,
        velocity: *mut c_double,
        global_velocity: *mut c_double,
        options: *mut SolverOptions,
    ) -> c_int;
}

pub const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

/// The 3D global `.dat` files of the shared collection.
pub const GLOBAL_FILES: &[&str] = &[
    "GFC3D_Example0.dat",
    "GFC3D_Example00.dat",
    "GFC3D_Example00_badly_scaled.dat",
    "GFC3D_Example0_SBM.dat",
    "GFC3D_Example1.dat",
    "GFC3D_OneContact.dat",
    "GFC3D_TwoRods1.dat",
];

/// The ids gfc3d_driver runs.
pub const IDS: [c_int; 13] = [
    600, 602, 603, 604, 605, 606, 607, 610, 611, 612, 613, 614, 615,
];

pub fn data(name: &str) -> PathBuf {
    Path::new(DATA_DIR).join(name)
}

pub fn available() -> bool {
    let ok = data("GFC3D_TwoRods1.dat").is_file();
    if !ok {
        eprintln!("../shared/data/siconos missing: skipped");
    }
    ok
}

pub fn c_path(p: &Path) -> CString {
    CString::new(p.to_str().unwrap()).unwrap()
}

/// The core problem of a 3D global file.
pub fn core_problem(name: &str) -> GlobalProblem<'static> {
    match read_global_dat_file(&data(name)).unwrap().problem {
        GlobalDatProblem::Spatial(p) => p,
        GlobalDatProblem::Planar(_) => panic!("{name} is 3D"),
    }
}

/// A problem read through the C ABI, freed on drop.
pub struct CProblem(pub *mut GlobalFrictionContactProblem);

impl CProblem {
    pub fn read(name: &str) -> Self {
        let path = c_path(&data(name));
        let p = unsafe { globalFrictionContact_new_from_filename(path.as_ptr()) };
        assert!(!p.is_null(), "{name}: {}", last_message());
        CProblem(p)
    }
    pub fn get(&self) -> &GlobalFrictionContactProblem {
        unsafe { &*self.0 }
    }
}

impl Drop for CProblem {
    fn drop(&mut self) {
        unsafe { globalFrictionContact_free(self.0) };
    }
}

pub fn last_message() -> String {
    unsafe {
        std::ffi::CStr::from_ptr(fc3d_last_error_message())
            .to_string_lossy()
            .into_owned()
    }
}

/// Every byte a NumericsMatrix holds (its struct, its storage arrays and blocks), for checking
/// that nothing changed.
pub unsafe fn matrix_bytes(m: *const NumericsMatrix) -> Vec<u8> {
    pub fn bytes<T>(p: *const T, n: usize) -> Vec<u8> {
        if p.is_null() || n == 0 {
            return Vec::new();
        }
        unsafe { std::slice::from_raw_parts(p as *const u8, n * std::mem::size_of::<T>()) }.to_vec()
    }
    let m = &*m;
    let mut out = bytes(m as *const NumericsMatrix, 1);
    let (r, c) = (m.size0 as usize, m.size1 as usize);
    match m.storageType {
        0 => out.extend(bytes(m.matrix0, r * c)),
        1 => {
            let s = &*m.matrix1;
            out.extend(bytes(s as *const _, 1));
            let (nbr, nbc) = (s.blocknumber0 as usize, s.blocknumber1 as usize);
            let bs0 = std::slice::from_raw_parts(s.blocksize0, nbr);
            let bs1 = std::slice::from_raw_parts(s.blocksize1, nbc);
            out.extend(bytes(s.blocksize0, nbr));
            out.extend(bytes(s.blocksize1, nbc));
            out.extend(bytes(s.index1_data, s.filled1));
            out.extend(bytes(s.index2_data, s.filled2));
            let row_ptr = std::slice::from_raw_parts(s.index1_data, s.filled1);
            let cols = std::slice::from_raw_parts(s.index2_data, s.filled2);
            for bi in 0..nbr {
                let h = bs0[bi] - if bi == 0 { 0 } else { bs0[bi - 1] };
                let blocks = row_ptr[bi]..row_ptr[bi + 1];
                for (k, &bj) in blocks.clone().zip(&cols[blocks]) {
                    let w = bs1[bj] - if bj == 0 { 0 } else { bs1[bj - 1] };
                    out.extend(bytes(*s.block.add(k), (h * w) as usize));
                }
            }
        }
        _ => {
            let s = &*m.matrix2;
            out.extend(bytes(s as *const _, 1));
            for cs in [s.triplet, s.csc, s.csr] {
                if let Some(cs) = cs.as_ref() {
                    out.extend(bytes(cs as *const _, 1));
                    let nzmax = cs.nzmax as usize;
                    let np = if cs.nz >= 0 { nzmax } else { cs.n as usize + 1 };
                    out.extend(bytes(cs.p, np));
                    out.extend(bytes(cs.i, nzmax));
                    out.extend(bytes(cs.x, nzmax));
                }
            }
        }
    }
    out
}

/// Every byte of the problem's data.
pub unsafe fn problem_bytes(p: &GlobalFrictionContactProblem) -> Vec<u8> {
    let n = (*p.M).size0 as usize;
    let m = 3 * p.numberOfContacts as usize;
    let f = |x: *const f64, k: usize| std::slice::from_raw_parts(x as *const u8, 8 * k).to_vec();
    let mut out = f(
        p as *const _ as *const f64,
        std::mem::size_of::<GlobalFrictionContactProblem>() / 8,
    );
    out.extend(matrix_bytes(p.M));
    out.extend(matrix_bytes(p.H));
    out.extend(f(p.q, n));
    out.extend(f(p.b, m));
    out.extend(f(p.mu, p.numberOfContacts as usize));
    out
}

pub fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// Options of `id` with the tolerance and iteration limit of Siconos' WR collection.
pub struct Options(pub *mut SolverOptions);

impl Options {
    pub fn new(id: c_int, tolerance: f64, max_iter: c_int) -> Self {
        let o = unsafe { solver_options_create(id) };
        assert!(!o.is_null(), "options of {id}");
        unsafe {
            *(*o).iparam = max_iter;
            *(*o).dparam = tolerance;
        }
        Options(o)
    }
    pub fn iparam(&self, k: usize) -> c_int {
        unsafe { *(*self.0).iparam.add(k) }
    }
    pub fn dparam(&self, k: usize) -> f64 {
        unsafe { *(*self.0).dparam.add(k) }
    }
    pub fn set_iparam(&self, k: usize, v: c_int) {
        unsafe { *(*self.0).iparam.add(k) = v }
    }
}

impl Drop for Options {
    fn drop(&mut self) {
        unsafe {
            solver_options_delete(self.0);
            free(self.0.cast());
        }
    }
}

extern "C" {
    pub fn globalFrictionContact_fclib_read(
        path: *const c_char,
    ) -> *mut GlobalFrictionContactProblem;
    pub fn globalFrictionContact_fclib_write(
        problem: *mut GlobalFrictionContactProblem,
        title: *mut c_char,
        description: *mut c_char,
        math_info: *mut c_char,
        path: *const c_char,
    ) -> c_int;
}
