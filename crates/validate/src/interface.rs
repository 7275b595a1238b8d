//! Checks across a program's stages and against the loader: vertex outputs against fragment
//! inputs, the render-target directive against the outputs written, and uniform and sampler
//! names against what OptiFine sets.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use tidepack_glsl::lower::{self, ResourceKind, VaryingDecl};
use tidepack_glsl::preprocess::Preprocessed;
use tidepack_glsl::token::{Token, TokenKind, argument_qualifiers, brace_depths, tokenize};
use tidepack_glsl::naga_check::LoweredStage;
use tidepack_glsl::{Code, Diagnostic, Drivers, Location, Stage};

use tidepack_loader::known;
use tidepack_loader::loader::Loader;
use tidepack_loader::directives::CustomNames;

fn version_of(pre: &Preprocessed) -> u32 {
    pre.version.as_ref().map_or(110, |v| v.number)
}

/// Identifiers a text reads as globals: name → first line. A name declared again as a local or
/// parameter means that local inside its block or function, so those uses are not counted;
/// nor are global declarations, or fields after `.`.
fn global_uses(text: &str) -> HashMap<&str, u32> {
    let tokens = tokenize(text).unwrap_or_default();
    let sig: Vec<_> = tokens.iter().filter(|t| !t.is_trivia() && !t.is_punct("#")).collect();
    let mut uses: HashMap<&str, u32> = HashMap::new();
    // Names declared inside functions, with the brace depth their scope closes below.
    let mut shadows: Vec<(&str, u32)> = Vec::new();
    let (mut depth, mut parens) = (0u32, 0u32);
    for (k, t) in sig.iter().enumerate() {
        match t.text {
            "{" => depth += 1,
            "}" => {
                depth = depth.saturating_sub(1);
                shadows.retain(|&(_, scope)| scope <= depth);
            }
            "(" => parens += 1,
            ")" => parens = parens.saturating_sub(1),
            // A prototype's parameters have no body.
            ";" if depth == 0 => shadows.clear(),
            _ => {}
        }
        if t.kind != TokenKind::Ident {
            continue;
        }
        let previous = k.checked_sub(1).map(|p| sig[p]);
        let declared = previous.is_some_and(|p| {
            p.kind == TokenKind::Ident && !lower::is_statement_keyword(p.text)
        });
        if declared {
            if depth > 0 {
                shadows.push((t.text, depth));
            } else if parens > 0 {
                // A parameter: its scope is the function body that follows.
                shadows.push((t.text, 1));
            }
            continue;
        }
        if previous.is_some_and(|p| p.is_punct(".")) || shadows.iter().any(|&(name, _)| name == t.text) {
            continue;
        }
        uses.entry(t.text).or_insert(t.line);
    }
    uses
}

