//! A small, dependency-free mutation fuzzer for the tokenizer, the preprocessor, the lowering
//! and the whole validator, seeded with real pack files. Deterministic for a given seed.
//!
//! Each execution mutates one file of a seed pack (byte flips, inserted GLSL and preprocessor
//! fragments, deleted or duplicated ranges, splices from other files, invalid UTF-8) and then
//! checks, with panics caught:
//! - the tokenizer gives back its input exactly;
//! - the preprocessor and the lowering return a result or a diagnostic, and the lowering keeps
//!   the preprocessed line count;
//! - the whole validator returns a report.
//!
//! A panic inside naga is counted apart (`naga_panics`): the validator turns it into a "not
//! checked" warning, so it is not a crash of the toolchain, but it is worth reporting upstream.

use rand_core::{Rng as _, SeedableRng};
use rand_xoshiro::SplitMix64;
use std::collections::BTreeMap;
use std::panic::AssertUnwindSafe;
use std::sync::Arc;
use std::time::{Duration, Instant};

use tidepack_glsl::preprocess::{self, PreprocessOptions};
use tidepack_glsl::token::tokenize;
use tidepack_glsl::naga_check;
use tidepack_glsl::Stage;

use tidepack_loader::input::pack_from_memory;
use crate::{Options, Profiles};

/// Fragments that reach the interesting paths quickly.
const DICTIONARY: &[&str] = &[
    "(", ")", "{", "}", "[", "]", ";", ",", "#", "\n", "\\\n", "/*", "*/", "//", "\"", "##", "\u{FEFF}", "é",
    "#include \"/lib/a.glsl\"\n", "#include \"../../x\"\n", "#include \"", "#define F(x) F(x) x\n", "#define X X X\n",
    "#if ", "#ifdef X\n", "#else\n", "#elif 1\n", "#endif\n", "#if defined(", "#version 120\n", "#version 330 compatibility\n",
    "#extension GL_EXT_gpu_shader4 : enable\n", "/* DRAWBUFFERS:0123456789 */\n", "/* RENDERTARGETS: 0,15,16 */\n",
    "varying mat3 m;\n", "varying vec3 a[2];\n", "flat varying int i;\n", "in vec4 ", "out vec4 outColor3;\n",
    "uniform sampler2D s;\n", "uniform bool b;\n", "uniform Light l;\n", "struct Light { vec3 c; };\n",
    "uniform float u = 1.0;\n", "gl_FragData[", "gl_FragData[9] = vec4(1.0);", "gl_TexCoord[", "gl_TexCoord[i]",
    "gl_FrontColor", "gl_Color", "gl_Fog.color", "gl_FogFragCoord", "ftransform()", "ftransform", "texture2D(",
    "shadow2D(s, vec3(0.0))", "texelFetch2D(", "texture2DLod(s, vec2(0.0), 0.0)", "sampler2D t", "void main() {",
    "main", "return;", "0x", "1e", "1.0e+", "99999999999999999999", "-", "defined", "tp_", "layout(location = 99)",
];

/// What a run did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FuzzStats {
    pub executions: u64,
    /// Panics in tidepack's own code (tokenizer, preprocessor, lowering, validator).
    pub crashes: u64,
    /// Broken invariants (round trip, line count) without a panic.
    pub invariant_failures: u64,
    /// Panics inside naga, caught and reported as diagnostics by the validator.
    pub naga_panics: u64,
    /// Inputs that crashed or broke an invariant (first few), with what happened.
    pub findings: Vec<(String, Vec<u8>)>,
}

/// The workspace's splitmix64: a seed replays the same run on every build.
struct Rng(SplitMix64);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(SplitMix64::seed_from_u64(seed))
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 { 0 } else { (self.0.next_u64() % n as u64) as usize }
    }
}

