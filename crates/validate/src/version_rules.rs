//! What the shader's own `#version` (and profile, and `#extension`s) allows. naga reads the
//! lowered text as GLSL 450, where everything is allowed; a real driver compiles the text at
//! the version it declares, and rejects (Mesa's wording in parentheses):
//! - in GLSL 1.10/1.20: `%`, bitwise operators and shifts ("operator '%' is reserved"),
//!   `flat`/`noperspective`, `uint`, `switch`, `in`/`out` globals, and the 1.30 functions
//!   (`texture`, `textureLod`, `texelFetch`, `textureSize`, …), unless `GL_EXT_gpu_shader4`
//!   is enabled for the parts it adds; `texture2DLod` & co. in fragment shaders without
//!   `GL_ARB_shader_texture_lod` or `GL_EXT_gpu_shader4`;
//! - before GLSL 4.20, `= { … }` initializer lists without `GL_ARB_shading_language_420pack`;
//! - in a core profile (`#version 150`+ without `compatibility`): the removed built-ins
//!   (`gl_FragData`, `gl_FragColor`, `gl_Vertex`, `ftransform`, `gl_ModelViewMatrix`,
//!   `texture2D`, `attribute`, `varying`, …).

use std::collections::BTreeSet;

use tidepack_glsl::compat::{
    GLSL130_FUNCTIONS, GPU_SHADER4, GPU_SHADER4_FUNCTIONS, glsl130_name, is_texture_lod_arb, GPU_SHADER4_OPERATORS, GPU_SHADER4_QUALIFIERS, GPU_SHADER4_TYPES, DEPRECATED_KEPT_BY_MESA, REMOVED_IN_CORE, TEXTURE_LOD, VERTEX_ONLY_LOD,
};
use tidepack_glsl::lower::is_statement_keyword;
use tidepack_glsl::preprocess::Preprocessed;
use tidepack_glsl::token::{ExtensionDirective, Token, TokenKind, extension_directives, function_definitions};
use tidepack_glsl::{Code, Diagnostic, Drivers, Stage};

use crate::glsl_rules::{Globals, code_tokens, place};
use tidepack_loader::loader::Loader;

const TEXTURE_QUERY_LOD: &str = "GL_ARB_texture_query_lod";
const EXPLICIT_LOCATION: &str = "GL_ARB_explicit_attrib_location";
const SHADING_LANGUAGE_420PACK: &str = "GL_ARB_shading_language_420pack";
const GPU_SHADER5: &str = "GL_ARB_gpu_shader5";


fn enabled_extensions(tokens: &[Token]) -> BTreeSet<String> {
    extension_directives(tokens).into_iter().filter(|d| d.enables()).map(|d| d.name.to_string()).collect()
}

/// The extension names GLSL compilers know: the union of the tables of Mesa's GLSL compiler
/// and glslang, one per line.
const KNOWN_EXTENSIONS: &str = include_str!("glsl_extensions.txt");

/// `#extension` lines naming an extension no compiler knows (a typo, or one made up): with
/// `require` an error, since drivers refuse to compile the stage (Mesa: "extension `…` unsupported
/// in … shader"); with `enable` or `warn` a warning, since drivers only warn and go on. A
/// vendor's own driver may know more names of that vendor's than the tables do, so it is not
/// among the drivers said to refuse it.
pub fn unknown_extensions(pre: &Preprocessed, tokens: &[Token]) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    for ExtensionDirective { line, name, behaviour } in extension_directives(tokens) {
        let at = pre.location(line);
        if name == "all" {
            if matches!(behaviour, "require" | "enable") {
                found.push(Diagnostic::error(Code::Extension, format!("`#extension all : {behaviour}` is not allowed: `all` takes only `warn` or `disable`"), at));
            }
            continue;
        }
        if behaviour == "disable" || KNOWN_EXTENSIONS.lines().any(|known| known == name) {
            continue;
        }
        let vendor = name.strip_prefix("GL_").and_then(|rest| rest.split('_').next()).unwrap_or("");
        let own_driver = match vendor {
            "NV" | "NVX" => Drivers::NVIDIA,
            "AMD" | "ATI" => Drivers::AMD,
            "INTEL" => Drivers::INTEL,
            "APPLE" => Drivers::MACOS,
            _ => Drivers::NONE,
        };
        let message = format!("`{name}` is an extension no GLSL compiler knows (Mesa's and glslang's tables): a misspelling?");
        found.push(match behaviour {
            "require" => Diagnostic::error(Code::Extension, message, at)
                .with_note("with `require`, drivers that do not have it refuse the shader")
                .refused_by(Drivers::ALL.without(own_driver)),
            _ => Diagnostic::warning(Code::Extension, message, at).with_note(format!("with `{behaviour}`, drivers only warn")),
        });
    }
    found
}