/// The components of the global `name` that `sig` (a stage's significant tokens) writes and reads, as bit masks (bit 0 for
/// `x`), given `all` for the variable's every component, and the line of the first read of
/// each component: a swizzled assignment (`texcoord.st = …`) writes its components, a plain one
/// all of them; any other use reads what it names. Where the text does not tell, writes are
/// taken wide and reads narrow, so that no read is found unwritten wrongly: an argument (maybe
/// an `out` parameter) writes every component, an element (`v[i]`) writes every one and reads
/// none, and a local of that name makes every component written and none read.
fn component_uses(sig: &[&Token], name: &str, all: u8) -> (u8, u8, [Option<u32>; 4]) {
    let (mut written, mut read) = (0u8, 0u8);
    let mut first_read = [None; 4];
    let mut depth = 0u32;
    for (k, t) in sig.iter().enumerate() {
        match t.text {
            "{" => depth += 1,
            "}" => depth = depth.saturating_sub(1),
            _ => {}
        }
        if !t.is_ident(name) || k.checked_sub(1).is_some_and(|p| sig[p].is_punct(".")) {
            continue;
        }
        let previous = k.checked_sub(1).map(|p| sig[p]);
        let declaration = previous.is_some_and(|p| p.kind == TokenKind::Ident && !lower::is_statement_keyword(p.text));
        if declaration && depth > 0 {
            return (all, 0, [None; 4]);
        }
        if declaration {
            continue;
        }
        let swizzle = match (sig.get(k + 1), sig.get(k + 2)) {
            (Some(dot), Some(s)) if dot.is_punct(".") => components(s.text),
            _ => None,
        };
        let after = sig.get(if swizzle.is_some() { k + 3 } else { k + 1 }).map_or("", |a| a.text);
        let argument = previous.is_some_and(|p| p.is_punct("(") || p.is_punct(",")) && matches!(after, ")" | ",");
        if after == "[" {
            written = all;
            continue;
        }
        if argument {
            written = all;
        }
        let mask = swizzle.unwrap_or(all);
        // `=` writes; `+=` and the like, `++` and `--` write what they read.
        let compound = matches!(after, "+=" | "-=" | "*=" | "/=" | "%=" | "&=" | "|=" | "^=" | "<<=" | ">>=" | "++" | "--");
        if after == "=" || compound {
            written |= mask;
        }
        if after != "=" {
            read |= mask;
            for (c, first) in first_read.iter_mut().enumerate() {
                if mask & (1 << c) != 0 && first.is_none() {
                    *first = Some(t.line);
                }
            }
        }
    }
    (written, read, first_read)
}

/// Every component of a varying of type `ty`, as a bit mask: one per component of a vector,
/// one for a scalar, four for what has no swizzle of its own (a matrix).
fn component_mask(ty: &str) -> u8 {
    let vector = ["vec", "ivec", "uvec", "bvec", "dvec"].iter().find_map(|prefix| ty.strip_prefix(prefix)).and_then(|n| n.parse::<u32>().ok());
    match vector {
        Some(n @ 2..=4) => (1u8 << n) - 1,
        _ if matches!(ty, "float" | "int" | "uint" | "bool" | "double") => 1,
        _ => 0b1111,
    }
}

/// The components a swizzle names, as a bit mask (bit 0 for `x`, `r` or `s`); None for a word
/// that is no swizzle.
fn components(swizzle: &str) -> Option<u8> {
    let sets = ["xyzw", "rgba", "stpq"];
    let set = sets.iter().find(|set| swizzle.chars().all(|c| set.contains(c)))?;
    (1..=4).contains(&swizzle.len()).then(|| swizzle.chars().fold(0u8, |mask, c| mask | 1 << set.find(c).unwrap_or(0)))
}

/// The components of `mask` as a swizzle (`xy`).
fn swizzle_of(mask: u8) -> String {
    "xyzw".chars().enumerate().filter(|(i, _)| mask & (1 << i) != 0).map(|(_, c)| c).collect()
}

fn describe(decl: &VaryingDecl) -> String {
    match decl.array {
        Some(n) => format!("{}{} {}[{n}]", decl.interpolation, decl.ty, decl.name),
        None => format!("{}{} {}", decl.interpolation, decl.ty, decl.name),
    }
}

/// A fragment input the vertex stage declares and never writes, read in GLSL 1.10/1.20: Mesa
/// refuses to link the program if the read survives its optimiser, which only the stage's IR
/// can tell ([`tidepack_glsl::liveness`]).
pub struct NeverWritten {
    pub input: String,
    /// What to report when the read reaches the stage's results.
    pub refused: Diagnostic,
    /// What to report when that cannot be told (naga does not read the stage).
    pub unknown: Diagnostic,
}