fn mutate(rng: &mut Rng, input: &[u8], others: &[&[u8]]) -> Vec<u8> {
    let mut data = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(data.len() + 1);
        match rng.below(7) {
            0 if !data.is_empty() => {
                let i = rng.below(data.len());
                data[i] ^= 1 << rng.below(8);
            }
            1 | 2 => {
                let word = DICTIONARY[rng.below(DICTIONARY.len())].as_bytes();
                data.splice(at..at, word.iter().copied());
            }
            3 if !data.is_empty() => {
                let len = rng.below(64.min(data.len() - at.min(data.len())) + 1);
                let end = (at + len).min(data.len());
                data.drain(at.min(end)..end);
            }
            4 if !data.is_empty() => {
                let start = rng.below(data.len());
                let end = (start + rng.below(256)).min(data.len());
                let copy = data[start..end].to_vec();
                let times = 1 + rng.below(3);
                for _ in 0..times {
                    data.splice(at..at, copy.iter().copied());
                }
            }
            5 if !others.is_empty() => {
                let other = others[rng.below(others.len())];
                let start = rng.below(other.len() + 1);
                let end = (start + rng.below(512)).min(other.len());
                data.splice(at..at, other[start..end].iter().copied());
            }
            _ => data.insert(at, [0xFF, 0xC3, b'\t', b'\r', 0][rng.below(5)]),
        }
    }
    data.truncate(1 << 16);
    data
}

/// One seed pack: files relative to `shaders/`.
pub type SeedPack = BTreeMap<String, Vec<u8>>;

/// Runs until `executions` inputs were tried or `time` ran out, whichever is first.
pub fn run(seeds: &[SeedPack], executions: u64, time: Duration, seed: u64) -> FuzzStats {
    let mut stats = FuzzStats::default();
    let mut rng = Rng::new(seed);
    let all_files: Vec<&[u8]> = seeds.iter().flat_map(|p| p.values().map(Vec::as_slice)).collect();
    let started = Instant::now();
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    while stats.executions < executions && started.elapsed() < time {
        let pack = &seeds[rng.below(seeds.len())];
        let shaders: Vec<&String> = pack.keys().filter(|p| !p.ends_with(".properties")).collect();
        if shaders.is_empty() {
            continue;
        }
        let target = shaders[rng.below(shaders.len())].clone();
        let mutated = mutate(&mut rng, &pack[&target], &all_files);
        stats.executions += 1;
        let outcome = std::panic::catch_unwind(AssertUnwindSafe(|| execute(pack, &target, &mutated)));
        let failure = match outcome {
            Ok(Ok(naga_panics)) => {
                stats.naga_panics += naga_panics;
                None
            }
            Ok(Err(broken)) => {
                stats.invariant_failures += 1;
                Some(broken)
            }
            Err(panic) => {
                stats.crashes += 1;
                let what = panic.downcast_ref::<String>().cloned().or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()));
                Some(format!("panic in {target}: {}", what.unwrap_or_default()))
            }
        };
        if let Some(what) = failure
            && stats.findings.len() < 20
        {
            stats.findings.push((what, mutated));
        }
    }
    std::panic::set_hook(previous_hook);
    stats
}

/// Runs one input through every layer. `Err` names a broken invariant; `Ok` the naga panics.
fn execute(pack: &SeedPack, target: &str, mutated: &[u8]) -> Result<u64, String> {
    let text = String::from_utf8_lossy(mutated);
    if let Ok(tokens) = tokenize(&text) {
        let joined: String = tokens.iter().map(|t| t.text).collect();
        if joined != text {
            return Err(format!("tokenizer round trip broken on {target}"));
        }
    }
    let files: std::collections::HashMap<String, Arc<str>> = pack
        .iter()
        .map(|(p, b)| (p.clone(), Arc::from(if p == target { text.as_ref().to_string() } else { String::from_utf8_lossy(b).into_owned() })))
        .collect();
    if let Some(stage) = Stage::from_path(target)
        && let Ok(pre) = preprocess::preprocess(&files, target, &PreprocessOptions::default())
        && let Ok(lowered) = naga_check::lower_program(&[(stage, Arc::new(pre))])
    {
        let (pre_lines, lowered_lines) =
            (lowered[0].preprocessed.text.matches('\n').count(), lowered[0].lowered.text.matches('\n').count());
        if pre_lines != lowered_lines {
            return Err(format!("lowering changed the line count of {target}: {pre_lines} -> {lowered_lines}"));
        }
    }
    if target.ends_with(".csh")
        && let Ok(pre) = preprocess::preprocess(&files, target, &PreprocessOptions::default())
        && let Ok(lowered) = naga_check::lower_compute(Arc::new(pre))
    {
        let (pre_lines, lowered_lines) =
            (lowered.preprocessed.text.matches('\n').count(), lowered.lowered.text.matches('\n').count());
        if pre_lines != lowered_lines {
            return Err(format!("lowering changed the line count of {target}: {pre_lines} -> {lowered_lines}"));
        }
    }
    let mut memory: Vec<(String, Vec<u8>)> = pack.iter().map(|(p, b)| (p.clone(), b.clone())).collect();
    for (p, b) in &mut memory {
        if p == target {
            *b = mutated.to_vec();
        }
    }
    let options = Options { threads: 1, profiles: Profiles::All, ..Options::default() };
    match crate::validate_pack(pack_from_memory("fuzz/", memory), &options) {
        Ok(report) => Ok(report.diagnostics.iter().filter(|d| d.message.contains("naga crashed on it")).count() as u64),
        Err(_) => Ok(0),
    }
}

