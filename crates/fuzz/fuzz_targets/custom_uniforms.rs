//! Any text as shaders.properties' custom uniforms and variables, evaluated for one frame:
//! every value finite or reported, never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;

// The check lives in tidepack_validate::fuzz::targets, where `cargo test` runs it too.
fuzz_target!(|data: &[u8]| tidepack_validate::fuzz::targets::custom_uniforms(data));
