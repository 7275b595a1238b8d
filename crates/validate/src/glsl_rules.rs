//! What GLSL requires of a stage that naga does not check, or checks only in its own words.
//! Each rule is an error Mesa gives (its wording quoted in the message), found on the tokens of
//! the preprocessed text:
//! - a reserved word used as a name (`output`, `input`, `class`, …; `common`, `filter`, … from
//!   GLSL 1.30);
//! - a function with a return type and no `return` anywhere in its body;
//! - a fragment shader writing both `gl_FragData`/`gl_FragColor` and `out` variables of its own;
//! - an assignment to a shader input (`in`, `varying`, `attribute`);
//! - texture2D & co. on a `sampler2DShadow` or an integer sampler, shadow2D & co. on a `sampler2D`;
//! - and, as a warning (drivers compile it, each to its own value), a local variable that is
//!   read but never assigned.

use std::collections::{BTreeMap, BTreeSet};

use tidepack_glsl::compat::{RESERVED, RESERVED_FROM_130};
use tidepack_glsl::preprocess::Preprocessed;
use tidepack_glsl::token::{Token, TokenKind, function_definitions};
use tidepack_glsl::{Code, Diagnostic, Drivers, Stage};

/// Lookups that take a `sampler2D`, and the `sampler2DShadow` form of each.
const COLOUR_LOOKUPS: [(&str, &str); 4] =
    [("texture2D", "shadow2D"), ("texture2DLod", "shadow2DLod"), ("texture2DProj", "shadow2DProj"), ("texture2DProjLod", "shadow2DProjLod")];

/// Assignment operators.
const ASSIGNMENTS: [&str; 11] = ["=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<=", ">>="];

/// Errors a driver gives for the stage that naga does not give in GLSL terms.
pub fn check(pre: &Preprocessed, tokens: &[Token], stage: Stage) -> Vec<Diagnostic> {
    let sig: Vec<&Token> = code_tokens(tokens);
    let version = pre.version.as_ref().map_or(110, |v| v.number);
    let globals = Globals::read(&sig, stage);
    // What these rules name, NVIDIA's compiler lets by (reported on pack trackers as "works on
    // NVIDIA only"); a syntax error every compiler refuses.
    let mut found = Vec::new();
    found.extend(reserved_words(pre, &sig, version));
    found.extend(missing_returns(pre, &sig));
    found.extend(input_writes(pre, &sig, &globals, stage));
    found.extend(shadow_lookups(pre, &sig, &globals));
    if stage == Stage::Fragment {
        found.extend(mixed_outputs(pre, &sig, &globals));
    }
    found.extend(never_assigned_locals(pre, &sig));
    let mut found: Vec<Diagnostic> =
        found.into_iter().map(|d| if d.is_error() { d.refused_by(Drivers::ALL_BUT_NVIDIA) } else { d }).collect();
    found.extend(empty_operands_after_commas(pre, &sig));
    found
}

/// A `,` or an assignment with nothing after it before `;`, `,` or `)` (`f(a, )`,
/// `float a = ;`): a syntax error every compiler reports (Mesa: "syntax error, unexpected
/// ';'"). naga's parser lets the comma by and reports the other in terms of its IR. An option
/// value with a stray comma in its list (`// [.0, .2 .4]`) substitutes one.
fn empty_operands_after_commas(pre: &Preprocessed, sig: &[&Token]) -> Vec<Diagnostic> {
    const ASSIGNMENTS: [&str; 11] = ["=", "+=", "-=", "*=", "/=", "%=", "<<=", ">>=", "&=", "|=", "^="];
    let mut found = Vec::new();
    let mut lines = std::collections::BTreeSet::new();
    for pair in sig.windows(2) {
        let (before, after) = (pair[0], pair[1]);
        let comma = before.is_punct(",") && (after.is_punct(";") || after.is_punct(")"));
        let assignment = ASSIGNMENTS.iter().any(|op| before.is_punct(op)) && [";", ",", ")"].iter().any(|p| after.is_punct(p));
        if (comma || assignment) && lines.insert(before.line) {
            let what = if comma { "`,` with no expression after it" } else { "an assignment with no value" };
            found.push(Diagnostic::error(
                Code::Syntax,
                format!("{what}, before `{}`: a syntax error (Mesa: \"syntax error, unexpected '{}'\")", after.text, after.text),
                pre.location(before.line),
            ));
        }
    }
    found
}

