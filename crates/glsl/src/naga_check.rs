//! A whole program through the toolchain: preprocess each stage, lower it, parse and validate
//! the lowered text with naga, and report every error at the pack file and line it came from.

use crate::Code;
use std::error::Error as _;
use std::fmt::Write as _;
use std::sync::Arc;

pub use naga::front::glsl::Frontend;
use naga::front::glsl::{ErrorKind, ExpectedToken, Options, TokenValue};
use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

use crate::diagnostic::{Diagnostic, Drivers, Location};
use crate::known_valid::{self, KnownValid};
use crate::lower::{self, Lowered, Stage, VaryingLayout};
use crate::preprocess::{FileProvider, Preprocessed, literal_integer_expression};
use crate::token::{TokenKind, blanked, brace_depths, function_definitions, matching_close, significant, tokenize};

/// One stage after lowering, ready for naga.
#[derive(Clone, Debug)]
pub struct LoweredStage {
    pub stage: Stage,
    pub preprocessed: Arc<Preprocessed>,
    pub lowered: Lowered,
}

/// A compute stage (`.csh`) after lowering, ready for naga.
#[derive(Clone, Debug)]
pub struct LoweredCompute {
    pub preprocessed: Arc<Preprocessed>,
    pub lowered: Lowered,
}

/// Lowers a preprocessed compute stage.
pub fn lower_compute(pre: Arc<Preprocessed>) -> Result<LoweredCompute, Diagnostic> {
    let lowered = lower::lower_compute(&pre.text).map_err(|e| Diagnostic::error(Code::Glsl, e.message, pre.location(e.line)))?;
    Ok(LoweredCompute { preprocessed: pre, lowered })
}

/// A stage naga accepted.
#[derive(Debug)]
pub struct ValidStage {
    pub module: naga::Module,
    pub info: ModuleInfo,
    /// What a lenient stage ([`Preprocessed::lenient`]) had repaired as NVIDIA takes it where
    /// GLSL does not.
    pub lenient_repairs: Vec<LenientRepair>,
}

/// A repair of what NVIDIA takes and GLSL refuses, made in the text naga read at `location` (the
/// pack's file and line).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LenientRepair {
    pub location: Option<Location>,
    pub leniency: Leniency,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Leniency {
    /// `value` became `constructor(value)`: a value NVIDIA converts implicitly.
    /// `beside`: an operator next to the value, which tells it from the same text elsewhere
    /// on its line (`count != 0` among other `0`s).
    Converted { constructor: String, value: String, beside: Option<String> },
    /// A lookup with an offset that is not a constant (`textureOffset(s, uv, o)`), which NVIDIA
    /// takes, became the plain lookup at the coordinate moved by the offset, in texels of a
    /// `dimensions`-dimensional texture, in a vertex stage or not
    /// ([`crate::compat::offset_as_coordinate`]).
    OffsetAsCoordinate { dimensions: u8, vertex: bool },
    /// `written` became `with`: an operation NVIDIA applies component by component that GLSL
    /// defines for scalars alone (`bvec2 || bvec2`).
    Replaced { written: String, with: String },
}

/// Lowers the stages of one program with a shared varying layout.
pub fn lower_program(stages: &[(Stage, Arc<Preprocessed>)]) -> Result<Vec<LoweredStage>, Diagnostic> {
    let version_of = |pre: &Preprocessed| pre.version.as_ref().map_or(110, |v| v.number);
    let texts: Vec<(Stage, &str, u32)> =
        stages.iter().map(|(stage, pre)| (*stage, pre.text.as_str(), version_of(pre))).collect();
    let layout = VaryingLayout::for_program(&texts).map_err(|e| {
        let pre = &stages.iter().find(|(_, p)| p.location(e.line).is_some()).expect("a stage").1;
        Diagnostic::error(Code::Glsl, e.message, pre.location(e.line))
    })?;
    stages
        .iter()
        .map(|(stage, pre)| {
            let lowered = lower::lower(&pre.text, *stage, &layout, pre.lenient)
                .map_err(|e| Diagnostic::error(Code::Glsl, e.message, pre.location(e.line)))?;
            Ok(LoweredStage { stage: *stage, preprocessed: pre.clone(), lowered })
        })
        .collect()
}

/// Parses and validates a lowered stage; errors point into the pack's files.
pub fn validate_stage(
    frontend: &mut Frontend,
    stage: &LoweredStage,
    provider: &dyn FileProvider,
) -> Result<ValidStage, Vec<Diagnostic>> {
    validate_text(frontend, naga_stage_of(stage.stage), &stage.preprocessed, &stage.lowered, provider, None).map(|valid| valid.expect("naga ran"))
}

/// [`validate_stage`] for a run that validates many stages with functions in common: naga reads
/// the prototype of each function `known` holds valid in the same surroundings, a text it
/// accepted before is not read again, and `known` learns what naga accepts. The verdict and the
/// diagnostics are those of [`validate_stage`].
pub fn validate_stage_reusing(
    frontend: &mut Frontend,
    stage: &LoweredStage,
    provider: &dyn FileProvider,
    known: &KnownValid,
) -> Result<(), Vec<Diagnostic>> {
    validate_text(frontend, naga_stage_of(stage.stage), &stage.preprocessed, &stage.lowered, provider, Some(known)).map(drop)
}

fn naga_stage_of(stage: Stage) -> naga::ShaderStage {
    match stage {
        Stage::Vertex => naga::ShaderStage::Vertex,
        Stage::Fragment => naga::ShaderStage::Fragment,
    }
}

/// Parses and validates a lowered compute stage; errors point into the pack's files.
pub fn validate_compute(
    frontend: &mut Frontend,
    stage: &LoweredCompute,
    provider: &dyn FileProvider,
) -> Result<ValidStage, Vec<Diagnostic>> {
    validate_text(frontend, naga::ShaderStage::Compute, &stage.preprocessed, &stage.lowered, provider, None).map(|valid| valid.expect("naga ran"))
}

/// [`validate_compute`] as [`validate_stage_reusing`] does it.
pub fn validate_compute_reusing(
    frontend: &mut Frontend,
    stage: &LoweredCompute,
    provider: &dyn FileProvider,
    known: &KnownValid,
) -> Result<(), Vec<Diagnostic>> {
    validate_text(frontend, naga::ShaderStage::Compute, &stage.preprocessed, &stage.lowered, provider, Some(known)).map(drop)
}

/// Deepest bracket nesting naga is given.
pub const MAX_NESTING: usize = 256;
/// Most operators one statement may hold. naga's parser and validator recurse once per operand
/// of a chain (`a + b + …`, `x.xy.xy…`, `- - x`); with [`NAGA_STACK_BYTES`] they handle several
/// times this, and no real shader comes near it.
pub const MAX_STATEMENT_OPERATORS: usize = 10_000;
/// Stack of the thread naga runs on.
const NAGA_STACK_BYTES: usize = 64 << 20;
/// Name of the thread naga runs on: a panic there is naga's, which callers turn into a
/// diagnostic (and may keep off the terminal).
pub const NAGA_THREAD: &str = "naga";

/// The line and the reason when `text` is beyond what naga is given: brackets nested past
/// [`MAX_NESTING`] or a statement past [`MAX_STATEMENT_OPERATORS`] operators. A text the
/// tokenizer refuses passes: naga reports it.
pub fn too_complex(text: &str) -> Option<(u32, String)> {
    let tokens = tokenize(text).ok()?;
    let (mut depth, mut operators) = (0usize, 0usize);
    for t in tokens.iter().filter(|t| t.kind == TokenKind::Punct) {
        match t.text {
            "(" | "[" | "{" => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Some((t.line, format!("brackets nest deeper than {MAX_NESTING} levels")));
                }
                if t.text == "{" {
                    operators = 0;
                }
            }
            ")" | "]" | "}" => depth = depth.saturating_sub(1),
            ";" => operators = 0,
            "," => {}
            _ => operators += 1,
        }
        if operators > MAX_STATEMENT_OPERATORS {
            return Some((t.line, format!("one statement holds more than {MAX_STATEMENT_OPERATORS} operators, more than tidepack validates")));
        }
    }
    None
}

/// Most rewrites [`implicit_conversion`] makes to one stage before naga's error stands.
const MAX_REPAIRS: usize = 64;