/// Extensions that some drivers do not offer in OpenGL: the start of their names, the drivers
/// without them, who those are in words, and the names of what they bring (`*`: every name
/// that starts so).
const EXTENSIONS_SOME_DRIVERS_LACK: [(&str, Drivers, &str, &[&str]); 2] = [
    (
        "GL_KHR_shader_subgroup_",
        Drivers::MESA.union(Drivers::MACOS),
        "Mesa's llvmpipe (OpenGL 4.5) and macOS (OpenGL 4.1)",
        &["subgroup*", "gl_Subgroup*", "gl_NumSubgroups"],
    ),
    // AMD's and Mesa's drivers offer it; packs that call `max3` guard it on NVIDIA and on
    // Intel's Windows driver (Luracasmus/renderpearl's prelude).
    (
        "GL_AMD_shader_trinary_minmax",
        Drivers::NVIDIA.union(Drivers::INTEL).union(Drivers::MACOS),
        "NVIDIA's driver, Intel's Windows driver and macOS",
        &["min3", "max3", "mid3"],
    ),
];

/// `#extension` lines naming an extension that some drivers lack, where the stage needs it:
/// with `require` the driver refuses the stage at the line; with `enable` or `warn` it only
/// warns, and refuses the first use of what the extension brings. An error naming the drivers
/// without it, once per extension family and stage.
pub fn extensions_some_drivers_lack(pre: &Preprocessed, tokens: &[Token]) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    let directives = extension_directives(tokens);
    for (prefix, lacking, who, brought) in EXTENSIONS_SOME_DRIVERS_LACK {
        let Some(&ExtensionDirective { line, name, behaviour }) = directives.iter().find(|d| d.name.starts_with(prefix) && d.enables()) else {
            continue;
        };
        // A name ending in `*` is a prefix of what the family brings.
        let brings = |word: &str| brought.iter().any(|b| b.strip_suffix('*').map_or(word == *b, |p| word.starts_with(p)));
        let first_use = tokens.iter().find(|t| t.kind == TokenKind::Ident && brings(t.text));
        let family = if prefix.ends_with('_') { format!("of the {prefix}* extensions") } else { format!("of {prefix}") };
        let (line, what) = match (behaviour, first_use) {
            ("require", _) => (line, format!("`#extension {name} : require`")),
            (_, Some(used)) => (used.line, format!("`{}`, {family},", used.text)),
            (_, None) => continue,
        };
        found.push(
            Diagnostic::error(Code::Extension, format!("{what} needs an extension that {who} do not offer: the stage does not compile there"), pre.location(line))
                .with_note(format!("the drivers that have it define the macro `{name}`: `#ifdef {name}` keeps a fallback for the others"))
                .refused_by(lacking),
        );
    }
    found
}

/// A compute stage needs GLSL 4.30 or `GL_ARB_compute_shader`; the error is at `#version`.
pub fn check_compute(pre: &Preprocessed, tokens: &[Token]) -> Option<Diagnostic> {
    let number = pre.version.as_ref().map_or(110, |v| v.number);
    if number >= 430 || enabled_extensions(tokens).contains("GL_ARB_compute_shader") {
        return None;
    }
    let line = pre.text.lines().position(|l| l.trim_start().starts_with('#') && l.contains("version")).map_or(1, |i| i as u32 + 1);
    Some(Diagnostic::error(
        Code::Version,
        format!("compute shaders need `#version 430` or later (or `#extension GL_ARB_compute_shader : require`); this stage is GLSL {number}"),
        pre.location(line),
    ))
}

