//! Any text as shaders.properties' custom uniforms and variables, evaluated for one frame:
//! every value finite or reported, never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::collections::BTreeMap;
use tidepack_loader::custom_uniforms::evaluate;
use tidepack_loader::properties::Properties;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let props = Properties::parse_plain(&text);
    let _ = evaluate(&props, &BTreeMap::new());
});
