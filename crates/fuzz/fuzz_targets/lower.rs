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
    // As validation lowers a stage alone, or with the layout its program gives.
    let layout = if selector & 2 == 0 { VaryingLayout::default() } else { VaryingLayout::for_program(&[(stage, &text, 330)]).unwrap_or_default() };
    if let Ok(lowered) = lower(&text, stage, &layout) {
        assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count(), "the lowering moved lines");
    }
});