/// Errors a driver gives for constructs the stage's `#version` does not have, and warnings for
/// the ones only some drivers accept.
pub fn check(pre: &Preprocessed, tokens: &[Token], stage: Stage, loader: Loader) -> Vec<Diagnostic> {
    let Some(version) = &pre.version else { return Vec::new() };
    let number = version.number;
    let core = version.is_core();
    let extensions = enabled_extensions(tokens);
    // Before 3.30, `layout(location = N)` on inputs and outputs needs an extension.
    let location_needs_extension = number < 330 && !extensions.contains(EXPLICIT_LOCATION);
    let legacy_rules = number < 130 || core;
    let gpu4 = extensions.contains(GPU_SHADER4);
    // GL_EXT_gpu_shader4 brings the `Lod` lookups to fragment shaders too.
    let lod = extensions.contains(TEXTURE_LOD) || gpu4;
    let sig = code_tokens(tokens);
    let globals = Globals::read(&sig, stage);
    let mut found: Vec<Diagnostic> = Vec::new();
    let mut warnings: Vec<Diagnostic> = Vec::new();
    let mut reported: BTreeSet<(String, u32)> = BTreeSet::new();
    let shown_version = match &version.profile {
        Some(p) => format!("#version {number} {p}"),
        None => format!("#version {number}"),
    };
    // Where each function body's `}` is, for a `;` after it.
    let function_ends: BTreeSet<usize> = function_definitions(&sig).iter().map(|f| f.close).collect();
    // Functions the text defines or declares itself (`float round(float x)` in GLSL 1.20, where
    // no built-in has that name): calls of them are no built-ins of a later version.
    let own_functions = own_functions(&sig);
    let mut depth = 0i32;
    let mut parens = 0i32;
    // Parameters of the function being read, and whether a local or a file-scope `const`
    // declaration is open.
    let mut parameters: BTreeSet<&str> = BTreeSet::new();
    let mut local_constant = false;
    let mut file_constant = false;
    for (k, t) in sig.iter().enumerate() {
        match t.text {
            "{" => depth += 1,
            "}" => depth -= 1,
            "(" => parens += 1,
            ")" => parens -= 1,
            _ => {}
        }
        let next_is_call = sig.get(k + 1).is_some_and(|n| n.is_punct("("));
        let explicit_location =
            t.is_ident("layout") && sig.get(k + 1).is_some_and(|n| n.is_punct("(")) && sig.get(k + 2).is_some_and(|n| n.is_ident("location"));
        if depth == 0 && parens == 0 && t.kind == TokenKind::Ident && next_is_call && k > 0 && sig[k - 1].kind == TokenKind::Ident {
            parameters = function_parameters(&sig[k + 1..]);
        }
        if depth > 0 && t.is_ident("const") {
            local_constant = true;
        } else if depth == 0 && parens == 0 && t.is_ident("const") {
            file_constant = true;
        } else if t.is_punct(";") {
            local_constant = false;
            file_constant = false;
        } else if let Some(what) = (file_constant && t.kind == TokenKind::Ident).then(|| runtime_value(t.text, &BTreeSet::new(), &globals)).flatten() {
            if reported.insert((t.text.to_string(), t.line)) {
                found.push(Diagnostic::error(
                    Code::ConstInitializer,
                    format!(
                        "a `const` outside functions must be initialised with a constant expression in every GLSL version, \
                         and the {what} `{}` is not one (Mesa: \"initializer of const variable must be a constant \
                         expression\"); drop `const`",
                        t.text
                    ),
                    pre.location(t.line),
                ));
            }
            continue;
        } else if let Some(what) = (local_constant && number < 420 && t.kind == TokenKind::Ident)
            .then(|| runtime_value(t.text, &parameters, &globals))
            .flatten()
        {
            if reported.insert((t.text.to_string(), t.line)) {
                found.push(Diagnostic::error(
                    Code::ConstInitializer,
                    format!(
                        "a local `const` must be initialised with a constant expression before GLSL 4.20, and the {what} \
                         `{}` is not one (Mesa: \"initializer of const variable must be a constant expression\" in \
                         `{shown_version}`); drop `const` or use #version 420",
                        t.text
                    ),
                    pre.location(t.line),
                ));
            }
            continue;
        }
        let initializer_list = t.is_punct("=") && sig.get(k + 1).is_some_and(|n| n.is_punct("{"));
        if t.is_punct(";") && depth == 0 && parens == 0 && number < 460 && k > 0 && function_ends.contains(&(k - 1)) {
            warnings.push(Diagnostic::warning(
                Code::EmptyDeclaration,
                format!(
                    "`;` after a function body is an empty declaration, which GLSL allows only from 4.60 on: Mesa and \
                     NVIDIA accept it in `{shown_version}`, glslang and stricter drivers refuse it"
                ),
                pre.location(t.line),
            ));
            continue;
        }
        let problem: Option<String> = if initializer_list && number < 420 && !extensions.contains(SHADING_LANGUAGE_420PACK) {
            Some(format!(
                "`= {{ … }}` initializer lists need GLSL 4.20 or `#extension {SHADING_LANGUAGE_420PACK} : enable` (Mesa and \
                 AMD refuse them in `{shown_version}`); write a constructor such as `float[2](a, b)`"
            ))
        } else if explicit_location && location_needs_extension {
            Some(format!(
                "`layout(location = …)` needs GLSL 3.30 or `#extension {EXPLICIT_LOCATION} : enable` (Mesa, AMD and Intel refuse it in `{shown_version}`)"
            ))
        } else if next_is_call && matches!(t.text, "textureQueryLod" | "textureQueryLOD") && number < 400 && !extensions.contains(TEXTURE_QUERY_LOD) {
            Some(format!(
                "{}() needs GLSL 4.00 or `#extension {TEXTURE_QUERY_LOD} : enable` (Mesa: \"no function with name '{}'\" in \
                 `{shown_version}`)",
                t.text, t.text
            ))
        } else if next_is_call && is_texture_lod_arb(t.text) && !extensions.contains(TEXTURE_LOD) {
            Some(format!("{}() needs `#extension {TEXTURE_LOD} : enable` (Mesa: \"no function with name '{}'\")", t.text, t.text))
        } else if next_is_call && number >= 130 && !core && GPU_SHADER4_FUNCTIONS.contains(&t.text) && !gpu4 {
            Some(format!(
                "{}() is not a GLSL {number} function: it comes from {GPU_SHADER4}, which `{shown_version}` does not enable (Mesa: \"no \
                 function with name '{}'\"); use {}()",
                t.text,
                t.text,
                glsl130_name(t.text)
            ))
        } else if !legacy_rules {
            None
        } else if core {
            (REMOVED_IN_CORE.contains(&t.text) || (depth == 0 && matches!(t.text, "attribute" | "varying")))
                .then(|| {
                    format!(
                        "`{}` does not exist in the core profile that `{shown_version}` selects; write `#version {number} compatibility`",
                        t.text
                    )
                })
        } else {
            match t.kind {
                TokenKind::Punct if GPU_SHADER4_OPERATORS.contains(&t.text) && !gpu4 => {
                    Some(format!("operator `{}` is reserved in GLSL {number}; enable {GPU_SHADER4} or use #version 130", t.text))
                }
                TokenKind::Ident => match t.text {
                    q if GPU_SHADER4_QUALIFIERS.contains(&q) && !gpu4 => {
                        Some(format!("`{}` needs GLSL 1.30 or `#extension {GPU_SHADER4} : enable`", t.text))
                    }
                    w if (GPU_SHADER4_TYPES.contains(&w) && !gpu4) || w == "switch" => {
                        Some(format!("`{}` does not exist in GLSL {number}", t.text))
                    }
                    "lowp" | "mediump" | "highp" | "precision" => {
                        Some(format!("precision qualifiers (`{}`) are reserved words in GLSL {number}; they came with 1.30", t.text))
                    }
                    "in" | "out" if depth == 0 && parens == 0 && sig.get(k + 1).is_some_and(|n| n.kind == TokenKind::Ident) => {
                        Some(format!("`{}` variables need GLSL 1.30; GLSL {number} uses `attribute` and `varying`", t.text))
                    }
                    f if own_functions.contains(f) => None,
                    "round" if next_is_call && !gpu4 => {
                        Some(format!("round() does not exist in GLSL {number} (it came with 1.30); write floor(x + 0.5) or define round() yourself"))
                    }
                    f if next_is_call && GLSL130_FUNCTIONS.contains(&f) && f != "round" => {
                        Some(format!("{f}() does not exist in GLSL {number} (it came with 1.30); use texture2D & co."))
                    }
                    f if next_is_call && GPU_SHADER4_FUNCTIONS.contains(&f) && !gpu4 => {
                        Some(format!("{f}() needs `#extension {GPU_SHADER4} : enable`"))
                    }
                    f if next_is_call && stage == Stage::Fragment && VERTEX_ONLY_LOD.contains(&f) && !lod => Some(format!(
                        "{f}() exists only in vertex shaders in GLSL {number}; enable {TEXTURE_LOD} (and call {f}ARB where the driver wants it)"
                    )),
                    _ => None,
                },
                _ => None,
            }
        };
        if let Some(message) = problem
            && reported.insert((t.text.to_string(), t.line))
        {
            let diag = Diagnostic::error(Code::VersionFeature, message, pre.location(t.line));
            // Mesa keeps the deprecated names (not the fixed-function state) in core stages
            // before 4.20.
            let mesa_keeps = core && number < 420 && (DEPRECATED_KEPT_BY_MESA.contains(&t.text) || matches!(t.text, "attribute" | "varying"));
            found.push(if mesa_keeps { diag.refused_by(Drivers::ALL.without(Drivers::MESA)) } else { diag });
        }
    }
    if version.is_es() && stage == Stage::Fragment {
        found.extend(float_without_precision(pre, &sig, &shown_version));
    }
    if number >= 130 {
        found.extend(hidden_builtin_calls(pre, &sig, loader));
    }
    if (130..400).contains(&number) && !extensions.contains(GPU_SHADER5) {
        found.extend(int_literals_for_uints(pre, &sig, &shown_version));
    }
    if number < 120 {
        found.extend(int_and_float_literals_mixed(pre, &sig, &shown_version));
    }
    found.extend(warnings);
    found
}

