//! Plants one mistake at a time into real packs and checks that `validate` reports it at the
//! planted file and line, in GLSL terms.
//!
//! For each pack: validate a copy unmodified (defaults), keep the programs with no error, collect
//! the lines of their stages (entry files and includes) that end a statement inside a function
//! body in the preprocessed text (so never in a comment or an inactive `#if` branch), then for
//! every kind of mistake insert one line after a seeded choice of such a line, validate again,
//! and restore the file. Only errors the unmodified pack did not have count.
//!
//! With `--behind-toggle`, each mistake sits behind a switch of its own, off by default
//! (`//#define PLANTED_TOGGLE` then `#ifdef PLANTED_TOGGLE`), as a mistake behind one menu toggle
//! does in released packs: the defaults never see it, and the packs are validated with
//! `--covering` (through a cache folder, so only the programs a plant touches are validated
//! again). An unterminated `#if` is not planted then: the toggle's `#endif` would close it.
//!
//! `cargo run --release -p tidepack-validate --example plant -- [--seed N] [--per-kind N]
//! [--threads N] [--behind-toggle] PACK_DIR...` (tools/plant runs it over packs of a folder). Packs are copied to a
//! temporary folder: the originals are never written.

use rand_core::{Rng as _, SeedableRng};
use rand_xoshiro::SplitMix64;
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use tidepack_glsl::Diagnostic;
use tidepack_loader::option_lines::OptionSet;
use tidepack_glsl::preprocess::{self, FileProvider, Preprocessed};
use tidepack_loader::SetProvider;
use tidepack_loader::programs::{self, RunBy};
use tidepack_loader::option_lines::OptionValue;
use tidepack_validate::{Coverage, Options, Profiles, Report, Status, driver};

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    UndeclaredVariable,
    TypeMismatch,
    MissingSemicolon,
    WrongArgumentCount,
    UnknownFunction,
    AssignUniform,
    AssignConst,
    BadSwizzle,
    RedeclaredLocal,
    ReturnValueInVoid,
    SamplerAsFloat,
    IntFromFloat,
    MissingInclude,
    UnterminatedIf,
    MacroRedefined,
    ErrorDirective,
    ReservedOutput,
    ReservedSample,
    ConstFromUniform,
    IntToUint,
    WriteToInput,
    MissingReturn,
    FragDataBesideOut,
    Texture2DOnShadow,
    UninitialisedRead,
}

const KINDS: [Kind; 25] = [
    Kind::UndeclaredVariable,
    Kind::TypeMismatch,
    Kind::MissingSemicolon,
    Kind::WrongArgumentCount,
    Kind::UnknownFunction,
    Kind::AssignUniform,
    Kind::AssignConst,
    Kind::BadSwizzle,
    Kind::RedeclaredLocal,
    Kind::ReturnValueInVoid,
    Kind::SamplerAsFloat,
    Kind::IntFromFloat,
    Kind::MissingInclude,
    Kind::UnterminatedIf,
    Kind::MacroRedefined,
    Kind::ErrorDirective,
    Kind::ReservedOutput,
    Kind::ReservedSample,
    Kind::ConstFromUniform,
    Kind::IntToUint,
    Kind::WriteToInput,
    Kind::MissingReturn,
    Kind::FragDataBesideOut,
    Kind::Texture2DOnShadow,
    Kind::UninitialisedRead,
];

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::UndeclaredVariable => "undeclared variable",
            Kind::TypeMismatch => "type mismatch (vec3 = vec2)",
            Kind::MissingSemicolon => "missing semicolon",
            Kind::WrongArgumentCount => "pack function, wrong argument count",
            Kind::UnknownFunction => "unknown function",
            Kind::AssignUniform => "assignment to a uniform",
            Kind::AssignConst => "assignment to a const",
            Kind::BadSwizzle => "swizzle mixing sets (.xyzq)",
            Kind::RedeclaredLocal => "local redeclared in its scope",
            Kind::ReturnValueInVoid => "return value in a void function",
            Kind::SamplerAsFloat => "sampler used as a float",
            Kind::IntFromFloat => "int initialised with a float",
            Kind::MissingInclude => "#include of a missing file",
            Kind::UnterminatedIf => "unterminated #if at file end",
            Kind::MacroRedefined => "macro redefined with another body",
            Kind::ErrorDirective => "#error",
            Kind::ReservedOutput => "reserved word `output` as a name",
            Kind::ReservedSample => "`sample` as a name (GLSL 4.00+)",
            Kind::ConstFromUniform => "local `const` from a uniform (before 4.20)",
            Kind::IntToUint => "int literal into a `uint` (1.30 to 3.30)",
            Kind::WriteToInput => "write to a fragment input",
            Kind::MissingReturn => "non-void function without `return`",
            Kind::FragDataBesideOut => "gl_FragData beside the stage's own `out`",
            Kind::Texture2DOnShadow => "texture2D on a sampler2DShadow",
            Kind::UninitialisedRead => "read of a local never assigned (warning)",
        }
    }

    /// Whether the mistake is a warning (drivers compile it) rather than an error.
    fn is_warning(self) -> bool {
        self == Kind::UninitialisedRead
    }
}

/// Scalar, vector and matrix types: the declarations the scanner recognises.
const VALUE_TYPES: [&str; 20] = [
    "float", "int", "uint", "bool", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "uvec2", "uvec3", "uvec4", "bvec2",
    "bvec3", "bvec4", "mat2", "mat3", "mat4", "double",
];

struct FnDef {
    out_line: usize,
    name: String,
    ret: String,
    params: usize,
}

struct Global {
    out_line: usize,
    ty: String,
    name: String,
}

/// One stage of a clean program, preprocessed under the defaults.
struct StageInfo {
    program: String,
    path: String,
    pre: Preprocessed,
    functions: Vec<FnDef>,
    uniforms: Vec<Global>,
    samplers: Vec<Global>,
    consts: Vec<Global>,
    /// `#version` number (110 without one).
    version: u32,
    /// A fragment stage (`.fsh`).
    fragment: bool,
    /// Fragment inputs (`in`/`varying` of one value-type name).
    inputs: Vec<Global>,
    /// The stage's own `out` variables that it writes somewhere (`name =`, `name.x =`, `name[0] =`).
    written_outputs: Vec<String>,
    /// Whether the stage names gl_FragData or gl_FragColor at all.
    builtin_outputs: bool,
}

/// A source line that ends a statement in a function body: a new line goes right after it.
struct Anchor {
    stage: usize,
    out_line: usize,
    path: String,
    line: u32,
    indent: String,
    function: usize,
    /// `(type, name)` declared earlier in the same block.
    locals: Vec<(String, String)>,
}

enum BlockKind {
    Function(usize),
    Control,
    /// Switch bodies and anything not code (structs, initializers, interface blocks): a
    /// declaration planted there would be a different mistake.
    Other,
}

struct Block {
    kind: BlockKind,
    locals: Vec<(String, String)>,
}

