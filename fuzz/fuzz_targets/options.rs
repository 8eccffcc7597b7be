//! `fc3d_driver` over option slots through the C ABI, as a hostile host would set them: any
//! solver id, random internal solver ids, extreme values (INT_MIN, INT_MAX, -1, 0, huge, NaN,
//! +-inf, 1e308, subnormals, ...) in random iparam/dparam slots of the options and of their
//! internal solvers, broken option trees (cycles, counts without arrays, short sizes), and
//! `solver_options_copy` of the result. The return code is 0..=4 or a negative FC3D_ERR_* code,
//! never FC3D_ERR_INTERNAL (a caught panic); see options_case.rs for every assertion.
#![no_main]

use libfuzzer_sys::fuzz_target;

include!("options_case.rs");

fuzz_target!(|data: &[u8]| run_options_case(data));
