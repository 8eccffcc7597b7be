//! The Siconos .dat reader on arbitrary text: it must return a problem or a `Parse` error, never
//! panic, hang or allocate without bound. A parsed problem must survive a write/read round trip.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(p) = fc3d::io::dat::parse_dat(&text, "fuzz") {
        let mut out = Vec::new();
        fc3d::io::dat::write_dat(&p, &mut out).expect("writing to memory");
        let again = fc3d::io::dat::parse_dat(std::str::from_utf8(&out).expect("utf-8"), "again")
            .expect("what we write, we read");
        assert_eq!(p.size(), again.size());
    }
});