struct Plant {
    pack: String,
    kind: Kind,
    program: String,
    path: String,
    line: u32,
    text: String,
    included: bool,
    outcome: Outcome,
    /// Which accepted line was hit (missing semicolon: planted or next).
    hit_line: Option<u32>,
    internals: bool,
    /// New errors, and warnings at the planted line, as reported.
    reported: Vec<String>,
    /// The drivers the diagnostic at the line says refuse it (`refused_by`).
    drivers: Vec<&'static str>,
    /// With `--mesa`: whether Mesa compiles and links the planted program.
    mesa: MesaVerdict,
    elapsed: Duration,
}

#[derive(Clone, PartialEq, Eq)]
enum MesaVerdict {
    /// Not asked (`--mesa` not given), the program could not be given to Mesa, or Mesa gave
    /// no verdict (it made no shader object).
    NotGiven,
    Accepts,
    /// Mesa's first error.
    Refuses(String),
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Outcome {
    AtLine,
    Elsewhere,
    Missed,
}

/// Deterministic choices on the workspace's splitmix64: a seed plants the same mistakes on
/// every build.
struct Rng(SplitMix64);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(SplitMix64::seed_from_u64(seed))
    }
    fn below(&mut self, n: usize) -> usize {
        (self.0.next_u64() % n as u64) as usize
    }
}

fn fnv(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3))
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut seed = 1u64;
    let mut per_kind = 1usize;
    let mut threads = 2usize;
    let mut behind_toggle = false;
    let mut in_dimension = false;
    let mut mesa = false;
    let mut kinds: Vec<Kind> = KINDS.to_vec();
    let mut dirs: Vec<PathBuf> = Vec::new();
    while let Some(arg) = args.next() {
        let mut number = |name: &str| -> u64 {
            args.next().and_then(|v| v.parse().ok()).unwrap_or_else(|| {
                eprintln!("{name} needs a number");
                std::process::exit(2)
            })
        };
        match arg.as_str() {
            "--seed" => seed = number("--seed"),
            "--per-kind" => per_kind = number("--per-kind") as usize,
            "--threads" => threads = number("--threads").max(1) as usize,
            "--behind-toggle" => behind_toggle = true,
            "--in-dimension" => in_dimension = true,
            "--mesa" => mesa = true,
            "--kinds" => {
                let list = args.next().unwrap_or_default();
                kinds = list
                    .split(',')
                    .map(|name| {
                        KINDS.iter().copied().find(|k| format!("{k:?}") == name.trim()).unwrap_or_else(|| {
                            let names: Vec<String> = KINDS.iter().map(|k| format!("{k:?}")).collect();
                            eprintln!("unknown kind `{name}`: {}", names.join(", "));
                            std::process::exit(2)
                        })
                    })
                    .collect();
            }
            _ => dirs.push(PathBuf::from(arg)),
        }
    }
    if dirs.is_empty() {
        eprintln!("usage: plant [--seed N] [--per-kind N] [--threads N] [--behind-toggle] [--in-dimension] [--mesa] [--kinds K,...] PACK_DIR...");
        std::process::exit(2);
    }
    let scratch = tempfile::tempdir().expect("temporary folder");
    let options = if behind_toggle {
        Options {
            threads,
            profiles: Profiles::Covering(Coverage::Pairwise),
            cache: Some(scratch.path().join("findings")),
            ..Options::default()
        }
    } else {
        Options { threads, ..Options::default() }
    };
    let gl = mesa.then(|| {
        driver::Driver::new(&options.macros).unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(2)
        })
    });
    let mut plants: Vec<Plant> = Vec::new();
    let mut skipped: Vec<String> = Vec::new();
    for dir in &dirs {
        let pack = dir.file_name().map_or_else(|| dir.display().to_string(), |n| n.to_string_lossy().into_owned());
        let copy = scratch.path().join(&pack);
        if let Err(e) = copy_dir(&dir.join("shaders"), &copy.join("shaders")) {
            eprintln!("{pack}: cannot copy: {e}");
            skipped.push(format!("{pack}: cannot copy ({e})"));
            continue;
        }
        let placing = Placing { behind_toggle, in_dimension };
        match plant_pack(&pack, &copy, &options, seed, per_kind, placing, &kinds, gl.as_ref()) {
            Ok(mut found) => plants.append(&mut found),
            Err(why) => {
                eprintln!("{pack}: {why}");
                skipped.push(format!("{pack}: {why}"));
            }
        }
        std::fs::remove_dir_all(&copy).ok();
    }
    print!("{}", markdown(&plants, &skipped, seed, per_kind, threads, in_dimension));
}

fn copy_dir(from: &Path, to: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(to)?;
    for entry in std::fs::read_dir(from)? {
        let entry = entry?;
        let kind = entry.file_type()?;
        if kind.is_dir() {
            copy_dir(&entry.path(), &to.join(entry.file_name()))?;
        } else if kind.is_file() {
            std::fs::copy(entry.path(), to.join(entry.file_name()))?;
        }
    }
    Ok(())
}

/// The lines that put a planted line behind a switch of its own, off by default; the planted
/// line is the third.
fn behind_a_toggle(text: &str) -> String {
    format!("//#define PLANTED_TOGGLE // planted mistake, off by default\n#ifdef PLANTED_TOGGLE\n{text}\n#endif")
}

/// shaders.properties with `PLANTED_TOGGLE` on the main screen, where a player can reach it
/// (unchanged when there is no `screen` entry: every option is on the menu then).
fn toggle_on_the_menu(properties: &str) -> String {
    let mut lines: Vec<String> = properties.lines().map(str::to_string).collect();
    let Some(mut main) = lines.iter().position(|l| l.trim_start().strip_prefix("screen").is_some_and(|r| r.trim_start().starts_with('='))) else {
        return properties.to_string();
    };
    while lines[main].trim_end().ends_with('\\') && main + 1 < lines.len() {
        main += 1;
    }
    lines[main].push_str(" PLANTED_TOGGLE");
    lines.join("\n") + "\n"
}

#[allow(clippy::too_many_arguments)]
/// Where mistakes go besides their line.
#[derive(Clone, Copy)]
struct Placing {
    /// Inside `#ifdef PLANTED_TOGGLE`, an option off by default.
    behind_toggle: bool,
    /// Only into a dimension folder's own files (`world-1/…`), which only that dimension loads.
    in_dimension: bool,
}