/// Where line `line` of the preprocessed text comes from, as `file:line` of the pack.
pub(crate) fn place(pre: &Preprocessed, line: u32) -> String {
    pre.location(line).map_or_else(|| format!("line {line}"), |l| format!("{}:{}", l.path, l.line))
}

/// The tokens of the code: no trivia, no preprocessor directive lines.
pub(crate) fn code_tokens<'t, 'a>(tokens: &'t [Token<'a>]) -> Vec<&'t Token<'a>> {
    let mut code = Vec::new();
    let mut directive_line = None;
    let mut line_start = true;
    for t in tokens {
        if t.kind == TokenKind::Newline {
            line_start = true;
            continue;
        }
        if t.is_trivia() {
            continue;
        }
        if line_start && t.is_punct("#") {
            directive_line = Some(t.line);
        }
        line_start = false;
        if directive_line != Some(t.line) {
            code.push(t);
        }
    }
    code
}

/// The global variables that matter to the rules: inputs, uniforms, `out` variables and
/// samplers, by name, with the line each is declared at.
#[derive(Default)]
pub(crate) struct Globals<'a> {
    pub(crate) inputs: BTreeMap<&'a str, u32>,
    pub(crate) uniforms: BTreeMap<&'a str, u32>,
    outputs: BTreeMap<&'a str, u32>,
    /// Sampler name → (type, line).
    pub(crate) samplers: BTreeMap<&'a str, (&'a str, u32)>,
}

