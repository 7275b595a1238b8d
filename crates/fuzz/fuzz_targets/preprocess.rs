//! A program and one include of any text through OptiFine's preprocessing: a result or a
//! diagnostic, and a result whose every line maps back to a pack file.
#![no_main]
use libfuzzer_sys::fuzz_target;

// The check lives in tidepack_validate::fuzz::targets, where `cargo test` runs it too.
fuzz_target!(|data: &[u8]| tidepack_validate::fuzz::targets::preprocess(data));