fn plant_pack(
    pack: &str,
    root: &Path,
    options: &Options,
    seed: u64,
    per_kind: usize,
    placing: Placing,
    kinds: &[Kind],
    gl: Option<&driver::Driver>,
) -> Result<Vec<Plant>, String> {
    let Placing { behind_toggle, in_dimension } = placing;
    let properties = root.join("shaders/shaders.properties");
    if behind_toggle && let Ok(text) = std::fs::read_to_string(&properties) {
        std::fs::write(&properties, toggle_on_the_menu(&text)).map_err(|e| format!("shaders.properties: {e}"))?;
    }
    let started = Instant::now();
    let base = tidepack_validate::validate_path(root, options).map_err(|e| e.to_string())?;
    eprintln!("{pack}: unmodified in {:.1} s, {} errors", started.elapsed().as_secs_f64(), base.errors());
    let clean: HashSet<String> = base
        .programs
        .iter()
        .filter(|p| p.status == Status::Valid && !p.diagnostics.iter().any(|&i| base.diagnostics[i].is_error()))
        .map(|p| p.id.clone())
        .collect();
    let set = OptionSet::new();
    let provider = SetProvider::new(&base.pack, &set);
    let macros = options.macros.preprocess_options();
    let mut stages: Vec<StageInfo> = Vec::new();
    let mut anchors: Vec<Anchor> = Vec::new();
    let mut seen_lines: HashSet<(String, u32)> = HashSet::new();
    let mut global_anchors: Vec<Anchor> = Vec::new();
    let mut seen_global_lines: HashSet<(String, u32)> = HashSet::new();
    let mut seen_texts: HashSet<String> = HashSet::new();
    for program in programs::find_programs(base.pack.files.keys()) {
        if program.run_by != RunBy::OptiFine || !clean.contains(&program.id()) {
            continue;
        }
        for (_, path) in &program.stages {
            let Ok(pre) = preprocess::preprocess(&provider, path, &macros) else { continue };
            // World folders often repeat the root's stages word for word.
            if !seen_texts.insert(pre.text.clone()) {
                continue;
            }
            let index = stages.len();
            stages.push(scan(
                index,
                program.id(),
                path.clone(),
                pre,
                &base,
                &mut anchors,
                &mut seen_lines,
                &mut global_anchors,
                &mut seen_global_lines,
            ));
        }
    }
    if in_dimension {
        let own = |path: &str| path.starts_with("world");
        anchors.retain(|a| own(&a.path));
        global_anchors.retain(|a| own(&a.path));
    }
    if anchors.is_empty() {
        let where_ = if in_dimension { " in a dimension folder's own file" } else { "" };
        return Err(format!("no clean program with a statement to plant after{where_} ({} clean programs)", clean.len()));
    }
    eprintln!("{pack}: {} clean programs, {} stages, {} anchor lines", clean.len(), stages.len(), anchors.len());
    let mut plants = Vec::new();
    for &kind in kinds {
        // The toggle's own `#endif` would close a planted unterminated `#if`.
        if behind_toggle && kind == Kind::UnterminatedIf {
            continue;
        }
        for round in 0..per_kind {
            let mut rng = Rng::new(seed ^ fnv(pack) ^ ((kind as u64) << 32) ^ round as u64);
            let Some((path, line, text, program)) = choose(kind, &mut rng, &stages, &anchors, &global_anchors, &base, &provider, &macros) else {
                eprintln!("{pack}: no place for {}", kind.name());
                continue;
            };
            let file = root.join("shaders").join(&path);
            let original = std::fs::read(&file).map_err(|e| format!("{path}: {e}"))?;
            let inserted = if behind_toggle { behind_a_toggle(&text) } else { text.clone() };
            let modified = insert_line(&original, line, &inserted);
            std::fs::write(&file, &modified).map_err(|e| format!("{path}: {e}"))?;
            let started = Instant::now();
            let result = tidepack_validate::validate_path(root, options);
            let elapsed = started.elapsed();
            // Mesa's verdict on the planted program, with the toggle on when there is one.
            let mesa = match (gl, &result) {
                (Some(gl), Ok(report)) => {
                    let mut set = OptionSet::new();
                    if behind_toggle {
                        set.insert("PLANTED_TOGGLE".into(), OptionValue::Switch(true));
                    }
                    let provider = SetProvider::new(&report.pack, &set);
                    programs::find_programs(report.pack.files.keys())
                        .into_iter()
                        .find(|p| p.id() == program)
                        .map(|p| match gl.check(&p, &provider) {
                            Ok(Ok(())) => MesaVerdict::Accepts,
                            Ok(Err(d)) if d.is_empty() => MesaVerdict::NotGiven,
                            Err(_) => MesaVerdict::NotGiven,
                            Ok(Err(d)) => MesaVerdict::Refuses(d.into_iter().find(|d| d.is_error()).map(|d| d.to_string().replace('\n', " ")).unwrap_or_default()),
                        })
                        .unwrap_or(MesaVerdict::NotGiven)
                }
                _ => MesaVerdict::NotGiven,
            };
            std::fs::write(&file, &original).map_err(|e| format!("{path}: cannot restore: {e}"))?;
            let planted_line = if behind_toggle { line + 3 } else { line + 1 };
            let accepted = accepted_lines(kind, &String::from_utf8_lossy(&modified), planted_line);
            let inserted_lines = inserted.lines().count() as u32;
            let mut plant = judge(pack, kind, program, path.clone(), planted_line, (line, inserted_lines), text, &accepted, &base, result, elapsed);
            plant.mesa = mesa;
            eprintln!(
                "{pack}: {} at {}:{} -> {} ({:.1} s)",
                kind.name(),
                path,
                planted_line,
                match plant.outcome {
                    Outcome::AtLine => "at line",
                    Outcome::Elsewhere => "ELSEWHERE",
                    Outcome::Missed => "MISSED",
                },
                elapsed.as_secs_f64()
            );
            // A file OptiFine loads as a stage, or one only reached through `#include`.
            let stage_file = programs::find_programs(std::iter::once(&path)).iter().any(|p| p.run_by == RunBy::OptiFine);
            plants.push(Plant { included: !stage_file, ..plant });
        }
    }
    Ok(plants)
}