impl<'a> Globals<'a> {
    pub(crate) fn read(sig: &[&Token<'a>], stage: Stage) -> Globals<'a> {
        let mut globals = Globals::default();
        let mut depth = 0i32;
        let mut statement_start = true;
        for (k, t) in sig.iter().enumerate() {
            if depth == 0 && statement_start && let Some(end) = declaration_end(sig, k) {
                globals.declaration(&sig[k..end], stage);
            }
            match t.text {
                "{" => depth += 1,
                "}" => depth -= 1,
                _ => {}
            }
            statement_start = matches!(t.text, ";" | "{" | "}");
        }
        globals
    }

    /// One global declaration without its `;`: `uniform sampler2D a, b`, `varying vec2 uv`,
    /// `layout(location = 0) out vec4 colour`. A vertex shader's inputs are `in` and
    /// `attribute`, a fragment shader's `in` and `varying`.
    fn declaration(&mut self, words: &[&Token<'a>], stage: Stage) {
        let qualifiers: BTreeSet<&str> = words.iter().map(|t| t.text).collect();
        let input_qualifier = if stage == Stage::Vertex { "attribute" } else { "varying" };
        let is_input = qualifiers.contains("in") || qualifiers.contains(input_qualifier);
        let is_output = qualifiers.contains("out") || (stage == Stage::Vertex && qualifiers.contains("varying"));
        let sampler = words.iter().find(|t| ["sampler", "usampler", "isampler"].iter().any(|p| t.text.starts_with(p))).map(|t| t.text);
        for (i, t) in words.iter().enumerate() {
            // A name: an identifier after the type (an array type's `]` too: `vec3[9] names`) or
            // a `,`, before a `,`, `[`, `=` or the end; not the type of `vec3[9] names` itself.
            let next = words.get(i + 1).map(|n| n.text);
            let previous = i.checked_sub(1).map(|p| words[p]);
            let after_name = matches!(next, None | Some("," | "[" | "="));
            let after_type = previous.is_some_and(|p| p.kind == TokenKind::Ident || p.is_punct(",") || p.is_punct("]"));
            let array_type = next == Some("[")
                && words[i + 1..].iter().position(|w| w.is_punct("]")).and_then(|close| words.get(i + 2 + close)).is_some_and(|w| w.kind == TokenKind::Ident);
            if t.kind != TokenKind::Ident || !after_name || !after_type || array_type || is_inside_parens(words, i) {
                continue;
            }
            match (qualifiers.contains("uniform"), sampler) {
                (true, Some(ty)) => {
                    self.samplers.insert(t.text, (ty, t.line));
                }
                (true, None) => {
                    self.uniforms.insert(t.text, t.line);
                }
                _ if is_input && !is_output => {
                    self.inputs.insert(t.text, t.line);
                }
                _ if is_output => {
                    self.outputs.insert(t.text, t.line);
                }
                _ => {}
            }
        }
    }
}

/// Where the global declaration starting at token `k` ends (its `;`), or none for a function,
/// a struct or an interface block (a `(` not of `layout`, or a `{` first).
fn declaration_end(sig: &[&Token], k: usize) -> Option<usize> {
    let mut parens = 0i32;
    for e in k..sig.len() {
        match sig[e].text {
            "(" if parens == 0 && !(e > 0 && sig[e - 1].is_ident("layout")) => return None,
            "(" => parens += 1,
            ")" => parens -= 1,
            "{" => return None,
            ";" if parens == 0 => return Some(e),
            _ => {}
        }
    }
    None
}

/// Whether token `i` of `words` is inside parentheses (a `layout(…)` argument).
fn is_inside_parens(words: &[&Token], i: usize) -> bool {
    let mut depth = 0i32;
    for t in &words[..i] {
        match t.text {
            "(" => depth += 1,
            ")" => depth -= 1,
            _ => {}
        }
    }
    depth > 0
}

fn reserved_words(pre: &Preprocessed, sig: &[&Token], version: u32) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    // Each word once, at its first use, as drivers stop there.
    let mut reported = BTreeSet::new();
    for t in sig.iter().filter(|t| t.kind == TokenKind::Ident) {
        let reserved = RESERVED.contains(&t.text) || (version >= 130 && RESERVED_FROM_130.contains(&t.text));
        if reserved && reported.insert(t.text) {
            found.push(Diagnostic::error(
                Code::ReservedWord,
                format!(
                    "`{}` is a reserved word in GLSL {version} and cannot name anything (Mesa: \"illegal use of reserved word \
                     `{}'\"; glslang, which AMD's compiler follows, refuses it too); rename it",
                    t.text, t.text
                ),
                pre.location(t.line),
            ));
        }
    }
    found
}

fn missing_returns(pre: &Preprocessed, sig: &[&Token]) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    for function in function_definitions(sig) {
        let Some(return_type) = function.name.checked_sub(1).map(|k| sig[k]) else { continue };
        if return_type.is_ident("void") || return_type.kind != TokenKind::Ident {
            continue;
        }
        let body = &sig[function.open..function.close.min(sig.len())];
        if !body.iter().any(|t| t.is_ident("return")) {
            let name = sig[function.name].text;
            found.push(Diagnostic::error(
                Code::MissingReturn,
                format!(
                    "{name}() returns {} but its body has no `return` statement (Mesa: \"function `{name}' has non-void return \
                     type {}, but no return statement\"); return a value, or declare it `void`",
                    return_type.text, return_type.text
                ),
                pre.location(sig[function.name].line),
            ));
        }
    }
    found
}

/// Whether token `k` is written: the left side of an assignment (`uv =`, `uv.x +=`,
/// `a[i] =`), or the operand of `++`/`--`.
fn is_written(sig: &[&Token], k: usize) -> bool {
    if k > 0 && matches!(sig[k - 1].text, "++" | "--") {
        return true;
    }
    let mut j = k + 1;
    let mut brackets = 0i32;
    while let Some(t) = sig.get(j) {
        match t.text {
            "[" => brackets += 1,
            "]" => brackets -= 1,
            "." if brackets == 0 => {}
            _ if brackets > 0 => {}
            _ if t.kind == TokenKind::Ident && sig[j - 1].is_punct(".") => {}
            "++" | "--" => return true,
            op => return ASSIGNMENTS.contains(&op),
        }
        j += 1;
    }
    false
}

fn input_writes(pre: &Preprocessed, sig: &[&Token], globals: &Globals, stage: Stage) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    let mut reported = BTreeSet::new();
    for function in function_definitions(sig) {
        let parameters = parameter_names(sig, function.name);
        for k in function.open..function.close.min(sig.len()) {
            let t = sig[k];
            let member = k > 0 && sig[k - 1].is_punct(".");
            let Some(declared) = globals.inputs.get(t.text) else { continue };
            let shadowed = parameters.contains(t.text) || declared_locally(sig, function.open, k);
            if t.kind != TokenKind::Ident || member || shadowed || !is_written(sig, k) || !reported.insert(t.line) {
                continue;
            }
            let at = place(pre, *declared);
            let stage_name = if stage == Stage::Vertex { "vertex" } else { "fragment" };
            found.push(Diagnostic::error(
                Code::InputWritten,
                format!(
                    "`{}` is an input of this {stage_name} shader (declared at {at}) and inputs are read-only (Mesa: \"assignment \
                     to read-only variable '{}'\"); copy it into a local variable and change that",
                    t.text, t.text
                ),
                pre.location(t.line),
            ));
        }
    }
    found
}