fn validate_text(
    frontend: &mut Frontend,
    naga_stage: naga::ShaderStage,
    pre: &Preprocessed,
    lowered: &Lowered,
    provider: &dyn FileProvider,
    known: Option<&KnownValid>,
) -> Result<Option<ValidStage>, Vec<Diagnostic>> {
    if let Some((line, message)) = too_complex(&lowered.text) {
        return Err(vec![Diagnostic::error(Code::Glsl, message, pre.location(line))]);
    }
    // GLSL converts int to float where naga wants the types to match: each such error is
    // repaired in the text (line for line) and naga runs again. naga stops at a stage's first
    // error; after one inside a function, the function's body is blanked (its signature kept)
    // and naga runs again, so that the errors of the other functions are found too.
    // A lenient stage's repairs are reported, so each of its functions is read whole.
    let known = known.filter(|_| !pre.lenient);
    let stage_name = format!("{naga_stage:?}");
    let mut functions = known.map(|_| known_valid::functions_of(&lowered.text, &stage_name)).unwrap_or_default();
    let mut text = match known {
        Some(known) => known.stubbed(&lowered.text, &functions),
        None => lowered.text.clone(),
    };
    let mut stubbed_digest = known.map(|known| known.text_digest(&stage_name, &text));
    if let (Some(known), Some(digest)) = (known, &stubbed_digest)
        && known.accepted(digest)
    {
        return Ok(None);
    }
    // Lines of the functions whose bodies were blanked after an error.
    let mut rejected: Vec<u32> = Vec::new();
    let version = pre.version.as_ref().map_or(110, |v| v.number);
    // Scalars take swizzles (`f().r`) from GLSL 4.20 or with GL_ARB_shading_language_420pack.
    let scalar_swizzles = version >= 420 || extension_enabled(&pre.text, "GL_ARB_shading_language_420pack");
    let mut found: Vec<Diagnostic> = Vec::new();
    let mut lenient_repairs = Vec::new();
    for repairs in 0.. {
        let (parsed, validated) = run_naga(frontend, naga_stage, &text)?;
        let (diagnostics, at) = match parsed {
            Ok(module) => match validated.expect("a parsed module is validated") {
                Ok(info) if found.is_empty() => {
                    if version < 130
                        && !pre.lenient
                        && let Some(span) = mix_of_bool_vector(&module, &info)
                    {
                        let message = "mix() with a bvec selector (taking each component from one side) came with GLSL 1.30; \
                                       under 1.20 write each component with ?: or declare #version 130";
                        let at = Some(span.location(&text));
                        return Err(vec![diagnostic_at(pre, &text, provider, message.to_string(), at).refused_by(Drivers::ALL.without(Drivers::NVIDIA))]);
                    }
                    if naga_stage == naga::ShaderStage::Compute
                        && let Some(diagnostic) = shared_memory_overflow(pre, &text, provider, &module)
                    {
                        return Err(vec![diagnostic]);
                    }
                    if let (Some(known), Some(digest)) = (known, stubbed_digest) {
                        known.remember(&functions, &rejected);
                        known.remember_text(digest);
                    }
                    return Ok(Some(ValidStage { module, info, lenient_repairs }));
                }
                Ok(_) => {
                    if let Some(known) = known {
                        known.remember(&functions, &rejected);
                    }
                    return Err(found);
                }
                Err(e) => {
                    if repairs < MAX_REPAIRS
                        && let Some(repair) = implicit_conversion(&text, &module, e.as_inner(), version, pre.lenient)
                    {
                        if let Some((offset, leniency)) = repair.lenient {
                            let line = line_at(&text, offset);
                            lenient_repairs.push(LenientRepair { location: pre.location(line), leniency });
                        }
                        text = repair.text;
                        continue;
                    }
                    let mix_selector = scalar_mix_selector(&module, e.as_inner());
                    let refused_by = if mix_selector.is_some() { Drivers::ALL.without(Drivers::NVIDIA) } else { Drivers::ALL };
                    let said = mix_selector
                        .or_else(|| built_in_of_another_stage(&text, e.as_inner(), naga_stage))
                        .or_else(|| glsl_message(&module, e.as_inner()));
                    let (message, span) = said.unwrap_or_else(|| {
                        let mut message = e.as_inner().to_string();
                        let mut source = e.as_inner().source();
                        while let Some(inner) = source {
                            message.push_str(": ");
                            message.push_str(&inner.to_string());
                            source = inner.source();
                        }
                        (message, None)
                    });
                    // naga's spans go from the enclosing function to the offending expression:
                    // use the last, unless the message knows a better place.
                    let span = span.filter(|s| s.is_defined()).or_else(|| e.spans().map(|(span, _)| *span).filter(|s| s.is_defined()).last());
                    let at = span.map(|span| span.location(&text));
                    let offset = span.and_then(|s| s.to_range()).map(|r| r.start);
                    (vec![diagnostic_at(pre, &text, provider, message, at).refused_by(refused_by)], offset)
                }
            },
            Err(errors) => {
                // A prototype in place of a function that overloads a built-in naga declares
                // (`float dot(float, float)`) clashes with it: that function gets a stub body
                // instead, and naga starts over.
                let clashes: Vec<u32> = errors
                    .errors
                    .iter()
                    .filter(|e| matches!(&e.kind, ErrorKind::SemanticError(m) if m.as_ref() == "Prototype already defined"))
                    .filter_map(|e| e.meta.to_range())
                    .map(|span| line_at(&text, span.start))
                    .collect();
                if let Some(known) = known
                    && known.stub_with_bodies(&mut functions, &clashes)
                {
                    text = known.stubbed(&lowered.text, &functions);
                    stubbed_digest = Some(known.text_digest(&stage_name, &text));
                    found.clear();
                    rejected.clear();
                    lenient_repairs.clear();
                    continue;
                }
                if repairs < MAX_REPAIRS
                    && let Some(repair) = errors.errors.iter().find_map(|e| parse_repair(&text, e, version, scalar_swizzles, pre.lenient))
                {
                    if let Some((offset, leniency)) = repair.lenient {
                        let line = line_at(&text, offset);
                        lenient_repairs.push(LenientRepair { location: pre.location(line), leniency });
                    }
                    text = repair.text;
                    continue;
                }
                let offset = errors.errors.first().and_then(|e| e.meta.to_range()).map(|r| r.start);
                (errors.errors.iter().map(|e| parse_diagnostic(pre, &text, provider, e)).collect(), offset)
            }
        };
        for diagnostic in diagnostics {
            if !found.contains(&diagnostic) {
                found.push(diagnostic);
            }
        }
        match at.and_then(|offset| Some((offset, without_body_at(&text, offset)?))) {
            Some((offset, blanked)) if repairs < MAX_REPAIRS => {
                rejected.push(line_at(&text, offset));
                text = blanked;
            }
            _ => return Err(found),
        }
    }
    unreachable!("the loop returns")
}

/// The 1-based line of byte `offset` of `text`.
fn line_at(text: &str, offset: usize) -> u32 {
    text[..offset].matches('\n').count() as u32 + 1
}

/// `text` with the body of the function definition around byte `offset` blanked out (every
/// character but line breaks a space, the braces kept); in `main`, whose blank body would have
/// errors of its own (no position), the statement there alone (see [`without_statement_at`]).
/// `None` outside every function body, or where the body is blank already.
fn without_body_at(text: &str, offset: usize) -> Option<String> {
    let tokens = tokenize(text).ok()?;
    let function = function_definitions(&tokens).into_iter().find(|f| {
        let (open, close) = (tokens[f.open].offset, tokens.get(f.close).map_or(text.len(), |t| t.offset));
        open < offset && offset < close
    })?;
    if tokens[function.name].text == "main" {
        return without_statement_at(text, &tokens, offset);
    }
    let body = tokens[function.open].offset + 1..tokens.get(function.close)?.offset;
    if text[body.clone()].trim().is_empty() {
        return None;
    }
    Some(blanked(text, &[body]))
}

/// `text` with the statement around byte `offset` blanked out: an expression statement whole,
/// a declaration from its `=` on (the variable stays declared for the statements after it).
/// `None` where the statement spans a brace, writes `gl_Position`, is a declaration without `=`,
/// or is blank already.
fn without_statement_at(text: &str, tokens: &[crate::token::Token], offset: usize) -> Option<String> {
    let significant: Vec<&crate::token::Token> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    let at = significant.iter().rposition(|t| t.offset <= offset)?;
    let start = significant[..at].iter().rposition(|t| t.is_punct(";") || t.is_punct("{") || t.is_punct("}")).map_or(0, |k| k + 1);
    let end = at + significant[at..].iter().position(|t| t.is_punct(";"))?;
    let statement = significant.get(start..end)?;
    // Without its position write a vertex stage has an error of its own.
    if statement.is_empty() || statement.iter().any(|t| t.is_punct("{") || t.is_punct("}") || t.is_ident("gl_Position")) {
        return None;
    }
    // A declaration starts with a type and a name (`vec3 x`, `const float y`, `Surface s`).
    let first_name = statement.iter().position(|t| !matches!(t.text, "const" | "highp" | "mediump" | "lowp"))?;
    let declaration = statement.get(first_name + 1).is_some_and(|t| t.kind == TokenKind::Ident);
    let from = if declaration { statement.iter().position(|t| t.is_punct("="))? } else { 0 };
    let range = statement[from].offset..significant[end].offset;
    if text[range.clone()].trim().is_empty() {
        return None;
    }
    Some(blanked(text, &[range]))
}

/// Shared memory OpenGL guarantees a compute shader (the least `GL_MAX_COMPUTE_SHARED_MEMORY_SIZE`
/// may be; Mesa's llvmpipe gives no more).
const SHARED_MEMORY_BYTES: u64 = 32768;

/// A compute stage whose `shared` variables take more than [`SHARED_MEMORY_BYTES`], which Mesa
/// refuses to link, reported at the largest of them. Sizes are naga's layout, within a few bytes
/// of Mesa's (a `vec3` array's last element counts 16 bytes, not 12).
fn shared_memory_overflow(pre: &Preprocessed, text: &str, provider: &dyn FileProvider, module: &naga::Module) -> Option<Diagnostic> {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).ok()?;
    let shared: Vec<_> = module
        .global_variables
        .iter()
        .filter(|(_, g)| g.space == naga::AddressSpace::WorkGroup)
        .map(|(handle, g)| (handle, u64::from(layouter[g.ty].size)))
        .collect();
    let total: u64 = shared.iter().map(|(_, size)| size).sum();
    if total <= SHARED_MEMORY_BYTES {
        return None;
    }
    let &(largest, _) = shared.iter().max_by_key(|(_, size)| *size)?;
    let span = module.global_variables.get_span(largest);
    let at = span.is_defined().then(|| span.location(text));
    let message = format!(
        "the `shared` variables take {total} bytes, more than the {SHARED_MEMORY_BYTES} bytes of shared memory OpenGL guarantees a compute shader: the program fails to link on Mesa"
    );
    Some(diagnostic_at(pre, text, provider, message, at))
}

type NagaResult = (Result<naga::Module, naga::front::glsl::ParseErrors>, Option<Result<ModuleInfo, naga::WithSpan<naga::valid::ValidationError>>>);

/// Parses and validates on a thread of its own, so that the caller's stack size does not
/// matter.
#[allow(clippy::result_large_err, reason = "naga's own result types, passed on as they are")]
fn run_naga(frontend: &mut Frontend, naga_stage: naga::ShaderStage, text: &str) -> Result<NagaResult, Vec<Diagnostic>> {
    std::thread::scope(|scope| {
        let worker = std::thread::Builder::new().name(NAGA_THREAD.into()).stack_size(NAGA_STACK_BYTES).spawn_scoped(scope, || {
            let mut parsed = frontend.parse(&Options::from(naga_stage), text);
            if let Ok(module) = &mut parsed {
                callees_first(module);
                member_array_types(module);
            }
            let validated =
                parsed.as_ref().ok().map(|module| Validator::new(ValidationFlags::all(), Capabilities::all()).validate(module));
            (parsed, validated)
        });
        match worker {
            Ok(handle) => Ok(handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))),
            Err(e) => Err(vec![Diagnostic::error(Code::NotChecked, format!("cannot start naga's thread: {e}"), None)]),
        }
    })
}

