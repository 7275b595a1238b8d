//! Any bytes as a zipped pack: the reader returns a pack or an error, within its limits.
#![no_main]
use libfuzzer_sys::fuzz_target;

// The check lives in tidepack_validate::fuzz::targets, where `cargo test` runs it too.
fuzz_target!(|data: &[u8]| tidepack_validate::fuzz::targets::zip_reader(data));
