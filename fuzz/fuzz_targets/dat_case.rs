// One fuzz case of the .dat reader, shared by fuzz/fuzz_targets/dat_parser.rs and
// tests/fuzz_regressions.rs (both include this file).

/// Parses arbitrary bytes; panics (assert) if a parsed problem does not survive a round trip.
pub fn run_dat_case(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Ok(p) = fc3d_core::io::dat::parse_dat(&text, "fuzz") {
        let mut out = Vec::new();
        fc3d_core::io::dat::write_dat(&p, &mut out).expect("writing to memory");
        let again = fc3d_core::io::dat::parse_dat(std::str::from_utf8(&out).expect("utf-8"), "again")
            .expect("what we write, we read");
        assert_eq!(p.size(), again.size());
    }
}