/// GLSL lets a function call one that a prototype declared and that is defined later; naga's
/// validator wants every function after the functions it calls. Reorders the function arena,
/// and the calls' handles with it; nothing else changes.
fn callees_first(module: &mut naga::Module) {
    use naga::{Block, Expression, Function, Handle, Statement};
    fn callees(block: &Block, out: &mut Vec<Handle<Function>>) {
        for statement in block.iter() {
            match statement {
                Statement::Call { function, .. } => out.push(*function),
                Statement::Block(inner) => callees(inner, out),
                Statement::If { accept, reject, .. } => {
                    callees(accept, out);
                    callees(reject, out);
                }
                Statement::Switch { cases, .. } => cases.iter().for_each(|c| callees(&c.body, out)),
                Statement::Loop { body, continuing, .. } => {
                    callees(body, out);
                    callees(continuing, out);
                }
                _ => {}
            }
        }
    }
    fn remap_block(block: &mut Block, map: &[Handle<Function>]) {
        for statement in block.iter_mut() {
            match statement {
                Statement::Call { function, .. } => *function = map[function.index()],
                Statement::Block(inner) => remap_block(inner, map),
                Statement::If { accept, reject, .. } => {
                    remap_block(accept, map);
                    remap_block(reject, map);
                }
                Statement::Switch { cases, .. } => cases.iter_mut().for_each(|c| remap_block(&mut c.body, map)),
                Statement::Loop { body, continuing, .. } => {
                    remap_block(body, map);
                    remap_block(continuing, map);
                }
                _ => {}
            }
        }
    }
    fn remap(function: &mut Function, map: &[Handle<Function>]) {
        remap_block(&mut function.body, map);
        for (_, expression) in function.expressions.iter_mut() {
            if let Expression::CallResult(callee) = expression {
                *callee = map[callee.index()];
            }
        }
    }
    let calls: Vec<Vec<Handle<Function>>> = module
        .functions
        .iter()
        .map(|(_, f)| {
            let mut out = Vec::new();
            callees(&f.body, &mut out);
            out
        })
        .collect();
    if calls.iter().enumerate().all(|(caller, callees)| callees.iter().all(|c| c.index() < caller)) {
        return;
    }
    // Depth-first post-order, without recursion (a pack may have thousands of functions); a
    // call cycle (GLSL forbids recursion) is left for the validator to report.
    let mut order = Vec::with_capacity(calls.len());
    let mut placed = vec![false; calls.len()];
    let mut entered = vec![false; calls.len()];
    for root in 0..calls.len() {
        let mut stack = vec![(root, 0usize)];
        while let Some((node, next)) = stack.pop() {
            if placed[node] {
                continue;
            }
            entered[node] = true;
            match calls[node].get(next) {
                Some(callee) => {
                    stack.push((node, next + 1));
                    let callee = callee.index();
                    if !entered[callee] {
                        stack.push((callee, 0));
                    }
                }
                None => {
                    placed[node] = true;
                    order.push(node);
                }
            }
        }
    }
    let mut old: Vec<Option<(Function, naga::Span)>> = module.functions.drain().map(|(_, f, span)| Some((f, span))).collect();
    let mut map: Vec<Option<Handle<Function>>> = vec![None; old.len()];
    for index in order {
        if let Some((function, span)) = old[index].take() {
            map[index] = Some(module.functions.append(function, span));
        }
    }
    let map: Vec<Handle<Function>> = map.into_iter().map(|h| h.expect("every function is placed")).collect();
    for (_, function) in module.functions.iter_mut() {
        remap(function, &map);
    }
    for entry in &mut module.entry_points {
        remap(&mut entry.function, &map);
    }
}

/// naga's GLSL front-end lays out an array inside a struct with a uniform block's stride and an
/// array constructor with its natural one, so to its validator `S(float[2](a, b))` composes a
/// struct from an array of another type; in GLSL both are `float[2]`. Each array constructor
/// composed into a struct member gets that member's type (same element type and size).
fn member_array_types(module: &mut naga::Module) {
    use naga::{Arena, Expression, TypeInner};
    let types = &module.types;
    let retype = |expressions: &mut Arena<Expression>| {
        let mut fixes = Vec::new();
        for (_, expression) in expressions.iter() {
            let Expression::Compose { ty, ref components } = *expression else { continue };
            let TypeInner::Struct { ref members, .. } = types[ty].inner else { continue };
            for (member, &component) in members.iter().zip(components) {
                let Expression::Compose { ty: given, .. } = expressions[component] else { continue };
                let same_array = match (&types[given].inner, &types[member.ty].inner) {
                    (TypeInner::Array { base, size, .. }, TypeInner::Array { base: b, size: s, .. }) => base == b && size == s,
                    _ => false,
                };
                if given != member.ty && same_array {
                    fixes.push((component, member.ty));
                }
            }
        }
        for (component, member_ty) in fixes {
            if let Expression::Compose { ty, .. } = expressions.get_mut(component) {
                *ty = member_ty;
            }
        }
    };
    retype(&mut module.global_expressions);
    for (_, function) in module.functions.iter_mut() {
        retype(&mut function.expressions);
    }
    for entry in &mut module.entry_points {
        retype(&mut entry.function.expressions);
    }
}

/// A parse error in GLSL's words, at the pack file and line.
fn parse_diagnostic(pre: &Preprocessed, text: &str, provider: &dyn FileProvider, e: &naga::front::glsl::Error) -> Diagnostic {
    let mut span = e.meta.to_range();
    let message = match &e.kind {
        ErrorKind::InvalidToken(_, expected) => {
            let found = span.as_ref().and_then(|r| text.get(r.clone())).map_or("this".to_string(), |t| format!("`{}`", t.trim()));
            let words: Vec<String> = expected.iter().map(expected_words).collect();
            format!("unexpected {found}: expected {}", words.join(" or "))
        }
        ErrorKind::EndOfFile => "the file ends inside a declaration or block: a `}`, `)` or `;` is missing".to_string(),
        ErrorKind::SemanticError(m) if m.starts_with("Can't lookup field on this type") => {
            let field = span.as_ref().and_then(|r| text.get(r.clone())).map_or("this field".to_string(), |t| format!("`{}`", t.trim()));
            format!(
                "{field} selects from a value that is neither a vector nor a struct: scalars take swizzles only from GLSL 4.20 (or with GL_ARB_shading_language_420pack), matrices never (Mesa refuses it)"
            )
        }
        // naga names the indexed expression by its handle.
        ErrorKind::SemanticError(m) if m.contains("OutOfBoundsIndex") => {
            let index = m.rsplit("index: ").next().and_then(|rest| rest.split(|c: char| !c.is_ascii_digit()).next()).unwrap_or("this");
            format!(
                "the constant index {index} is past the end of the vector, matrix or array it selects from (every compiler refuses it)"
            )
        }
        // naga's lookups take a sampler variable or parameter only.
        ErrorKind::SemanticError(m) if m.as_ref() == "Bad call" => {
            "this lookup's sampler is an expression: GLSL takes a sampler by its name, an element of a sampler array or a \
             parameter, never the result of `?:` or of an assignment (samplers are opaque; Mesa refuses it)"
                .to_string()
        }
        // naga names the expression by its internal form.
        ErrorKind::SemanticError(m) if m.ends_with("cannot be in the left hand side") => {
            "this cannot be assigned to: the left side of an assignment must be a variable, an element, a field or a swizzle"
                .to_string()
        }
        other => other.to_string(),
    };
    if let (Some(range), ErrorKind::InvalidToken(_, expected)) = (&mut span, &e.kind)
        && expected.contains(&ExpectedToken::Token(TokenValue::Semicolon))
    {
        // A missing `;` belongs after the previous token, not at the next line.
        let end = text[..range.start].trim_end().len();
        *range = end.saturating_sub(1)..end;
    }
    let at = span.clone().map(|r| naga::Span::new(r.start as u32, r.end as u32).location(text));
    let mut diagnostic = diagnostic_at(pre, text, provider, message, at);
    if let ErrorKind::SemanticError(message) = &e.kind
        && let Some(name) = message.strip_prefix("Unknown function '").and_then(|m| m.strip_suffix('\''))
        && let Some(swizzle) = name.strip_prefix("tp_store_")
    {
        // A store to a matrix column's swizzle, which the repair made a call.
        diagnostic.message = format!("the value assigned to `.{swizzle}` of a matrix column is not a {}", match swizzle.len() {
            1 => "float".to_string(),
            n => format!("vec{n}"),
        });
    } else if let ErrorKind::SemanticError(message) = &e.kind
        && message.as_ref() == "Function already defined"
        && let Some(name) = span.as_ref().and_then(|r| defined_function_name(&text[r.clone()]))
    {
        let definitions = declarations_of(pre, name);
        let here = diagnostic.location.as_ref().map(|l| (l.path.clone(), l.line));
        if definitions.iter().all(|(_, l)| l.as_ref().map(|l| (l.path.clone(), l.line)) == here) {
            diagnostic.message = format!(
                "`{name}` is defined a second time with the same parameters, by the same lines: their file is included twice without \
                 a guard (`#ifndef NAME` / `#define NAME` around it), and GLSL takes one body per signature"
            );
        } else {
            diagnostic.message = format!("`{name}` is defined a second time with the same parameters: GLSL takes one body per signature");
            for (signature, location) in definitions {
                let at = location.map_or_else(String::new, |l| format!(" at {}:{}", l.path, l.line));
                diagnostic = diagnostic.with_note(format!("defined: `{signature}`{at}"));
            }
        }
    } else if let ErrorKind::SemanticError(message) = &e.kind
        && let Some(name) = message.strip_prefix("Unknown function '").and_then(|m| m.strip_suffix('\''))
    {
        // The function exists, only not with these arguments: show what is declared.
        let declared = declarations_of(pre, name);
        if !declared.is_empty() {
            diagnostic.message = format!("no declaration of `{name}` takes these arguments (their number or types differ)");
            for (signature, location) in declared {
                let at = location.map_or_else(String::new, |l| format!(" at {}:{}", l.path, l.line));
                diagnostic = diagnostic.with_note(format!("declared: `{signature}`{at}"));
            }
        }
    }
    diagnostic
}

/// The name a function definition's text (`float phase(float a) { … }`) defines: the word before
/// its first `(`.
fn defined_function_name(definition: &str) -> Option<&str> {
    let head = definition[..definition.find('(')?].trim_end();
    let start = head.rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).map_or(0, |i| i + 1);
    Some(&head[start..]).filter(|name| !name.is_empty())
}

/// The pack's own declarations of function `name`: their signatures as written and where.
fn declarations_of(pre: &Preprocessed, name: &str) -> Vec<(String, Option<Location>)> {
    let Ok(tokens) = tokenize(&pre.text) else { return Vec::new() };
    let sig: Vec<_> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    let depths = brace_depths(&sig);
    let mut found = Vec::new();
    for k in 0..sig.len() {
        let declares = depths[k] == 0
            && sig[k].is_ident(name)
            && k > 0
            && sig[k - 1].kind == TokenKind::Ident
            && sig.get(k + 1).is_some_and(|t| t.is_punct("("));
        if !declares {
            continue;
        }
        let Some(close) = (k..sig.len()).find(|&j| sig[j].is_punct(")")) else { continue };
        let parameters: Vec<&str> = sig[k + 2..close].iter().map(|t| t.text).collect();
        let signature = format!("{} {name}({})", sig[k - 1].text, parameters.join(" ").replace(" ,", ","));
        if !found.iter().any(|(s, _)| *s == signature) {
            found.push((signature, pre.location(sig[k].line)));
        }
    }
    found
}