/// The checks of the cargo-fuzz targets in crates/fuzz, one per reader, callable on the stable
/// toolchain so that [`run_targets`] (and with it `cargo test`) runs them too. Each returns
/// normally or panics where its check fails.
pub mod targets {
    use std::collections::{BTreeMap, HashMap};
    use std::sync::Arc;

    use tidepack_glsl::Stage;
    use tidepack_glsl::lower::{VaryingLayout, lower as lower_stage};
    use tidepack_glsl::preprocess::{IncludeRules, PreprocessOptions, preprocess as preprocess_program};
    use tidepack_loader::custom_uniforms::evaluate;
    use tidepack_loader::input::{Limits, read_zip_bytes};
    use tidepack_loader::option_space::{ProfileResolver, profiles};
    use tidepack_loader::properties::Properties;

    /// Any bytes as a zipped pack: a pack or an error; what is kept fits the budget and no
    /// path climbs out.
    pub fn zip_reader(data: &[u8]) {
        let limits = Limits::default();
        if let Ok(pack) = read_zip_bytes(data, "fuzz.zip", &limits) {
            let kept: u64 = pack.files.values().map(|f| f.len() as u64).sum();
            assert!(kept <= limits.max_total_bytes, "{kept} bytes kept");
            assert!(pack.files.keys().all(|p| !p.split('/').any(|part| part == "..")), "a path climbs out");
        }
    }

    /// A program and one include (split at the first NUL) through the preprocessor, with
    /// OptiFine's include syntax or, when the first byte is odd, Iris's: every output line
    /// maps to a pack file.
    pub fn preprocess(data: &[u8]) {
        let text = String::from_utf8_lossy(data);
        let (program, include) = text.split_once('\0').unwrap_or((&text, "float included;\n"));
        let files: HashMap<String, Arc<str>> =
            [("composite.fsh".to_string(), Arc::from(program)), ("lib/a.glsl".to_string(), Arc::from(include))].into();
        let include_rules = if data.first().is_some_and(|b| b & 1 == 1) { IncludeRules::Iris } else { IncludeRules::OptiFine };
        let options = PreprocessOptions { predefined: vec![("MC_VERSION".into(), "12004".into())], include_rules, lenient: false, token_cache: None };
        if let Ok(pre) = preprocess_program(&files, "composite.fsh", &options) {
            for line in 1..=pre.text.matches('\n').count() as u32 {
                if let Some(at) = pre.location(line) {
                    assert!(files.contains_key(&at.path), "line {line} maps to {}", at.path);
                }
            }
        }
    }

    /// Any text (after a selector byte: stage, layout) through the lowering: a result or an
    /// error, and a result with as many lines.
    pub fn lower(data: &[u8]) {
        let Some((&selector, rest)) = data.split_first() else { return };
        let text = String::from_utf8_lossy(rest);
        let stage = if selector & 1 == 0 { Stage::Vertex } else { Stage::Fragment };
        let layout = if selector & 2 == 0 { VaryingLayout::default() } else { VaryingLayout::for_program(&[(stage, &text, 330)]).unwrap_or_default() };
        if let Ok(lowered) = lower_stage(&text, stage, &layout, false) {
            assert_eq!(lowered.text.matches('\n').count(), text.matches('\n').count(), "the lowering moved lines");
        }
    }

