//! `fc3d_driver` on arbitrary small problems and options, called through the C ABI as a host
//! would: any bytes give a return code; 0, 1, 2 and 3 come with finite r and u and a `dparam[1]`
//! equal to `fc3d_compute_error` of the returned reaction; a negative code leaves r, u, iparam[1]
//! and dparam[1] untouched. Never a panic, an abort or a hang (iterations and time are capped).
#![no_main]

use libfuzzer_sys::fuzz_target;

include!("driver_case.rs");

fuzz_target!(|data: &[u8]| run_driver_case(data));
