//! Bindings to the C test functions in `c/` (compiled by build.rs against the public headers).
//! Each returns 0 on success, or a non-zero code after printing what failed.

use std::os::raw::{c_char, c_double, c_int};

// Link the fc3d library's C symbols into every test binary that uses this crate.
pub use fc3d;

/// Storage a C test rebuilds W into before solving.
pub const STORAGE_AS_FILE: c_int = -1;
pub const STORAGE_DENSE: c_int = 0;
pub const STORAGE_SPARSE_BLOCK: c_int = 1;
pub const STORAGE_CSR: c_int = 2;

/// What a C-side solve returned.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct CSolveResult {
    pub info: c_int,
    pub iterations: c_int,
    /// dparam[1] as reported by fc3d_driver.
    pub reported_error: c_double,
    /// fc3d_compute_error with norm = ||q||.
    pub api_error: c_double,
    /// The error recomputed in plain C from W (read entry by entry), q, mu, r.
    pub independent_error: c_double,
    /// The storage type of the matrix that was solved.
    pub storage: c_int,
}

/// What a C-side 2D solve returned (`c/fc2d_checks.c`).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct Fc2dResult {
    pub info: c_int,
    pub iterations: c_int,
    /// dparam[1] as reported by fc2d_driver.
    pub reported_error: c_double,
    /// fc2d_compute_error with norm = ||q||.
    pub api_error: c_double,
    /// The error recomputed in plain C from W (read entry by entry), q, mu, r.
    pub independent_error: c_double,
    pub dimension: c_int,
}

/// What a C-side rolling solve returned (`c/rolling_checks.c`).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct RollingResult {
    pub info: c_int,
    pub iterations: c_int,
    /// dparam[1] as reported by the rolling driver.
    pub reported_error: c_double,
    /// rolling_fc3d_compute_error (or the 2D one) with norm = ||q||.
    pub api_error: c_double,
    /// The error recomputed in plain C (own projection by bisection) from W read entry by entry.
    pub independent_error: c_double,
    pub dimension: c_int,
}

extern "C" {
    /// Solves a rolling file with NSGS (3000 or 4000) and the local solver `local_id` (0: the
    /// default), or with ADMM when `local_id` is 3003, through the rolling driver, from r = 0.
    pub fn capi_rolling_solve_file(
        path: *const c_char,
        local_id: c_int,
        tolerance: c_double,
        max_iter: c_int,
        r_out: *mut c_double,
        n: c_int,
        out: *mut RollingResult,
    ) -> c_int;
    /// The rolling API checks; `scratch` is a writable directory.
    pub fn capi_rolling_check_api(scratch: *const c_char) -> c_int;
    /// The workspace (warm start by contact id) and the per-contact diagnostics
    /// (`c/workspace_checks.c`).
    pub fn capi_check_workspace() -> c_int;
    /// Solves a 2D file with `solver_id` through `fc2d_driver`.
    pub fn capi_fc2d_solve_file(
        path: *const c_char,
        solver_id: c_int,
        tolerance: c_double,
        max_iter: c_int,
        reaction_out: *mut c_double,
        capacity: c_int,
        result: *mut Fc2dResult,
    ) -> c_int;
    /// The 2D API checks of `c/fc2d_checks.c`.
    pub fn capi_fc2d_check_api() -> c_int;
    /// A 2D file solved with W as read, rebuilt dense and rebuilt as 2x2 sparse blocks.
    pub fn capi_fc2d_check_storages(path: *const c_char) -> c_int;
    pub fn capi_solve_file(
        path: *const c_char,
        storage: c_int,
        local_solver: c_int,
        tolerance: c_double,
        max_iter: c_int,
        reaction_out: *mut c_double,
        velocity_out: *mut c_double,
        capacity: c_int,
        result: *mut CSolveResult,
    ) -> c_int;
    pub fn capi_check_single_contacts() -> c_int;
    pub fn capi_check_bad_input(data_dir: *const c_char) -> c_int;
    pub fn capi_check_ownership(data_dir: *const c_char, scratch_dir: *const c_char) -> c_int;
    pub fn capi_check_options() -> c_int;
    pub fn capi_check_callback() -> c_int;
    pub fn capi_check_nsgs_options(data_dir: *const c_char) -> c_int;
    /// `capi_solve_file` for any solver id (its Siconos defaults, tolerance and max_iter set).
    pub fn capi_solve_file_with_solver(
        path: *const c_char,
        storage: c_int,
        solver_id: c_int,
        tolerance: c_double,
        max_iter: c_int,
        reaction_out: *mut c_double,
        velocity_out: *mut c_double,
        capacity: c_int,
        result: *mut CSolveResult,
    ) -> c_int;
    pub fn capi_check_vi_admm_single_contacts() -> c_int;
    pub fn capi_check_vi_admm_options() -> c_int;
    pub fn opt5_check_single_contacts_and_options() -> c_int;
    pub fn capi_solve_file_with(
        path: *const c_char,
        storage: c_int,
        solver_id: c_int,
        internal_id: c_int,
        tolerance: c_double,
        max_iter: c_int,
        reaction_out: *mut c_double,
        velocity_out: *mut c_double,
        capacity: c_int,
        result: *mut CSolveResult,
    ) -> c_int;
    pub fn capi_check_newton_and_prox() -> c_int;
    /// The matrix helpers against hostile structs (c/matrix_hostile.c).
    pub fn capi_check_hostile_matrices() -> c_int;
    pub fn capi_check_solver_entries(data_dir: *const c_char) -> c_int;
    pub fn capi_check_problem_copy(data_dir: *const c_char) -> c_int;
    pub fn capi_check_global(data_dir: *const c_char, scratch_dir: *const c_char) -> c_int;
}

/// Reference to the shared Siconos data set beside the repository.
pub fn data_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/siconos")
}

/// `libfc3d.so` of the profile the calling test runs in, (re)built: `cargo test` builds fc3d as
/// an rlib only. For C programs that open it with dlopen beside the installed Siconos.
pub fn shared_library() -> std::path::PathBuf {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().unwrap().parent().unwrap().to_path_buf();
    let mut build = std::process::Command::new(env!("CARGO"));
    build
        .args(["build", "-p", "fc3d", "--lib"])
        .current_dir(&root);
    // target/<profile>: "debug" is the dev profile, any other directory names its profile.
    let profile = profile_dir.file_name().unwrap().to_str().unwrap();
    if profile != "debug" {
        build.args(["--profile", profile]);
    }
    assert!(build.status().unwrap().success(), "cargo build -p fc3d");
    profile_dir.join("libfc3d.so")
}

/// Compiles the C program `capi-tests/c/<source>` against fc3d's compat headers (the struct
/// layouts, identical to Siconos') into `program`, linked with -ldl -lm only.
pub fn compile_dlopen_program(source: &str, program: &std::path::Path) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::process::Command::new("cc")
        .args(["-O1", "-Wall", "-Wextra", "-Werror"])
        .arg(format!(
            "-I{}",
            root.join("capi/include/siconos-compat").display()
        ))
        .arg(format!("-I{}", root.join("capi/include").display()))
        .arg(root.join("capi-tests/c").join(source))
        .args(["-ldl", "-lm", "-o"])
        .arg(program)
        .output()
        .expect("run cc");
    assert!(
        out.status.success(),
        "cc: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}