/// Fragment inputs the vertex stage does not write, or writes with another type; and the
/// inputs whose verdict waits for the fragment stage's IR.
pub fn check_varyings(vertex: &Preprocessed, fragment: &Preprocessed) -> (Vec<Diagnostic>, Vec<NeverWritten>) {
    let (Ok(outputs), Ok(inputs)) = (
        lower::varying_declarations(&vertex.text, Stage::Vertex, version_of(vertex)),
        lower::varying_declarations(&fragment.text, Stage::Fragment, version_of(fragment)),
    ) else {
        return (Vec::new(), Vec::new());
    };
    // `in vec4 gl_FragCoord;` (a layout qualifier given to a built-in) redeclares a built-in:
    // the stages do not pass it to each other.
    let built_in = |d: &&VaryingDecl| d.name.starts_with("gl_");
    let outputs: BTreeMap<&str, &VaryingDecl> = outputs.iter().filter(|d| !built_in(d)).map(|d| (d.name.as_str(), d)).collect();
    let inputs: Vec<&VaryingDecl> = inputs.iter().filter(|d| !built_in(d)).collect();
    let uses = global_uses(&fragment.text);
    let vertex_uses = global_uses(&vertex.text);
    let vertex_path = vertex.files.first().cloned().unwrap_or_default();
    // Mesa's linker (like the GLSL 4.20 specification) refuses a statically read input that
    // the vertex stage does not declare in GLSL 1.10/1.20 and from 4.20 on, by the higher
    // `#version` of the two; from 1.30 to 4.10 it links the program.
    let version = version_of(vertex).max(version_of(fragment));
    let mesa_links = (130..420).contains(&version);
    let (vertex_tokens, fragment_tokens) = (tokenize(&vertex.text).unwrap_or_default(), tokenize(&fragment.text).unwrap_or_default());
    let vertex_sig: Vec<&Token> = vertex_tokens.iter().filter(|t| !t.is_trivia()).collect();
    let fragment_sig: Vec<&Token> = fragment_tokens.iter().filter(|t| !t.is_trivia()).collect();
    // Of an input the fragment stage reads: the components the vertex stage writes, those the
    // fragment stage reads and the vertex stage never writes, and the line of the first such read.
    let unwritten_read = |output: &VaryingDecl, input: &VaryingDecl| {
        let all = component_mask(&input.ty);
        let written = if vertex_uses.contains_key(output.name.as_str()) { component_uses(&vertex_sig, &output.name, all).0 } else { 0 };
        let (_, read, first_read) = component_uses(&fragment_sig, &input.name, all);
        let unwritten = read & !written;
        let line = (0..4).filter(|c| unwritten & (1 << c) != 0).filter_map(|c| first_read[c]).min();
        (written, unwritten, line)
    };
    let mut found = Vec::new();
    let mut never_written = Vec::new();
    for input in inputs {
        let at = fragment.location(input.line);
        let output = outputs.get(input.name.as_str());
        let (written, unwritten, first_unwritten_read) = match output {
            Some(output) if uses.contains_key(input.name.as_str()) => unwritten_read(output, input),
            _ => (0, 0, None),
        };
        match output {
            None => {
                // Only a statically read input must be declared by the vertex stage.
                let Some(&read_at) = uses.get(input.name.as_str()) else { continue };
                let declare =
                    format!("declare `varying {} {};` (or `out`) in the vertex shader and write it", input.ty, input.name);
                if mesa_links {
                    found.push(
                        Diagnostic::warning(
                            Code::InputUndeclared,
                            format!(
                                "fragment input `{}` is read at {} but {vertex_path} does not declare it: GLSL wants every input that is read written by the previous stage (stated as a link error from GLSL 4.20 on); Mesa links it under #version {version} (it refuses it only from 4.20 and in 1.10/1.20), stricter drivers may not",
                                input.name,
                                crate::glsl_rules::place(fragment, read_at),
                            ),
                            at,
                        )
                        .with_note(declare),
                    );
                } else {
                    found.push(
                        Diagnostic::error(
                            Code::Link,
                            format!("fragment input `{}` is not an output of {vertex_path}: the program fails to link", input.name),
                            at,
                        )
                        .with_note(declare),
                    );
                }
            }
            Some(output) if unwritten != 0 => {
                // Declared, never written (or written in other components than are read). Mesa's
                // linker refuses the read in GLSL 1.10/1.20 ("fragment shader varying … not
                // written by vertex shader") when its optimiser keeps the read; from 1.30 on it
                // links.
                let out_at = vertex.location(output.line).map_or(vertex_path.clone(), |l| l.to_string());
                let never = if written == 0 {
                    format!("fragment input `{}` is read, but the vertex shader never writes it (declared at {out_at})", input.name)
                } else {
                    format!(
                        "fragment input `{}` is read in `.{}`, which the vertex shader never writes (it writes `.{}` only; declared at {out_at})",
                        input.name,
                        swizzle_of(unwritten),
                        swizzle_of(written)
                    )
                };
                if version <= 120 {
                    let read_at = first_unwritten_read.or(uses.get(input.name.as_str()).copied()).and_then(|line| fragment.location(line)).or_else(|| at.clone());
                    never_written.push(NeverWritten {
                        input: input.name.clone(),
                        refused: Diagnostic::error(
                            Code::InputNeverWritten,
                            format!("{never}, and the value read here reaches the shader's outputs: the program fails to link on Mesa in #version {version}"),
                            read_at,
                        )
                        .refused_by(Drivers::MESA)
                        .with_note(format!("write `{}` in the vertex shader, or stop reading it", input.name)),
                        unknown: Diagnostic::warning(
                            Code::InputNeverWritten,
                            format!("{never}: Mesa refuses to link it in #version {version} where the read is not optimised away"),
                            at,
                        ),
                    });
                } else {
                    found.push(Diagnostic::warning(Code::InputNeverWritten, format!("{never}: it reads undefined values"), at));
                }
            }
            Some(output) => {
                // From GLSL 4.30 on only the fragment stage's interpolation qualifier counts.
                let flat = |d: &VaryingDecl| d.interpolation.contains("flat");
                let qualifiers_must_match = version_of(vertex).min(version_of(fragment)) < 430;
                if output.ty != input.ty || output.array != input.array || (qualifiers_must_match && flat(output) != flat(input)) {
                    let out_at = vertex.location(output.line).map_or(vertex_path.clone(), |l| l.to_string());
                    found.push(Diagnostic::error(
                        Code::Link,
                        format!(
                            "`{}` here does not match `{}` at {out_at}: the program fails to link",
                            describe(input),
                            describe(output)
                        ),
                        at,
                    ));
                }
            }
        }
    }
    found.extend(check_blocks(vertex, fragment, &uses));
    (found, never_written)
}

