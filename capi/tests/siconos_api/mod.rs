//! The functions of libfc3d's Siconos surface that several of these tests call, declared once
//! (each test file is a crate of its own: it takes this module with `mod siconos_api;`). A test
//! declares the functions only it calls itself.

#![allow(dead_code)] // each test file uses a part of them

use std::ffi::{c_char, c_double, c_int, c_void};

use fc3d::types::{FrictionContactProblem, SolverOptions};

extern "C" {
    pub fn solver_options_create(id: c_int) -> *mut SolverOptions;
    pub fn solver_options_delete(options: *mut SolverOptions);
    pub fn solver_options_update_internal(parent: *mut SolverOptions, n: usize, id: c_int);
    pub fn solver_options_name_to_id(name: *const c_char) -> c_int;
    pub fn solver_options_id_to_name(id: c_int) -> *const c_char;
    pub fn frictionContact_new_from_filename(path: *const c_char) -> *mut FrictionContactProblem;
    pub fn frictionContactProblem_free(problem: *mut FrictionContactProblem);
    pub fn fc3d_driver(
        problem: *mut FrictionContactProblem,
        reaction: *mut c_double,
        velocity: *mut c_double,
        options: *mut SolverOptions,
    ) -> c_int;
    pub fn fc3d_compute_error(
        problem: *mut FrictionContactProblem,
        z: *mut c_double,
        w: *mut c_double,
        tolerance: c_double,
        options: *mut SolverOptions,
        norm: c_double,
        error: *mut c_double,
    ) -> c_int;
    pub fn fc3d_last_error_code() -> c_int;
    pub fn fc3d_last_error_message() -> *const c_char;
    pub fn fc3d_clear_last_error();
    pub fn calloc(n: usize, size: usize) -> *mut c_void;
    pub fn free(p: *mut c_void);
}