    /// Any text as shaders.properties: parsed, and every profile resolved or an error.
    pub fn properties(data: &[u8]) {
        let props = Properties::parse_plain(&String::from_utf8_lossy(data));
        let options = BTreeMap::new();
        let mut resolver = ProfileResolver::new(&props, &options);
        for name in profiles(&props).keys() {
            let _ = resolver.resolve(name);
        }
    }

    /// Any text as shaders.properties' custom uniforms and variables, evaluated for one frame.
    pub fn custom_uniforms(data: &[u8]) {
        let _ = evaluate(&Properties::parse_plain(&String::from_utf8_lossy(data)), &BTreeMap::new());
    }

    /// The targets by name, as crates/fuzz names them.
    pub const ALL: [(&str, fn(&[u8])); 5] =
        [("zip_reader", zip_reader), ("preprocess", preprocess), ("lower", lower), ("properties", properties), ("custom_uniforms", custom_uniforms)];
}

/// Runs [`targets`] on mutations of the seed packs' files (their zip for `zip_reader`, their
/// shaders.properties for the properties targets) until `executions` or `time` is reached;
/// a panic in a target is a crash.
pub fn run_targets(seeds: &[SeedPack], executions: u64, time: Duration, seed: u64) -> FuzzStats {
    let mut stats = FuzzStats::default();
    let mut rng = Rng::new(seed);
    let all_files: Vec<&[u8]> = seeds.iter().flat_map(|p| p.values().map(Vec::as_slice)).collect();
    let zips: Vec<Vec<u8>> = seeds.iter().map(zip_of).collect();
    let started = Instant::now();
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    while stats.executions < executions && started.elapsed() < time {
        let (name, target) = targets::ALL[rng.below(targets::ALL.len())];
        let pack = rng.below(seeds.len());
        let input: &[u8] = match name {
            "zip_reader" => &zips[pack],
            "properties" | "custom_uniforms" => seeds[pack].get("shaders.properties").map_or(&b"profile.A=profile.B\n"[..], Vec::as_slice),
            _ => all_files[rng.below(all_files.len())],
        };
        let mutated = mutate(&mut rng, input, &all_files);
        stats.executions += 1;
        if let Err(panic) = std::panic::catch_unwind(AssertUnwindSafe(|| target(&mutated))) {
            stats.crashes += 1;
            let what = panic.downcast_ref::<String>().cloned().or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()));
            if stats.findings.len() < 20 {
                stats.findings.push((format!("panic in the {name} target: {}", what.unwrap_or_default()), mutated));
            }
        }
    }
    std::panic::set_hook(previous_hook);
    stats
}

/// A seed pack as a zip, its files under `shaders/`.
fn zip_of(pack: &SeedPack) -> Vec<u8> {
    use std::io::Write;
    let mut buffer = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut buffer);
    for (path, bytes) in pack {
        if zip.start_file(format!("shaders/{path}"), zip::write::SimpleFileOptions::default()).is_ok() {
            let _ = zip.write_all(bytes);
        }
    }
    let _ = zip.finish();
    buffer.into_inner()
}

/// Reads every file of the packs under `dir` (each subfolder holding `shaders/` somewhere).
pub fn seeds_from(dirs: &[std::path::PathBuf]) -> Vec<SeedPack> {
    let mut seeds = Vec::new();
    for dir in dirs {
        if let Ok(pack) = tidepack_loader::input::read_pack(dir, &tidepack_loader::Limits::default()) {
            seeds.push(pack.files.iter().map(|(p, b)| (p.clone(), b.to_vec())).collect());
        }
    }
    seeds
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mutation_is_deterministic() {
        let (mut a, mut b) = (Rng::new(7), Rng::new(7));
        let input = b"#version 120\nvoid main() {}\n";
        assert_eq!(mutate(&mut a, input, &[]), mutate(&mut b, input, &[]));
    }
}