/// Walks a stage's preprocessed text (comments already dropped) with a stack of braces, and
/// records the pack's functions, uniforms, samplers and consts and the anchor lines.
fn scan(
    index: usize,
    program: String,
    path: String,
    pre: Preprocessed,
    base: &Report,
    anchors: &mut Vec<Anchor>,
    seen_lines: &mut HashSet<(String, u32)>,
    global_anchors: &mut Vec<Anchor>,
    seen_global_lines: &mut HashSet<(String, u32)>,
) -> StageInfo {
    let version = pre.version.as_ref().map_or(110, |v| v.number);
    let fragment = path.ends_with(".fsh");
    let mut info = StageInfo {
        program,
        path,
        pre,
        functions: Vec::new(),
        uniforms: Vec::new(),
        samplers: Vec::new(),
        consts: Vec::new(),
        version,
        fragment,
        inputs: Vec::new(),
        written_outputs: Vec::new(),
        builtin_outputs: false,
    };
    let text = info.pre.text.clone();
    info.builtin_outputs = text.contains("gl_FragData") || text.contains("gl_FragColor");
    let mut outputs: Vec<String> = Vec::new();
    let lines: Vec<&str> = text.split('\n').collect();
    let mut stack: Vec<Block> = Vec::new();
    let mut parens = 0i32;
    let mut offset = 0usize;
    let mut pending: Vec<Anchor> = Vec::new();
    for (out_line, line) in lines.iter().enumerate() {
        let trimmed = line.trim();
        if parens == 0 {
            if stack.is_empty() {
                global_declaration(trimmed, out_line, &mut info, &mut outputs);
            } else if let Some(decl) = local_declaration(trimmed) {
                stack.last_mut().unwrap().locals.push(decl);
            }
        }
        for (i, c) in line.char_indices() {
            match c {
                '(' => parens += 1,
                ')' => parens -= 1,
                '{' => {
                    let kind = block_kind(&text[..offset + i], stack.is_empty(), out_line, &mut info.functions);
                    stack.push(Block { kind, locals: Vec::new() });
                }
                '}' => {
                    stack.pop();
                }
                _ => {}
            }
        }
        offset += line.len() + 1;
        // A statement that ends at file scope: a function or a global can follow it.
        if stack.is_empty() && parens == 0 && trimmed.ends_with(';') && !trimmed.starts_with('#') {
            if let Some(loc) = info.pre.location(out_line as u32 + 1)
                && let Some(source) = base.pack.texts.get(&loc.path)
                && let Some(indent) = plantable(source, loc.line)
                && seen_global_lines.insert((loc.path.clone(), loc.line))
            {
                global_anchors.push(Anchor { stage: index, out_line, path: loc.path, line: loc.line, indent, function: 0, locals: Vec::new() });
            }
            continue;
        }
        let function = stack.iter().find_map(|b| if let BlockKind::Function(f) = b.kind { Some(f) } else { None });
        let code_only = !stack.is_empty() && stack.iter().all(|b| !matches!(b.kind, BlockKind::Other));
        // After a jump, a planted line would be unreachable code: not the mistake measured.
        let jump = ["return", "break", "continue", "discard"].iter().any(|w| starts_with_word(trimmed, w));
        if let (Some(function), true, 0, true, false) = (function, code_only, parens, trimmed.ends_with(';'), jump) {
            // A line before `else` would split the `if` from its `else`.
            let next = lines[out_line + 1..].iter().map(|l| l.trim()).find(|l| !l.is_empty()).unwrap_or("");
            if starts_with_word(next, "else") {
                continue;
            }
            let Some(loc) = info.pre.location(out_line as u32 + 1) else { continue };
            let Some(source) = base.pack.texts.get(&loc.path) else { continue };
            let Some(indent) = plantable(source, loc.line) else { continue };
            if seen_lines.insert((loc.path.clone(), loc.line)) {
                pending.push(Anchor {
                    stage: index,
                    out_line,
                    path: loc.path,
                    line: loc.line,
                    indent,
                    function,
                    locals: stack.last().map(|b| b.locals.clone()).unwrap_or_default(),
                });
            }
        }
    }
    anchors.append(&mut pending);
    info.written_outputs = outputs.into_iter().filter(|name| is_assigned(&text, name)).collect();
    info
}

/// Whether `text` assigns `name` (`name =`, `name.xy =`, `name[0] +=`), not only compares it.
fn is_assigned(text: &str, name: &str) -> bool {
    let bytes = text.as_bytes();
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut from = 0;
    while let Some(i) = text[from..].find(name).map(|i| i + from) {
        from = i + name.len();
        if i > 0 && (word(bytes[i - 1]) || bytes[i - 1] == b'.') || bytes.get(from).is_some_and(|&c| word(c)) {
            continue;
        }
        let rest = text[from..].trim_start();
        let rest = if rest.starts_with('[') { rest.find(']').map_or("", |e| rest[e + 1..].trim_start()) } else { rest };
        let rest = rest.strip_prefix('.').map_or(rest, |r| r.trim_start_matches(|c: char| c.is_alphanumeric() || c == '_').trim_start());
        let assigned = rest.starts_with('=') && !rest.starts_with("==")
            || ["+=", "-=", "*=", "/="].iter().any(|op| rest.starts_with(op));
        if assigned {
            return true;
        }
    }
    false
}

fn starts_with_word(text: &str, word: &str) -> bool {
    text.strip_prefix(word).is_some_and(|rest| !rest.starts_with(|c: char| c.is_alphanumeric() || c == '_'))
}

/// The source line itself must end the statement, outside any comment or continuation, so
/// that a new line after it is code in the same block. Returns its indentation.
fn plantable(source: &str, line: u32) -> Option<String> {
    let mut lines = source.lines();
    let previous = if line >= 2 { lines.by_ref().nth(line as usize - 2)? } else { "" };
    let this = lines.next()?;
    if previous.trim_end().ends_with('\\') || this.contains("/*") || this.contains("*/") {
        return None;
    }
    let code = this.split("//").next().unwrap_or("").trim_end();
    if !code.ends_with(';') || code.trim_start().starts_with('#') {
        return None;
    }
    Some(this.chars().take_while(|c| c.is_whitespace()).collect())
}

fn identifier_before(text: &str) -> (&str, &str) {
    let text = text.trim_end();
    let start = text.rfind(|c: char| !(c.is_alphanumeric() || c == '_')).map_or(0, |i| i + 1);
    (&text[..start], &text[start..])
}

/// What a `{` opens, from the text before it.
fn block_kind(before: &str, top_level: bool, out_line: usize, functions: &mut Vec<FnDef>) -> BlockKind {
    let before = before.trim_end();
    if let Some(head) = before.strip_suffix(')') {
        let mut depth = 1;
        let mut open = None;
        for (i, c) in head.char_indices().rev() {
            match c {
                ')' => depth += 1,
                '(' => {
                    depth -= 1;
                    if depth == 0 {
                        open = Some(i);
                        break;
                    }
                }
                _ => {}
            }
        }
        let Some(open) = open else { return BlockKind::Other };
        let params = head[open + 1..].trim();
        let (rest, name) = identifier_before(&head[..open]);
        if top_level {
            let (_, ret) = identifier_before(rest);
            if name.is_empty() || ret.is_empty() {
                return BlockKind::Other;
            }
            let count = if params.is_empty() || params == "void" { 0 } else { top_level_commas(params) + 1 };
            functions.push(FnDef { out_line, name: name.to_string(), ret: ret.to_string(), params: count });
            return BlockKind::Function(functions.len() - 1);
        }
        return match name {
            "if" | "for" | "while" => BlockKind::Control,
            _ => BlockKind::Other,
        };
    }
    if top_level {
        return BlockKind::Other;
    }
    let (_, word) = identifier_before(before);
    if word == "else" || word == "do" || before.ends_with(['{', '}', ';']) {
        BlockKind::Control
    } else {
        BlockKind::Other
    }
}

fn top_level_commas(text: &str) -> usize {
    let mut depth = 0;
    let mut count = 0;
    for c in text.chars() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' if depth == 0 => count += 1,
            _ => {}
        }
    }
    count
}

/// `TYPE NAME` followed by `=`, `;` or `,`.
fn type_and_name(text: &str) -> Option<(String, String, &str)> {
    let mut words = text.splitn(2, char::is_whitespace);
    let ty = words.next()?;
    let rest = words.next()?.trim_start();
    let end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
    let (name, after) = rest.split_at(end);
    if name.is_empty() || name.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    Some((ty.to_string(), name.to_string(), after.trim_start()))
}