/// What naga expected, as GLSL source spells it.
fn expected_words(expected: &ExpectedToken) -> String {
    let token = match expected {
        ExpectedToken::Token(token) => token,
        ExpectedToken::TypeName => return "a type".into(),
        ExpectedToken::Identifier => return "a name".into(),
        ExpectedToken::IntLiteral => return "an integer".into(),
        ExpectedToken::FloatLiteral => return "a number".into(),
        ExpectedToken::BoolLiteral => return "true or false".into(),
        ExpectedToken::Eof => return "the end of the file".into(),
    };
    let symbol = match token {
        TokenValue::Semicolon => ";",
        TokenValue::Comma => ",",
        TokenValue::Colon => ":",
        TokenValue::Dot => ".",
        TokenValue::Question => "?",
        TokenValue::Assign => "=",
        TokenValue::LeftBrace => "{",
        TokenValue::RightBrace => "}",
        TokenValue::LeftParen => "(",
        TokenValue::RightParen => ")",
        TokenValue::LeftBracket => "[",
        TokenValue::RightBracket => "]",
        TokenValue::LeftAngle => "<",
        TokenValue::RightAngle => ">",
        TokenValue::Identifier(name) => return format!("`{name}`"),
        other => return format!("{other:?}").to_lowercase(),
    };
    format!("`{symbol}`")
}

/// Repairs what naga's parser refuses and GLSL allows, from the parse error: a swizzle
/// assigned on a matrix column, a built-in called with mixed argument types,
/// a constant shift whose bits run out of the integer, a swizzle of a scalar where the version
/// allows one; in a `lenient` stage, `||` and `&&` of bool vectors, which NVIDIA applies
/// component by component.
fn parse_repair(text: &str, e: &naga::front::glsl::Error, version: u32, scalar_swizzles: bool, lenient: bool) -> Option<Repair> {
    let ErrorKind::SemanticError(message) = &e.kind else { return None };
    let span = e.meta.to_range()?;
    let repaired = |text: Option<String>| text.map(|text| Repair { text, lenient: None });
    if let Some(field) = message.strip_prefix("Can't lookup field on this type \"").and_then(|m| m.strip_suffix('"')) {
        repaired(column_swizzle_store(text, span.clone(), field, scalar_swizzles).or_else(|| if scalar_swizzles { scalar_swizzle(text, span, field) } else { None }))
    } else if let Some(name) = message.strip_prefix("Ambiguous best function for '").and_then(|m| m.strip_suffix('\'')) {
        repaired(mixed_type_overloads(text, name, version))
    } else if message.as_ref() == "<< operation overflowed" {
        repaired(literal_shift(text, span))
    } else if message.starts_with("Unknown function '") {
        repaired(bool_vector_arguments(text, span))
    } else if let (true, Some((operator, size))) = (lenient, logical_operator_on_vectors(message)) {
        // The sum of the two vectors' ints says where one or both hold.
        let written = text.get(span.clone())?;
        let at = top_level_operator(written, operator)?;
        let (left, right) = (written[..at].trim(), written[at + 2..].trim());
        let ints = format!("ivec{size}");
        let with = if operator == "||" {
            format!("notEqual({ints}({left}) + {ints}({right}), {ints}(0))")
        } else {
            format!("equal({ints}({left}) + {ints}({right}), {ints}(2))")
        };
        let text = format!("{}{with}{}", &text[..span.start], &text[span.end..]);
        Some(Repair { text, lenient: Some((span.start, Leniency::Replaced { written: written.to_string(), with })) })
    } else {
        None
    }
}

/// `||` or `&&` and the vectors' size, where naga's parser says the operator met bool vectors
/// (`Can't resolve type: IncompatibleOperands("LogicalOr(vec2<bool>, _)")`).
pub fn logical_operator_on_vectors(message: &str) -> Option<(&'static str, char)> {
    let operands = message.strip_prefix("Can't resolve type: IncompatibleOperands(\"")?;
    let (operator, rest) = if let Some(rest) = operands.strip_prefix("LogicalOr(vec") {
        ("||", rest)
    } else {
        ("&&", operands.strip_prefix("LogicalAnd(vec")?)
    };
    let size = rest.chars().next().filter(|c| ('2'..='4').contains(c))?;
    rest[1..].starts_with("<bool>").then_some((operator, size))
}

/// `text` with each argument of the call at `span` that constructs a vector of one bool
/// (`vec3(b)`, `ivec2(x > 0)`) converting the bool first (`vec3(float(b))`). GLSL makes such a
/// vector of 0 or 1 in each component; naga's front end makes it a scalar and then finds no
/// function taking it. A bool is told from the text: a comparison or logical operator at the
/// argument's top level (not one choosing with `?:`), `!`, `true`, `false`, or a name the text
/// declares `bool`.
fn bool_vector_arguments(text: &str, span: std::ops::Range<usize>) -> Option<String> {
    let tokens = tokenize(text.get(span.clone())?).ok()?;
    let sig = significant(&tokens);
    let open = sig.iter().position(|&i| tokens[i].is_punct("("))?;
    let close = matching_close(&sig, &tokens, open)?;
    let all_tokens = tokenize(text).ok()?;
    let declared_bool = |name: &str| all_tokens.windows(3).any(|w| w[0].is_ident("bool") && w[1].is_trivia() && w[2].is_ident(name));
    let mut insertions: Vec<(usize, String)> = Vec::new();
    let mut k = open + 1;
    while k < close {
        let constructor = tokens[sig[k]].text;
        let scalar = match constructor.strip_suffix(['2', '3', '4']) {
            Some("vec") => "float",
            Some("ivec") => "int",
            Some("uvec") => "uint",
            _ => "",
        };
        if !scalar.is_empty()
            && tokens[sig[k + 1]].is_punct("(")
            && let Some(end) = matching_close(&sig, &tokens, k + 1)
        {
            let inner = &sig[k + 2..end];
            let mut depth = 0i32;
            let (mut boolean, mut chosen) = (false, false);
            let mut single = !inner.is_empty();
            for &i in inner {
                let t = &tokens[i];
                match t.text {
                    "(" | "[" => depth += 1,
                    ")" | "]" => depth -= 1,
                    "," if depth == 0 => single = false,
                    "?" if depth == 0 => chosen = true,
                    "==" | "!=" | "<" | ">" | "<=" | ">=" | "&&" | "||" | "^^" if depth == 0 && t.kind == TokenKind::Punct => boolean = true,
                    _ => {}
                }
            }
            let first = &tokens[inner.first().copied().unwrap_or(sig[end])];
            boolean |= inner.len() == 1 && (first.is_ident("true") || first.is_ident("false") || declared_bool(first.text));
            boolean |= first.is_punct("!");
            if single && boolean && !chosen {
                insertions.push((span.start + tokens[inner[0]].offset, format!("{scalar}(")));
                insertions.push((span.start + tokens[sig[end]].offset, ")".to_string()));
            }
            k = end + 1;
            continue;
        }
        k += 1;
    }
    if insertions.is_empty() {
        return None;
    }
    let mut out = text.to_string();
    for (at, inserted) in insertions.into_iter().rev() {
        out.insert_str(at, &inserted);
    }
    Some(out)
}

/// `text` with `stand_in` on the lowering's header line (the line after `#version`), once.
fn with_stand_in(mut text: String, stand_in: &str) -> Option<String> {
    if !text.contains(stand_in) {
        // `#version` may be preceded by comments.
        let version = text.find("#version")?;
        let header = version + text[version..].find('\n')? + 1;
        text.insert_str(header, stand_in);
    }
    Some(text)
}

/// `m[i].xz = v;` (or `+=`, `-=`, `*=`, `/=`): naga's parser cannot assign a swizzle of a matrix
/// column (`field`, the span of `.xz`); drivers can. It becomes `tp_store_xz(m[i], v);`, a
/// stand-in that takes the column `inout` (a compound assignment passes `m[i].xz - (v)`). Where
/// the version swizzles scalars (`scalar_swizzles`), `s.depth.x = v;` on a float member is the
/// same store, and `.x` gets a float overload.
fn column_swizzle_store(text: &str, field: std::ops::Range<usize>, swizzle: &str, scalar_swizzles: bool) -> Option<String> {
    let set = ["xyzw", "rgba", "stpq"].into_iter().find(|set| swizzle.chars().all(|c| set.contains(c)))?;
    let highest = swizzle.chars().filter_map(|c| set.find(c)).max()?;
    if swizzle.len() > 4 || !text.get(field.clone())?.starts_with('.') {
        return None;
    }
    let lhs = postfix_start(text, field.start)..field.end;
    let column = text[lhs.start..field.start].trim();
    if !column.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') {
        return None;
    }
    let after = text.get(lhs.end..)?;
    let operator_at = after.len() - after.trim_start().len();
    let operator = ["+=", "-=", "*=", "/=", "="].into_iter().find(|op| after[operator_at..].starts_with(op))?;
    let value_start = lhs.end + operator_at + operator.len();
    if text[value_start..].starts_with('=') {
        return None;
    }
    let mut depth = 0i32;
    let value_len = text[value_start..].find(|c: char| {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            _ => {}
        }
        depth < 0 || (depth == 0 && c == ';')
    })?;
    let value_end = value_start + value_len;
    if !text[value_end..].starts_with(';') {
        return None;
    }
    let value = &text[value_start..value_end];
    let value = match operator.strip_suffix('=').filter(|op| !op.is_empty()) {
        // The copy of the column's text keeps the line count: no line break in it.
        Some(op) => format!("{}.{swizzle} {op} ({value})", column.replace(['\n', '\r'], " ")),
        None => value.to_string(),
    };
    let repaired = format!("{}tp_store_{swizzle}({column}, {value}){}", &text[..lhs.start], &text[value_end..]);
    let value_ty = if swizzle.len() == 1 { "float".to_string() } else { format!("vec{}", swizzle.len()) };
    let mut stand_ins: String = (highest + 1..=4)
        .filter(|&n| n >= 2)
        .map(|n| format!("void tp_store_{swizzle}(inout vec{n} c, {value_ty} v) {{ c.{swizzle} = v; }} "))
        .collect();
    if scalar_swizzles && swizzle.len() == 1 && highest == 0 {
        stand_ins.push_str(&format!("void tp_store_{swizzle}(inout float c, float v) {{ c = v; }} "));
    }
    with_stand_in(repaired, &stand_ins)
}

/// `extension` enabled by an `#extension` line of `text`.
fn extension_enabled(text: &str, extension: &str) -> bool {
    text.lines().any(|line| {
        let words: Vec<&str> = line.split([' ', '\t', ':']).filter(|w| !w.is_empty()).collect();
        matches!(words.as_slice(), ["#", "extension", name, behaviour, ..] | ["#extension", name, behaviour, ..]
            if *name == extension && *behaviour != "disable")
    })
}

