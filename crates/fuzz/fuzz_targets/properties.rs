//! Any text as shaders.properties: parsed with its preprocessor lines, then every profile
//! resolved; each returns a value or a diagnostic.
#![no_main]
use libfuzzer_sys::fuzz_target;

// The check lives in tidepack_validate::fuzz::targets, where `cargo test` runs it too.
fuzz_target!(|data: &[u8]| tidepack_validate::fuzz::targets::properties(data));
