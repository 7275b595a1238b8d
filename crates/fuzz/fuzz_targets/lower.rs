//! Any text as a preprocessed stage through the lowering to Vulkan GLSL: a result or an error,
//! and a result with the same number of lines (errors keep their line).
#![no_main]
use libfuzzer_sys::fuzz_target;
use tidepack_glsl::Stage;
use tidepack_glsl::lower::{VaryingLayout, lower};

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else { return };
    let text = String::from_utf8_lossy(rest);
    let stage = if selector & 1 == 0 { Stage::Vertex } else { Stage::Fragment };
    if let Ok(lowered) = lower(&text, stage, &VaryingLayout::default()) {
        assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count(), "the lowering moved lines");
    }
});