/// A member of an `in`/`out` interface block: its qualifiers (`flat`, `centroid`, …), type,
/// name and array suffix as written.
#[derive(PartialEq, Eq)]
struct BlockMember {
    qualifiers: Vec<String>,
    ty: String,
    name: String,
    array: String,
}

impl BlockMember {
    fn describe(&self) -> String {
        let qualifiers: String = self.qualifiers.iter().map(|q| format!("{q} ")).collect();
        format!("{qualifiers}{} {}{}", self.ty, self.name, self.array)
    }
}

/// An `in` or `out` interface block of a stage.
struct Block {
    name: String,
    /// The instance name, if any (members are globals without one).
    instance: Option<String>,
    line: u32,
    members: Vec<BlockMember>,
}

/// The interface blocks of `direction` (`in` or `out`) a stage declares.
fn interface_blocks(text: &str, direction: &str) -> Vec<Block> {
    let tokens = tokenize(text).unwrap_or_default();
    let sig: Vec<_> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    let depths = brace_depths(&sig);
    let mut blocks = Vec::new();
    for k in 0..sig.len() {
        if depths[k] != 0
            || sig[k].text != direction
            || !sig.get(k + 1).is_some_and(|t| t.kind == TokenKind::Ident)
            || !sig.get(k + 2).is_some_and(|t| t.is_punct("{"))
        {
            continue;
        }
        let mut members = Vec::new();
        let mut words: Vec<&str> = Vec::new();
        let mut j = k + 3;
        while let Some(t) = sig.get(j) {
            j += 1;
            match t.text {
                "}" => break,
                ";" | "," => {
                    // `[qualifiers] type name[size]`; after a `,` the next declarator shares them.
                    let array_at = words.iter().position(|w| *w == "[").unwrap_or(words.len());
                    if array_at >= 2 {
                        let (head, array) = words.split_at(array_at);
                        let (name, head) = head.split_last().expect("two words");
                        let (ty, qualifiers) = head.split_last().expect("one word");
                        members.push(BlockMember {
                            qualifiers: qualifiers.iter().map(|q| q.to_string()).collect(),
                            ty: ty.to_string(),
                            name: name.to_string(),
                            array: array.concat(),
                        });
                        words = if t.text == "," { head.to_vec() } else { Vec::new() };
                    } else {
                        words.clear();
                    }
                }
                w => words.push(w),
            }
        }
        let instance = sig.get(j).filter(|t| t.kind == TokenKind::Ident).map(|t| t.text.to_string());
        blocks.push(Block { name: sig[k + 1].text.to_string(), instance, line: sig[k].line, members });
    }
    blocks
}

