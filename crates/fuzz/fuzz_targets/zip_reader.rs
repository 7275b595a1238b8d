//! Any bytes as a zipped pack: the reader returns a pack or an error, within its limits.
#![no_main]
use libfuzzer_sys::fuzz_target;
use tidepack_loader::input::{Limits, read_zip_bytes};

fuzz_target!(|data: &[u8]| {
    let limits = Limits::default();
    if let Ok(pack) = read_zip_bytes(data, "fuzz.zip", &limits) {
        let kept: u64 = pack.files.values().map(|f| f.len() as u64).sum();
        assert!(kept <= limits.max_total_bytes);
        assert!(pack.files.keys().all(|p| !p.split('/').any(|part| part == "..")));
    }
});