/// `f(x).rr` (GLSL 4.20 swizzles scalars; naga's parser does not): the operand before `field`
/// (the span of `.rr`) becomes `tp_splat2(f(x))`, overloads for each scalar type; `.r` alone
/// becomes `(f(x))`. Only the first component (`x`, `r`, `s`) exists in a scalar.
fn scalar_swizzle(text: &str, field: std::ops::Range<usize>, swizzle: &str) -> Option<String> {
    let n = swizzle.len();
    let first = swizzle.chars().next()?;
    if !(1..=4).contains(&n) || !"xrs".contains(first) || swizzle.chars().any(|c| c != first) || !text.get(field.clone())?.starts_with('.') {
        return None;
    }
    let start = operand_start(text, field.start);
    let operand = text[start..field.start].trim();
    if operand.is_empty() {
        return None;
    }
    if n == 1 {
        return Some(format!("{}({operand}){}", &text[..start], &text[field.end..]));
    }
    let repaired = format!("{}tp_splat{n}({operand}){}", &text[..start], &text[field.end..]);
    let stand_ins: String = [("float", "vec"), ("int", "ivec"), ("uint", "uvec"), ("bool", "bvec")]
        .iter()
        .map(|(scalar, vector)| format!("{vector}{n} tp_splat{n}({scalar} a) {{ return {vector}{n}(a); }} "))
        .collect();
    with_stand_in(repaired, &stand_ins)
}

/// The start of the operand that ends at byte `end`: a call or parenthesised expression
/// (`f(x)`, `(a + b)`), or what [`postfix_start`] finds.
fn operand_start(text: &str, end: usize) -> usize {
    let last = text[..end].trim_end().len();
    if !text[..last].ends_with(')') {
        return postfix_start(text, end);
    }
    let bytes = text.as_bytes();
    let mut depth = 0;
    let Some(open) = (0..last).rev().find(|&i| {
        match bytes[i] {
            b')' => depth += 1,
            b'(' => depth -= 1,
            _ => {}
        }
        depth == 0
    }) else {
        return end;
    };
    // The called function's name, if any.
    let before = text[..open].trim_end();
    let name = before.trim_end_matches(|c: char| c.is_ascii_alphanumeric() || c == '_');
    if name.len() < before.len() { name.len() } else { open }
}

/// The start of the variable, element or field (`s.m[i]`, `m[i][j]`) that ends at byte `end`.
fn postfix_start(text: &str, end: usize) -> usize {
    let bytes = text.as_bytes();
    let is_word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut at = end;
    loop {
        let last = text[..at].trim_end().len();
        match last.checked_sub(1).map(|i| bytes[i]) {
            Some(b']') => {
                let mut depth = 0;
                let Some(open) = (0..last).rev().find(|&i| {
                    match bytes[i] {
                        b']' => depth += 1,
                        b'[' => depth -= 1,
                        _ => {}
                    }
                    depth == 0
                }) else {
                    return at;
                };
                at = open;
            }
            Some(b) if is_word(b) => {
                let word = text[..last].trim_end_matches(|c: char| c.is_ascii() && is_word(c as u8)).len();
                let before = text[..word].trim_end();
                if !before.ends_with('.') {
                    return word;
                }
                at = before.len() - 1;
            }
            _ => return at,
        }
    }
}

/// `1 << 31` (bits shifted out of an `int` or `uint`, which GLSL drops and naga's constant
/// evaluator calls an overflow) of literals only, at `span`: replaced by its value, computed as
/// `#if` computes and cut to 32 bits.
fn literal_shift(text: &str, span: std::ops::Range<usize>) -> Option<String> {
    let shift = text.get(span.clone())?;
    let (left, _) = shift.rsplit_once("<<")?;
    let value = literal_integer_expression(shift)? as u32;
    // A shift has the type of its left operand.
    let literal = if left.contains(['u', 'U']) { format!("{value}u") } else { format!("int({value}u)") };
    Some(format!("{}{literal}{}", &text[..span.start], &text[span.end..]))
}

/// Built-ins that take several arguments of one type, among `int`, `uint` and `float`
/// vectors, and whether they compare (returning a `bvec`).
const MIXED_TYPE_BUILTINS: &[(&str, usize, bool)] = &[
    ("min", 2, false),
    ("max", 2, false),
    ("clamp", 3, false),
    ("lessThan", 2, true),
    ("lessThanEqual", 2, true),
    ("greaterThan", 2, true),
    ("greaterThanEqual", 2, true),
    ("equal", 2, true),
    ("notEqual", 2, true),
];

/// A built-in called with mixed `int`, `uint` and `float` arguments (`max(uint, int)`,
/// `lessThan(uvec2, ivec2)`): GLSL converts them implicitly to one type, naga calls the call
/// ambiguous. Overloads of the built-in for every mixed combination, each converting its
/// arguments to the type GLSL picks, make the call an exact match: before GLSL 4.00 only
/// integers convert to `float`; from 4.00 `int` converts to `uint` too, which is then closer.
fn mixed_type_overloads(text: &str, name: &str, version: u32) -> Option<String> {
    const KINDS: [(&str, &str); 3] = [("int", "i"), ("uint", "u"), ("float", "")];
    let &(_, arity, compares) = MIXED_TYPE_BUILTINS.iter().find(|(n, ..)| *n == name)?;
    let type_name = |kind: usize, size: u32| match size {
        1 => KINDS[kind].0.to_string(),
        n => format!("{}vec{n}", KINDS[kind].1),
    };
    let mut stand_ins = String::new();
    for size in if compares { 2..=4 } else { 1..=4 } {
        // The other arguments of `min`, `max` and `clamp` may be scalars beside a vector.
        let other_sizes: &[u32] = if compares || size == 1 { &[size] } else { &[size, 1] };
        for &other_size in other_sizes {
            for combination in 0..3usize.pow(arity as u32) {
                let kinds: Vec<usize> = (0..arity).map(|a| combination / 3usize.pow(a as u32) % 3).collect();
                if kinds.iter().all(|&k| k == kinds[0]) {
                    continue;
                }
                let target = if kinds.contains(&2) || (version < 400 && kinds.contains(&0)) { 2 } else { 1 };
                let sizes: Vec<u32> = (0..arity).map(|a| if a == 0 { size } else { other_size }).collect();
                let parameters: Vec<String> = (0..arity).map(|a| format!("{} a{a}", type_name(kinds[a], sizes[a]))).collect();
                let arguments: Vec<String> = (0..arity).map(|a| format!("{}(a{a})", type_name(target, sizes[a]))).collect();
                let result = if compares { format!("bvec{size}") } else { type_name(target, size) };
                write!(stand_ins, "{result} {name}({}) {{ return {name}({}); }} ", parameters.join(", "), arguments.join(", ")).ok()?;
            }
        }
    }
    // Once added, the overloads leave nothing ambiguous; an error that remains is naga's to report.
    if text.contains(&stand_ins) {
        return None;
    }
    with_stand_in(text.to_string(), &stand_ins)
}

/// The function a validation error is in, and the function's error.
fn failing_function<'m>(
    module: &'m naga::Module,
    error: &'m naga::valid::ValidationError,
) -> Option<(&'m naga::Function, &'m naga::valid::FunctionError)> {
    use naga::valid::{EntryPointError, ValidationError};
    match error {
        ValidationError::Function { handle, source, .. } => Some((&module.functions[*handle], source)),
        ValidationError::EntryPoint { name, source: EntryPointError::Function(source), .. } => {
            Some((&module.entry_points.iter().find(|ep| &ep.name == name)?.function, source))
        }
        _ => None,
    }
}

/// The types of `function`'s expressions, as naga resolves them.
fn expression_types<'m>(
    module: &'m naga::Module,
    function: &'m naga::Function,
) -> impl FnMut(naga::Handle<naga::Expression>) -> Option<naga::TypeInner> + 'm {
    let resolve = naga::proc::ResolveContext::with_locals(module, &function.local_variables, &function.arguments);
    let mut typifier = naga::front::Typifier::new();
    move |expr| {
        typifier.grow(expr, &function.expressions, &resolve).ok()?;
        Some(typifier.get(expr, &module.types).clone())
    }
}

/// naga's "built-in not available at this stage" (a vertex shader that reads `gl_FragCoord`, a
/// fragment shader that writes `gl_Position`), said in GLSL's words at the variable's first use.
fn built_in_of_another_stage(text: &str, error: &naga::valid::ValidationError, stage: naga::ShaderStage) -> Option<(String, Option<naga::Span>)> {
    use naga::valid::{EntryPointError, ValidationError, VaryingError};
    use naga::{BuiltIn, ShaderStage};
    let ValidationError::EntryPoint {
        source: EntryPointError::Argument(_, VaryingError::InvalidBuiltInStage(built_in)) | EntryPointError::Result(VaryingError::InvalidBuiltInStage(built_in)),
        ..
    } = error
    else {
        return None;
    };
    let (name, owner) = match (built_in, stage) {
        (BuiltIn::Position { .. }, ShaderStage::Vertex) => ("gl_FragCoord", "fragment"),
        (BuiltIn::FrontFacing, _) => ("gl_FrontFacing", "fragment"),
        (BuiltIn::PointCoord, _) => ("gl_PointCoord", "fragment"),
        (BuiltIn::FragDepth, _) => ("gl_FragDepth", "fragment"),
        (BuiltIn::SampleIndex, _) => ("gl_SampleID", "fragment"),
        (BuiltIn::Position { .. }, _) => ("gl_Position", "vertex"),
        (BuiltIn::VertexIndex, _) => ("gl_VertexID", "vertex"),
        (BuiltIn::InstanceIndex, _) => ("gl_InstanceID", "vertex"),
        (BuiltIn::PointSize, _) => ("gl_PointSize", "vertex"),
        _ => return None,
    };
    let this = if stage == ShaderStage::Vertex { "vertex" } else { "fragment" };
    let tokens = tokenize(text).ok()?;
    let first = tokens.iter().find(|t| t.is_ident(name))?;
    let span = naga::Span::new(first.offset as u32, (first.offset + first.text.len()) as u32);
    Some((built_in_of_another_stage_message(name, owner, this), Some(span)))
}

/// What a stage of kind `this` naming `name`, a built-in of `owner` stages only, is told.
pub fn built_in_of_another_stage_message(name: &str, owner: &str, this: &str) -> String {
    format!("`{name}` is a {owner} shader built-in: a {this} shader has no such variable (Mesa: \"`{name}' undeclared\")")
}

