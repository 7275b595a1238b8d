//! Any text as a preprocessed stage through the lowering to Vulkan GLSL: a result or an error,
//! and a result with the same number of lines (errors keep their line).
#![no_main]
use libfuzzer_sys::fuzz_target;

// The check lives in tidepack_validate::fuzz::targets, where `cargo test` runs it too.
fuzz_target!(|data: &[u8]| tidepack_validate::fuzz::targets::lower(data));
