//! Every input the fuzzers (`fuzz/`, `cargo +nightly fuzz run driver|dat_parser|options`) ever failed
//! on, replayed with the very same case functions, so a fixed bug stays fixed. Crashes are kept
//! in `fuzz/regressions/<target>/`.

#![allow(clippy::missing_safety_doc)]

include!("../../fuzz/fuzz_targets/driver_case.rs");
include!("../../fuzz/fuzz_targets/dat_case.rs");

/// The `options` target's case (in its own module: it declares the same C functions).
mod options_case {
    include!("../../fuzz/fuzz_targets/options_case.rs");
}

fn saved(target: &str) -> Vec<(String, Vec<u8>)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz/regressions")
        .join(target);
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .map(|d| {
            d.map(|e| {
                let p = e.unwrap().path();
                (p.display().to_string(), std::fs::read(&p).unwrap())
            })
            .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

#[test]
fn saved_driver_inputs() {
    let cases = saved("driver");
    assert!(!cases.is_empty());
    for (name, bytes) in cases {
        eprintln!("{name}");
        run_driver_case(&bytes);
    }
}

#[test]
fn saved_dat_inputs() {
    for (name, bytes) in saved("dat_parser") {
        eprintln!("{name}");
        run_dat_case(&bytes);
    }
}

#[test]
fn saved_options_inputs() {
    let cases = saved("options");
    assert!(!cases.is_empty());
    for (name, bytes) in cases {
        eprintln!("{name}");
        options_case::run_options_case(&bytes);
    }
}