/// Fragment input blocks against the vertex stage's output blocks of the same name: GLSL
/// matches blocks by name, and their members must agree in order, name, type and (before GLSL
/// 4.40) interpolation; a block the fragment stage uses must be an output of the vertex stage.
fn check_blocks(vertex: &Preprocessed, fragment: &Preprocessed, uses: &HashMap<&str, u32>) -> Vec<Diagnostic> {
    let outputs = interface_blocks(&vertex.text, "out");
    let vertex_path = vertex.files.first().cloned().unwrap_or_default();
    let version = version_of(vertex).max(version_of(fragment));
    // Mesa compares `centroid` and `sample` always, the interpolation only before 4.40.
    let counted = |m: &BlockMember| -> Vec<String> {
        m.qualifiers
            .iter()
            .filter(|q| matches!(q.as_str(), "centroid" | "sample") || (version < 440 && matches!(q.as_str(), "flat" | "smooth" | "noperspective")))
            .cloned()
            .collect()
    };
    let mut found = Vec::new();
    for input in interface_blocks(&fragment.text, "in") {
        let at = fragment.location(input.line);
        let Some(output) = outputs.iter().find(|b| b.name == input.name) else {
            let used = match &input.instance {
                Some(instance) => uses.contains_key(instance.as_str()),
                None => input.members.iter().any(|m| uses.contains_key(m.name.as_str())),
            };
            if used {
                found.push(Diagnostic::error(
                    Code::Link,
                    format!("input block `{}` is not an output block of {vertex_path}: the program fails to link", input.name),
                    at,
                ));
            }
            continue;
        };
        let out_at = vertex.location(output.line).map_or(vertex_path.clone(), |l| l.to_string());
        let mismatch = (0..input.members.len().max(output.members.len())).find_map(|i| {
            match (input.members.get(i), output.members.get(i)) {
                (Some(a), Some(b)) if a.ty == b.ty && a.name == b.name && a.array == b.array && counted(a) == counted(b) => None,
                (Some(a), Some(b)) => Some(format!("member {} is `{}` here and `{}` there", i + 1, a.describe(), b.describe())),
                (Some(a), None) => Some(format!("`{}` is missing there", a.describe())),
                (None, Some(b)) => Some(format!("`{}` is missing here", b.describe())),
                (None, None) => None,
            }
        });
        if let Some(mismatch) = mismatch {
            found.push(Diagnostic::error(
                Code::Link,
                format!("block `{}` here does not match its declaration at {out_at} ({mismatch}): the program fails to link", input.name),
                at,
            ));
        }
    }
    found
}