fn local_declaration(line: &str) -> Option<(String, String)> {
    let line = line.strip_prefix("const ").unwrap_or(line);
    let (ty, name, after) = type_and_name(line)?;
    (VALUE_TYPES.contains(&ty.as_str()) && after.starts_with(['=', ';', ','])).then_some((ty, name))
}

fn global_declaration(line: &str, out_line: usize, info: &mut StageInfo, outputs: &mut Vec<String>) {
    let strip_precision = |t: &str| {
        let mut t = t.trim_start();
        for p in ["lowp ", "mediump ", "highp "] {
            t = t.strip_prefix(p).unwrap_or(t).trim_start();
        }
        t.to_string()
    };
    // Interpolation and layout qualifiers before `in`/`out`/`varying`.
    let mut qualified = line.trim_start();
    if let Some(rest) = qualified.strip_prefix("layout")
        && let Some(close) = rest.find(')')
    {
        qualified = rest[close + 1..].trim_start();
    }
    for q in ["flat ", "smooth ", "noperspective ", "centroid "] {
        qualified = qualified.strip_prefix(q).unwrap_or(qualified).trim_start();
    }
    if info.fragment
        && let Some(rest) = qualified.strip_prefix("in ").or_else(|| qualified.strip_prefix("varying "))
        && let Some((ty, name, ";")) = type_and_name(&strip_precision(rest))
        && VALUE_TYPES.contains(&ty.as_str())
    {
        info.inputs.push(Global { out_line, ty, name });
        return;
    }
    if info.fragment
        && let Some(rest) = qualified.strip_prefix("out ")
        && let Some((_, name, after)) = type_and_name(&strip_precision(rest))
        && after.starts_with([';', '['])
    {
        outputs.push(name);
        return;
    }
    if let Some(rest) = line.strip_prefix("uniform ") {
        // One name, no array: `NAME = NAME;` and `NAME + 1.0` then mean what they say.
        let decl = strip_precision(rest);
        if let Some((ty, name, ";")) = type_and_name(&decl) {
            let global = Global { out_line, ty: ty.clone(), name };
            if VALUE_TYPES.contains(&ty.as_str()) {
                info.uniforms.push(global);
            } else if ty.starts_with("sampler") {
                info.samplers.push(global);
            }
        }
    } else if let Some(rest) = line.strip_prefix("const ")
        && let Some((ty, name, after)) = type_and_name(&strip_precision(rest))
        && VALUE_TYPES.contains(&ty.as_str())
        && after.starts_with('=')
    {
        info.consts.push(Global { out_line, ty, name });
    }
}

/// Overrides one file of the pack, to test whether a line of it is active.
struct Override<'a> {
    inner: &'a SetProvider<'a>,
    path: &'a str,
    text: Arc<str>,
}

impl FileProvider for Override<'_> {
    fn read(&self, path: &str) -> Result<Arc<str>, String> {
        if path == self.path { Ok(self.text.clone()) } else { self.inner.read(path) }
    }
}

type Choice = (String, u32, String, String);