/// The types a local declaration `T name;` can start with.
fn is_value_type(word: &str) -> bool {
    let sized = |prefix: &str| word.strip_prefix(prefix).is_some_and(|n| matches!(n, "2" | "3" | "4"));
    matches!(word, "float" | "int" | "uint" | "bool" | "double")
        || ["vec", "ivec", "uvec", "bvec", "dvec", "mat"].iter().any(|p| sized(p))
        || word.strip_prefix("mat").is_some_and(|n| matches!(n, "2x2" | "2x3" | "2x4" | "3x2" | "3x3" | "3x4" | "4x2" | "4x3" | "4x4"))
}

/// Locals declared without a value (`vec3 color;`) that the function reads and nothing in it
/// ever assigns: not assigned, incremented, or passed to a function (which may fill it through an
/// `out` parameter). Drivers compile the read and each gives its own value (often 0, on some
/// GPUs what the register held). A name any write touches is left alone, so branches and loops
/// cannot make this a false warning.
fn never_assigned_locals(pre: &Preprocessed, sig: &[&Token]) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    for function in function_definitions(sig) {
        let body = function.open + 1..function.close.min(sig.len());
        for k in body.clone() {
            let declares = sig[k].kind == TokenKind::Ident
                && is_value_type(sig[k - 1].text)
                && sig.get(k + 1).is_some_and(|t| t.is_punct(";"))
                && sig[k - 2].ends_statement();
            if !declares {
                continue;
            }
            let name = sig[k].text;
            let uses: Vec<usize> =
                body.clone().filter(|&j| j != k && sig[j].text == name && !(j > 0 && sig[j - 1].is_punct("."))).collect();
            let written = uses.iter().any(|&j| {
                let argument = matches!(sig[j - 1].text, "(" | ",") && sig.get(j + 1).is_some_and(|t| matches!(t.text, ")" | "," | "." | "["));
                is_written(sig, j) || argument
            });
            if let Some(&first) = uses.iter().find(|&&j| j > k).filter(|_| !written) {
                found.push(Diagnostic::warning(
                    Code::UninitialisedRead,
                    format!(
                        "`{name}` is read but nothing assigns it (declared `{} {name};` at {}): its value is undefined, and drivers \
                         differ in what they read; give it a value where it is declared",
                        sig[k - 1].text,
                        place(pre, sig[k].line)
                    ),
                    pre.location(sig[first].line),
                ));
            }
        }
    }
    found
}

/// Whether the name at token `k` is declared as a local variable there or since token `from`
/// (a type before it: `vec2 uv`).
fn declared_locally(sig: &[&Token], from: usize, k: usize) -> bool {
    (from + 1..=k).any(|j| sig[j].text == sig[k].text && sig[j - 1].kind == TokenKind::Ident && !sig[j - 1].is_ident("return"))
}

/// The parameter names of the function whose name is token `name`.
fn parameter_names<'a>(sig: &[&Token<'a>], name: usize) -> BTreeSet<&'a str> {
    let mut names = BTreeSet::new();
    let mut k = name + 2;
    while let Some(t) = sig.get(k) {
        if t.is_punct(")") {
            break;
        }
        if t.kind == TokenKind::Ident && sig.get(k + 1).is_some_and(|n| matches!(n.text, "," | ")" | "[")) {
            names.insert(t.text);
        }
        k += 1;
    }
    names
}