/// The first line of `pre` where `needle` (a token sequence such as `gl_FragData [ 1 ]`) is
/// assigned to (`=`, `+=`, …, possibly through a swizzle or index), if any.
/// The line of the first write of the output `needle`: an assignment, or an argument given to an
/// `out` or `inout` parameter of a function the stage defines.
fn first_write_of(pre: &Preprocessed, needle: &[&str]) -> Option<u32> {
    let tokens = tokenize(&pre.text).ok()?;
    let sig: Vec<_> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    (0..sig.len().saturating_sub(needle.len() - 1)).find_map(|k| {
        if !sig[k..k + needle.len()].iter().zip(needle).all(|(t, n)| t.text == *n) {
            return None;
        }
        let mut j = k + needle.len();
        // A swizzle (`.rgb`) or index (`[0]`) between the output and the operator.
        loop {
            match sig.get(j).map(|t| t.text) {
                Some(".") => j += 2,
                Some("[") => j = (j..sig.len()).find(|&m| sig[m].is_punct("]"))? + 1,
                _ => break,
            }
        }
        let op = sig.get(j)?.text;
        let assigned = matches!(op, "=" | "+=" | "-=" | "*=" | "/=" | "++" | "--");
        let argument = matches!(op, "," | ")") && k > 0 && matches!(sig[k - 1].text, "(" | ",");
        (assigned || (argument && passed_to_out_parameter(&sig, k))).then_some(sig[k].line)
    })
}

