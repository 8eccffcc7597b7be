//! The exported matrix helpers (`NM_*`, `SBM_*`, `SBCM_*`) and `fc3d_driver` on matrices a
//! hostile host fills (see matrix_case.rs): any bytes give a clean result or a clean negative
//! code, never a crash, an out-of-bounds access, a leak or a caught panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

include!("matrix_case.rs");

/// Sizes no allocator can give must make malloc return NULL (fc3d then reports
/// FC3D_ERR_OUT_OF_MEMORY), not stop the address sanitizer.
#[no_mangle]
pub extern "C" fn __asan_default_options() -> *const std::os::raw::c_char {
    b"allocator_may_return_null=1\0".as_ptr().cast()
}

fuzz_target!(|data: &[u8]| run_matrix_case(data));