fn shadow_lookups(pre: &Preprocessed, sig: &[&Token], globals: &Globals) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    for (k, t) in sig.iter().enumerate() {
        let (Some(open), Some(argument)) = (sig.get(k + 1), sig.get(k + 2)) else { continue };
        if t.kind != TokenKind::Ident || !open.is_punct("(") || k > 0 && sig[k - 1].is_punct(".") {
            continue;
        }
        let Some(&(ty, declared)) = globals.samplers.get(argument.text) else { continue };
        let is_sampler_argument = sig.get(k + 3).is_some_and(|n| n.is_punct(","));
        let colour = COLOUR_LOOKUPS.iter().find(|(c, _)| *c == t.text);
        let shadow = COLOUR_LOOKUPS.iter().find(|(_, s)| *s == t.text);
        let problem = match (colour, shadow, ty) {
            (Some((lookup, shadow_form)), _, "sampler2DShadow") => Some((lookup, shadow_form, "a depth comparison")),
            (_, Some((colour_form, lookup)), "sampler2D") => Some((lookup, colour_form, "a colour lookup")),
            _ => None,
        };
        // The 1.20 lookups take float samplers only; NVIDIA reads an integer one anyway.
        let integer = ty.starts_with("usampler") || ty.starts_with("isampler");
        if integer && is_sampler_argument && let Some(modern) = tidepack_glsl::compat::modern_lookup(t.text) {
            let at = place(pre, declared);
            found.push(
                Diagnostic::error(
                    Code::NoMatchingOverload,
                    format!(
                        "no overload of {}() takes a {ty}: `{}` is declared `{ty}` at {at} (Mesa: \"no matching function for call to \
                         `{}'\"); an integer sampler is read with {modern}()",
                        t.text, argument.text, t.text
                    ),
                    pre.location(t.line),
                )
                .refused_by(Drivers::ALL.without(Drivers::NVIDIA)),
            );
        }
        if let (Some((lookup, other, what)), true) = (problem, is_sampler_argument) {
            let at = place(pre, declared);
            found.push(Diagnostic::error(
                Code::NoMatchingOverload,
                format!(
                    "no overload of {lookup}() takes a {ty}: `{}` is declared `{ty}` at {at} (Mesa: \"no matching function for \
                     call to `{lookup}'\"); use {other}() for {what}, or declare the sampler as the lookup needs",
                    argument.text
                ),
                pre.location(t.line),
            ));
        }
    }
    found
}