/// naga's validation errors that name expression handles, said with GLSL's types instead.
/// The message, and the span to point at when naga's own points elsewhere (a store's pointer
/// spans the variable's declaration, not the assignment).
fn glsl_message(module: &naga::Module, error: &naga::valid::ValidationError) -> Option<(String, Option<naga::Span>)> {
    use naga::valid::{ExpressionError, FunctionError, LocalVariableError};
    let (function, source) = failing_function(module, error)?;
    let mut type_of = expression_types(module, function);
    let mut name = |expr| match type_of(expr) {
        Some(naga::TypeInner::Image { .. } | naga::TypeInner::Sampler { .. }) => "a sampler".to_string(),
        Some(t) => glsl_type_name(&t).unwrap_or_else(|| "another type".into()),
        None => "another type".into(),
    };
    let function_name = function.name.as_deref().unwrap_or("main").trim_start_matches("tp_");
    if let FunctionError::InvalidStorePointer(pointer) = source {
        let variable = pointer_name(module, function, *pointer).map_or("this".to_string(), |n| format!("`{n}`"));
        let message = format!("{variable} cannot be assigned to: uniforms, inputs and constants are read-only");
        return Some((message, store_span(&function.body, *pointer)));
    }
    let message = match source {
        FunctionError::InvalidReturnType { expression: Some(value), expected_ty: None } => {
            format!("`return` gives {} in `{function_name}`, which is declared `void`", name(*value))
        }
        FunctionError::LocalVariable { handle, name: local, source: LocalVariableError::InitializerType } => {
            let declared = glsl_type_name(&module.types[function.local_variables[*handle].ty].inner).unwrap_or_else(|| "another type".into());
            let init = function.local_variables[*handle].init.map_or_else(|| "another type".into(), &mut name);
            format!("`{local}` is declared {declared} but initialised with {init} (GLSL converts only int to float implicitly)")
        }
        FunctionError::InvalidReturnType { expression: Some(value), expected_ty: Some(ty) } => {
            let declared = glsl_type_name(&module.types[*ty].inner).unwrap_or_else(|| "another type".into());
            match function_name.strip_prefix("init_") {
                // The lowering's function that holds a global's initializer.
                Some(global) => format!("`{global}` is declared {declared} but initialised with {}", name(*value)),
                None => format!(
                    "`return` gives {} in `{function_name}`, which is declared to return {declared} (GLSL converts \
                     return values only from 4.20 on: write a constructor)",
                    name(*value)
                ),
            }
        }
        FunctionError::InvalidStoreTypes { pointer, value } => {
            let target = match type_of_pointee(module, function, *pointer) {
                Some(t) => glsl_type_name(&t).unwrap_or_else(|| "another type".into()),
                None => "another type".into(),
            };
            format!("a value of type {} is assigned to a variable of type {target}", name(*value))
        }
        FunctionError::Expression { source: ExpressionError::InvalidBinaryOperandTypes { op, lhs_expr, rhs_expr, .. }, .. } => {
            format!("`{}` cannot combine {} and {}", operator_symbol(*op), name(*lhs_expr), name(*rhs_expr))
        }
        _ => return None,
    };
    Some((message, None))
}

/// `mix(vec3, vec3, bool)` said in GLSL's terms, at the call: GLSL picks the components of
/// vectors with a bool vector of their size; NVIDIA takes one bool for every component.
fn scalar_mix_selector(module: &naga::Module, error: &naga::valid::ValidationError) -> Option<(String, Option<naga::Span>)> {
    let (function, source) = failing_function(module, error)?;
    let (mix, size, value) = bool_mix_selector(function, source)?;
    let naga::Expression::Math { arg, .. } = function.expressions[mix] else { return None };
    let vector = expression_types(module, function)(arg)?;
    let vector = glsl_type_name(&vector)?;
    let n = size as u8;
    let message = format!(
        "`mix` of two {vector}s takes a bvec{n} (GLSL 1.30 on) as its third argument to pick components, not a bool: write bvec{n}(...) \
         (NVIDIA takes the bool for every component; Mesa, AMD, Intel and macOS refuse it)"
    );
    let span = [value, mix, arg].into_iter().map(|e| function.expressions.get_span(e)).find(naga::Span::is_defined);
    Some((message, span))
}

/// naga's error at `mix(vec3, vec3, b)` of one bool `b`, which naga's front end makes a bool
/// vector and its validator refuses as a selector: the `mix`, the vector size and `b`.
fn bool_mix_selector(
    function: &naga::Function,
    source: &naga::valid::FunctionError,
) -> Option<(naga::Handle<naga::Expression>, naga::VectorSize, naga::Handle<naga::Expression>)> {
    use naga::valid::{ExpressionError, FunctionError};
    let FunctionError::Expression { handle, source: ExpressionError::InvalidArgumentType(naga::MathFunction::Mix, 2, selector) } = source else {
        return None;
    };
    let naga::Expression::Splat { size, value } = function.expressions[*selector] else { return None };
    Some((*handle, size, value))
}

/// Where a function of `module` selects between vectors by a bool vector: naga's reading of
/// `mix(x, y, bvecN)`, as no other GLSL form has a vector condition.
fn mix_of_bool_vector(module: &naga::Module, info: &ModuleInfo) -> Option<naga::Span> {
    let in_function = |function: &naga::Function, function_info: &naga::valid::FunctionInfo| {
        function.expressions.iter().find_map(|(handle, expression)| {
            let naga::Expression::Select { condition, accept, reject } = *expression else { return None };
            let bool_vector = matches!(
                function_info[condition].ty.inner_with(&module.types),
                naga::TypeInner::Vector { scalar: naga::Scalar { kind: naga::ScalarKind::Bool, .. }, .. }
            );
            // naga gives the selection itself no span: its operands have theirs.
            let spans = [handle, condition, accept, reject].map(|e| function.expressions.get_span(e));
            spans.into_iter().find(|span| span.is_defined()).filter(|_| bool_vector)
        })
    };
    module
        .functions
        .iter()
        .find_map(|(handle, function)| in_function(function, &info[handle]))
        .or_else(|| module.entry_points.iter().enumerate().find_map(|(i, entry)| in_function(&entry.function, info.get_entry_point(i))))
}

/// The name of the variable (or uniform block member) a pointer expression designates.
fn pointer_name(module: &naga::Module, function: &naga::Function, pointer: naga::Handle<naga::Expression>) -> Option<String> {
    use naga::Expression as E;
    match function.expressions[pointer] {
        E::GlobalVariable(g) => module.global_variables[g].name.clone(),
        E::LocalVariable(l) => function.local_variables[l].name.clone(),
        E::AccessIndex { base, index } => match function.expressions[base] {
            E::GlobalVariable(g) => match &module.types[module.global_variables[g].ty].inner {
                naga::TypeInner::Struct { members, .. } => members.get(index as usize)?.name.clone(),
                _ => module.global_variables[g].name.clone(),
            },
            _ => pointer_name(module, function, base),
        },
        E::Access { base, .. } => pointer_name(module, function, base),
        _ => None,
    }
    .map(|n| n.trim_start_matches("tp_").to_string())
}

/// The span of the statement that stores through `pointer`.
fn store_span(block: &naga::Block, pointer: naga::Handle<naga::Expression>) -> Option<naga::Span> {
    use naga::Statement as S;
    block.span_iter().find_map(|(statement, span)| match statement {
        S::Store { pointer: p, .. } if *p == pointer => Some(*span),
        S::Block(inner) => store_span(inner, pointer),
        S::If { accept, reject, .. } => store_span(accept, pointer).or_else(|| store_span(reject, pointer)),
        S::Loop { body, continuing, .. } => store_span(body, pointer).or_else(|| store_span(continuing, pointer)),
        S::Switch { cases, .. } => cases.iter().find_map(|c| store_span(&c.body, pointer)),
        _ => None,
    })
}

fn operator_symbol(op: naga::BinaryOperator) -> &'static str {
    use naga::BinaryOperator as B;
    match op {
        B::Add => "+",
        B::Subtract => "-",
        B::Multiply => "*",
        B::Divide => "/",
        B::Modulo => "%",
        B::Equal => "==",
        B::NotEqual => "!=",
        B::Less => "<",
        B::LessEqual => "<=",
        B::Greater => ">",
        B::GreaterEqual => ">=",
        B::And => "&",
        B::ExclusiveOr => "^",
        B::InclusiveOr => "|",
        B::LogicalAnd => "&&",
        B::LogicalOr => "||",
        B::ShiftLeft => "<<",
        B::ShiftRight => ">>",
    }
}

/// Where `operator` stands in `text` outside every bracket, the first time.
fn top_level_operator(text: &str, operator: &str) -> Option<usize> {
    let mut depth = 0i32;
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            _ if depth == 0 && text[i..].starts_with(operator) => return Some(i),
            _ => {}
        }
    }
    None
}

/// The type a pointer expression points to.
fn type_of_pointee(module: &naga::Module, function: &naga::Function, pointer: naga::Handle<naga::Expression>) -> Option<naga::TypeInner> {
    match expression_types(module, function)(pointer)? {
        naga::TypeInner::Pointer { base, .. } => Some(module.types[base].inner.clone()),
        naga::TypeInner::ValuePointer { size: None, scalar, .. } => Some(naga::TypeInner::Scalar(scalar)),
        naga::TypeInner::ValuePointer { size: Some(size), scalar, .. } => Some(naga::TypeInner::Vector { size, scalar }),
        _ => None,
    }
}

/// A repaired text, and the repair beyond GLSL's (a lenient stage's) if it made one, with its
/// byte offset in the text before the repair.
struct Repair {
    text: String,
    lenient: Option<(usize, Leniency)>,
}