/// The first declaration of a float type in a GLSL ES fragment shader before any
/// `precision … float;`: ES gives float no default precision in fragment shaders (Mesa: "No
/// precision specified in this scope for type `vec2'"). NVIDIA's desktop driver compiles such a
/// stage as desktop GLSL and accepts it.
fn float_without_precision(pre: &Preprocessed, sig: &[&tidepack_glsl::token::Token<'_>], shown_version: &str) -> Option<Diagnostic> {
    const QUALIFIERS: [&str; 3] = ["lowp", "mediump", "highp"];
    let is_float_type = |text: &str| {
        text == "float" || matches!(text, "vec2" | "vec3" | "vec4") || (text.starts_with("mat") && text[3..].chars().all(|c| matches!(c, '2'..='4' | 'x')))
    };
    for (k, t) in sig.iter().enumerate() {
        if t.is_ident("precision") && sig.get(k + 2).is_some_and(|n| n.is_ident("float")) {
            return None;
        }
        let declares = sig.get(k + 1).is_some_and(|n| n.kind == TokenKind::Ident);
        let qualified = k > 0 && QUALIFIERS.iter().any(|q| sig[k - 1].is_ident(q));
        if t.kind == TokenKind::Ident && is_float_type(t.text) && declares && !qualified {
            return Some(
                Diagnostic::error(
                    Code::VersionFeature,
                    format!(
                        "`{shown_version}` is GLSL ES, whose fragment shaders give float no default precision: `{}` needs \
                         `precision mediump float;` (or highp) before it (Mesa: \"No precision specified in this scope for type \
                         `{}'\"); for desktop OpenGL write `#version 120`",
                        t.text, t.text
                    ),
                    pre.location(t.line),
                )
                .refused_by(Drivers::ALL.without(Drivers::NVIDIA)),
            );
        }
    }
    None
}

/// Calls of a GLSL 1.30 function (`texture(…)`) after a global variable of the same name was
/// declared (`uniform sampler2D texture;`, OptiFine's old atlas name): the variable hides the
/// built-in from that scope on, so the call names no function (Mesa: "no function with name
/// 'texture'"). naga never sees it, since the lowering renames the sampler.
fn hidden_builtin_calls(pre: &Preprocessed, sig: &[&tidepack_glsl::token::Token<'_>], loader: Loader) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    let mut declared: Vec<(&str, u32)> = Vec::new();
    let mut reported: BTreeSet<u32> = BTreeSet::new();
    let (mut depth, mut parens) = (0i32, 0i32);
    for (k, t) in sig.iter().enumerate() {
        match t.text {
            "{" => depth += 1,
            "}" => depth -= 1,
            "(" => parens += 1,
            ")" => parens -= 1,
            _ => {}
        }
        // Iris renames a sampler named `texture` to `gtexture` where it is not called, so the
        // built-in stays visible there.
        let renamed_by_loader = loader == Loader::Iris && t.text == "texture";
        if t.kind != TokenKind::Ident || !GLSL130_FUNCTIONS.contains(&t.text) || renamed_by_loader {
            continue;
        }
        let previous = k.checked_sub(1).map(|p| sig[p]);
        let next = sig.get(k + 1);
        if depth == 0 && parens == 0 && previous.is_some_and(|p| p.kind == TokenKind::Ident) && next.is_some_and(|n| matches!(n.text, ";" | "=" | "," | "[")) {
            declared.push((t.text, t.line));
        } else if next.is_some_and(|n| n.is_punct("("))
            && !previous.is_some_and(|p| p.is_punct("."))
            && let Some(&(_, declared_at)) = declared.iter().find(|(name, _)| *name == t.text)
            && reported.insert(t.line)
        {
            let at = place(pre, declared_at);
            let hint = if t.text == "texture" { " (OptiFine binds the atlas as `gtexture` and `tex` too; Iris renames a sampler called `texture` to `gtexture` by itself)" } else { "" };
            found.push(Diagnostic::error(
                Code::HiddenBuiltin,
                format!(
                    "`{0}` is a variable here (declared at {at}), which hides the built-in function {0}() from GLSL 1.30 on: this call names no function (Mesa: \"no function with name '{0}'\"); rename the variable{hint}",
                    t.text
                ),
                pre.location(t.line),
            ));
        }
    }
    found
}

/// What `name` is when it is no constant: a parameter of the function, a uniform or an input.
fn runtime_value(name: &str, parameters: &BTreeSet<&str>, globals: &Globals) -> Option<&'static str> {
    if parameters.contains(name) {
        Some("parameter")
    } else if globals.uniforms.contains_key(name) || globals.samplers.contains_key(name) {
        Some("uniform")
    } else if globals.inputs.contains_key(name) {
        Some("input")
    } else {
        None
    }
}

/// The names of the functions `sig` (significant tokens) defines or declares: a name after a
/// type and before `(`, outside any body.
fn own_functions<'t>(sig: &[&tidepack_glsl::token::Token<'t>]) -> BTreeSet<&'t str> {
    let mut depth = 0u32;
    let mut found = BTreeSet::new();
    for (k, t) in sig.iter().enumerate() {
        match t.text {
            "{" => depth += 1,
            "}" => depth = depth.saturating_sub(1),
            _ => {}
        }
        let after_type = k.checked_sub(1).is_some_and(|p| sig[p].kind == TokenKind::Ident && !is_statement_keyword(sig[p].text));
        if depth == 0 && t.kind == TokenKind::Ident && after_type && sig.get(k + 1).is_some_and(|n| n.is_punct("(")) {
            found.insert(t.text);
        }
    }
    found
}