fn mixed_outputs(pre: &Preprocessed, sig: &[&Token], globals: &Globals) -> Vec<Diagnostic> {
    let mut builtin: Option<&Token> = None;
    let mut own: Option<&Token> = None;
    for function in function_definitions(sig) {
        for k in function.open..function.close.min(sig.len()) {
            let t = sig[k];
            if t.kind != TokenKind::Ident || k > 0 && sig[k - 1].is_punct(".") {
                continue;
            }
            if matches!(t.text, "gl_FragData" | "gl_FragColor") && builtin.is_none() && is_written(sig, k) {
                builtin = Some(t);
            } else if globals.outputs.contains_key(t.text) && own.is_none() && is_written(sig, k) {
                own = Some(t);
            }
        }
    }
    let (Some(builtin), Some(own)) = (builtin, own) else { return Vec::new() };
    let at = place(pre, own.line);
    vec![Diagnostic::error(
        Code::MixedOutputs,
        format!(
            "this fragment shader writes {} and its own output `{}` (at {at}): a shader writes either the built-in outputs or \
             `out` variables, never both (Mesa refuses it: \"fragment shader writes to both `{}' and `{}'\"; glslang does not \
             check it); write every buffer through one of the two",
            builtin.text, own.text, builtin.text, own.text
        ),
        pre.location(builtin.line),
    )]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn errors(src: &str, stage: Stage) -> Vec<String> {
        crate::version_rules::tests::found_by(check, src, stage)
    }

    #[test]
    fn reserved_words_cannot_name_anything() {
        let found = errors("#version 120\nvoid main() {\n vec4 output = vec4(1.0);\n float common = 1.0;\n gl_FragData[0] = output * common;\n}\n", Stage::Fragment);
        // `common` is reserved from GLSL 1.30 on; each word is reported at its first use.
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].starts_with("3: `output` is a reserved word in GLSL 120"), "{found:?}");
        let found = errors("#version 330\nout vec4 c;\nvoid main() { float common = 1.0; c = vec4(common); }\n", Stage::Fragment);
        assert!(found.len() == 1 && found[0].starts_with("3: `common`"), "{found:?}");
    }

    #[test]
    fn a_function_with_a_type_needs_a_return() {
        let src = "#version 120\nfloat f(float x) {\n if (x > 0.0) return x;\n}\nfloat g(float x) {\n x += 1.0;\n}\nvoid main() { gl_FragData[0] = vec4(f(1.0) + g(1.0)); }\n";
        let found = errors(src, Stage::Fragment);
        assert!(found.len() == 1 && found[0].starts_with("5: g() returns float but its body has no `return`"), "{found:?}");
    }

    #[test]
    fn inputs_are_read_only() {
        let src = "#version 120\nvarying vec2 uv;\nvarying vec3 n;\nvoid main() {\n uv.x = 1.0;\n n *= 2.0;\n vec2 local = uv;\n gl_FragData[0] = vec4(local, n.x, uv[0]);\n}\n";
        let found = errors(src, Stage::Fragment);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].starts_with("5: `uv` is an input of this fragment shader (declared at a.fsh:2)"), "{found:?}");
        assert!(found[1].starts_with("6: `n`"), "{found:?}");
        // A local variable of an input's name is no input.
        let local = "#version 120\nvarying vec4 color;\nvec3 f() { vec3 color = vec3(0.0); color.r = 1.0; return color; }\nvoid main() { gl_FragData[0] = vec4(f(), color.a); }\n";
        assert!(errors(local, Stage::Fragment).is_empty(), "{:?}", errors(local, Stage::Fragment));
        // A vertex shader's `out` and a parameter of the same name are not inputs.
        let vertex = "#version 330\nin vec3 vaPosition;\nout vec2 uv;\nvec2 f(vec2 uv) { uv *= 2.0; return uv; }\nvoid main() { uv = f(vec2(1.0)); gl_Position = vec4(vaPosition, 1.0); }\n";
        assert!(errors(vertex, Stage::Vertex).is_empty(), "{:?}", errors(vertex, Stage::Vertex));
    }

    #[test]
    fn shadow_samplers_take_the_shadow_lookups() {
        let src = "#version 120\nuniform sampler2DShadow shadowtex0;\nuniform sampler2D colortex0;\nvarying vec2 uv;\nvoid main() {\n float a = texture2D(shadowtex0, uv).r;\n float b = shadow2D(colortex0, vec3(uv, 0.5)).r;\n float c = shadow2D(shadowtex0, vec3(uv, 0.5)).r + texture2D(colortex0, uv).r;\n gl_FragData[0] = vec4(a + b + c);\n}\n";
        let found = errors(src, Stage::Fragment);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].starts_with("6: no overload of texture2D() takes a sampler2DShadow"), "{found:?}");
        assert!(found[1].starts_with("7: no overload of shadow2D() takes a sampler2D"), "{found:?}");
    }

    #[test]
    fn built_in_and_own_outputs_do_not_mix() {
        let src = "#version 330 compatibility\nlayout(location = 1) out vec4 extra;\nvoid main() {\n gl_FragData[0] = vec4(1.0);\n extra = vec4(0.0);\n}\n";
        let found = errors(src, Stage::Fragment);
        assert!(found.len() == 1 && found[0].starts_with("4: this fragment shader writes gl_FragData and its own output `extra` (at a.fsh:5)"), "{found:?}");
        // Declared but never written: drivers accept it.
        let unused = "#version 330 compatibility\nout vec4 extra;\nvoid main() { gl_FragData[0] = vec4(1.0); }\n";
        assert!(errors(unused, Stage::Fragment).is_empty());
    }
}