/// Repairs what GLSL allows and naga refuses once types are known: a value GLSL converts
/// implicitly (an `int` or `ivec` returned or stored where a `float` or `vec` is declared) gets
/// a constructor, a scalar beside a vector a vector constructor, a function whose end is
/// reachable without a `return` a final one. In a `lenient` stage, values NVIDIA converts are
/// converted too (returned at any version, between int, uint and float, and vectors cut to
/// fewer components), and a lookup whose offset is not a constant moves its coordinate instead.
fn implicit_conversion(text: &str, module: &naga::Module, error: &naga::valid::ValidationError, version: u32, lenient: bool) -> Option<Repair> {
    use naga::valid::{ExpressionError, FunctionError};
    let (function, source) = failing_function(module, error)?;
    let mut type_of = expression_types(module, function);
    // GLSL 1.10 converts nothing; 1.20 converts in assignments (the lowering's `tp_init_`
    // functions return a global's initializer); returns convert from 4.20 on.
    let is_initializer = function.name.as_deref().is_some_and(|n| n.starts_with("tp_init_"));
    if version < 120 && !lenient {
        return None;
    }
    let repaired = |text: String| Some(Repair { text, lenient: None });
    // `vec3(b)` of a bool, which GLSL makes a vector of 0.0 or 1.0: naga's front end selects
    // 1.0 or 0.0 and leaves the vector out, so a scalar stands where the text has a vector (a
    // store, a return, an argument, an operand). Every such bool of the failing function is
    // converted in the text first (`vec3(float(b))`).
    let bool_conversions: Vec<(std::ops::Range<usize>, String)> = function
        .expressions
        .iter()
        .filter_map(|(value, expression)| {
            let naga::Expression::Select { condition, .. } = *expression else { return None };
            let is_bool = matches!(type_of(condition), Some(naga::TypeInner::Scalar(naga::Scalar { kind: naga::ScalarKind::Bool, .. })));
            let scalar @ naga::TypeInner::Scalar(naga::Scalar { kind: naga::ScalarKind::Float | naga::ScalarKind::Sint | naga::ScalarKind::Uint, .. }) =
                type_of(value)?
            else {
                return None;
            };
            let span = whole_span(text, function, condition).filter(|_| is_bool)?;
            let before = text[..span.start].trim_end().strip_suffix('(')?;
            // `vec3(b)`, `ivec2(b)`, `uvec4(b)`: the condition alone between the brackets.
            let constructs = before.trim_end().strip_suffix(['2', '3', '4']).is_some_and(|b| b.ends_with("vec"));
            (constructs && text[span.end..].trim_start().starts_with(')')).then(|| Some((span, glsl_type_name(&scalar)?))).flatten()
        })
        .collect();
    if !bool_conversions.is_empty() {
        let mut converted = text.to_string();
        let mut spans = bool_conversions;
        spans.sort_by_key(|(span, _)| std::cmp::Reverse(span.start));
        spans.dedup_by_key(|(span, _)| span.start);
        for (span, scalar) in spans {
            converted = format!("{}{scalar}({}){}", &converted[..span.start], &converted[span.clone()], &converted[span.end..]);
        }
        return repaired(converted);
    }
    // The value converted, its target type, and whether GLSL (from 1.20) converts it there.
    let (value, target, glsl_converts) = match source {
        FunctionError::InvalidReturnType { expression: None, expected_ty: Some(ty) } => {
            // Control reaches the end of a function that returns a value: GLSL leaves the value
            // undefined and drivers compile it; naga wants a `return` there.
            let naga::valid::ValidationError::Function { handle, .. } = error else { return None };
            let header = module.functions.get_span(*handle).to_range()?;
            let tokens = tokenize(text).ok()?;
            let body = function_definitions(&tokens).into_iter().find(|f| tokens[f.open].offset >= header.start)?;
            let body_end = tokens.get(body.close)?.offset;
            let returned = match (glsl_type_name(&module.types[*ty].inner), &module.types[*ty]) {
                (Some(zero), _) => format!("return {zero}(0);"),
                (None, naga::Type { name: Some(name), inner: naga::TypeInner::Struct { .. } }) => lower::undefined_return(name),
                _ => return None,
            };
            return repaired(format!("{} {returned} {}", &text[..body_end], &text[body_end..]));
        }
        FunctionError::InvalidReturnType { expression: Some(value), expected_ty: Some(ty) } => {
            (*value, module.types[*ty].inner.clone(), is_initializer || version >= 420)
        }
        FunctionError::Expression {
            handle,
            source: ExpressionError::InvalidBinaryOperandTypes { lhs_expr, rhs_expr, .. },
        } => {
            // A vector and a scalar (`ivec2 % int`): GLSL applies the scalar to each component,
            // in arithmetic and bitwise operations; comparisons take operands of one type, and
            // NVIDIA makes a vector of the scalar for `==` and `!=` (`vec2 != 0`).
            use naga::BinaryOperator as Op;
            let naga::Expression::Binary { op, .. } = function.expressions[*handle] else { return None };
            let equality = matches!(op, Op::Equal | Op::NotEqual);
            if matches!(op, Op::Less | Op::LessEqual | Op::Greater | Op::GreaterEqual | Op::LogicalAnd | Op::LogicalOr) || (equality && !lenient) {
                return None;
            }
            let (lhs, rhs) = (type_of(*lhs_expr)?, type_of(*rhs_expr)?);
            let (scalar, other, vector) = match (&lhs, &rhs) {
                (naga::TypeInner::Vector { .. }, naga::TypeInner::Scalar(_)) => (*rhs_expr, *lhs_expr, lhs),
                (naga::TypeInner::Scalar(_), naga::TypeInner::Vector { .. }) => (*lhs_expr, *rhs_expr, rhs),
                _ => return None,
            };
            let whole = function.expressions.get_span(*handle).to_range()?;
            let operand_span = |e: naga::Handle<naga::Expression>| function.expressions.get_span(e).to_range().filter(|s| whole.start <= s.start && s.end <= whole.end);
            // A named constant's span is its declaration's, and a built-in's call (`sign(x)`) has
            // none: the operand at this use is then the part of the whole expression beside the
            // other operand and the operator, or, without the other's span either, the side of
            // `==` or `!=` found outside brackets.
            let operator_chars: &[char] = &['%', '*', '/', '+', '-', '&', '|', '^', '<', '>', '=', '!', ' ', '\t'];
            let span = match (operand_span(scalar), operand_span(other)) {
                (Some(span), _) => span,
                (None, Some(other)) if scalar == *rhs_expr => {
                    other.end + text.get(other.end..whole.end)?.find(|c: char| !operator_chars.contains(&c))?..whole.end
                }
                (None, Some(other)) => whole.start..whole.start + text.get(whole.start..other.start)?.trim_end_matches(operator_chars).len(),
                (None, None) => {
                    let operator = if op == Op::Equal { "==" } else { "!=" };
                    let at = whole.start + top_level_operator(text.get(whole.clone())?, operator).filter(|_| equality)?;
                    let side = if scalar == *rhs_expr { at + 2..whole.end } else { whole.start..at };
                    let written = text.get(side.clone())?;
                    let start = side.start + (written.len() - written.trim_start().len());
                    start..start + written.trim().len()
                }
            };
            let inner = text.get(span.clone())?;
            let constructor = glsl_type_name(&vector)?;
            let converted = format!("{}{constructor}({inner}){}", &text[..span.start], &text[span.end..]);
            let beside = Some(if op == Op::Equal { "==" } else { "!=" }.to_string());
            let lenient = equality.then(|| (span.start, Leniency::Converted { constructor, value: inner.to_string(), beside }));
            return Some(Repair { text: converted, lenient });
        }
        FunctionError::Expression { handle, source: ExpressionError::Compose(naga::valid::ComposeError::ComponentType { .. }) } => {
            // `mat2(v)` of a `vec4`: GLSL fills the matrix from the vector's components, column
            // by column; naga composes each column of the whole vector.
            let naga::Expression::Compose { ty, ref components } = function.expressions[*handle] else { return None };
            let naga::TypeInner::Matrix { columns: naga::VectorSize::Bi, rows: naga::VectorSize::Bi, .. } = module.types[ty].inner else { return None };
            // naga gives each column the one vector.
            let (Some(component), true) = (components.first(), components.windows(2).all(|w| w[0] == w[1])) else { return None };
            let naga::TypeInner::Vector { size: naga::VectorSize::Quad, .. } = type_of(*component)? else { return None };
            let span = whole_span(text, function, *component)?;
            let inner = text.get(span.clone())?;
            return repaired(format!("{}({inner}).xy, ({inner}).zw{}", &text[..span.start], &text[span.end..]));
        }
        FunctionError::Expression { source: ExpressionError::InvalidUnaryOperandType(naga::UnaryOperator::Negate, operand), .. } => {
            // GLSL negates unsigned integers (modulo 2^32), naga does not: `-u` becomes `0u - u`.
            let ty = type_of(*operand)?;
            let unsigned = matches!(ty, naga::TypeInner::Scalar(s) | naga::TypeInner::Vector { scalar: s, .. } if s.kind == naga::ScalarKind::Uint);
            if !unsigned {
                return None;
            }
            let span = whole_span(text, function, *operand)?;
            let minus = text[..span.start].trim_end().strip_suffix('-')?.len();
            let zero = glsl_type_name(&ty)?;
            let inner = text.get(span.clone())?;
            return repaired(format!("{}({zero}(0u) - {inner}){}", &text[..minus], &text[span.end..]));
        }
        FunctionError::InvalidStoreTypes { pointer, value } => (*value, type_of_pointee(module, function, *pointer)?, true),
        FunctionError::Expression { source: ExpressionError::InvalidArgumentType(naga::MathFunction::Mix, ..), .. } if lenient => {
            // `mix(vec3, vec3, bool)`: NVIDIA takes the bool for every component, which
            // `bvec3(b)` says.
            let (_, size, value) = bool_mix_selector(function, source)?;
            let span = whole_span(text, function, value)?;
            let inner = text.get(span.clone())?;
            let constructor = format!("bvec{}", size as u8);
            let lenient = Some((span.start, Leniency::Converted { constructor: constructor.clone(), value: inner.to_string(), beside: None }));
            return Some(Repair { text: format!("{}{constructor}({inner}){}", &text[..span.start], &text[span.end..]), lenient });
        }
        FunctionError::Expression { handle, source: ExpressionError::InvalidSampleOffsetExprType } if lenient => {
            let naga::Expression::ImageSample { image, .. } = function.expressions[*handle] else { return None };
            let dimensions = match type_of(image)? {
                naga::TypeInner::Image { dim: naga::ImageDimension::D2, arrayed: false, .. } => 2,
                naga::TypeInner::Image { dim: naga::ImageDimension::D3, .. } => 3,
                _ => return None,
            };
            let span = function.expressions.get_span(*handle).to_range()?;
            let vertex = module.entry_points.iter().any(|e| e.stage == naga::ShaderStage::Vertex);
            let call = crate::compat::offset_as_coordinate(text.get(span.clone())?, dimensions, vertex)?;
            let lenient = Some((span.start, Leniency::OffsetAsCoordinate { dimensions, vertex }));
            return Some(Repair { text: format!("{}{call}{}", &text[..span.start], &text[span.end..]), lenient });
        }
        _ => return None,
    };
    let from = type_of(value)?;
    let (constructor, beyond_glsl) = match implicit_target(&from, &target, version).filter(|_| glsl_converts && version >= 120) {
        Some(constructor) => (constructor, false),
        None if lenient => (lenient_target(&from, &target)?, true),
        None => return None,
    };
    let span = whole_span(text, function, value)?;
    let inner = text.get(span.clone())?;
    let lenient = beyond_glsl.then(|| (span.start, Leniency::Converted { constructor: constructor.clone(), value: inner.to_string(), beside: None }));
    Some(Repair { text: format!("{}{constructor}({inner}){}", &text[..span.start], &text[span.end..]), lenient })
}