/// An int literal: decimal, octal or hex digits and no suffix (`3`, not `3u` or `3.0`).
fn is_int_literal(t: &tidepack_glsl::token::Token<'_>) -> bool {
    let hex = t.text.strip_prefix("0x").or_else(|| t.text.strip_prefix("0X"));
    t.kind == TokenKind::Number
        && match hex {
            Some(digits) => !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_hexdigit()),
            None => t.text.bytes().all(|b| b.is_ascii_digit()),
        }
}

/// A float literal (`2.`, `.5`, `1e3`, `1.0f`).
fn is_float_literal(t: &tidepack_glsl::token::Token<'_>) -> bool {
    t.kind == TokenKind::Number && !t.text.starts_with("0x") && !t.text.starts_with("0X") && t.text.contains(['.', 'e', 'E', 'f', 'F'])
}

/// An int literal and a float literal on either side of an arithmetic operator (`18. + 258 * 2`)
/// in GLSL 1.10, which converts nothing implicitly (1.20 brought int to float): whatever the
/// operands around them, one side of that operator is an int and the other a float. Mesa: "could
/// not implicitly convert operands to arithmetic operator".
fn int_and_float_literals_mixed(pre: &Preprocessed, sig: &[&tidepack_glsl::token::Token<'_>], shown_version: &str) -> Vec<Diagnostic> {
    let mut found = Vec::new();
    let mut reported = BTreeSet::new();
    for w in sig.windows(3) {
        let [left, op, right] = w else { continue };
        if !matches!(op.text, "+" | "-" | "*" | "/") || op.kind != TokenKind::Punct {
            continue;
        }
        let int = if is_int_literal(left) && is_float_literal(right) {
            left
        } else if is_float_literal(left) && is_int_literal(right) {
            right
        } else {
            continue;
        };
        let as_float = if int.text.len() > 1 && int.text.starts_with('0') { format!("float({})", int.text) } else { format!("{}.0", int.text) };
        if reported.insert(op.line) {
            found.push(Diagnostic::error(
                Code::ImplicitConversion,
                format!(
                    "`{} {} {}` mixes an int with a float: GLSL 1.10 converts nothing implicitly (Mesa: \"could not implicitly convert \
                     operands\" in `{shown_version}`; NVIDIA accepts it); write {as_float}, or #version 120 or later",
                    left.text, op.text, right.text
                ),
                pre.location(op.line),
            ));
        }
    }
    found
}

/// An int literal (`3`, not `3u`) where a `uint` variable is assigned, initialised, compared or
/// computed with: GLSL converts int to uint implicitly only from 4.00 (or with
/// `GL_ARB_gpu_shader5`); Mesa: "could not implicitly convert".
fn int_literals_for_uints(pre: &Preprocessed, sig: &[&tidepack_glsl::token::Token<'_>], shown_version: &str) -> Vec<Diagnostic> {
    const OPERATORS: [&str; 22] = [
        "=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "+", "-", "*", "/", "%", "<", ">", "<=", ">=", "==", "!=", "&", "|",
    ];
    // Names declared `uint`, but none also declared with another type somewhere (a `uint x`
    // parameter beside a loop's `int x`): without scopes, which one a use means is not known.
    let declared = |other: bool| -> BTreeSet<&str> {
        sig.windows(2)
            .filter(|w| w[1].kind == TokenKind::Ident && w[0].kind == TokenKind::Ident)
            .filter(|w| if other { w[0].text != "uint" && tidepack_glsl::lower::is_builtin_type(w[0].text) } else { w[0].is_ident("uint") })
            .map(|w| w[1].text)
            .collect()
    };
    let others = declared(true);
    let uints: BTreeSet<&str> = declared(false).into_iter().filter(|name| !others.contains(name)).collect();
    let mut found = Vec::new();
    let mut reported = BTreeSet::new();
    for (k, t) in sig.iter().enumerate() {
        if t.kind != TokenKind::Ident || !uints.contains(t.text) || k > 0 && sig[k - 1].is_punct(".") {
            continue;
        }
        // `n = 3`, `n += 3`, `n > 3`, and `3 * n` (the literal a whole operand: no `.` or call after it).
        let after = sig.get(k + 1).copied().zip(sig.get(k + 2).copied()).filter(|(op, lit)| OPERATORS.contains(&op.text) && is_int_literal(lit));
        let after = after.filter(|_| !sig.get(k + 3).is_some_and(|n| matches!(n.text, "." | "(" | "[")));
        let before = k.checked_sub(2).map(|p| (sig[p + 1], sig[p])).filter(|(op, lit)| {
            OPERATORS[9..].contains(&op.text) && is_int_literal(lit) && !(k >= 3 && matches!(sig[k - 3].text, "." | "*" | "/" | "%"))
        });
        let Some((op, literal)) = after.or(before) else { continue };
        if reported.insert(t.line) {
            found.push(Diagnostic::error(
                Code::ImplicitConversion,
                format!(
                    "`{} {} {}` mixes the uint `{}` with the int literal {}: before GLSL 4.00 nothing converts int to uint \
                     implicitly (Mesa: \"could not implicitly convert\" in `{shown_version}`; NVIDIA accepts it); write {}u",
                    t.text, op.text, literal.text, t.text, literal.text, literal.text
                ),
                pre.location(t.line),
            ));
        }
    }
    found
}

/// The parameter names of the list that opens `from` (`(float a, const in vec3 b)`), or none
/// when `from` is a call rather than a definition.
fn function_parameters<'a>(from: &[&tidepack_glsl::token::Token<'a>]) -> BTreeSet<&'a str> {
    let mut names = BTreeSet::new();
    let mut depth = 0;
    let mut previous: Option<&'a str> = None;
    for (k, t) in from.iter().enumerate() {
        match t.text {
            "(" => depth += 1,
            ")" | "," if depth == 1 => {
                names.extend(previous.take());
                if t.text == ")" {
                    return if from.get(k + 1).is_some_and(|n| n.is_punct("{")) { names } else { BTreeSet::new() };
                }
            }
            ")" => depth -= 1,
            _ if t.kind == TokenKind::Ident && depth == 1 => previous = Some(t.text),
            _ => previous = None,
        }
    }
    BTreeSet::new()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::collections::HashMap;
    use std::sync::Arc;
    use tidepack_glsl::preprocess::{PreprocessOptions, preprocess};
    use tidepack_glsl::token::tokenize;

    /// What `rules` finds in `src` as file `a.fsh`, as `line: message`.
    pub(crate) fn found_by(rules: fn(&Preprocessed, &[Token], Stage) -> Vec<Diagnostic>, src: &str, stage: Stage) -> Vec<String> {
        let files: HashMap<String, Arc<str>> = [("a.fsh".to_string(), Arc::from(src))].into();
        let pre = preprocess(&files, "a.fsh", &PreprocessOptions::default()).unwrap();
        let tokens = tokenize(&pre.text).unwrap();
        rules(&pre, &tokens, stage).iter().map(|d| format!("{}: {}", d.location.as_ref().unwrap().line, d.message)).collect()
    }

    fn errors(src: &str, stage: Stage) -> Vec<String> {
        found_by(|pre, tokens, stage| check(pre, tokens, stage, Loader::default()), src, stage)
    }

    #[test]
    fn unknown_extensions_are_refused_by_every_driver_but_their_vendors() {
        let src = "#version 120\n#extension GL_NOPE_not_an_extension : require\n#extension GL_NV_private_thing : require\n\
                   #extension GL_EXT_made_up : warn\n#extension GL_EXT_gpu_shader4 : require\n#extension all : warn\nvoid main() {}\n";
        let files: HashMap<String, Arc<str>> = [("a.fsh".to_string(), Arc::from(src))].into();
        let pre = preprocess(&files, "a.fsh", &PreprocessOptions::default()).unwrap();
        let found = unknown_extensions(&pre, &tokenize(&pre.text).unwrap());
        let lines: Vec<(u32, bool, Drivers)> = found.iter().map(|d| (d.location.as_ref().unwrap().line, d.is_error(), d.refused_by)).collect();
        assert_eq!(lines.len(), 3, "{found:?}");
        assert_eq!(lines[0], (2, true, Drivers::ALL));
        assert_eq!(lines[1], (3, true, Drivers::ALL.without(Drivers::NVIDIA)));
        assert_eq!((lines[2].0, lines[2].1), (4, false));
    }

    #[test]
    fn glsl_120_rules() {
        let src = "#version 120\nflat varying int i;\nvoid main() {\n int a = i % 2;\n vec4 c = texture(s, v);\n c = texture2DLod(s, v, 0.0);\n}\n";
        let found = errors(src, Stage::Fragment);
        assert_eq!(found.len(), 4, "{found:?}");
        assert!(found[0].starts_with("2: `flat`"));
        assert!(found[1].starts_with("4: operator `%`"));
        assert!(found[2].starts_with("5: texture()"));
        assert!(found[3].starts_with("6: texture2DLod()"));
        let with_extensions = "#version 120\n#extension GL_EXT_gpu_shader4 : enable\n#extension GL_ARB_shader_texture_lod : enable\nflat varying int i;\nvoid main() { int a = i % 2; vec4 c = texture2DLod(s, v, 0.0); }\n";
        assert!(errors(with_extensions, Stage::Fragment).is_empty());
        assert!(errors("#version 120\nvoid main() { vec4 c = texture2DLod(s, v, 0.0); }\n", Stage::Vertex).is_empty());
        assert!(errors("#version 120\nfloat f(in float x, out float y) { y = x; return x; }\n", Stage::Vertex).is_empty());
    }

    #[test]
    fn a_sampler_named_texture_hides_the_built_in_except_under_iris() {
        let src = "#version 330 compatibility\nuniform sampler2D texture;\nin vec2 uv;\nvoid main() { gl_FragData[0] = texture(texture, uv); }\n";
        let found = errors(src, Stage::Fragment);
        assert!(found.len() == 1 && found[0].starts_with("4: `texture` is a variable here"), "{found:?}");
        let iris = found_by(|pre, tokens, stage| check(pre, tokens, stage, Loader::Iris), src, Stage::Fragment);
        assert!(iris.is_empty(), "{iris:?}");
    }

    #[test]
    fn a_local_const_takes_constants_only_before_420() {
        let src = "#version 150 compatibility\nuniform float viewWidth;\nin vec2 uv;\nvoid main() {\n const float pixel = 1.0 / viewWidth;\n const vec2 at = uv;\n const float k = 2.0;\n gl_FragData[0] = vec4(at * pixel * k, 0.0, 1.0);\n}\n";
        let found = errors(src, Stage::Fragment);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].starts_with("5: a local `const` must be initialised") && found[0].contains("the uniform `viewWidth`"), "{found:?}");
        assert!(found[1].starts_with("6: ") && found[1].contains("the input `uv`"), "{found:?}");
        assert!(errors(&src.replace("#version 150 compatibility", "#version 420 compatibility"), Stage::Fragment).is_empty());
    }

    #[test]
    fn int_literals_do_not_become_uints_before_400() {
        let src = "#version 330 compatibility\nuniform uint frame;\nout vec4 color;\nvoid main() {\n uint n = 3;\n n += 1u;\n if (n > 2) n = frame;\n uint m = n * 2u + frame % 4u;\n color = vec4(float(m) + float(2 * n));\n}\n";
        let found = errors(src, Stage::Fragment);
        assert_eq!(found.len(), 3, "{found:?}");
        assert!(found[0].starts_with("5: `n = 3` mixes the uint `n` with the int literal 3"), "{found:?}");
        assert!(found[1].starts_with("7: `n > 2`"), "{found:?}");
        assert!(found[2].starts_with("9: `n * 2`"), "{found:?}");
        assert!(errors(&src.replace("#version 330 compatibility", "#version 400 compatibility"), Stage::Fragment).is_empty());
    }

    #[test]
    fn glsl_110_converts_no_int_literal_to_float() {
        let src = "#version 110\nuniform vec2 texelSize;\nvoid main() {\n vec2 r = vec2(18. + 258 * 2, 258.) * texelSize;\n float a = 2 * 0.5;\n float b = 2.0 * 0.5 + float(2);\n gl_Position = vec4(r, a, b);\n}\n";
        let found = errors(src, Stage::Vertex);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].starts_with("4: `18. + 258` mixes an int with a float") && found[0].contains("write 258.0"), "{found:?}");
        assert!(found[1].starts_with("5: `2 * 0.5`"), "{found:?}");
        assert!(errors(&src.replace("#version 110", "#version 120"), Stage::Vertex).is_empty());
    }

    #[test]
    fn core_profile_rules() {
        let found = errors("#version 330\nvarying vec2 uv;\nvoid main() { gl_FragData[0] = texture2D(s, uv); }\n", Stage::Fragment);
        assert_eq!(found.len(), 3, "{found:?}");
        assert!(found.iter().all(|f| f.contains("core profile")));
        assert!(errors("#version 330 compatibility\nvarying vec2 uv;\nvoid main() { gl_FragData[0] = texture2D(s, uv); }\n", Stage::Fragment).is_empty());
        assert!(errors("#version 130\nin vec2 uv;\nvoid main() { gl_FragData[0] = texture2D(s, uv) + texture(s, uv); }\n", Stage::Fragment).is_empty());
        let found = errors("#version 150 compatibility\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n", Stage::Fragment);
        assert!(found.len() == 1 && found[0].starts_with("2: `layout(location"), "{found:?}");
        assert!(errors("#version 150\n#extension GL_ARB_explicit_attrib_location : enable\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n", Stage::Fragment).is_empty());
        assert!(errors("#version 330\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n", Stage::Fragment).is_empty());
    }
}
