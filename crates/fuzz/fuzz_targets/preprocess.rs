//! A program and one include of any text through OptiFine's preprocessing: a result or a
//! diagnostic, and a result whose every line maps back to a pack file.
#![no_main]
use std::collections::HashMap;
use std::sync::Arc;

use libfuzzer_sys::fuzz_target;
use tidepack_glsl::preprocess::{IncludeQuotes, PreprocessOptions, preprocess};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let (program, include) = text.split_once('\0').unwrap_or((&text, "float included;\n"));
    let files: HashMap<String, Arc<str>> =
        [("composite.fsh".to_string(), Arc::from(program)), ("lib/a.glsl".to_string(), Arc::from(include))].into();
    // OptiFine's include syntax, or Iris's when the program's first byte is odd.
    let include_quotes = if program.as_bytes().first().is_some_and(|b| b & 1 == 1) { IncludeQuotes::Optional } else { IncludeQuotes::Required };
    let options = PreprocessOptions { predefined: vec![("MC_VERSION".into(), "12004".into())], include_quotes };
    if let Ok(pre) = preprocess(&files, "composite.fsh", &options) {
        let lines = pre.text.matches('\n').count() as u32;
        for line in 1..=lines {
            if let Some(at) = pre.location(line) {
                assert!(files.contains_key(&at.path), "line {line} maps to {}", at.path);
            }
        }
    }
});