/// Picks where to plant a mistake of `kind` and what to write: (file, line to insert after,
/// the new line, the program whose stage it was found in).
fn choose(
    kind: Kind,
    rng: &mut Rng,
    stages: &[StageInfo],
    anchors: &[Anchor],
    global_anchors: &[Anchor],
    base: &Report,
    provider: &SetProvider<'_>,
    macros: &preprocess::PreprocessOptions,
) -> Option<Choice> {
    let pick_global = |rng: &mut Rng, fits: &dyn Fn(&Anchor) -> bool| -> Option<&Anchor> {
        let mut by_file: BTreeMap<&str, Vec<&Anchor>> = BTreeMap::new();
        for a in global_anchors.iter().filter(|a| fits(a)) {
            by_file.entry(&a.path).or_default().push(a);
        }
        let file = by_file.values().nth(rng.below(by_file.len().max(1)))?;
        Some(file[rng.below(file.len())])
    };
    // A file first, then a line of it: long files would take nearly every plant otherwise.
    let pick = |rng: &mut Rng, fits: &dyn Fn(&Anchor) -> bool| -> Option<&Anchor> {
        let mut by_file: BTreeMap<&str, Vec<&Anchor>> = BTreeMap::new();
        for a in anchors.iter().filter(|a| fits(a)) {
            by_file.entry(&a.path).or_default().push(a);
        }
        let file = by_file.values().nth(rng.below(by_file.len().max(1)))?;
        Some(file[rng.below(file.len())])
    };
    let before = |globals: &[Global], a: &Anchor| -> Vec<(String, String)> {
        globals.iter().filter(|g| g.out_line < a.out_line).map(|g| (g.ty.clone(), g.name.clone())).collect()
    };
    let done = |a: &Anchor, text: String| Some((a.path.clone(), a.line, format!("{}{text}", a.indent), stages[a.stage].program.clone()));
    let simple = |rng: &mut Rng, text: &str| -> Option<Choice> {
        let a = pick(rng, &|_| true)?;
        done(a, text.to_string())
    };
    match kind {
        Kind::UndeclaredVariable => simple(rng, "float undeclared_tp = undeclaredName_tp;"),
        Kind::TypeMismatch => simple(rng, "vec3 mismatch_tp = vec2(0.0);"),
        Kind::MissingSemicolon => simple(rng, "float semicolon_tp = 1.0"),
        Kind::UnknownFunction => simple(rng, "float unknown_tp = unknownFunction_tp(1.0);"),
        Kind::BadSwizzle => simple(rng, "vec4 swizzle_tp = vec4(0.0); vec4 swizzle2_tp = swizzle_tp.xyzq;"),
        Kind::IntFromFloat => simple(rng, "int int_tp = 1.5;"),
        Kind::MissingInclude => simple(rng, "#include \"/missing_tp.glsl\""),
        Kind::ErrorDirective => simple(rng, "#error planted by tidepack plant"),
        Kind::ReturnValueInVoid => {
            let a = pick(rng, &|a| stages[a.stage].functions[a.function].ret == "void")?;
            done(a, "return 1.0;".into())
        }
        Kind::RedeclaredLocal => {
            let a = pick(rng, &|a| !a.locals.is_empty())?;
            let (ty, name) = &a.locals[rng.below(a.locals.len())];
            done(a, format!("{ty} {name} = {ty}(0);"))
        }
        Kind::WrongArgumentCount => {
            let callable = |a: &Anchor| -> Vec<(String, usize)> {
                let stage = &stages[a.stage];
                let current = &stage.functions[a.function].name;
                stage
                    .functions
                    .iter()
                    .filter(|f| f.out_line < a.out_line && &f.name != current && f.name != "main")
                    // Another overload taking one more argument would make the call right.
                    .filter(|f| !stage.functions.iter().any(|g| g.name == f.name && g.params == f.params + 1))
                    .map(|f| (f.name.clone(), f.params))
                    .collect()
            };
            let a = pick(rng, &|a| !callable(a).is_empty())?;
            let options = callable(a);
            let (name, params) = &options[rng.below(options.len())];
            let args = vec!["1.0"; params + 1].join(", ");
            done(a, format!("{name}({args});"))
        }
        Kind::AssignUniform => {
            let a = pick(rng, &|a| !before(&stages[a.stage].uniforms, a).is_empty())?;
            let options = before(&stages[a.stage].uniforms, a);
            let (_, name) = &options[rng.below(options.len())];
            done(a, format!("{name} = {name};"))
        }
        Kind::AssignConst => match pick(rng, &|a| !before(&stages[a.stage].consts, a).is_empty()) {
            Some(a) => {
                let options = before(&stages[a.stage].consts, a);
                let (_, name) = &options[rng.below(options.len())];
                done(a, format!("{name} = {name};"))
            }
            None => simple(rng, "const float const_tp = 1.0; const_tp = 2.0;"),
        },
        Kind::SamplerAsFloat => {
            let a = pick(rng, &|a| !before(&stages[a.stage].samplers, a).is_empty())?;
            let options = before(&stages[a.stage].samplers, a);
            let (_, name) = &options[rng.below(options.len())];
            done(a, format!("float sampler_tp = {name} + 1.0;"))
        }
        Kind::ReservedOutput => simple(rng, "float output = 1.0;"),
        // `sample` is a qualifier from GLSL 4.00 on; before, an identifier like any other.
        Kind::ReservedSample => {
            let a = pick(rng, &|a| stages[a.stage].version >= 400)?;
            done(a, "float sample = 1.0;".into())
        }
        // Before GLSL 4.20 a `const` takes only a constant expression.
        Kind::ConstFromUniform => {
            let fits = |a: &Anchor| stages[a.stage].version < 420 && !before(&stages[a.stage].uniforms, a).is_empty();
            let a = pick(rng, &fits)?;
            let options = before(&stages[a.stage].uniforms, a);
            let (ty, name) = &options[rng.below(options.len())];
            done(a, format!("const {ty} const_uniform_tp = {name};"))
        }
        // `uint` exists from 1.30; an int converts to it implicitly from 4.00.
        Kind::IntToUint => {
            let a = pick(rng, &|a| (130..400).contains(&stages[a.stage].version))?;
            done(a, "uint uint_tp = 1;".into())
        }
        Kind::WriteToInput => {
            let inputs = |a: &Anchor| -> Vec<(String, String)> {
                let stage = &stages[a.stage];
                // In `main`, which has no parameters to hide the input, and not hidden by a local.
                if !stage.fragment || stage.functions[a.function].name != "main" {
                    return Vec::new();
                }
                before(&stage.inputs, a).into_iter().filter(|(_, n)| !a.locals.iter().any(|(_, l)| l == n)).collect()
            };
            let a = pick(rng, &|a| !inputs(a).is_empty())?;
            let options = inputs(a);
            let (_, name) = &options[rng.below(options.len())];
            done(a, format!("{name} = {name};"))
        }
        Kind::MissingReturn => {
            let a = pick_global(rng, &|_| true)?;
            done(a, "float missing_return_tp(float x) { x += 1.0; }".into())
        }
        // A fragment stage that writes its own `out`s (GLSL 1.30 and later) and names neither
        // built-in output.
        Kind::FragDataBesideOut => {
            let fits = |a: &Anchor| {
                let stage = &stages[a.stage];
                stage.fragment && stage.version >= 130 && !stage.written_outputs.is_empty() && !stage.builtin_outputs
            };
            let a = pick(rng, &fits)?;
            done(a, "gl_FragData[0] = vec4(0.0);".into())
        }
        Kind::Texture2DOnShadow => {
            let shadows = |a: &Anchor| -> Vec<(String, String)> {
                before(&stages[a.stage].samplers, a).into_iter().filter(|(ty, _)| ty == "sampler2DShadow").collect()
            };
            match pick(rng, &|a| !shadows(a).is_empty()) {
                Some(a) => {
                    let options = shadows(a);
                    let (_, name) = &options[rng.below(options.len())];
                    done(a, format!("float shadow_tp = texture2D({name}, vec2(0.0)).r;"))
                }
                // No shadow sampler in any clean stage: one declared with the function that misuses it.
                None => {
                    let a = pick_global(rng, &|a| stages[a.stage].version < 420 || stages[a.stage].pre.version.as_ref().is_some_and(|v| v.profile.as_deref() == Some("compatibility")))?;
                    done(a, "uniform sampler2DShadow shadowtex0_tp; float shadow_read_tp() { return texture2D(shadowtex0_tp, vec2(0.0)).r; }".into())
                }
            }
        }
        Kind::UninitialisedRead => simple(rng, "float uninit_tp; float uninit_use_tp = uninit_tp * 2.0;"),
        Kind::UnterminatedIf => {
            let stage = &stages[rng.below(stages.len())];
            let text = base.pack.texts.get(&stage.path)?;
            // Inserted after the last line: nothing follows that could close it.
            Some((stage.path.clone(), text.lines().count() as u32, "#ifdef TP_UNTERMINATED".into(), stage.program.clone()))
        }
        Kind::MacroRedefined => {
            // Anchors in random order; the first with an active object-like macro defined once
            // before it. `(body)` differs as a token list but means the same, so nothing else
            // in the stage changes.
            let mut order: Vec<usize> = (0..anchors.len()).collect();
            for i in (1..order.len()).rev() {
                order.swap(i, rng.below(i + 1));
            }
            for &i in order.iter().take(50) {
                let a = &anchors[i];
                if let Some((name, body)) = macro_before(&stages[a.stage], a.out_line, rng, provider, macros) {
                    return done(a, format!("#define {name} ({body})"));
                }
            }
            None
        }
    }
}