/// Whether the argument starting at `sig[at]` goes to an `out` or `inout` parameter of the
/// function called there, as the stage defines it.
fn passed_to_out_parameter(sig: &[&Token<'_>], at: usize) -> bool {
    argument_qualifiers(sig, at).is_some_and(|qualifiers| qualifiers.iter().any(|q| matches!(*q, "out" | "inout")))
}

fn output_tokens(shipped: &str) -> Vec<&str> {
    match shipped.strip_prefix("gl_FragData[") {
        Some(index) => vec!["gl_FragData", "[", index.trim_end_matches(']'), "]"],
        None => vec![shipped],
    }
}

/// `DRAWBUFFERS`/`RENDERTARGETS` against the outputs the fragment stage writes.
pub fn check_render_targets(fragment: &Preprocessed, lowered: &LoweredStage) -> Vec<Diagnostic> {
    let Some(targets) = &fragment.render_targets else { return Vec::new() };
    let directive_at = Location::line(fragment.files[targets.line.file as usize].clone(), targets.line.line);
    let name = if targets.modern { "RENDERTARGETS" } else { "DRAWBUFFERS" };
    let listed: Vec<String> = targets.buffers.iter().map(|b| b.map_or_else(|| "N".to_string(), |b| b.to_string())).collect();
    let shown = if targets.modern { format!("/* RENDERTARGETS: {} */", listed.join(",")) } else { format!("/* DRAWBUFFERS:{} */", listed.join("")) };
    let mut found = Vec::new();
    let mut seen = BTreeSet::new();
    for b in targets.buffers.iter().flatten() {
        if !seen.insert(b) {
            found.push(Diagnostic::error(
                Code::DrawBuffers,
                format!("{shown} lists buffer {b} twice: glDrawBuffers refuses the list and the program draws nothing"),
                Some(directive_at.clone()),
            ));
        }
    }
    let outputs = &lowered.lowered.interface.outputs;
    let count = targets.buffers.len() as u32;
    // Outputs the shader assigns to (reading one is not writing it), with the line.
    let written: BTreeMap<u32, u32> = outputs
        .iter()
        .filter_map(|(location, shipped)| Some((*location, first_write_of(fragment, &output_tokens(shipped))?)))
        .collect();
    for (location, line) in &written {
        if *location >= count {
            let shipped = &outputs[location];
            let at = fragment.location(*line).or(Some(directive_at.clone()));
            // OptiFine runs the program; the driver drops the value. Almost always a mistake
            // (a buffer missing from the list), but not a failure: a warning.
            found.push(
                Diagnostic::warning(
                    Code::DrawBuffers,
                    format!("`{shipped}` is written but {shown} lists {count} buffer{}: the value goes nowhere", if count == 1 { "" } else { "s" }),
                    at,
                )
                .with_note(format!("the {name} directive is at {directive_at}")),
            );
        }
    }
    let broadcast = outputs.values().any(|s| s == "gl_FragColor");
    if !broadcast {
        for (i, buffer) in targets.buffers.iter().enumerate() {
            let Some(buffer) = buffer else { continue };
            if !written.contains_key(&(i as u32)) {
                let output = if targets.modern { format!("outColor{i}") } else { format!("gl_FragData[{i}]") };
                found.push(Diagnostic::warning(
                    Code::DrawBuffers,
                    format!("{shown} lists buffer {buffer} as output {i}, but `{output}` is never written: the buffer gets undefined values"),
                    Some(directive_at.clone()),
                ));
            }
        }
    }
    found
}

/// Line of the `uniform` declaration of `name` in `pre`.
fn uniform_line(pre: &Preprocessed, name: &str) -> Option<u32> {
    let tokens = tokenize(&pre.text).ok()?;
    let mut line_has_uniform = 0;
    for t in &tokens {
        if t.is_ident("uniform") {
            line_has_uniform = t.line;
        } else if t.kind == TokenKind::Ident && t.text == name && t.line == line_has_uniform {
            return Some(t.line);
        }
    }
    None
}

/// Uniforms and samplers `loader` does not set, and known uniforms declared with another type.
pub fn check_resources(pre: &Preprocessed, lowered: &lower::Lowered, program: &str, names: &CustomNames, loader: Loader) -> Vec<Diagnostic> {
    let who = known::loader_name(loader);
    let mut found = Vec::new();
    for name in lowered.interface.images.keys() {
        if !known::is_image(name) && !names.images.contains(name) {
            let at = uniform_line(pre, name).and_then(|l| pre.location(l));
            found.push(Diagnostic::warning(
                Code::UnknownImage,
                format!(
                    "`{name}` is not an image OptiFine binds (colorimg0-15, shadowcolorimg0-1) nor an `image.{name}` of shaders.properties: nothing is bound to it"
                ),
                at,
            ));
        }
    }
    for (name, kind) in &lowered.interface.resources {
        if name.starts_with("gl_") {
            continue;
        }
        let at = || uniform_line(pre, name).and_then(|l| pre.location(l));
        match kind {
            ResourceKind::Texture { .. } => {
                if !known::is_sampler_for(name, loader) && !names.samplers.contains(name) {
                    found.push(Diagnostic::warning(
                        Code::UnknownSampler,
                        format!("`{name}` is not a sampler {who} binds: it silently reads texture unit 0"),
                        at(),
                    ));
                } else if let Some(why) = known::sampler_unavailable(program, name) {
                    found.push(Diagnostic::warning(Code::UnknownSampler, format!("`{name}` in {program}: {why}"), at()));
                }
            }
            ResourceKind::Uniform { ty } => {
                if let Some(custom) = names.uniforms.get(name) {
                    if custom != ty {
                        found.push(Diagnostic::warning(
                            Code::UniformType,
                            format!("`{name}` is declared `{ty}` but shaders.properties defines it as `{custom}`"),
                            at(),
                        ));
                    }
                } else if let Some(expected) = known::uniform_type_for(name, loader) {
                    // glUniform1i sets a bool uniform, and an int one where the loader sets a bool.
                    if expected != ty && !(matches!((expected, ty.as_str()), ("int", "bool") | ("bool", "int"))) {
                        found.push(Diagnostic::warning(
                            Code::UniformType,
                            format!("`{name}` is declared `{ty}` but {who} sets it as `{expected}`: it is never set"),
                            at(),
                        ));
                    }
                } else {
                    found.push(Diagnostic::warning(
                        Code::UnknownUniform,
                        format!("`{name}` is not a uniform {who} sets: it silently reads 0"),
                        at(),
                    ));
                }
            }
        }
    }
    found
}
