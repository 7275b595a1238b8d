//! Any text as shaders.properties: parsed with its preprocessor lines, then every profile
//! resolved; each returns a value or a diagnostic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::collections::BTreeMap;
use tidepack_loader::option_space::{profile_set, profiles};
use tidepack_loader::properties::Properties;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let props = Properties::parse_plain(&text);
    for name in profiles(&props).keys() {
        let _ = profile_set(&props, name, &BTreeMap::new());
    }
});