/// The text range of `expression` whole: naga gives a swizzle or a member's span from its `.`
/// on (`.xy` of `textureSize(s, 0).xy`), so the range reaches back over what it applies to.
fn whole_span(text: &str, function: &naga::Function, expression: naga::Handle<naga::Expression>) -> Option<std::ops::Range<usize>> {
    let span = function.expressions.get_span(expression).to_range()?;
    let mut start = span.start;
    while text.get(start..)?.starts_with('.') {
        start = postfix_base_start(text, start)?;
        // A member of a member (`a.b.xy`): on to the first.
        if start > 0 && text.as_bytes()[start - 1] == b'.' {
            start -= 1;
        }
    }
    Some(start..span.end)
}

/// Where the operand ends at `end` begins: a call or bracketed group with the name before it,
/// or a name.
fn postfix_base_start(text: &str, end: usize) -> Option<usize> {
    let bytes = text.as_bytes();
    let mut i = end;
    if matches!(bytes.get(i.checked_sub(1)?), Some(b')' | b']')) {
        let mut depth = 0i32;
        loop {
            i = i.checked_sub(1)?;
            match bytes[i] {
                b')' | b']' => depth += 1,
                b'(' | b'[' => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                break;
            }
        }
    }
    while i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_') {
        i -= 1;
    }
    (i < end).then_some(i)
}

/// The constructor NVIDIA applies implicitly where GLSL applies none: between int, uint and
/// float scalars or vectors of one size, and from a vector to a scalar or a shorter vector of
/// any of them (its first components).
fn lenient_target(from: &naga::TypeInner, to: &naga::TypeInner) -> Option<String> {
    use naga::{ScalarKind, TypeInner};
    let numeric = |s: &naga::Scalar| matches!(s.kind, ScalarKind::Sint | ScalarKind::Uint | ScalarKind::Float) && s.width == 4;
    let converts = match (from, to) {
        (TypeInner::Scalar(a), TypeInner::Scalar(b)) => numeric(a) && numeric(b),
        (TypeInner::Vector { size: n, scalar: a }, TypeInner::Vector { size: m, scalar: b }) => (*m as u8) <= (*n as u8) && numeric(a) && numeric(b),
        (TypeInner::Vector { scalar: a, .. }, TypeInner::Scalar(b)) => numeric(a) && numeric(b),
        _ => false,
    };
    converts.then(|| glsl_type_name(to)).flatten()
}

/// GLSL's name of a scalar or vector type of 32-bit components (or bools).
fn glsl_type_name(ty: &naga::TypeInner) -> Option<String> {
    use naga::{ScalarKind, TypeInner};
    let names = |s: &naga::Scalar| match (s.kind, s.width) {
        (ScalarKind::Float, 4) => Some(("", "float")),
        (ScalarKind::Sint, 4) => Some(("i", "int")),
        (ScalarKind::Uint, 4) => Some(("u", "uint")),
        (ScalarKind::Bool, _) => Some(("b", "bool")),
        _ => None,
    };
    match ty {
        TypeInner::Scalar(s) => names(s).map(|(_, name)| name.to_string()),
        TypeInner::Vector { size, scalar } => names(scalar).map(|(prefix, _)| format!("{prefix}vec{}", *size as u8)),
        TypeInner::Matrix { columns, rows, scalar } if scalar.kind == ScalarKind::Float && scalar.width == 4 => {
            let (columns, rows) = (*columns as u8, *rows as u8);
            Some(if columns == rows { format!("mat{columns}") } else { format!("mat{columns}x{rows}") })
        }
        _ => None,
    }
}

/// The GLSL constructor of `to` when GLSL converts `from` to it implicitly.
fn implicit_target(from: &naga::TypeInner, to: &naga::TypeInner, version: u32) -> Option<String> {
    use naga::{ScalarKind, TypeInner};
    // int and uint become float; from GLSL 4.00 on, int becomes uint too.
    let converts = |a: &naga::Scalar, b: &naga::Scalar| match (a.kind, b.kind) {
        (ScalarKind::Sint | ScalarKind::Uint, ScalarKind::Float) => b.width == 4,
        (ScalarKind::Sint, ScalarKind::Uint) => version >= 400,
        _ => false,
    };
    match (from, to) {
        (TypeInner::Scalar(a), TypeInner::Scalar(b)) if converts(a, b) => glsl_type_name(to),
        (TypeInner::Vector { size: n, scalar: a }, TypeInner::Vector { size: m, scalar: b }) if n == m && converts(a, b) => glsl_type_name(to),
        _ => None,
    }
}

/// Maps a naga location in the lowered text back to the pack file and line, narrowing it to
/// the offending token when that token appears once on the original line.
fn diagnostic_at(
    pre: &Preprocessed,
    text: &str,
    provider: &dyn FileProvider,
    message: String,
    at: Option<naga::SourceLocation>,
) -> Diagnostic {
    let Some(at) = at else {
        let entry = pre.files.first().map_or("the shader", String::as_str);
        return Diagnostic::error(Code::Glsl, message, None).with_note(format!("naga gives no line; the error is in {entry}"));
    };
    let mut location = pre.location(at.line_number);
    if let Some(loc) = &mut location {
        let start = at.offset as usize;
        let token = text.get(start..start + at.length as usize).unwrap_or("");
        if !token.is_empty() && !token.contains('\n') {
            loc.columns = unique_columns(provider, loc, token);
        }
    }
    Diagnostic::error(Code::Glsl, message, location)
}

fn unique_columns(provider: &dyn FileProvider, loc: &Location, token: &str) -> Option<std::ops::Range<usize>> {
    let file = provider.read(&loc.path).ok()?;
    let line = file.lines().nth(loc.line as usize - 1)?;
    let mut found = line.match_indices(token);
    let (first, _) = found.next()?;
    found.next().is_none().then_some(first..first + token.len())
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;
    use crate::preprocess::{PreprocessOptions, preprocess};

    #[test]
    fn texts_that_would_exhaust_naga_are_refused_at_their_line() {
        assert_eq!(too_complex(&format!("a\n{}", "(".repeat(MAX_NESTING + 1))).map(|(l, _)| l), Some(2));
        assert_eq!(too_complex("f((a)[b]{c})"), None);
        let long = format!("// {}\nfloat x;\nfloat y = x{};", "-".repeat(20_000), " + x".repeat(MAX_STATEMENT_OPERATORS));
        assert_eq!(too_complex(&long).map(|(l, _)| l), Some(3), "comments do not count");
        let swizzles = format!("void f() {{ vec4 v; v = v{}; }}", ".xyzw".repeat(MAX_STATEMENT_OPERATORS + 1));
        assert!(too_complex(&swizzles).is_some_and(|(_, m)| m.contains("operators")));
        let many_statements = "float a = 1.0 + 2.0;\n".repeat(MAX_STATEMENT_OPERATORS);
        assert_eq!(too_complex(&many_statements), None);
    }

    fn compute(text: &str) -> Result<ValidStage, Vec<Diagnostic>> {
        let files: HashMap<String, Arc<str>> = [("composite.csh".to_string(), Arc::from(text))].into();
        let pre = preprocess(&files, "composite.csh", &PreprocessOptions::default()).unwrap();
        let lowered = lower_compute(Arc::new(pre)).map_err(|e| vec![e])?;
        assert_eq!(lowered.lowered.text.lines().count(), text.lines().count(), "{}", lowered.lowered.text);
        validate_compute(&mut Frontend::default(), &lowered, &files)
    }

    const VALID: &str = "#version 430 compatibility
layout(local_size_x = 16, local_size_y = 16) in;
const vec2 workGroupsRender = vec2(1.0, 1.0);
layout(rgba16f) uniform image2D colorimg0;
layout(r32ui) uniform readonly uimage2D colorimg1;
uniform writeonly image2D colorimg2;
uniform sampler2D colortex3;
uniform float frameTimeCounter;
uniform bool hideGUI;
shared uint tileCount;
shared vec4 tile[256];
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (gl_LocalInvocationIndex == 0u) tileCount = 0u;
    barrier();
    memoryBarrierShared();
    atomicAdd(tileCount, 1u);
    vec4 c = imageLoad(colorimg0, p) + texelFetch(colortex3, p, 0) * frameTimeCounter;
    tile[gl_LocalInvocationIndex] = c;
    if (hideGUI) c.r += float(imageLoad(colorimg1, p).r);
    imageStore(colorimg0, p, c);
    imageStore(colorimg2, p, vec4(imageSize(colorimg0), 0.0, 1.0));
}
";

    #[test]
    fn a_compute_stage_with_images_samplers_uniforms_and_shared_memory_validates() {
        if let Err(e) = compute(VALID) {
            panic!("{e:?}");
        }
    }

    #[test]
    fn sampling_outside_fragment_stages_reads_the_base_level() {
        let text = "#version 430\nlayout(local_size_x = 8) in;\nuniform sampler2D colortex3;\nuniform sampler2DShadow shadowtex0;\n\
                    layout(rgba8) uniform image2D colorimg1;\nvoid main() {\n\
                    vec4 c = texture(colortex3, vec2(0.5)) + texture2D(colortex3, vec2(texture(colortex3, vec2(0.1)).r));\n\
                    float s = shadow2D(shadowtex0, vec3(0.5)).r + texture(shadowtex0, vec3(0.2));\n\
                    imageStore(colorimg1, ivec2(0), c * s);\n}\n";
        if let Err(e) = compute(text) {
            panic!("{e:?}");
        }
        let files: HashMap<String, Arc<str>> = [
            ("a.vsh".to_string(), Arc::from("#version 120\nuniform sampler2D noisetex;\nvoid main() { gl_Position = ftransform() + texture2D(noisetex, vec2(0.5)); }\n")),
        ]
        .into();
        let pre = preprocess(&files, "a.vsh", &PreprocessOptions::default()).unwrap();
        let stages = lower_program(&[(Stage::Vertex, Arc::new(pre))]).unwrap();
        assert!(stages[0].lowered.text.contains("textureLod(sampler2D(noisetex, tp_sampler_noisetex), vec2(0.5), 0.0)"), "{}", stages[0].lowered.text);
        if let Err(e) = validate_stage(&mut Frontend::default(), &stages[0], &files) {
            panic!("{e:?}");
        }
    }

    #[test]
    fn a_type_error_in_a_compute_stage_is_located() {
        let text = VALID.replace("    vec4 c = imageLoad", "    float bad = vec3(1.0);\n    vec4 c = imageLoad");
        let errors = compute(&text).unwrap_err();
        assert!(errors.iter().any(|e| e.location.as_ref().is_some_and(|l| l.line == 18)), "{errors:?}");
    }
}
