//! The Siconos .dat reader on arbitrary text: it must return a problem or a `Parse` error, never
//! panic, hang or allocate without bound. A parsed problem must survive a write/read round trip.
#![no_main]

use libfuzzer_sys::fuzz_target;

include!("dat_case.rs");

fuzz_target!(|data: &[u8]| run_dat_case(data));