/// An object-like macro with one `#define` (no `#undef`) in the stage's files, on a line that
/// is active and comes before `out_line`.
fn macro_before(
    stage: &StageInfo,
    out_line: usize,
    rng: &mut Rng,
    provider: &SetProvider<'_>,
    macros: &preprocess::PreprocessOptions,
) -> Option<(String, String)> {
    let mut defines: BTreeMap<String, Vec<(usize, u32, String)>> = BTreeMap::new();
    let mut undefined: HashSet<String> = HashSet::new();
    let mut texts = Vec::new();
    for (file, path) in stage.pre.files.iter().enumerate() {
        let text = provider.read(path).ok()?;
        for (n, line) in text.lines().enumerate() {
            let directive = line.trim_start().strip_prefix('#').map(str::trim_start);
            if let Some(rest) = directive.and_then(|d| d.strip_prefix("undef")) {
                undefined.insert(rest.trim().to_string());
            }
            let Some(rest) = directive.and_then(|d| d.strip_prefix("define ")) else { continue };
            let rest = rest.trim_start();
            let end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
            let (name, after) = rest.split_at(end);
            let body = after.split("//").next().unwrap_or("").trim();
            if after.starts_with('(') || !after.starts_with([' ', '\t']) && !after.is_empty() {
                defines.entry(name.to_string()).or_default().push((file, 0, String::new()));
                continue;
            }
            defines.entry(name.to_string()).or_default().push((file, n as u32 + 1, body.to_string()));
        }
        texts.push(text);
    }
    let position: HashMap<(u32, u32), usize> =
        stage.pre.lines.iter().enumerate().rev().map(|(i, l)| ((l.file, l.line), i)).collect();
    let mut fitting: Vec<(String, usize, u32, String)> = defines
        .into_iter()
        .filter(|(name, defs)| defs.len() == 1 && !undefined.contains(name) && !name.starts_with("MC_"))
        .filter_map(|(name, defs)| {
            let (file, line, body) = defs.into_iter().next()?;
            let ok = line > 0
                && !body.is_empty()
                && !body.ends_with('\\')
                && !body.contains("/*")
                && position.get(&(file as u32, line)).is_some_and(|&p| p < out_line);
            ok.then_some((name, file, line, body))
        })
        .collect();
    // A few probes per anchor: each preprocesses the whole stage.
    for _ in 0..5 {
        if fitting.is_empty() {
            break;
        }
        let (name, file, line, body) = fitting.swap_remove(rng.below(fitting.len()));
        // The line is active when a marker put in its place reaches the output: only what
        // comes before a line decides that.
        let path = &stage.pre.files[file];
        let marked: String = texts[file]
            .lines()
            .enumerate()
            .map(|(n, l)| if n as u32 + 1 == line { "tp_active_marker_tp;\n".to_string() } else { format!("{l}\n") })
            .collect();
        let probe = Override { inner: provider, path, text: Arc::from(marked) };
        if preprocess::preprocess(&probe, &stage.path, macros).is_ok_and(|p| p.text.contains("tp_active_marker_tp")) {
            return Some((name, body));
        }
    }
    None
}

/// Inserts `text` as a new line after line `after` (1-based), keeping the file's line ending.
fn insert_line(original: &[u8], after: u32, text: &str) -> Vec<u8> {
    let crlf = original.windows(2).any(|w| w == b"\r\n");
    let ending: &[u8] = if crlf { b"\r\n" } else { b"\n" };
    let mut out = Vec::with_capacity(original.len() + text.len() + 2);
    let mut line = 1;
    let mut inserted = false;
    for (i, &b) in original.iter().enumerate() {
        out.push(b);
        if b == b'\n' {
            if line == after {
                out.extend_from_slice(text.as_bytes());
                out.extend_from_slice(ending);
                out.extend_from_slice(&original[i + 1..]);
                inserted = true;
                break;
            }
            line += 1;
        }
    }
    if !inserted {
        if !out.is_empty() && !out.ends_with(b"\n") {
            out.extend_from_slice(ending);
        }
        out.extend_from_slice(text.as_bytes());
        out.extend_from_slice(ending);
    }
    out
}

/// Lines an error may be reported at: the planted line; for a missing semicolon also the
/// next line with code, where the parser meets the token that should have followed it.
fn accepted_lines(kind: Kind, modified: &str, planted: u32) -> Vec<u32> {
    let mut lines = vec![planted];
    if kind == Kind::MissingSemicolon {
        let next = modified
            .lines()
            .enumerate()
            .skip(planted as usize)
            .find(|(_, l)| {
                let code = l.split("//").next().unwrap_or("").trim();
                !code.is_empty()
            })
            .map(|(n, _)| n as u32 + 1);
        lines.extend(next);
    }
    lines
}

/// naga's own vocabulary, which a pack author cannot act on.
fn has_internals(text: &str) -> bool {
    let bracketed_number = text.char_indices().any(|(i, c)| {
        c == '['
            && !text[..i].ends_with(|p: char| p.is_alphanumeric() || p == '_')
            && text[i + 1..].find(']').is_some_and(|e| e > 0 && text[i + 1..i + 1 + e].chars().all(|d| d.is_ascii_digit()))
    });
    // The lowering's own names start with `tp_` (the planted ones end with `_tp`).
    let lowering_name = text.match_indices("tp_").any(|(i, _)| !text[..i].ends_with(|p: char| p.is_alphanumeric() || p == '_'));
    bracketed_number
        || lowering_name
        || ["Handle", "TypeName(", "Expression", "naga::", "Some(", "HirExpr"].iter().any(|w| text.contains(w))
}

#[allow(clippy::too_many_arguments)]
fn judge(
    pack: &str,
    kind: Kind,
    program: String,
    path: String,
    line: u32,
    // The line the planted lines went after, and how many went in.
    (after, inserted): (u32, u32),
    text: String,
    accepted: &[u32],
    base: &Report,
    result: Result<Report, Diagnostic>,
    elapsed: Duration,
) -> Plant {
    let mut plant = Plant {
        pack: pack.to_string(),
        kind,
        program,
        path: path.clone(),
        line,
        text: text.trim().to_string(),
        included: false,
        outcome: Outcome::Missed,
        hit_line: None,
        internals: false,
        reported: Vec::new(),
        drivers: Vec::new(),
        mesa: MesaVerdict::NotGiven,
        elapsed,
    };
    let report = match result {
        Ok(r) => r,
        Err(e) => {
            plant.outcome = Outcome::Elsewhere;
            plant.internals = has_internals(&e.to_string());
            plant.reported.push(format!("pack not read: {e}"));
            return plant;
        }
    };
    // The unmodified pack's errors, with lines after the planted ones moved down.
    let known: HashSet<(String, Option<(String, u32)>)> = base
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| {
            let loc = d.location.as_ref().map(|l| (l.path.clone(), if l.path == path && l.line > after { l.line + inserted } else { l.line }));
            (d.message.clone(), loc)
        })
        .collect();
    // A warning kind is found by its warning; it is not an error anywhere.
    let counts = |d: &&Diagnostic| if kind.is_warning() { d.code == tidepack_glsl::Code::UninitialisedRead } else { d.is_error() };
    let new: Vec<&Diagnostic> = report
        .diagnostics
        .iter()
        .filter(counts)
        .filter(|d| !known.contains(&(d.message.clone(), d.location.as_ref().map(|l| (l.path.clone(), l.line)))))
        .collect();
    let at = |d: &&Diagnostic| d.location.as_ref().is_some_and(|l| l.path == path && accepted.contains(&l.line));
    let hits: Vec<&Diagnostic> = new.iter().copied().filter(at).collect();
    let spoken = |d: &Diagnostic| format!("{} {}", d.message, d.notes.join(" "));
    if let Some(first) = hits.first() {
        plant.outcome = Outcome::AtLine;
        plant.hit_line = first.location.as_ref().map(|l| l.line);
        plant.internals = hits.iter().any(|d| has_internals(&spoken(d)));
        plant.drivers = first.refused_by.names();
    } else if !new.is_empty() {
        plant.outcome = Outcome::Elsewhere;
        plant.internals = new.iter().any(|d| has_internals(&spoken(d)));
    }
    let warnings_here = report.diagnostics.iter().filter(|d| !d.is_error() && !new.contains(d)).filter(at);
    plant.reported = new.iter().copied().chain(warnings_here).take(6).map(|d| d.to_string().replace('\n', " ")).collect();
    if plant.outcome == Outcome::Missed {
        // A miss is often explained by what the program was warned about (a stage naga never
        // checked, for instance).
        let warned = report.programs.iter().filter(|p| p.id == plant.program).flat_map(|p| &p.diagnostics);
        let warnings: Vec<String> =
            warned.map(|&i| &report.diagnostics[i]).filter(|d| !d.is_error()).take(3).map(|d| format!("program warning: {d}").replace('\n', " ")).collect();
        plant.reported.extend(warnings);
    }
    plant
}

#[derive(Default)]
struct Tally {
    planted: usize,
    at_line: usize,
    elsewhere: usize,
    missed: usize,
    internals: usize,
    /// At the line with the refusing drivers named (errors; a warning names none).
    drivers_named: usize,
    mesa_refuses: usize,
    mesa_accepts: usize,
}

impl Tally {
    fn add(&mut self, p: &Plant) {
        self.planted += 1;
        match p.outcome {
            Outcome::AtLine => self.at_line += 1,
            Outcome::Elsewhere => self.elsewhere += 1,
            Outcome::Missed => self.missed += 1,
        }
        self.internals += usize::from(p.internals);
        self.drivers_named += usize::from(p.outcome == Outcome::AtLine && !p.drivers.is_empty());
        match p.mesa {
            MesaVerdict::Refuses(_) => self.mesa_refuses += 1,
            MesaVerdict::Accepts => self.mesa_accepts += 1,
            MesaVerdict::NotGiven => {}
        }
    }
    fn row(&self, label: &str) -> String {
        format!(
            "| {label} | {} | {} | {} | {} | {} | {} | {} / {} |\n",
            self.planted, self.at_line, self.elsewhere, self.missed, self.internals, self.drivers_named, self.mesa_refuses, self.mesa_accepts
        )
    }
}

fn markdown(plants: &[Plant], skipped: &[String], seed: u64, per_kind: usize, threads: usize, in_dimension: bool) -> String {
    let mut out = String::new();
    let packs: BTreeSet<&str> = plants.iter().map(|p| p.pack.as_str()).collect();
    let seconds: f64 = plants.iter().map(|p| p.elapsed.as_secs_f64()).sum();
    writeln!(
        out,
        "# Planted mistakes\n\n{} plants in {} packs (seed {seed}, {per_kind} per kind and pack, {threads} threads, \
         {seconds:.0} s validating). A plant counts as reported when a new error is at the planted file and line \
         (missing semicolon: or the next line with code).{}\n",
        plants.len(),
        packs.len(),
        if in_dimension { " Every plant is in a dimension folder's own file, which only that dimension loads." } else { "" }
    )
    .unwrap();
    let header = |first: &str| {
        format!(
            "| {first} | planted | at file+line | elsewhere | missed | messages with naga internals | at line, drivers named | Mesa refuses / accepts |\n\
             |---|---:|---:|---:|---:|---:|---:|---:|\n"
        )
    };
    let mut total = Tally::default();
    let mut by_kind: BTreeMap<Kind, Tally> = BTreeMap::new();
    let mut by_pack: BTreeMap<&str, Tally> = BTreeMap::new();
    for p in plants {
        total.add(p);
        by_kind.entry(p.kind).or_default().add(p);
        by_pack.entry(&p.pack).or_default().add(p);
    }
    out.push_str("## By kind\n\n");
    out.push_str(&header("kind"));
    for (kind, tally) in &by_kind {
        out.push_str(&tally.row(kind.name()));
    }
    out.push_str(&total.row("**total**"));
    out.push_str("\n## By pack\n\n");
    out.push_str(&header("pack"));
    for (pack, tally) in &by_pack {
        out.push_str(&tally.row(pack));
    }
    out.push_str(&total.row("**total**"));
    let semicolons: Vec<&Plant> = plants.iter().filter(|p| p.kind == Kind::MissingSemicolon && p.outcome == Outcome::AtLine).collect();
    if !semicolons.is_empty() {
        let same = semicolons.iter().filter(|p| p.hit_line == Some(p.line)).count();
        writeln!(out, "\nMissing semicolon: {same} reported at the planted line, {} at the next line with code.", semicolons.len() - same)
            .unwrap();
    }
    let included = plants.iter().filter(|p| p.included).count();
    writeln!(out, "\nPlanted in an included file: {included}; in a stage file: {}.", plants.len() - included).unwrap();
    if !skipped.is_empty() {
        writeln!(out, "\nPacks left out: {}", skipped.join("; ")).unwrap();
    }
    out.push_str("\n## Failures\n\n");
    let failures: Vec<&Plant> = plants.iter().filter(|p| p.outcome != Outcome::AtLine).collect();
    if failures.is_empty() {
        out.push_str("None.\n");
    }
    for p in failures {
        describe(&mut out, p);
    }
    out.push_str("\n## Reported at the line, with naga internals\n\n");
    let internal: Vec<&Plant> = plants.iter().filter(|p| p.outcome == Outcome::AtLine && p.internals).collect();
    if internal.is_empty() {
        out.push_str("None.\n");
    }
    for p in internal {
        describe(&mut out, p);
    }
    out.push_str("\n## Every plant\n\n| pack | kind | file:line | planted | outcome | refused by | Mesa | first message |\n|---|---|---|---|---|---|---|---|\n");
    for p in plants {
        let outcome = match p.outcome {
            Outcome::AtLine if p.hit_line != Some(p.line) => "at next line",
            Outcome::AtLine => "at line",
            Outcome::Elsewhere => "elsewhere",
            Outcome::Missed => "missed",
        };
        let first = p.reported.first().map_or("", String::as_str);
        let mesa = match &p.mesa {
            MesaVerdict::NotGiven => "-".to_string(),
            MesaVerdict::Accepts => "accepts".to_string(),
            MesaVerdict::Refuses(first) => format!("refuses: {}", cell(first)),
        };
        writeln!(
            out,
            "| {} | {} | {}:{} | `{}` | {outcome} | {} | {mesa} | {} |",
            p.pack,
            p.kind.name(),
            p.path,
            p.line,
            p.text,
            p.drivers.join(", "),
            cell(first)
        )
        .unwrap();
    }
    out
}

fn cell(text: &str) -> String {
    let text = text.replace('|', "\\|");
    if text.chars().count() > 160 { format!("{}…", text.chars().take(160).collect::<String>()) } else { text }
}

fn describe(out: &mut String, p: &Plant) {
    let outcome = match p.outcome {
        Outcome::AtLine => "reported at the line",
        Outcome::Elsewhere => "reported elsewhere",
        Outcome::Missed => "missed",
    };
    writeln!(
        out,
        "- **{}** / {}: {outcome}; `{}` at {}:{} ({}, program {})",
        p.pack,
        p.kind.name(),
        p.text,
        p.path,
        p.line,
        if p.included { "included file" } else { "stage file" },
        p.program
    )
    .unwrap();
    if p.reported.is_empty() {
        out.push_str("  - nothing new reported\n");
    }
    for r in &p.reported {
        writeln!(out, "  - {}", r.replace('`', "'")).unwrap();
    }
}
