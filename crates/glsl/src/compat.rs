//! What lenient compilers let pass and strict ones refuse, and the rewrites that let a strict
//! compiler (Mesa) compile such a stage as the lenient one runs it.
//!
//! NVIDIA's compiler accepts an `#extension` after code and a reserved word used as a name;
//! Iris renames a sampler called `texture` (which from GLSL 1.30 hides the built-in function)
//! to `gtexture` before any driver sees it. `validate` reports every one of these as an error
//! (they fail on Mesa, AMD, Intel and macOS); the renderer applies [`for_strict_drivers`] to the
//! text it gives OpenGL, so that such packs still render, and lists what it rewrote.

use std::borrow::Cow;
use std::collections::{HashMap, HashSet};

use crate::Stage;
use crate::lower::{float_components, is_implicit_level_lookup};
use crate::preprocess::VersionDirective;
use crate::token::{
    FunctionDefinition, Token, TokenKind, argument_count, argument_qualifiers, brace_depths, depth_read_never_written, function_definitions, matching_close, precision_qualifiers, significant,
    tokenize,
};

/// Tokens no paste joins into one with what comes before them.
const PASTE_NEVER_JOINS: [&str; 8] = ["(", ")", ",", ";", "[", "]", "{", "}"];

/// Words GLSL reserves in every version (Mesa: "illegal use of reserved word").
pub const RESERVED: [&str; 35] = [
    "asm", "class", "union", "enum", "typedef", "template", "this", "packed", "goto", "inline", "noinline", "volatile", "public",
    "static", "extern", "external", "interface", "long", "short", "half", "fixed", "unsigned", "input", "output", "hvec2", "hvec3",
    "hvec4", "fvec2", "fvec3", "fvec4", "sampler3DRect", "sizeof", "cast", "namespace", "using",
];

/// Words GLSL reserves from 1.30 on.
pub const RESERVED_FROM_130: [&str; 5] = ["superp", "common", "partition", "active", "filter"];

/// Built-ins a core profile removed.
pub const REMOVED_IN_CORE: [&str; 22] = [
    "gl_FragData", "gl_FragColor", "gl_Vertex", "gl_Normal", "gl_Color", "gl_MultiTexCoord0", "gl_MultiTexCoord1",
    "gl_MultiTexCoord2", "gl_ModelViewMatrix", "gl_ProjectionMatrix", "gl_ModelViewProjectionMatrix", "gl_NormalMatrix",
    "gl_TextureMatrix", "gl_TexCoord", "gl_FrontColor", "gl_Fog", "gl_FogFragCoord", "ftransform", "texture2D",
    "texture2DLod", "shadow2D", "texture3D",
];

/// Of [`REMOVED_IN_CORE`], the lookups whose successors a core profile has (`texture()` & co.).
const LEGACY_LOOKUPS: [&str; 4] = ["texture2D", "texture2DLod", "shadow2D", "texture3D"];

/// The GLSL 1.30 lookup that replaced a 1.20 one (`texture2D` → `texture`, `texture2DLod` →
/// `textureLod`, `texture2DProj` → `textureProj`), which core profiles and integer samplers take.
pub fn modern_lookup(legacy: &str) -> Option<&'static str> {
    match legacy {
        "texture2D" | "texture3D" => Some("texture"),
        "texture2DLod" | "texture3DLod" => Some("textureLod"),
        "texture2DProj" => Some("textureProj"),
        _ => None,
    }
}

/// Of [`REMOVED_IN_CORE`], the deprecated names Mesa still compiles in a core stage before
/// GLSL 4.20 (measured with Mesa 25.0 in a compatibility context, `#version 330` to `410`);
/// `attribute` and `varying` too. The fixed-function vertex state it refuses at any version.
pub const DEPRECATED_KEPT_BY_MESA: [&str; 6] = ["gl_FragData", "gl_FragColor", "texture2D", "texture2DLod", "shadow2D", "texture3D"];

/// Functions GLSL 1.30 added; the ones `GL_EXT_gpu_shader4` does not bring to 1.20 under
/// these names.
pub const GLSL130_FUNCTIONS: [&str; 12] = [
    "texture", "textureLod", "textureProj", "textureGrad", "textureOffset", "texelFetch", "textureSize",
    "textureLodOffset", "texelFetchOffset", "textureProjLod", "textureGather", "round",
];

/// What GLSL 4.60 added that a 4.50 compiler does not know (the draw parameters, the vote
/// functions, the atomic counter operations); a stage that uses none compiles the same as 4.50.
pub const GLSL460_ADDITIONS: [&str; 15] = [
    "gl_BaseVertex", "gl_BaseInstance", "gl_DrawID", "anyInvocation", "allInvocations", "allInvocationsEqual", "atomicCounterAdd",
    "atomicCounterSubtract", "atomicCounterMin", "atomicCounterMax", "atomicCounterAnd", "atomicCounterOr", "atomicCounterXor",
    "atomicCounterExchange", "atomicCounterCompSwap",
];

/// What GLSL 4.60 took from an ARB extension, with its name there: a 4.50 compiler with the
/// extension (Mesa's llvmpipe has all three) takes a 4.60 stage using them as 4.50 with the
/// extension enabled, under the extension's names.
const GLSL460_FROM_EXTENSIONS: [(&str, &str, &str); 15] = [
    ("gl_BaseVertex", "gl_BaseVertexARB", "GL_ARB_shader_draw_parameters"),
    ("gl_BaseInstance", "gl_BaseInstanceARB", "GL_ARB_shader_draw_parameters"),
    ("gl_DrawID", "gl_DrawIDARB", "GL_ARB_shader_draw_parameters"),
    ("anyInvocation", "anyInvocationARB", "GL_ARB_shader_group_vote"),
    ("allInvocations", "allInvocationsARB", "GL_ARB_shader_group_vote"),
    ("allInvocationsEqual", "allInvocationsEqualARB", "GL_ARB_shader_group_vote"),
    ("atomicCounterAdd", "atomicCounterAddARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterSubtract", "atomicCounterSubtractARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterMin", "atomicCounterMinARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterMax", "atomicCounterMaxARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterAnd", "atomicCounterAndARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterOr", "atomicCounterOrARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterXor", "atomicCounterXorARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterExchange", "atomicCounterExchangeARB", "GL_ARB_shader_atomic_counter_ops"),
    ("atomicCounterCompSwap", "atomicCounterCompSwapARB", "GL_ARB_shader_atomic_counter_ops"),
];

/// Lookups with an explicit level that GLSL 1.20 allows only in vertex shaders, unless
/// `GL_ARB_shader_texture_lod` is enabled.
pub const VERTEX_ONLY_LOD: [&str; 7] =
    ["texture2DLod", "texture2DProjLod", "texture3DLod", "textureCubeLod", "shadow2DLod", "texture1DLod", "shadow2DProjLod"];

/// The extension that brings [`VERTEX_ONLY_LOD`] to fragment shaders.
pub const TEXTURE_LOD: &str = "GL_ARB_shader_texture_lod";
/// The extension that brings `layout(location = N)` on inputs and outputs before GLSL 3.30.
pub const EXPLICIT_ATTRIB_LOCATION: &str = "GL_ARB_explicit_attrib_location";

/// The extension that brings integer operations and the lookups below to GLSL 1.10 and 1.20.
pub const GPU_SHADER4: &str = "GL_EXT_gpu_shader4";

/// Functions of [`GPU_SHADER4`].
pub const GPU_SHADER4_FUNCTIONS: [&str; 16] = [
    "texelFetch1D", "texelFetch2D", "texelFetch3D", "texelFetch2DRect", "texelFetch2DOffset", "textureSize1D", "textureSize2D",
    "textureSize3D", "textureSizeCube", "texture2DArray", "texture2DArrayLod", "shadow2DArray", "texture2DGrad", "texture3DGrad",
    "texture2DOffset", "texture2DLodOffset",
];

/// Interpolation qualifiers and integer types GLSL 1.10 and 1.20 lack that [`GPU_SHADER4`] brings.
pub const GPU_SHADER4_QUALIFIERS: [&str; 2] = ["flat", "noperspective"];
pub const GPU_SHADER4_TYPES: [&str; 6] = ["uint", "uvec2", "uvec3", "uvec4", "usampler2D", "isampler2D"];

/// Operators GLSL 1.10 and 1.20 reserve that [`GPU_SHADER4`] allows.
pub const GPU_SHADER4_OPERATORS: [&str; 13] = ["%", "%=", "<<", ">>", "<<=", ">>=", "~", "&", "|", "^", "&=", "|=", "^="];

/// The lookups `GL_ARB_shader_texture_lod` names with an `ARB` suffix (`texture2DGradARB`,
/// `texture2DLodARB`, `shadow2DProjGradARB`, …): no GLSL version has them without it.
pub fn is_texture_lod_arb(name: &str) -> bool {
    name.strip_suffix("ARB").is_some_and(|base| (base.starts_with("texture") || base.starts_with("shadow")) && (base.ends_with("Lod") || base.ends_with("Grad")))
}

/// The GLSL 1.30 lookup that does what a `GL_EXT_gpu_shader4` one does (`texture2DGrad` →
/// `textureGrad`, `texelFetch2D` → `texelFetch`, `textureSize2D` → `textureSize`).
pub fn glsl130_name(name: &str) -> String {
    let base = ["texelFetch", "textureSize", "texture", "shadow"].iter().find(|b| name.starts_with(**b)).copied().unwrap_or("texture");
    let rest = name[base.len()..].trim_start_matches(['1', '2', '3', 'D']).trim_start_matches("Array").trim_start_matches("Rect").trim_start_matches("Cube");
    format!("{}{rest}", if base == "shadow" { "texture" } else { base })
}

/// Qualifiers of an input's or output's interpolation, which both sides of a varying share.
const INTERPOLATION_QUALIFIERS: [&str; 4] = ["flat", "smooth", "noperspective", "centroid"];

/// The types a function can return that `T(0)` constructs.
const VALUE_TYPES: [&str; 19] = [
    "float", "vec2", "vec3", "vec4", "int", "ivec2", "ivec3", "ivec4", "uint", "uvec2", "uvec3", "uvec4", "bool", "bvec2", "bvec3", "bvec4",
    "mat2", "mat3", "mat4",
];

/// One rewrite, at the line of the text it was made on (before any rewrite).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rewrite {
    pub line: u32,
    pub what: String,
}

/// `text` with what lenient compilers accept rewritten for a strict one, and the rewrites made.
/// `text` may still hold its conditionals (the driver evaluates them); `preprocessed` is the
/// same stage with them evaluated, which decides what the driver would meet:
/// - an `#extension` after code, outside any `#if` or in a branch the driver takes, moves up to
///   just after `#version` (its
///   old line is left empty, so the lines after it keep their numbers, and the ones between
///   move down by one);
/// - from GLSL 1.30 on, a sampler uniform named `texture` and every use of it that is not a
///   call become `gtexture`, as Iris renames it;
/// - a reserved word used as a name gets a `_` appended wherever it appears;
/// - `#ifdef NAME`, `#ifndef NAME`, `#else` and `#endif` lose the tokens after them (lenient
///   preprocessors ignore them);
/// - a `#version 110` or `120` stage that calls a GLSL 1.30 function (`texture()`, …) or has a
///   `switch` is compiled as `#version 130`, which keeps everything 1.20 has (a compatibility
///   driver still takes `varying`, `gl_FragData` and `texture2D` there);
/// - a stage below 1.30 that calls `texture2DLod` & co. without `GL_ARB_shader_texture_lod` gets
///   that extension enabled after `#version` (a fragment shader needs it; elsewhere it is
///   harmless), and one that calls `texelFetch2D` & co., uses an integer operator (`%`, `<<`,
///   …) or type, or `flat` without `GL_EXT_gpu_shader4` gets that one;
/// - a function returning a value whose body has no `return` at all gets `return T(0);` before
///   its closing brace (NVIDIA returns an undefined value; Mesa refuses the stage);
/// - a vertex stage's output that nothing writes gets 0 at the start of `main` (Mesa refuses
///   to link a fragment stage that reads it), and so does one `main` does not write whole on
///   every path (its value is undefined elsewhere; wgpu has 0); so does `gl_Position` in a
///   stage below GLSL 1.40 that never names it (Mesa refuses to link it);
/// - a fragment `out` that nothing writes, in a stage writing `gl_FragData` or `gl_FragColor`,
///   becomes a global holding 0 (Mesa refuses the mix);
/// - a `#version 100` stage (GLSL ES 1.00) is compiled as desktop `#version 120`;
/// - precision qualifiers and statements in a 1.10/1.20 stage, reserved words there, are
///   removed;
/// - `texture2D()`, `texture3D()` and their `Lod` forms of an integer sampler (`usampler2D`)
///   become `texture()` and `textureLod()`, which alone take one;
/// - in a core profile, `texture2D()`, `texture3D()`, `texture2DLod()` & co. become `texture()`,
///   `textureLod()`, `textureProj()`;
/// - before each line of `redefined` (1-based lines of `text`, with the macro each `#define`
///   there redefines with another body, as the lenient preprocessor found them) a line
///   `#undef NAME` is inserted: the one rewrite that moves the lines after it down;
/// - and first, the expressions of [`lenient_expressions`].
pub fn for_strict_drivers(text: &str, preprocessed: &str, stage: Stage, redefined: &[(u32, String)]) -> (String, Vec<Rewrite>) {
    let (text, mut rewrites) = lenient_expressions(text).unwrap_or_else(|| (text.to_string(), Vec::new()));
    let text = text.as_str();
    let (Ok(tokens), Ok(met)) = (tokenize(text), tokenize(preprocessed)) else { return (text.to_string(), rewrites) };
    let met: Vec<&Token> = met.iter().filter(|t| !t.is_trivia()).collect();
    // Replacement text per token index.
    let mut replaced: Vec<Option<String>> = vec![None; tokens.len()];
    let significant = significant(&tokens);
    let taken = |name: &str| tokens.iter().any(|t| t.is_ident(name));
    // Where `#version` is, as an index into `significant`, and its number (110 without one).
    let version_at = significant.windows(2).position(|w| tokens[w[0]].is_punct("#") && tokens[w[1]].is_ident("version"));
    let version_number = version_at.and_then(|at| significant.get(at + 2).copied()).filter(|&i| tokens[i].kind == TokenKind::Number);
    let mut version: u32 = version_number.and_then(|i| tokens[i].text.parse().ok()).unwrap_or(110);
    // The first call the driver meets of one of `functions`, named for a rewrite.
    let call_of = |functions: &[&str]| {
        met.windows(2).find(|w| w[0].kind == TokenKind::Ident && functions.contains(&w[0].text) && w[1].is_punct("(")).map(|w| format!("`{}()`", w[0].text))
    };

    // Reserved words as names: every use, so that the declaration and the uses still agree.
    let reserved = RESERVED.iter().chain(if version >= 130 { &RESERVED_FROM_130[..] } else { &[] });
    for word in reserved {
        let uses: Vec<usize> = significant.iter().copied().filter(|&i| tokens[i].is_ident(word)).collect();
        if let (Some(&first), true) = (uses.first(), met.iter().any(|t| t.is_ident(word))) {
            let mut new_name = format!("{word}_");
            while taken(&new_name) {
                new_name.push('_');
            }
            for &i in &uses {
                replaced[i] = Some(new_name.clone());
            }
            rewrites.push(Rewrite { line: tokens[first].line, what: format!("`{word}`, a reserved word, renamed to `{new_name}` ({} uses)", uses.len()) });
        }
    }

    // Conditionals open at each directive, to tell an `#endif` with none open.
    let mut open_conditionals = 0usize;
    for (i, d, on_line) in directive_lines(&tokens, &significant) {
        let no_name = on_line.first().is_some_and(|&e| tokens[e].kind != TokenKind::Ident);
        // A paste with a bracket or separator (`b ##(x)`) gives no single token: Mesa refuses
        // it, Iris's preprocessor keeps the two tokens, as the text without the `##` has them.
        if tokens[d].is_ident("define") {
            let lone = on_line.windows(2).filter(|w| tokens[w[0]].is_punct("##") && PASTE_NEVER_JOINS.iter().any(|p| tokens[w[1]].is_punct(p)));
            let pastes: Vec<usize> = lone.map(|w| w[0]).collect();
            if let (Some(&name), false) = (on_line.first(), pastes.is_empty()) {
                for &e in &pastes {
                    replaced[e] = Some(String::new());
                }
                rewrites.push(Rewrite {
                    line: tokens[i].line,
                    what: format!(
                        "`##` before a bracket or separator in the macro `{}`, which gives no single token, removed as Iris's preprocessor keeps the two tokens ({} pastes)",
                        tokens[name].text,
                        pastes.len()
                    ),
                });
            }
        }
        match tokens[d].text {
            "if" | "ifdef" | "ifndef" => open_conditionals += 1,
            "endif" if open_conditionals == 0 => {
                for e in [i, d].into_iter().chain(on_line.iter().copied()) {
                    replaced[e] = Some(String::new());
                }
                rewrites.push(Rewrite {
                    line: tokens[i].line,
                    what: "`#endif` with no `#if` open, which Iris's preprocessor reports and skips, removed".into(),
                });
                continue;
            }
            "endif" => open_conditionals -= 1,
            _ => {}
        }
        match tokens[d].text {
            // `#define`, `#ifdef` and `#ifndef` whose name is not one (`#define 2D_CLOUDS`):
            // Iris's preprocessor reports the line and skips the `#define`, and keeps the groups
            // the others open; so does the lenient preprocessor.
            "define" | "ifdef" | "ifndef" if no_name => {
                let last = on_line[on_line.len() - 1];
                let directive = &text[tokens[i].offset..tokens[last].offset + tokens[last].text.len()];
                let what = if tokens[d].text == "define" {
                    for e in [i, d].into_iter().chain(on_line.iter().copied()) {
                        replaced[e] = Some(String::new());
                    }
                    format!("`{directive}`, which names no macro, removed as Iris's preprocessor skips it")
                } else {
                    replaced[d] = Some("if".into());
                    replaced[on_line[0]] = Some("1".into());
                    for &e in &on_line[1..] {
                        replaced[e] = Some(String::new());
                    }
                    format!("`{directive}`, which tests no macro, taken as Iris's preprocessor takes it")
                };
                rewrites.push(Rewrite { line: tokens[i].line, what });
            }
            // `#ifdef NAME …`, `#ifndef NAME …`, `#else …` and `#endif …`: lenient preprocessors
            // read the name (or nothing) and ignore the rest, which Mesa refuses.
            word @ ("ifdef" | "ifndef" | "else" | "endif") => {
                let kept = if matches!(word, "ifdef" | "ifndef") { 1 } else { 0 };
                if on_line.len() > kept {
                    let ignored: Vec<&str> = on_line[kept..].iter().map(|&e| tokens[e].text).collect();
                    for &e in &on_line[kept..] {
                        replaced[e] = Some(String::new());
                    }
                    let directive: Vec<&str> = std::iter::once(word).chain(on_line[..kept].iter().map(|&e| tokens[e].text)).collect();
                    rewrites.push(Rewrite {
                        line: tokens[i].line,
                        what: format!("`#{}` ignores what follows: `{}` removed", directive.join(" "), ignored.join(" ")),
                    });
                }
            }
            _ => {}
        }
    }

    // GLSL ES 1.00 in a desktop context: Mesa holds the stage to ES's rules (a fragment shader
    // needs a default float precision; ES and desktop stages do not link), NVIDIA compiles it
    // as desktop GLSL.
    if let (100, Some(number)) = (version, version_number) {
        replaced[number] = Some("120".into());
        rewrites.push(Rewrite {
            line: tokens[number].line,
            what: "#version 100 (GLSL ES 1.00) compiled as desktop #version 120, as NVIDIA compiles it in a desktop context".into(),
        });
        version = 120;
    }

    if version < 130 {
        let called = call_of(&GLSL130_FUNCTIONS)
            .map(|call| format!("{call}, a GLSL 1.30 function"))
            .or_else(|| met.iter().any(|t| t.is_ident("switch")).then(|| "`switch`, a GLSL 1.30 statement".to_string()))
            .or_else(|| storage_qualifier_in_out(&met).map(|word| format!("`{word}` declarations, GLSL 1.30 storage qualifiers")));
        if let (Some(what), Some(number)) = (called, version_number) {
            replaced[number] = Some("130".into());
            rewrites.push(Rewrite { line: tokens[number].line, what: format!("#version {version} raised to 130 for {what}") });
            version = 130;
            // GLSL 1.30 keeps `varying` but refuses an interpolation qualifier on it, which
            // GL_EXT_gpu_shader4 had allowed: `flat varying` becomes `flat out` or `flat in`.
            let direction = match stage {
                Stage::Vertex => "out",
                Stage::Fragment => "in",
            };
            let qualified: Vec<usize> = significant
                .windows(2)
                .filter(|w| GPU_SHADER4_QUALIFIERS.iter().chain(&["smooth"]).any(|q| tokens[w[0]].is_ident(q)) && tokens[w[1]].is_ident("varying"))
                .map(|w| w[1])
                .collect();
            if let Some(&first) = qualified.first() {
                for &i in &qualified {
                    replaced[i] = Some(direction.into());
                }
                rewrites.push(Rewrite {
                    line: tokens[first].line,
                    what: format!("`varying` after an interpolation qualifier, which GLSL 1.30 refuses, made `{direction}` ({} declarations)", qualified.len()),
                });
            }
        }
    }

    // Mesa's OpenGL, llvmpipe's included, and macOS stop at GLSL 4.50 and 4.10.
    let mut extensions_for_450: Vec<&str> = Vec::new();
    if version == 460
        && let Some(number) = version_number
    {
        let used: Vec<&str> = GLSL460_ADDITIONS.iter().copied().filter(|name| met.iter().any(|t| t.is_ident(name))).collect();
        if used.is_empty() {
            replaced[number] = Some("450".into());
            rewrites.push(Rewrite { line: tokens[number].line, what: "#version 460 lowered to 450: the stage uses nothing GLSL 4.60 added".into() });
            version = 450;
        } else {
            // Everything 4.60 added is in GLSL460_FROM_EXTENSIONS: under its extension's name.
            for &(name, arb_name, extension) in GLSL460_FROM_EXTENSIONS.iter().filter(|(name, ..)| used.contains(name)) {
                for &i in significant.iter().filter(|&&i| tokens[i].is_ident(name)) {
                    replaced[i] = Some(arb_name.to_string());
                }
                if !extensions_for_450.contains(&extension) {
                    extensions_for_450.push(extension);
                }
            }
            replaced[number] = Some("450".into());
            rewrites.push(Rewrite {
                line: tokens[number].line,
                what: format!("#version 460 lowered to 450 with {} enabled, which bring what the stage uses of 4.60 ({}) under their names", extensions_for_450.join(" and "), used.join(", ")),
            });
            version = 450;
        }
    }

    // Precision qualifiers are reserved words before 1.30, and change nothing after it.
    if version < 130 {
        let qualifiers = precision_qualifiers(&tokens);
        for &(first, last) in &qualifiers {
            for i in (first..=last).filter(|&i| !tokens[i].is_trivia()) {
                replaced[i] = Some(String::new());
            }
        }
        if let Some(&(first, _)) = qualifiers.first() {
            let what = format!("precision qualifiers, reserved words in GLSL {version}, removed ({})", qualifiers.len());
            rewrites.push(Rewrite { line: tokens[first].line, what });
        }
    }

    // `varying` on a member of an `in` or `out` block: Iris makes it the block's own direction
    // (its storage-qualifier upgrade reaches block members); Mesa refuses it.
    let mut block_members_varying = Vec::new();
    for (k, w) in significant.windows(3).enumerate() {
        if !(matches!(tokens[w[0]].text, "in" | "out") && tokens[w[1]].kind == TokenKind::Ident && tokens[w[2]].is_punct("{")) {
            continue;
        }
        let Some(close) = matching_close(&significant, &tokens, k + 2) else { continue };
        block_members_varying.extend(significant[k + 3..close].iter().copied().filter(|&i| tokens[i].is_ident("varying")));
    }
    if let Some(&first) = block_members_varying.first() {
        for &i in &block_members_varying {
            replaced[i] = Some(String::new());
        }
        rewrites.push(Rewrite {
            line: tokens[first].line,
            what: format!("`varying` on a member of an interface block, which takes the block's `in` or `out`, removed as Iris makes it the block's ({} members)", block_members_varying.len()),
        });
    }

    // A sampler called `texture` hides the built-in function from 1.30 on.
    if version >= 130 {
        let is_declaration = |w: [&Token; 3]| {
            w[0].is_ident("uniform") && w[1].kind == TokenKind::Ident && w[1].text.trim_start_matches(['i', 'u']).starts_with("sampler") && w[2].is_ident("texture")
        };
        let met_declaration = met.windows(3).any(|w| is_declaration([w[0], w[1], w[2]]));
        let declaration = significant.windows(3).find(|w| is_declaration([&tokens[w[0]], &tokens[w[1]], &tokens[w[2]]]));
        if let (true, Some(w)) = (met_declaration, declaration) {
            let mut renamed = 0;
            for (k, &i) in significant.iter().enumerate() {
                let called = significant.get(k + 1).is_some_and(|&n| tokens[n].is_punct("("));
                if tokens[i].is_ident("texture") && !called {
                    replaced[i] = Some("gtexture".into());
                    renamed += 1;
                }
            }
            rewrites.push(Rewrite {
                line: tokens[w[2]].line,
                what: format!("the sampler `texture`, which hides the function texture() from GLSL 1.30 on, renamed to `gtexture` as Iris does ({renamed} uses)"),
            });
        }
    }

    // A core profile has the fixed-function built-ins no more (`gl_FragColor`, `ftransform()`):
    // NVIDIA compiles a stage that uses them as the compatibility profile, and so does this.
    // Without them, the deprecated lookups it lacks too (Mesa drops them from 4.20) become the
    // lookups that replaced them, as Iris renames them.
    let profile_at = version_at.and_then(|at| significant.get(at + 3).copied()).filter(|&i| matches!(tokens[i].text, "core" | "compatibility" | "es"));
    let profile = profile_at.map(|i| tokens[i].text);
    let kept_by_mesa = |name: &str| LEGACY_LOOKUPS.contains(&name) || (version < 420 && DEPRECATED_KEPT_BY_MESA.contains(&name));
    let fixed_function = met.iter().find(|t| t.kind == TokenKind::Ident && REMOVED_IN_CORE.contains(&t.text) && !kept_by_mesa(t.text));
    let core = (VersionDirective { number: version, profile: profile.map(str::to_string) }).is_core();
    if let (true, Some(used), Some(number)) = (core, fixed_function, version_number) {
        match profile_at {
            Some(at) => replaced[at] = Some("compatibility".into()),
            None => replaced[number] = Some(format!("{version} compatibility")),
        }
        rewrites.push(Rewrite {
            line: tokens[number].line,
            what: format!("`{}`, which a core profile lacks, taken by compiling the stage as `#version {version} compatibility`, as NVIDIA takes it", used.text),
        });
    } else if core {
        let replacement = |_: usize, name: &str| modern_lookup(name).map(str::to_string);
        if let Some((first, renamed)) = rename_calls(&tokens, &significant, &met, &mut replaced, replacement) {
            rewrites.push(Rewrite {
                line: tokens[first].line,
                what: format!("texture2D() & co., which a core profile lacks, renamed to texture() & co. ({renamed} calls)"),
            });
        }
    }

    // texture2D() & co. on an integer sampler, which only texture() & co. take: NVIDIA takes
    // the old name for the new.
    let integer_samplers: Vec<&str> = met
        .windows(2)
        .filter(|w| (w[0].text.starts_with("usampler") || w[0].text.starts_with("isampler")) && w[1].kind == TokenKind::Ident)
        .map(|w| w[1].text)
        .collect();
    if !integer_samplers.is_empty() {
        let of_integer_sampler = |k: usize, name: &str| {
            let first_argument = significant.get(k + 2).map(|&i| tokens[i].text)?;
            if !integer_samplers.contains(&first_argument) {
                return None;
            }
            modern_lookup(name).map(str::to_string)
        };
        if let Some((first, renamed)) = rename_calls(&tokens, &significant, &met, &mut replaced, of_integer_sampler) {
            rewrites.push(Rewrite {
                line: tokens[first].line,
                what: format!("texture2D() & co. of an integer sampler, which only texture() & co. take, renamed to them as NVIDIA reads them ({renamed} calls)"),
            });
        }
    }

    // A bias in a vertex stage, which has no level to bias: NVIDIA takes it as the level.
    if stage == Stage::Vertex {
        let with_bias = |k: usize, name: &str| {
            (is_implicit_level_lookup(name) && argument_count(&significant, &tokens, k + 1) == 3).then(|| format!("{name}Lod"))
        };
        if let Some((first, biased)) = rename_calls(&tokens, &significant, &met, &mut replaced, with_bias) {
            let (name, lod) = (tokens[first].text, replaced[first].as_deref().unwrap_or_default());
            rewrites.push(Rewrite {
                line: tokens[first].line,
                what: format!("`{name}()` with a bias in a vertex stage, which has no level to bias, reads the bias as the level as NVIDIA does: {lod}() ({biased} calls)"),
            });
        }
    }

    let mut added: Vec<String> = extensions_for_450.iter().map(|extension| format!("#extension {extension} : enable")).collect();
    let version_line = version_at.map_or(1, |at| tokens[significant[at]].line);
    let operator = || {
        met.iter()
            .find(|t| {
                (t.kind == TokenKind::Punct && GPU_SHADER4_OPERATORS.contains(&t.text))
                    || (t.kind == TokenKind::Ident && (GPU_SHADER4_QUALIFIERS.contains(&t.text) || GPU_SHADER4_TYPES.contains(&t.text)))
            })
            .map(|t| format!("`{}`", t.text))
    };
    let arb_lookup = || met.windows(2).find(|w| is_texture_lod_arb(w[0].text) && w[1].is_punct("(")).map(|w| format!("`{}()`", w[0].text));
    let placed = || {
        met.windows(3).any(|w| w[0].is_ident("layout") && w[1].is_punct("(") && w[2].is_ident("location")).then(|| "`layout(location = …)`".to_string())
    };
    let needed = [
        (TEXTURE_LOD, call_of(&VERTEX_ONLY_LOD).filter(|_| version < 130).or_else(arb_lookup)),
        (GPU_SHADER4, call_of(&GPU_SHADER4_FUNCTIONS).or_else(operator).filter(|_| version < 130)),
        (EXPLICIT_ATTRIB_LOCATION, placed().filter(|_| version < 330)),
    ];
    for (extension, used) in needed {
        if let (true, Some(used)) = (!tokens.iter().any(|t| t.is_ident(extension)), used) {
            added.push(format!("#extension {extension} : enable"));
            rewrites.push(Rewrite { line: version_line, what: format!("{extension} enabled after #version for {used}") });
        }
    }
    // From 1.30 on, GL_EXT_gpu_shader4's lookups have GLSL names of their own, which lenient
    // drivers take them as.
    if version >= 130 && !tokens.iter().any(|t| t.is_ident(GPU_SHADER4)) {
        let replacement = |_: usize, name: &str| GPU_SHADER4_FUNCTIONS.contains(&name).then(|| glsl130_name(name));
        if let Some((first, renamed)) = rename_calls(&tokens, &significant, &met, &mut replaced, replacement) {
            rewrites.push(Rewrite {
                line: tokens[first].line,
                what: format!("{GPU_SHADER4}'s lookups (texture2DGrad() & co.), which GLSL {version} lacks, renamed to its own ({renamed} calls)"),
            });
        }
    }

    let sig: Vec<&Token> = significant.iter().map(|&i| &tokens[i]).collect();
    let definitions = function_definitions(&sig);
    // The function bodies of the text, as ranges of `sig`.
    let bodies: Vec<std::ops::Range<usize>> = definitions.iter().map(|f| f.open + 1..f.close).collect();
    // A function named as a statement of its own, with no call (`atmosphereCommons;`): NVIDIA
    // ignores it, Mesa refuses it.
    let named = functions_named_as_statements(&sig);
    if let Some(&first) = named.first().filter(|&&k| met.iter().any(|t| t.is_ident(tokens[significant[k]].text))) {
        let name = tokens[significant[first]].text;
        for &k in &named {
            replaced[significant[k]] = Some(String::new());
        }
        rewrites.push(Rewrite {
            line: tokens[significant[first]].line,
            what: format!("`{name};`, a function named without a call, which NVIDIA ignores, removed ({} statements)", named.len()),
        });
    }

    // Default values of parameters: the values written out in each call that leaves them.
    let (edits, functions) = default_arguments_spelled_out(&tokens, &significant);
    if let (Some(&(first, _)), false) = (edits.first(), functions.is_empty()) {
        for (i, text) in edits {
            replaced[i] = Some(text);
        }
        rewrites.push(Rewrite {
            line: tokens[first].line,
            what: format!("default values of parameters, which GLSL lacks and NVIDIA takes, given in the calls that leave them out: {}", functions.join(", ")),
        });
    }

    // A function returning a sampler (`sampler2D opticalDepth() { return gaux4; }`): GLSL has no
    // such function, NVIDIA takes it. Decided on what the driver meets; each definition (one per
    // branch of an `#if`, say) becomes a macro giving its sampler.
    let met_sampler_functions = functions_returning_samplers(&met);
    for f in functions_returning_samplers(&sig).into_iter().filter(|f| met_sampler_functions.iter().any(|m| m.name == f.name)) {
        let first_on_line = tokens[..significant[f.start]].iter().rev().take_while(|t| t.kind != TokenKind::Newline).all(|t| t.is_trivia());
        if !first_on_line {
            continue;
        }
        replaced[significant[f.start]] = Some(format!("#define {}() {}", f.name, f.returned));
        for k in f.start + 1..=f.close {
            replaced[significant[k]] = Some(String::new());
        }
        rewrites.push(Rewrite {
            line: sig[f.start].line,
            what: format!("`{}()`, a function returning the sampler `{}`, which GLSL forbids and NVIDIA takes, made a macro", f.name, f.returned),
        });
    }

    // A `const` whose initializer is not a constant expression (`const float c = a + b;` with
    // `a` a parameter, or a uniform at the file's scope): NVIDIA takes it as a read-only
    // variable, Mesa refuses it (and takes a plain global with such an initializer). Decided on
    // what the driver meets, per function and at the file's scope; the declaration of that name
    // there loses its `const`, also where a macro gives the `const` (`cfloat`, `cv(float)`) or
    // declares the whole constant (`cRCP(float, total);`, expanded in place).
    let not_constant = constants_not_constant(&met);
    let function_at = |k: usize| definitions.iter().find(|f| (f.open + 1..f.close).contains(&k)).map(|f| sig[f.name].text);
    let declared_not_constant = |k: usize, name: &str| not_constant.contains(&(function_at(k), name));
    let const_macros = macros_giving_const(&tokens, &significant);
    // A macro call starting at `sig[start]` and ending before `sig[end]`, expanded without
    // `const`.
    let without_const = |start: usize, end: usize| -> Option<Vec<String>> {
        let (params, body) = const_macros.get(sig[start].text)?;
        let expansion = match params {
            None if end == start + 1 => body.iter().map(|t| t.to_string()).collect(),
            Some(params) if sig[start + 1].is_punct("(") && matching_close(&significant, &tokens, start + 1) == Some(end - 1) => {
                expand_pasting(params, body, &arguments(&sig[start + 2..end - 1]))
            }
            _ => return None,
        };
        Some(expansion.into_iter().filter(|t| t != "const").collect())
    };
    let mut unconst: Vec<(u32, &str)> = Vec::new();
    let replace_span = |replaced: &mut Vec<Option<String>>, start: usize, end: usize, text: String| {
        replaced[significant[start]] = Some(text);
        for j in start + 1..end {
            replaced[significant[j]] = Some(String::new());
        }
    };
    for (k, start) in non_constant_declarators(&sig, &definitions, &not_constant) {
        if let Some(c) = (start..k).find(|&j| sig[j].is_ident("const")) {
            replaced[significant[c]] = Some(String::new());
        } else if let Some(type_) = without_const(start, k) {
            replace_span(&mut replaced, start, k, type_.join(" "));
        } else {
            continue;
        }
        unconst.push((sig[k].line, sig[k].text));
    }
    if let Some(&(line, name)) = unconst.first() {
        rewrites.push(Rewrite { line, what: const_dropped(name, unconst.len()) });
    }
    let mut expanded_in_place = Vec::new();
    for s in 1..sig.len().saturating_sub(1) {
        let at_statement = sig[s - 1].ends_statement() && sig[s + 1].is_punct("(") && const_macros.contains_key(sig[s].text);
        let Some(end) = matching_close(&significant, &tokens, s + 1).map(|c| c + 1).filter(|&e| at_statement && sig.get(e).is_some_and(|t| t.is_punct(";"))) else {
            continue;
        };
        let Some(expansion) = without_const(s, end) else { continue };
        let declared = expansion.iter().position(|t| t == "=").and_then(|eq| eq.checked_sub(1)).map(|n| expansion[n].clone());
        let Some(name) = declared.filter(|d| declared_not_constant(s, d)) else { continue };
        replace_span(&mut replaced, s, end, expansion.join(" "));
        expanded_in_place.push((sig[s].line, sig[s].text, name));
    }
    if let Some((line, macro_name, name)) = expanded_in_place.first() {
        rewrites.push(Rewrite {
            line: *line,
            what: format!(
                "`{macro_name}(…)`, which declares `{name}` `const` from a value that is not constant, expanded in place without `const`, as NVIDIA takes it ({} calls)",
                expanded_in_place.len()
            ),
        });
    }

    // A user output never written beside `gl_FragData`/`gl_FragColor` (an input declared `out`):
    // Mesa refuses the mix, NVIDIA compiles it and the reads get an undefined value. It
    // becomes a global holding 0, as wgpu reads it.
    let only_read = if stage == Stage::Fragment { outputs_only_read_beside_legacy_outputs(&met) } else { Vec::new() };
    {
        for (type_, name) in &only_read {
            let declares = |k: usize| {
                (k == 0 || !sig[k - 1].is_punct(")")) && sig[k].is_ident("out") && sig[k + 1].is_ident(type_) && sig[k + 2].is_ident(name) && sig[k + 3].is_punct(";")
            };
            let Some(k) = (0..sig.len().saturating_sub(3)).find(|&k| declares(k)) else { continue };
            replaced[significant[k]] = Some(String::new());
            replaced[significant[k + 3]] = Some(format!(" = {type_}(0);"));
            rewrites.push(Rewrite {
                line: sig[k].line,
                what: format!(
                    "`out {type_} {name}`, read and never written beside `gl_FragData` (Mesa refuses the mix; NVIDIA takes it), made a global holding 0"
                ),
            });
        }
    }

    // `gl_FragDepth` read and never written is undefined; the fragment keeps the depth it was
    // rasterised at, which wgpu's frame reads there too.
    if stage == Stage::Fragment && !depth_read_never_written(&met).is_empty() {
        let reads = depth_read_never_written(&sig);
        for &k in &reads {
            replaced[significant[k]] = Some("gl_FragCoord.z".into());
        }
        if let Some(&first) = reads.first() {
            rewrites.push(Rewrite {
                line: sig[first].line,
                what: format!("`gl_FragDepth`, read and never written (undefined), read as the fragment's own depth, `gl_FragCoord.z` ({} reads)", reads.len()),
            });
        }
    }

    let met_functions = value_functions(&met);
    let met_without_return: Vec<&str> =
        met_functions.iter().filter(|f| !met[f.open..f.close].iter().any(|t| t.is_ident("return"))).map(|f| met[f.name].text).collect();
    for f in value_functions(&sig) {
        let (name, type_) = (sig[f.name].text, sig[f.name - 1].text);
        let body = f.open..f.close;
        if met_without_return.contains(&name) && !sig[body.clone()].iter().any(|t| t.is_ident("return")) {
            replaced[significant[f.close]] = Some(format!("return {type_}(0); }}"));
            rewrites.push(Rewrite {
                line: sig[f.name].line,
                what: format!("`{name}` returns {type_} but has no `return`: `return {type_}(0);` added at its end"),
            });
        }
    }

    {
        let (mut unwritten, mut sometimes) = outputs_not_always_written(&met, stage);
        sometimes.retain(|output| !only_read.contains(output));
        // Before GLSL 1.40 Mesa refuses to link a vertex stage that never writes `gl_Position`
        // (its position is undefined: nothing is drawn where it is 0, as wgpu has it).
        if stage == Stage::Vertex && version < 140 && !met.iter().any(|t| t.is_ident("gl_Position")) {
            unwritten.push(("vec4".to_string(), "gl_Position".to_string()));
        }
        let main_open = sig.windows(5).position(|w| w[0].is_ident("void") && w[1].is_ident("main") && w[2].is_punct("(") && w[3].is_punct(")") && w[4].is_punct("{"));
        if let (false, Some(at)) = (unwritten.is_empty() && sometimes.is_empty(), main_open) {
            let zeroes: String = unwritten.iter().chain(&sometimes).map(|(type_, name)| format!(" {name} = {type_}(0);")).collect();
            replaced[significant[at + 4]] = Some(format!("{{{zeroes}"));
            let names = |outputs: &[(String, String)]| outputs.iter().map(|(_, name)| format!("`{name}`")).collect::<Vec<_>>().join(", ");
            if !unwritten.is_empty() {
                rewrites.push(Rewrite { line: sig[at + 4].line, what: format!("outputs nothing writes set to 0 at the start of main: {}", names(&unwritten)) });
            }
            if !sometimes.is_empty() {
                rewrites.push(Rewrite {
                    line: sig[at + 4].line,
                    what: format!(
                        "outputs not written whole on every path set to 0 at the start of main (undefined where not written; 0 as wgpu has them): {}",
                        names(&sometimes)
                    ),
                });
            }
        }
    }

    // Locals read before anything writes them: GLSL leaves their value undefined (Mesa's may be
    // anything, NaN included), wgpu's is 0. Decided on what the driver meets, given in every
    // declaration of the name: a 0 where the stage writes first changes nothing.
    let zeros = struct_zeros(&met, version);
    let unset = locals_read_unset(&met);
    let mut declared_at: Vec<(&str, u32)> = Vec::new();
    for (k, w) in sig.windows(3).enumerate() {
        let statement_start = k.checked_sub(1).is_none_or(|p| sig[p].ends_statement());
        if bodies.iter().any(|b| b.contains(&k))
            && statement_start
            && w[2].is_punct(";")
            && let Some((type_, name)) = unset.iter().find(|(type_, name)| w[0].is_ident(type_) && w[1].is_ident(name))
        {
            replaced[significant[k + 1]] = Some(format!("{name} = {type_}(0)"));
            if !declared_at.iter().any(|(n, _)| n == name) {
                declared_at.push((name, w[1].line));
            }
        }
    }
    for (name, line) in declared_at {
        rewrites.push(Rewrite {
            line,
            what: format!("`{name}`, which may be read before it is written whole, set to 0 where declared (undefined in GLSL; 0 as wgpu has it)"),
        });
    }

    // Struct instances declared without a value (`struct Sky { … } sky;`, `Sky sky;`) hold
    // undefined members until written (Mesa's may be NaN; SEUS's composites read a member they
    // never set); wgpu's are 0.
    let met_globals: Vec<(&str, &str)> = unset_globals_at(&met, &zeros).into_iter().map(|(type_, name, _)| (type_, name)).collect();
    let mut zeroed = Vec::new();
    for (type_, name, at) in unset_globals_at(&sig, &zeros) {
        if met_globals.contains(&(type_, name)) {
            let shown = replaced[significant[at]].clone().unwrap_or_else(|| name.to_string());
            replaced[significant[at]] = Some(format!("{shown} = {}", zeros[type_]));
            zeroed.push((name, sig[at].line));
        }
    }
    if let Some(&(_, line)) = zeroed.first() {
        let names: Vec<String> = zeroed.iter().map(|(name, _)| format!("`{name}`")).collect();
        rewrites.push(Rewrite {
            line,
            what: format!("struct instances declared without a value set to 0 (undefined in GLSL; 0 as wgpu has them): {}", names.join(", ")),
        });
    }

    let mut out: String = tokens.iter().zip(&replaced).map(|(t, r)| r.as_deref().unwrap_or(t.text)).collect();
    if !redefined.is_empty() {
        let mut lines: Vec<String> = out.split_inclusive('\n').map(str::to_string).collect();
        let mut sorted: Vec<&(u32, String)> = redefined.iter().collect();
        sorted.sort_by_key(|(line, _)| std::cmp::Reverse(*line));
        for (line, name) in sorted {
            let at = (*line as usize).saturating_sub(1).min(lines.len());
            lines.insert(at, format!("#undef {name}\n"));
            rewrites.push(Rewrite { line: *line, what: format!("`{name}` redefined with another body: `#undef {name}` inserted before it") });
        }
        out = lines.concat();
    }
    // Extensions the driver meets, active `#if` or not.
    let met_extensions: Vec<&str> = crate::token::extension_directives(&met).iter().map(|d| d.name).collect();
    if let Some((first, rewrite)) = version_moved_first(&out) {
        out = first;
        rewrites.push(rewrite);
    }
    let (out, moved) = extensions_after_version(&out, &added, &met_extensions);
    rewrites.extend(moved);
    rewrites.sort_by_key(|r| r.line);
    (out, rewrites)
}

/// The preprocessor directives of `tokens` (`significant`: the indices of its significant
/// tokens): the `#`, the directive's word, and the significant tokens after it on its line.
pub(crate) fn directive_lines(tokens: &[Token], significant: &[usize]) -> Vec<(usize, usize, Vec<usize>)> {
    let mut found = Vec::new();
    for (k, &i) in significant.iter().enumerate() {
        let starts_line = k == 0 || tokens[significant[k - 1]].line != tokens[i].line;
        let Some(&d) = significant.get(k + 1).filter(|_| starts_line && tokens[i].is_punct("#")) else { continue };
        let on_line: Vec<usize> = significant[k + 2..].iter().copied().take_while(|&e| tokens[e].line == tokens[i].line).collect();
        found.push((i, d, on_line));
    }
    found
}

/// Locals (type, name) of `toks` (significant tokens) declared `TYPE NAME;` inside a function
/// whose first use after the declaration, in the text's order, is neither a whole assignment
/// (`NAME = …`, a branch's included) nor a bare argument of a call (an `out` parameter may
/// write it): `NAME += …`, `NAME.x = …` or a read.
/// Renames each call (a name before `(`) of the significant tokens to what `replacement` gives
/// for its place in `significant` and its name as the text stands so far (a rewrite before may
/// have renamed it), where the driver meets the name; the token index of the first renamed and
/// how many.
fn rename_calls(
    tokens: &[Token],
    significant: &[usize],
    met: &[&Token],
    replaced: &mut [Option<String>],
    replacement: impl Fn(usize, &str) -> Option<String>,
) -> Option<(usize, usize)> {
    let mut renamed = 0;
    let mut first = None;
    for (k, &i) in significant.iter().enumerate() {
        let called = significant.get(k + 1).is_some_and(|&n| tokens[n].is_punct("("));
        if !called || !met.iter().any(|t| t.is_ident(tokens[i].text)) {
            continue;
        }
        if let Some(new_name) = replacement(k, replaced[i].as_deref().unwrap_or(tokens[i].text)) {
            replaced[i] = Some(new_name);
            renamed += 1;
            first.get_or_insert(i);
        }
    }
    first.map(|first| (first, renamed))
}

/// The zero value of each struct type `toks` defines, as a constructor (`Sky(vec3(0), 0.0 …)`),
/// for the types whose members are value types, arrays of them of a literal size (from GLSL
/// 1.20, which has array constructors) or structs defined before.
fn struct_zeros<'t>(toks: &[&'t Token], version: u32) -> HashMap<&'t str, String> {
    let mut zeros: HashMap<&'t str, String> = HashMap::new();
    for (k, w) in toks.windows(3).enumerate() {
        if !(w[0].is_ident("struct") && w[1].kind == TokenKind::Ident && w[2].is_punct("{")) {
            continue;
        }
        let Some(close) = (k + 3..toks.len()).find(|&j| toks[j].is_punct("}")) else { continue };
        let mut members = Vec::new();
        let complete = toks[k + 3..close].split(|t| t.is_punct(";")).filter(|m| !m.is_empty()).all(|member| {
            let words: Vec<&Token> = member.iter().copied().filter(|t| !matches!(t.text, "lowp" | "mediump" | "highp")).collect();
            let Some((ty, declarators)) = words.split_first() else { return false };
            let zero = if VALUE_TYPES.contains(&ty.text) { format!("{}(0)", ty.text) } else if let Some(z) = zeros.get(ty.text) { z.clone() } else { return false };
            declarators.split(|t| t.is_punct(",")).all(|declarator| match declarator {
                [name] if name.kind == TokenKind::Ident => {
                    members.push(zero.clone());
                    true
                }
                [name, open, size, close] if name.kind == TokenKind::Ident && open.is_punct("[") && close.is_punct("]") && version >= 120 => {
                    let Ok(n) = size.text.parse::<usize>() else { return false };
                    members.push(format!("{}[{n}]({})", ty.text, vec![zero.as_str(); n].join(", ")));
                    n > 0
                }
                _ => false,
            })
        });
        if complete && !members.is_empty() {
            zeros.insert(w[1].text, format!("{}({})", w[1].text, members.join(", ")));
        }
    }
    zeros
}

/// Globals of a struct type declared without a value and without a storage qualifier:
/// `S NAME;` outside any braces, or `struct S { … } NAME;`. Each with the index of its name.
fn unset_globals_at<'t>(toks: &[&'t Token], struct_zeros: &HashMap<&str, String>) -> Vec<(&'t str, &'t str, usize)> {
    let mut found = Vec::new();
    let depths = brace_depths(toks);
    let mut struct_open: Vec<(i32, &'t str)> = Vec::new();
    for i in 0..toks.len() {
        let t = toks[i];
        if t.is_punct("{") && i >= 2 && toks[i - 2].is_ident("struct") {
            struct_open.push((depths[i], toks[i - 1].text));
        }
        let semicolon_at = |j: usize| toks.get(j).is_some_and(|e| e.is_punct(";"));
        // `} NAME;` closing a struct definition at the top level.
        if t.is_punct("}")
            && depths[i] == 1
            && let Some(&(1, struct_name)) = struct_open.last()
        {
            struct_open.pop();
            if toks.get(i + 1).is_some_and(|n| n.kind == TokenKind::Ident) && semicolon_at(i + 2) && struct_zeros.contains_key(struct_name) {
                found.push((struct_name, toks[i + 1].text, i + 1));
            }
            continue;
        }
        let statement_start = i == 0 || toks[i - 1].ends_statement();
        if depths[i] == 0 && statement_start && struct_zeros.contains_key(t.text) && toks.get(i + 1).is_some_and(|n| n.kind == TokenKind::Ident) && semicolon_at(i + 2) {
            found.push((t.text, toks[i + 1].text, i + 1));
        }
    }
    found
}

fn locals_read_unset<'t>(toks: &[&'t Token]) -> Vec<TypedName<'t>> {
    let mut found: Vec<TypedName<'t>> = Vec::new();
    for function in function_definitions(toks) {
        let body = function.open + 1..function.close.min(toks.len());
        for i in body.clone() {
            let t = toks[i];
            let declaration = VALUE_TYPES.contains(&t.text)
                && toks.get(i + 2).is_some_and(|e| e.is_punct(";"))
                && toks.get(i + 1).is_some_and(|n| n.kind == TokenKind::Ident)
                && toks[i - 1].ends_statement();
            if !declaration {
                continue;
            }
            let name = toks[i + 1].text;
            // The first use in the same block (the scope ends with the block's closing brace);
            // `other.NAME` is another variable's member.
            let mut level = 0i32;
            for k in i + 3..body.end {
                let u = toks[k];
                if u.is_punct("{") {
                    level += 1;
                } else if u.is_punct("}") {
                    level -= 1;
                    if level < 0 {
                        break;
                    }
                } else if u.is_ident(name) && !toks[k - 1].is_punct(".") {
                    let statement_start = toks[k - 1].ends_statement();
                    let whole_assignment = statement_start && toks.get(k + 1).is_some_and(|e| e.is_punct("="));
                    // A bare argument may be an `out` parameter, which writes it; one the stage
                    // defines as `in` or `inout` is read.
                    let argument =
                        ["(", ","].iter().any(|x| toks[k - 1].is_punct(x)) && toks.get(k + 1).is_some_and(|e| e.is_punct(")") || e.is_punct(","));
                    let written = argument && !argument_is_read(toks, k);
                    if !whole_assignment && !written && !found.contains(&(t.text, name)) {
                        found.push((t.text, name));
                    }
                    break;
                }
            }
        }
    }
    found
}

/// Indices into `toks` (significant tokens) of the names of functions the text defines that
/// stand as statements of their own, with no call (`atmosphereCommons;`).
pub(crate) fn functions_named_as_statements(toks: &[&Token]) -> Vec<usize> {
    let definitions = function_definitions(toks);
    let defined: HashSet<&str> = definitions.iter().map(|f| toks[f.name].text).collect();
    let bodies: Vec<std::ops::Range<usize>> = definitions.iter().map(|f| f.open + 1..f.close).collect();
    (1..toks.len().saturating_sub(1))
        .filter(|&k| {
            toks[k].kind == TokenKind::Ident
                && defined.contains(toks[k].text)
                && toks[k + 1].is_punct(";")
                && toks[k - 1].ends_statement()
                && bodies.iter().any(|b| b.contains(&k))
        })
        .collect()
}

/// A function that returns the sampler it names (`sampler2D opticalDepth() { return gaux4; }`),
/// which GLSL forbids (a sampler is no return type) and NVIDIA takes: positions in the
/// significant tokens of its return type and closing brace, its name and the sampler.
pub(crate) struct SamplerFunction<'t> {
    pub start: usize,
    pub close: usize,
    pub name: &'t str,
    pub returned: &'t str,
}

/// The file-scope declarations `KEYWORD TYPE NAME;` of `text` with KEYWORD one of `keywords`,
/// TYPE a float type: (name, type, position in the significant tokens of its type).
fn float_declarations<'t>(sig: &[&'t Token], keywords: &[&str]) -> Vec<(&'t str, &'t str, usize)> {
    let depths = brace_depths(sig);
    (0..sig.len().saturating_sub(3))
        .filter(|&k| depths[k] == 0 && keywords.iter().any(|w| sig[k].is_ident(w)))
        .filter(|&k| float_components(sig[k + 1].text).is_some() && sig[k + 2].kind == TokenKind::Ident && sig[k + 3].is_punct(";"))
        .map(|k| (sig[k + 2].text, sig[k + 1].text, k + 1))
        .collect()
}

/// Varyings the vertex stage declares at one float type and the fragment stage at another
/// (`out vec2 texcoord;` and `in vec4 texcoord;`), which NVIDIA links and Mesa refuses: (name,
/// the vertex stage's type, the fragment stage's).
pub fn varyings_resized(vertex: &str, fragment: &str) -> Vec<(String, String, String)> {
    let (Ok(vertex), Ok(fragment)) = (tokenize(vertex), tokenize(fragment)) else { return Vec::new() };
    let vertex: Vec<&Token> = vertex.iter().filter(|t| !t.is_trivia()).collect();
    let fragment: Vec<&Token> = fragment.iter().filter(|t| !t.is_trivia()).collect();
    let written = float_declarations(&vertex, &["varying", "out"]);
    float_declarations(&fragment, &["varying", "in"])
        .into_iter()
        .filter_map(|(name, read_as, _)| {
            let (_, written_as, _) = written.iter().find(|(n, ..)| *n == name)?;
            (*written_as != read_as).then(|| (name.to_string(), written_as.to_string(), read_as.to_string()))
        })
        .collect()
}

/// `vertex` (a vertex stage as OpenGL gets it) with an output declared just before its `main`
/// for each input `fragment` reads (`varying` or `in` at file scope, with its interpolation
/// qualifiers) whose name the vertex stage never names, and set to 0 first thing in `main`, and
/// what was done; None where none is missing. NVIDIA links such a program and the input reads
/// undefined; Mesa refuses to link it; wgpu reads 0.
pub fn vertex_outputs_completed(vertex: &str, fragment: &str) -> Option<(String, String)> {
    let (vertex_tokens, fragment_tokens) = (tokenize(vertex).ok()?, tokenize(fragment).ok()?);
    let vertex_sig: Vec<&Token> = vertex_tokens.iter().filter(|t| !t.is_trivia()).collect();
    let fragment_sig: Vec<&Token> = fragment_tokens.iter().filter(|t| !t.is_trivia()).collect();
    let depths = brace_depths(&fragment_sig);
    // (interpolation qualifiers, type, name) of each input the fragment stage reads.
    let mut missing: Vec<(Vec<&str>, &str, &str)> = Vec::new();
    for k in 0..fragment_sig.len().saturating_sub(3) {
        let (keyword, ty, name, end) = (fragment_sig[k], fragment_sig[k + 1], fragment_sig[k + 2], fragment_sig[k + 3]);
        let declares = depths[k] == 0 && (keyword.is_ident("varying") || keyword.is_ident("in")) && VALUE_TYPES.contains(&ty.text);
        let read = fragment_sig.iter().filter(|t| t.is_ident(name.text)).count() > 1;
        if declares && read && name.kind == TokenKind::Ident && end.is_punct(";") && !vertex_sig.iter().any(|t| t.is_ident(name.text)) {
            let qualifiers = fragment_sig[..k].iter().rev().take_while(|t| INTERPOLATION_QUALIFIERS.contains(&t.text)).map(|t| t.text).collect();
            missing.push((qualifiers, ty.text, name.text));
        }
    }
    let main = function_definitions(&vertex_sig).into_iter().find(|f| vertex_sig[f.name].is_ident("main"))?;
    // The return type before `main`: the declarations go before it, on its line.
    let return_type = vertex_sig[main.name.checked_sub(1)?];
    if missing.is_empty() {
        return None;
    }
    let version = vertex_sig.windows(3).find(|w| w[0].is_punct("#") && w[1].is_ident("version")).and_then(|w| w[2].text.parse::<u32>().ok()).unwrap_or(110);
    // The fragment stage's interpolation qualifiers, which the two stages must share (`flat`
    // for an integer from GLSL 1.30 on).
    let declarations: String = missing
        .iter()
        .map(|(qualifiers, ty, name)| match (version >= 130, qualifiers.is_empty() && ty.starts_with(['i', 'u'])) {
            (false, _) => format!("varying {ty} {name}; "),
            (true, false) => format!("{}out {ty} {name}; ", qualifiers.iter().rev().map(|q| format!("{q} ")).collect::<String>()),
            (true, true) => format!("flat out {ty} {name}; "),
        })
        .collect();
    let zeros: String = missing.iter().map(|(_, ty, name)| format!(" {name} = {ty}(0);")).collect();
    let (at, body) = (return_type.offset, vertex_sig[main.open].offset + 1);
    let names: Vec<String> = missing.iter().map(|(_, _, name)| format!("`{name}`")).collect();
    let what = format!(
        "inputs of the fragment stage the vertex stage never declares, which NVIDIA links, declared as outputs there and set to 0 (as wgpu has them): {}",
        names.join(", ")
    );
    Some((format!("{}{declarations}{}{zeros}{}", &vertex[..at], &vertex[at..body], &vertex[body..]), what))
}

/// `text` with the expressions NVIDIA's compiler takes and GLSL refuses written as what they
/// compute there, and the rewrites made; None where it holds none. Every line stays where it
/// was:
/// - a lookup whose sampler is chosen by `?:` (`texture2D(c ? a : b, uv)`; samplers are opaque)
///   becomes the choice of two lookups, `(c ? texture2D(a, uv) : texture2D(b, uv))`, which
///   evaluates the condition and the coordinates once as before;
/// - an integer with a float suffix (`37f`; GLSL's float literals need a `.` or an exponent)
///   becomes the float it names, `37.0`.
pub fn lenient_expressions(text: &str) -> Option<(String, Vec<Rewrite>)> {
    let (chosen, mut rewrites) = samplers_chosen_as_lookups(text)?;
    let tokens = tokenize(&chosen).ok()?;
    let suffixed: Vec<&Token> = tokens
        .iter()
        .filter(|t| t.kind == TokenKind::Number && t.text.strip_suffix(['f', 'F']).is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit())))
        .collect();
    let as_float = |t: &Token| format!("{}.0", &t.text[..t.text.len() - 1]);
    if let Some(first) = suffixed.first() {
        rewrites.push(Rewrite {
            line: first.line,
            what: format!("`{}`, an integer with a float suffix, which NVIDIA reads as a float, written `{}` ({} literals)", first.text, as_float(first), suffixed.len()),
        });
    }
    rewrites.sort_by_key(|r| r.line);
    if rewrites.is_empty() {
        return None;
    }
    let out = tokens.iter().map(|t| if suffixed.iter().any(|s| std::ptr::eq(*s, t)) { as_float(t) } else { t.text.to_string() }).collect();
    Some((out, rewrites))
}

/// `text` with each lookup of a sampler chosen by `?:` made a choice of two lookups (see
/// [`lenient_expressions`]), and the rewrites made; None where `text` does not tokenize.
fn samplers_chosen_as_lookups(text: &str) -> Option<(String, Vec<Rewrite>)> {
    let tokens = tokenize(text).ok()?;
    let sig = significant(&tokens);
    let mut replaced: Vec<Option<String>> = vec![None; tokens.len()];
    let mut rewrites = Vec::new();
    // A run of significant tokens as written, each space, line break or comment within one space.
    let joined = |range: &[usize]| match (range.first(), range.last()) {
        (Some(&first), Some(&last)) => tokens[first..=last].iter().map(|t| if t.is_trivia() { " " } else { t.text }).collect::<String>(),
        _ => String::new(),
    };
    let mut k = 0;
    while k + 1 < sig.len() {
        let name = &tokens[sig[k]];
        let is_call = name.kind == TokenKind::Ident && tokens[sig[k + 1]].is_punct("(");
        let Some(close) = is_call.then(|| matching_close(&sig, &tokens, k + 1)).flatten() else {
            k += 1;
            continue;
        };
        let inside = &sig[k + 2..close];
        let rewritten = if ["texture", "texel", "shadow"].iter().any(|p| name.text.starts_with(p)) {
            sampler_choice(&tokens, inside).map(|(condition, first, second, rest)| {
                let rest = joined(rest);
                let call = |sampler: &str| format!("{}({sampler}{}{rest})", name.text, if rest.is_empty() { "" } else { ", " });
                let what = format!("`{}()` of a sampler chosen by `?:`, which GLSL refuses, made a choice of two lookups", name.text);
                (format!("({} ? {} : {})", joined(condition), call(first), call(second)), what)
            })
        } else {
            None
        };
        match rewritten {
            Some((expression, what)) => {
                // The call's line breaks follow it, so that every line after stays where it was.
                let breaks = tokens[sig[k]..=sig[close]].iter().map(|t| t.text.matches('\n').count()).sum::<usize>();
                replaced[sig[k]] = Some(expression + &"\n".repeat(breaks));
                for r in &mut replaced[sig[k] + 1..=sig[close]] {
                    *r = Some(String::new());
                }
                rewrites.push(Rewrite { line: name.line, what });
                k = close + 1;
            }
            None => k += 1,
        }
    }
    Some((tokens.iter().zip(&replaced).map(|(t, r)| r.as_deref().unwrap_or(t.text)).collect(), rewrites))
}

/// Where each token of `inside` (indices of significant tokens) sits: at the top level of the
/// list (not inside a bracket of its own).
fn at_top_level(tokens: &[Token], inside: &[usize]) -> Vec<bool> {
    let mut depth = 0i32;
    inside
        .iter()
        .map(|&i| {
            let t = &tokens[i];
            let opens = t.kind == TokenKind::Punct && matches!(t.text, "(" | "[" | "{");
            let closes = t.kind == TokenKind::Punct && matches!(t.text, ")" | "]" | "}");
            if closes {
                depth -= 1;
            }
            let top = depth == 0 && !closes;
            if opens {
                depth += 1;
            }
            top
        })
        .collect()
}

/// A call's arguments (`inside`) whose first is `condition ? first : second`, each of the two
/// a name: the condition, the two names and the arguments after the first.
fn sampler_choice<'a, 't>(tokens: &'a [Token<'t>], inside: &'a [usize]) -> Option<(&'a [usize], &'t str, &'t str, &'a [usize])> {
    let top = at_top_level(tokens, inside);
    let at = |text: &str| (0..inside.len()).filter(|&j| top[j] && tokens[inside[j]].is_punct(text)).collect::<Vec<_>>();
    let end = at(",").first().copied().unwrap_or(inside.len());
    let (questions, colons) = (at("?"), at(":"));
    let (&[question], &[colon]) = (&questions[..], &colons[..]) else { return None };
    let name = |j: usize| (tokens[inside[j]].kind == TokenKind::Ident).then_some(tokens[inside[j]].text);
    if question == 0 || colon != question + 2 || end != colon + 2 {
        return None;
    }
    Some((&inside[..question], name(question + 1)?, name(colon + 1)?, inside.get(end + 1..).unwrap_or(&[])))
}

/// `fragment` reading each varying of `resized` ([`varyings_resized`]) at the type the vertex
/// stage writes: its declaration given that type, and each use widened as a vertex input's
/// missing components are (`vec4(texcoord, 0.0, 1.0)`) or cut (`texcoord.xy`) to the type it
/// declared; and what was done. None where it declares none of them.
pub fn inputs_resized(fragment: &str, resized: &[(String, String, String)]) -> Option<(String, String)> {
    let tokens = tokenize(fragment).ok()?;
    let significant = significant(&tokens);
    let sig: Vec<&Token> = significant.iter().map(|&i| &tokens[i]).collect();
    let mut replaced: Vec<Option<String>> = vec![None; tokens.len()];
    let mut done = Vec::new();
    let declared = float_declarations(&sig, &["varying", "in"]);
    for (name, written_as, read_as) in resized {
        let Some(&(_, _, at)) = declared.iter().find(|(n, ..)| n == name) else { continue };
        let (written, read) = (float_components(written_as)?, float_components(read_as)?);
        replaced[significant[at]] = Some(written_as.clone());
        let as_read = if written < read {
            let missing: Vec<&str> = (written..read).map(|c| if c == 3 { "1.0" } else { "0.0" }).collect();
            format!("{read_as}({name}, {})", missing.join(", "))
        } else {
            format!("{name}.{}", &"xyzw"[..read])
        };
        for k in (0..sig.len()).filter(|&k| k != at + 1 && sig[k].is_ident(name) && (k == 0 || !sig[k - 1].is_punct("."))) {
            replaced[significant[k]] = Some(as_read.clone());
        }
        done.push(format!("`{name}`"));
    }
    if done.is_empty() {
        return None;
    }
    let text = tokens.iter().zip(&replaced).map(|(t, r)| r.as_deref().unwrap_or(t.text)).collect();
    Some((text, format!("varyings the vertex stage writes at another size read at that size, as NVIDIA links them: {}", done.join(", "))))
}

/// Default values of parameters (`vec4 move(in vec3 at = vec3(0.0))`), which GLSL lacks and
/// NVIDIA takes: the edits that spell them out, as (index into `tokens`, replacement): each
/// `= value` of a definition or prototype removed, and each call giving fewer arguments than
/// the function has parameters given the missing values before its `)`. Empty without them.
pub(crate) fn default_arguments_spelled_out(tokens: &[Token], significant: &[usize]) -> (Vec<(usize, String)>, Vec<String>) {
    let sig: Vec<&Token> = significant.iter().map(|&i| &tokens[i]).collect();
    let mut edits = Vec::new();
    // Per function: each parameter's default, as text.
    let mut defaults: HashMap<&str, Vec<Option<String>>> = HashMap::new();
    let mut headers = HashSet::new();
    for k in 1..sig.len().saturating_sub(1) {
        // `TYPE NAME (`, the type not a directive's word (`#endif` before a `for (`).
        let directive_word = || {
            let type_line_start = sig[..k].iter().rposition(|t| t.line != sig[k - 1].line).map_or(0, |p| p + 1);
            sig[type_line_start].is_punct("#")
        };
        let header = sig[k].kind == TokenKind::Ident
            && sig[k - 1].kind == TokenKind::Ident
            && sig[k + 1].is_punct("(")
            && !["for", "while", "if", "switch", "return"].contains(&sig[k].text)
            && !directive_word();
        let Some(close) = header.then(|| matching_close(significant, tokens, k + 1)).flatten() else { continue };
        let list = &sig[k + 2..close];
        if !list.iter().any(|t| t.is_punct("=")) || !sig.get(close + 1).is_some_and(|t| t.is_punct("{") || t.is_punct(";")) {
            continue;
        }
        let mut values = Vec::new();
        let (mut depth, mut equals) = (0i32, None);
        for (j, t) in list.iter().enumerate().chain(std::iter::once((list.len(), &sig[close]))) {
            match t.text {
                "(" | "[" => depth += 1,
                ")" | "]" if j < list.len() => depth -= 1,
                "=" if depth == 0 => equals = Some(j),
                _ => {}
            }
            if (t.is_punct(",") && depth == 0) || j == list.len() {
                values.push(equals.map(|e| list[e + 1..j].iter().map(|t| t.text).collect::<Vec<_>>().join(" ")));
                if let Some(e) = equals.take() {
                    for m in e..j {
                        edits.push((significant[k + 2 + m], String::new()));
                    }
                }
            }
        }
        headers.insert(k);
        defaults.insert(sig[k].text, values);
    }
    for k in 0..sig.len().saturating_sub(1) {
        let Some(values) = defaults.get(sig[k].text).filter(|_| sig[k + 1].is_punct("(") && !headers.contains(&k)) else { continue };
        let Some(close) = matching_close(significant, tokens, k + 1) else { continue };
        let given = argument_count(significant, tokens, k + 1);
        let missing: Vec<&str> = values[given.min(values.len())..].iter().map_while(|v| v.as_deref()).collect();
        if !missing.is_empty() {
            let separator = if given == 0 { "" } else { ", " };
            edits.push((significant[close], format!("{separator}{})", missing.join(", "))));
        }
    }
    (edits, defaults.keys().map(|n| n.to_string()).collect())
}

/// The [`SamplerFunction`]s `toks` (significant tokens) defines.
pub(crate) fn functions_returning_samplers<'t>(toks: &[&'t Token]) -> Vec<SamplerFunction<'t>> {
    function_definitions(toks)
        .into_iter()
        .filter_map(|f| {
            let returns_sampler = toks[f.name - 1].text.trim_start_matches(['i', 'u']).starts_with("sampler");
            let no_parameters = f.open == f.name + 3 && toks[f.name + 2].is_punct(")");
            let returned = match &toks[f.open + 1..f.close] {
                [r, n, end] if r.is_ident("return") && n.kind == TokenKind::Ident && end.is_punct(";") => n.text,
                _ => return None,
            };
            (returns_sampler && no_parameters).then_some(SamplerFunction { start: f.name - 1, close: f.close, name: toks[f.name].text, returned })
        })
        .collect()
}

/// The declarators of `sig` (a text's significant tokens, whose function definitions are
/// `definitions`) that `not_constant` names ([`constants_not_constant`] of what the driver
/// meets, per function): the position of each one's name and of its statement's start, past the
/// directive lines before it (`#endif`).
fn non_constant_declarators(sig: &[&Token], definitions: &[FunctionDefinition], not_constant: &HashSet<(Option<&str>, &str)>) -> Vec<(usize, usize)> {
    let function_at = |k: usize| definitions.iter().find(|f| (f.open + 1..f.close).contains(&k)).map(|f| sig[f.name].text);
    let mut found = Vec::new();
    for k in 1..sig.len().saturating_sub(1) {
        // `NAME =` or `NAME[N] =`.
        let array_end = sig[k + 1].is_punct("[").then(|| (k + 2..sig.len()).find(|&j| sig[j].is_punct("]"))).flatten();
        let assigned = sig[k + 1].is_punct("=") || array_end.is_some_and(|j| sig.get(j + 1).is_some_and(|t| t.is_punct("=")));
        if sig[k].kind != TokenKind::Ident || !assigned || !not_constant.contains(&(function_at(k), sig[k].text)) {
            continue;
        }
        let mut start = sig[..k].iter().rposition(|t| t.ends_statement()).map_or(0, |p| p + 1);
        while start < k && sig[start].is_punct("#") {
            let line = sig[start].line;
            while start < k && sig[start].line == line {
                start += 1;
            }
        }
        found.push((k, start));
    }
    found
}

/// The rewrite that drops `const` from `count` declarations, the first of `name`.
fn const_dropped(name: &str, count: usize) -> String {
    format!("`const` dropped from `{name}`, whose initializer is not a constant expression, as NVIDIA takes it ({count} declarations)")
}

/// `text` (a stage as the preprocessor leaves it) with `const` dropped from each declaration
/// whose initializer is not a constant expression, as NVIDIA takes it (a read-only variable),
/// and the rewrite made; None where it has none. For naga, which refuses such a `const` as Mesa
/// does; [`for_strict_drivers`] does the same for OpenGL, through macros too.
pub fn constants_made_variables(text: &str) -> Option<(String, Rewrite)> {
    let tokens = tokenize(text).ok()?;
    let significant = significant(&tokens);
    let sig: Vec<&Token> = significant.iter().map(|&i| &tokens[i]).collect();
    let definitions = function_definitions(&sig);
    let not_constant = constants_not_constant(&sig);
    let dropped: Vec<(usize, usize)> = non_constant_declarators(&sig, &definitions, &not_constant)
        .into_iter()
        .filter_map(|(k, start)| Some(((start..k).find(|&j| sig[j].is_ident("const"))?, k)))
        .collect();
    let &(_, first) = dropped.first()?;
    let mut replaced: Vec<Option<&str>> = vec![None; tokens.len()];
    for &(c, _) in &dropped {
        replaced[significant[c]] = Some("");
    }
    let text = tokens.iter().zip(&replaced).map(|(t, r)| r.unwrap_or(t.text)).collect();
    Some((text, Rewrite { line: sig[first].line, what: const_dropped(sig[first].text, dropped.len()) }))
}

/// The `const` declarations of `toks` (significant tokens) whose initializer is not a constant
/// expression: it reads a variable that is not itself a constant (a parameter, a uniform, a
/// plain local) or calls a function the text defines. Each as (the function it is declared in,
/// None at the file's scope; name).
fn constants_not_constant<'t>(toks: &[&'t Token]) -> HashSet<(Option<&'t str>, &'t str)> {
    let definitions = function_definitions(toks);
    let functions: HashSet<&str> = definitions.iter().map(|f| toks[f.name].text).collect();
    // Constants by where they were declared: a function (its index) or the file's scope (None).
    let mut constants: HashSet<(Option<usize>, &str)> = HashSet::new();
    let mut found = HashSet::new();
    // Whether toks[k - 1] ends a directive's line (`#version 120`).
    let after_directive = |k: usize| {
        let line = toks[k - 1].line;
        let first = toks[..k].iter().rposition(|t| t.line != line).map_or(0, |p| p + 1);
        line != toks[k].line && toks[first].is_punct("#")
    };
    // A function's parameter names: a name before `,`, `)` or `[` in its list (they hide
    // constants of the file's scope).
    let parameters = |f: usize| -> Vec<&str> {
        let list = definitions[f].name + 2..definitions[f].open.saturating_sub(1);
        list.filter(|&m| toks[m].kind == TokenKind::Ident && toks.get(m + 1).is_some_and(|n| [",", ")", "["].iter().any(|p| n.is_punct(p))))
            .map(|m| toks[m].text)
            .collect()
    };
    for k in 0..toks.len() {
        let statement_start = k == 0 || toks[k - 1].ends_statement() || after_directive(k);
        if !statement_start || !toks[k].is_ident("const") {
            continue;
        }
        // `const TYPE NAME = INIT, NAME = INIT;` (qualifiers and a precision may come between).
        let Some(end) = (k..toks.len()).find(|&m| toks[m].is_punct(";")) else { continue };
        let function = definitions.iter().position(|f| (f.open + 1..f.close).contains(&k));
        let hidden = function.map(parameters).unwrap_or_default();
        // The names the statement declares, and whether one of them reads a variable: then the
        // `const` they share goes for all of them.
        let mut names = Vec::new();
        let mut any_reads_variable = false;
        let mut from = k + 1;
        while let Some(eq) = (from..end).find(|&m| toks[m].is_punct("=")) {
            // This declarator's initializer ends at a `,` outside brackets, or at the `;`.
            let mut depth = 0i32;
            let stop = (eq + 1..end)
                .find(|&m| {
                    match toks[m].text {
                        "(" | "[" | "{" => depth += 1,
                        ")" | "]" | "}" => depth -= 1,
                        "," => return depth == 0,
                        _ => {}
                    }
                    false
                })
                .unwrap_or(end);
            from = stop + 1;
            // The declarator's name: before the `=`, or before an array's `[N]`.
            let named_at = if toks[eq - 1].is_punct("]") { (k + 1..eq - 1).rev().find(|&m| toks[m].is_punct("[")).map(|m| m - 1) } else { Some(eq - 1) };
            let Some(named_at) = named_at.filter(|&m| m >= k + 2 && toks[m].kind == TokenKind::Ident) else { continue };
            let name = toks[named_at].text;
            let is_constant = |name: &str| {
                !hidden.contains(&name) && (constants.contains(&(function, name)) || constants.contains(&(None, name)) || names.contains(&name))
            };
            let reads_variable = (eq + 1..stop).any(|m| {
                let t = toks[m];
                let member = toks[m - 1].is_punct(".");
                let called = toks.get(m + 1).is_some_and(|n| n.is_punct("("));
                t.kind == TokenKind::Ident
                    && !member
                    && if called {
                        functions.contains(t.text)
                    } else {
                        !is_constant(t.text) && !VALUE_TYPES.contains(&t.text) && !t.text.starts_with("gl_Max") && !matches!(t.text, "true" | "false")
                    }
            });
            any_reads_variable |= reads_variable;
            names.push(name);
        }
        for name in names {
            if any_reads_variable {
                found.insert((function.map(|f| toks[definitions[f].name].text), name));
            } else {
                constants.insert((function, name));
            }
        }
    }
    found
}

/// The macros `#define`d in `tokens` whose body starts with `const`, object-like (`cfloat`) or
/// function-like (`cv(type)`): by name, the parameters of a function-like one and the body's
/// token texts.
fn macros_giving_const<'t>(tokens: &[Token<'t>], significant: &[usize]) -> HashMap<&'t str, (Option<Vec<&'t str>>, Vec<&'t str>)> {
    directive_lines(tokens, significant)
        .into_iter()
        .filter_map(|(_, d, on_line)| {
            let (&name, rest) = on_line.split_first()?;
            if !tokens[d].is_ident("define") {
                return None;
            }
            let function_like = rest.first().is_some_and(|&open| tokens[open].is_punct("(") && tokens[open].offset == tokens[name].offset + tokens[name].text.len());
            let (params, body) = if function_like {
                let close = rest.iter().position(|&e| tokens[e].is_punct(")"))?;
                (Some(rest[1..close].iter().map(|&e| tokens[e].text).filter(|t| *t != ",").collect()), &rest[close + 1..])
            } else {
                (None, rest)
            };
            let body: Vec<&str> = body.iter().map(|&e| tokens[e].text).collect();
            (body.first() == Some(&"const")).then_some((tokens[name].text, (params, body)))
        })
        .collect()
}

/// The arguments of a call, from the significant tokens between its brackets: each the tokens'
/// text joined, split at the commas outside inner brackets.
fn arguments(inside: &[&Token]) -> Vec<String> {
    let mut found = vec![Vec::new()];
    let mut depth = 0i32;
    for t in inside {
        match t.text {
            "(" | "[" => depth += 1,
            ")" | "]" => depth -= 1,
            "," if depth == 0 && t.kind == TokenKind::Punct => {
                found.push(Vec::new());
                continue;
            }
            _ => {}
        }
        found.last_mut().expect("one argument at least").push(t.text);
    }
    found.into_iter().map(|a| a.join(" ")).collect()
}

/// A function-like macro's `body` (token texts) with each of `params` replaced by its argument
/// and `##` joining its neighbours: the tokens the call gives, where the body calls no other
/// macro.
fn expand_pasting(params: &[&str], body: &[&str], args: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut paste = false;
    for &t in body {
        if t == "##" {
            paste = true;
            continue;
        }
        let text = params.iter().position(|p| *p == t).and_then(|i| args.get(i)).cloned().unwrap_or_else(|| t.to_string());
        match (paste, out.last_mut()) {
            (true, Some(last)) => last.push_str(&text),
            _ => out.push(text),
        }
        paste = false;
    }
    out
}

/// Whether the bare argument `toks[at]` of a call is read: the stage defines the called function
/// and no definition of it takes that argument `out`. A function not defined there (a built-in
/// such as `modf`) may write it.
fn argument_is_read(toks: &[&Token], at: usize) -> bool {
    argument_qualifiers(toks, at).is_some_and(|qualifiers| !qualifiers.is_empty() && !qualifiers.contains(&"out"))
}

/// The first `in` or `out` of `met` (significant tokens) that qualifies a file-scope
/// declaration: outside braces and parentheses, where a parameter's `in` cannot be.
fn storage_qualifier_in_out<'t>(met: &[&Token<'t>]) -> Option<&'t str> {
    let depths = brace_depths(met);
    let mut parens = 0i32;
    met.iter().zip(depths).find_map(|(t, depth)| {
        if t.is_punct("(") {
            parens += 1;
        } else if t.is_punct(")") {
            parens -= 1;
        }
        (depth == 0 && parens == 0 && (t.is_ident("in") || t.is_ident("out"))).then_some(t.text)
    })
}

/// `text` with a value on line `line` (1-based) given `constructor`, as the renderer's checks
/// converted it in the stage naga read (`naga_check::Leniency::Converted`): `value` itself where
/// its tokens appear once on the line, or once next to the operator `beside`; otherwise
/// everything after the line's one `return` or assignment up to its `;` (the same value, where
/// the line has macros naga saw expanded). Returns the new text and the text converted; `None`
/// when neither is found.
pub fn convert_on_line(text: &str, line: u32, constructor: &str, value: &str, beside: Option<&str>) -> Option<(String, String)> {
    let tokens = tokenize(text).ok()?;
    let (on_line, runs, length) = runs_on_line(&tokens, line, value)?;
    let next_to = |k: usize| {
        beside.is_none_or(|op| k.checked_sub(1).is_some_and(|p| on_line[p].text == op) || on_line.get(k + length).is_some_and(|n| n.text == op))
    };
    let matches: Vec<usize> = runs.into_iter().filter(|&k| next_to(k)).collect();
    let (first, last) = match matches.as_slice() {
        [k] => (on_line[*k], on_line[*k + length - 1]),
        _ => {
            let operators = ["return", "=", "+=", "-=", "*=", "/="];
            let starts: Vec<usize> = (0..on_line.len()).filter(|&k| operators.contains(&on_line[k].text)).collect();
            let [start] = starts.as_slice() else { return None };
            let end = (start + 1..on_line.len()).find(|&k| on_line[k].is_punct(";"))?;
            if end == start + 1 {
                return None;
            }
            (on_line[start + 1], on_line[end - 1])
        }
    };
    let end = last.offset + last.text.len();
    let converted = &text[first.offset..end];
    Some((format!("{}{constructor}({converted}){}", &text[..first.offset], &text[end..]), converted.to_string()))
}

/// `text` with the tokens of `written` on `line` (the one place they stand there) replaced by
/// `with`.
pub fn replace_on_line(text: &str, line: u32, written: &str, with: &str) -> Option<String> {
    let tokens = tokenize(text).ok()?;
    let (on_line, runs, length) = runs_on_line(&tokens, line, written)?;
    let [k] = runs.as_slice() else { return None };
    let (first, last) = (on_line[*k], on_line[*k + length - 1]);
    Some(format!("{}{with}{}", &text[..first.offset], &text[last.offset + last.text.len()..]))
}

/// The significant tokens of `line`, where on them the tokens of `wanted` stand in a run (the
/// positions of its first; none where `wanted` holds no token), and how many tokens `wanted`
/// has.
fn runs_on_line<'a>(tokens: &'a [Token<'a>], line: u32, wanted: &str) -> Option<(Vec<&'a Token<'a>>, Vec<usize>, usize)> {
    let wanted = tokenize(wanted).ok()?;
    let wanted: Vec<&str> = wanted.iter().filter(|t| !t.is_trivia()).map(|t| t.text).collect();
    let on_line: Vec<&Token> = tokens.iter().filter(|t| t.line == line && !t.is_trivia()).collect();
    let runs = (0..on_line.len().saturating_sub(wanted.len().saturating_sub(1)))
        .filter(|&k| !wanted.is_empty() && on_line[k..k + wanted.len()].iter().map(|t| t.text).eq(wanted.iter().copied()))
        .collect();
    Some((on_line, runs, wanted.len()))
}

/// The lookups with an offset that [`offset_as_coordinate`] rewrites.
const OFFSET_LOOKUPS: [&str; 3] = ["textureOffset", "textureLodOffset", "texelFetchOffset"];

/// A lookup with an offset (`call`, the whole `textureOffset(s, P, offset)` &c.) as the plain
/// lookup at the coordinate moved by the offset, in texels of the `dimensions`-dimensional
/// texture's base level (`texture(s, P + vec2(offset) / vec2(textureSize(s, 0)))`), for an offset
/// that is not a constant: NVIDIA takes it, GLSL and naga want a constant. The same texels but at
/// a mipmap level above the base one, where the offset counts that level's texels. In a vertex
/// stage, which has no derivatives, `textureOffset` reads level 0 (`textureLod`), as GLSL has it
/// there. `None` for any other call.
pub fn offset_as_coordinate(call: &str, dimensions: u8, vertex: bool) -> Option<String> {
    let tokens = tokenize(call).ok()?;
    let sig: Vec<&Token> = tokens.iter().filter(|t| !t.is_trivia()).collect();
    let (name, open) = (sig.first()?.text, sig.get(1)?);
    if !OFFSET_LOOKUPS.contains(&name) || !open.is_punct("(") || !sig.last()?.is_punct(")") {
        return None;
    }
    // The arguments' text, split at the commas outside brackets.
    let mut args = Vec::new();
    let (mut depth, mut start) = (0, open.offset + 1);
    for t in &sig[2..] {
        match t.text {
            "(" | "[" => depth += 1,
            ")" | "]" if depth > 0 => depth -= 1,
            "," | ")" if depth == 0 => {
                args.push(call[start..t.offset].trim());
                start = t.offset + 1;
            }
            _ => {}
        }
    }
    let float = format!("vec{dimensions}");
    let moved = |sampler: &str, coordinate: &str, offset: &str, level: &str| {
        format!("{coordinate} + {float}({offset}) / {float}(textureSize({sampler}, {level}))")
    };
    Some(match (name, args.as_slice()) {
        ("textureOffset", [s, p, o]) if vertex => format!("textureLod({s}, {}, 0.0)", moved(s, p, o, "0")),
        ("textureOffset", [s, p, o]) => format!("texture({s}, {})", moved(s, p, o, "0")),
        ("textureOffset", [s, p, o, bias]) => format!("texture({s}, {}, {bias})", moved(s, p, o, "0")),
        ("textureLodOffset", [s, p, lod, o]) => format!("textureLod({s}, {}, {lod})", moved(s, p, o, &format!("int({lod})"))),
        ("texelFetchOffset", [s, p, lod, o]) => format!("texelFetch({s}, {p} + {o}, {lod})"),
        _ => return None,
    })
}

/// `text` with every lookup with an offset on line `line` (1-based) rewritten by
/// [`offset_as_coordinate`]; the new text and the number rewritten, `None` when there is none.
pub fn offsets_as_coordinates_on_line(text: &str, line: u32, dimensions: u8, vertex: bool) -> Option<(String, usize)> {
    let tokens = tokenize(text).ok()?;
    let sig = significant(&tokens);
    let mut calls = Vec::new();
    for (k, &i) in sig.iter().enumerate() {
        let t = &tokens[i];
        if t.line != line || !OFFSET_LOOKUPS.contains(&t.text) || !sig.get(k + 1).is_some_and(|&o| tokens[o].is_punct("(")) {
            continue;
        }
        let close = &tokens[sig[matching_close(&sig, &tokens, k + 1)?]];
        calls.push((t.offset, close.offset + 1));
    }
    let mut out = text.to_string();
    let mut rewritten = 0;
    for (start, end) in calls.into_iter().rev() {
        if let Some(call) = offset_as_coordinate(&text[start..end], dimensions, vertex) {
            out.replace_range(start..end, &call);
            rewritten += 1;
        }
    }
    (rewritten > 0).then_some((out, rewritten))
}

/// A declaration's type and name.
type TypedName<'t> = (&'t str, &'t str);

/// What a function body does in statements of its own: the outputs it assigns whole (by name,
/// `gl_FragData[1]` written out), the functions it calls.
type Statements<'t> = (HashSet<Cow<'t, str>>, HashSet<&'t str>);

/// Outputs the stage may leave unwritten: those declared outside every brace, one name each
/// (`[flat] varying|out TYPE NAME;`, `out` alone in a fragment stage), and in a fragment stage
/// each `gl_FragData[N]` written somewhere. As (type, name): those whose name appears nowhere else
/// (vertex stages only: a fragment output named nowhere is no draw buffer), and those `main`
/// does not assign whole (`NAME =`) as a statement of its own, nor a function it calls so (one
/// level down), so that some paths (an `if`, a loop) or components (`NAME.rgb =`) are left
/// undefined.
fn outputs_not_always_written(toks: &[&Token], stage: Stage) -> (Vec<(String, String)>, Vec<(String, String)>) {
    let mut depth = 0i32;
    let mut declared: Vec<(String, String)> = Vec::new();
    // `gl_FragData[N]` at `toks[k]`, with N a literal: its name as written whole.
    let frag_data = |k: usize| {
        let index = toks.get(k + 2).filter(|n| n.kind == TokenKind::Number && toks[k + 1].is_punct("[") && toks.get(k + 3).is_some_and(|c| c.is_punct("]")));
        index.filter(|_| toks[k].is_ident("gl_FragData")).map(|n| format!("gl_FragData[{}]", n.text))
    };
    for (i, t) in toks.iter().enumerate() {
        if t.is_punct("{") {
            depth += 1;
        } else if t.is_punct("}") {
            depth -= 1;
        } else if depth == 0
            && (t.is_ident("out") || (t.is_ident("varying") && stage == Stage::Vertex))
            && let [type_, name, end] = [toks.get(i + 1), toks.get(i + 2), toks.get(i + 3)]
            && let (Some(type_), Some(name), Some(end)) = (type_, name, end)
            && VALUE_TYPES.contains(&type_.text)
            && name.kind == TokenKind::Ident
            && end.is_punct(";")
        {
            declared.push((type_.text.to_string(), name.text.to_string()));
        } else if stage == Stage::Fragment
            && let Some(name) = frag_data(i)
            && toks.get(i + 4).is_some_and(|e| e.is_punct("="))
            && !declared.iter().any(|(_, d)| *d == name)
        {
            declared.push(("vec4".to_string(), name));
        }
    }
    // Per function: the names its body assigns whole before anything else names them (`x += …`
    // or `x.r = …` first reads or leaves the rest undefined), and the functions it calls, as
    // statements of their own at the body's own level (not the body of an `if (…)`, `else`,
    // `for (…)` or `while (…)` without braces).
    let statements = |open: usize, close: usize| {
        let (mut assigned, mut called, mut named) = (HashSet::new(), HashSet::new(), HashSet::new());
        let mut depth = 0i32;
        // After a `return` (an early one inside an `if`), what the body assigns is left
        // unassigned on the path that returned.
        let mut returned = false;
        for k in open..close.min(toks.len()) {
            let t = toks[k];
            if t.is_punct("{") {
                depth += 1;
            } else if t.is_punct("}") {
                depth -= 1;
            } else if t.is_ident("return") {
                returned = true;
            } else if t.kind == TokenKind::Ident {
                let statement_start = depth == 1 && toks[k - 1].ends_statement();
                let (name, after): (Cow<str>, usize) = match frag_data(k) {
                    Some(name) => (Cow::Owned(name), k + 4),
                    None => (Cow::Borrowed(t.text), k + 1),
                };
                // Handed whole to an `out` parameter (`outputs(colour, outColor0);`).
                let bare_argument = (toks[k - 1].is_punct("(") || toks[k - 1].is_punct(","))
                    && toks.get(after).is_some_and(|n| n.is_punct(",") || n.is_punct(")"));
                if depth == 1 && !returned && bare_argument && !named.contains(&name) && argument_qualifiers(toks, k).is_some_and(|q| q.contains(&"out")) {
                    assigned.insert(name.clone());
                }
                match toks.get(after) {
                    Some(e) if statement_start && !returned && e.is_punct("=") && !named.contains(&name) => {
                        assigned.insert(name.clone());
                    }
                    Some(p) if statement_start && !returned && p.is_punct("(") => {
                        called.insert(t.text);
                    }
                    _ => {}
                }
                named.insert(name);
            }
        }
        (assigned, called)
    };
    let functions: Vec<(&str, Statements)> =
        function_definitions(toks).into_iter().map(|f| (toks[f.name].text, statements(f.open, f.close))).collect();
    let main = functions.iter().find(|(name, _)| *name == "main");
    let mut assigned_in_main: HashSet<&str> = HashSet::new();
    if let Some((_, (assigned, called))) = main {
        assigned_in_main.extend(assigned.iter().map(|n| n.as_ref()));
        for (_, (by_callee, _)) in functions.iter().filter(|(name, _)| called.contains(name)) {
            assigned_in_main.extend(by_callee.iter().map(|n| n.as_ref()));
        }
    }
    let mut unwritten = Vec::new();
    let mut sometimes = Vec::new();
    for (type_, name) in declared {
        let named_elsewhere = name.starts_with("gl_FragData") || toks.iter().filter(|u| u.is_ident(&name)).count() > 1;
        if !named_elsewhere {
            if stage == Stage::Vertex {
                unwritten.push((type_, name));
            }
        } else if main.is_some() && !assigned_in_main.contains(name.as_str()) {
            sometimes.push((type_, name));
        }
    }
    (unwritten, sometimes)
}

/// File-scope `out T name;` declarations of a fragment stage that also writes `gl_FragData` or
/// `gl_FragColor`, where nothing assigns to `name` (whole, an element or a swizzle of it).
fn outputs_only_read_beside_legacy_outputs(toks: &[&Token]) -> Vec<(String, String)> {
    if !toks.iter().any(|t| t.is_ident("gl_FragData") || t.is_ident("gl_FragColor")) {
        return Vec::new();
    }
    let depths = brace_depths(toks);
    // A declaration of its own (no `layout(…)` before it, which a global cannot keep).
    let declared = toks.windows(4).enumerate().filter(|(k, w)| {
        depths[*k] == 0
            && (*k == 0 || !toks[k - 1].is_punct(")"))
            && w[0].is_ident("out")
            && VALUE_TYPES.contains(&w[1].text)
            && w[2].kind == TokenKind::Ident
            && w[3].is_punct(";")
    });
    let assigns = |name: &str| {
        toks.iter().enumerate().filter(|(_, t)| t.is_ident(name)).any(|(k, _)| {
            // Past `.xyz` and `[…]` to the operator after the name.
            let mut j = k + 1;
            loop {
                match toks.get(j) {
                    Some(t) if t.is_punct(".") => j += 2,
                    Some(t) if t.is_punct("[") => j = (j..toks.len()).find(|&e| toks[e].is_punct("]")).map_or(toks.len(), |e| e + 1),
                    Some(t) => return ["=", "+=", "-=", "*=", "/=", "++", "--"].iter().any(|op| t.is_punct(op)),
                    None => return false,
                }
            }
        })
    };
    declared.map(|(_, w)| (w[1].text.to_string(), w[2].text.to_string())).filter(|(_, name)| !assigns(name)).collect()
}

/// A function definition in a list of significant tokens: where its name and its body's braces are.
struct Definition {
    name: usize,
    open: usize,
    close: usize,
}

/// The definitions, outside every brace, of functions returning a [`VALUE_TYPES`] value.
fn value_functions(toks: &[&Token]) -> Vec<Definition> {
    let mut found = Vec::new();
    let (mut depth, mut i) = (0i32, 0);
    // The index of the brace matching the one at `open` (or of `close` of the parenthesis).
    let matching = |open: usize, opening: &str, closing: &str| {
        let mut d = 0;
        (open..toks.len()).find(|&k| {
            if toks[k].is_punct(opening) {
                d += 1;
            } else if toks[k].is_punct(closing) {
                d -= 1;
            }
            d == 0
        })
    };
    while i < toks.len() {
        let t = toks[i];
        if t.is_punct("{") {
            depth += 1;
        } else if t.is_punct("}") {
            depth -= 1;
        } else if depth == 0
            && t.kind == TokenKind::Ident
            && VALUE_TYPES.contains(&t.text)
            && toks.get(i + 1).is_some_and(|n| n.kind == TokenKind::Ident)
            && toks.get(i + 2).is_some_and(|n| n.is_punct("("))
            && let Some(params_end) = matching(i + 2, "(", ")")
            && toks.get(params_end + 1).is_some_and(|n| n.is_punct("{"))
            && let Some(close) = matching(params_end + 1, "{", "}")
        {
            found.push(Definition { name: i + 1, open: params_end + 1, close });
            i = close + 1;
            continue;
        }
        i += 1;
    }
    found
}

/// `text` with a `#version` that directives precede (`#define` lines, an `#ifndef` it sits in)
/// moved to the first line, each line before it one line down, so that the lines after it keep
/// their numbers: NVIDIA takes such a `#version`, Mesa wants it before any directive. None where
/// `#version` is first, or where code or a block comment precedes it.
fn version_moved_first(text: &str) -> Option<(String, Rewrite)> {
    let lines: Vec<&str> = text.split('\n').collect();
    let is_directive = |line: &str, word: &str| line.trim_start().strip_prefix('#').is_some_and(|rest| rest.trim_start().starts_with(word));
    let at = lines.iter().position(|l| is_directive(l, "version"))?;
    let before = &lines[..at];
    let only_directives = before.iter().all(|l| {
        let t = l.trim();
        t.is_empty() || t.starts_with("//") || t.starts_with('#')
    });
    if !only_directives || !before.iter().any(|l| l.trim_start().starts_with('#')) {
        return None;
    }
    let moved: Vec<&str> = std::iter::once(lines[at].trim()).chain(before.iter().copied()).chain(lines[at + 1..].iter().copied()).collect();
    let what = format!("`{}`, after directives, moved to the first line as NVIDIA takes it", lines[at].trim());
    Some((moved.join("\n"), Rewrite { line: at as u32 + 1, what }))
}

/// `#extension` lines after the first line of code and outside every `#if` (or in one the
/// driver meets) moved to just after `#version` (or to the top without one), their old lines left
/// empty, with the `added` lines after them; the rewrites are the moves. A `#pragma` counts as
/// code: Mesa's grammar reads it as a declaration.
fn extensions_after_version(text: &str, added: &[String], met: &[&str]) -> (String, Vec<Rewrite>) {
    let Ok(tokens) = tokenize(text) else { return (text.to_string(), Vec::new()) };
    // Per line: its first significant token, and whether the line holds any.
    let mut first_on_line: Vec<Option<usize>> = vec![None; text.lines().count() + 2];
    for (i, t) in tokens.iter().enumerate() {
        if !t.is_trivia() {
            let line = t.line as usize;
            if line < first_on_line.len() && first_on_line[line].is_none() {
                first_on_line[line] = Some(i);
            }
        }
    }
    // The names after a `#` at token i: the directive's, and the one after it.
    let words = |i: usize| {
        let mut names = tokens.iter().skip(i + 1).filter(|t| t.kind != TokenKind::Whitespace).map(|t| (t.kind == TokenKind::Ident).then_some(t.text));
        (names.next().flatten(), names.next().flatten())
    };
    let (mut depth, mut code_seen, mut version_line) = (0i32, false, None);
    let mut moved_lines = Vec::new();
    for (line, first) in first_on_line.iter().enumerate() {
        let Some(i) = *first else { continue };
        if !tokens[i].is_punct("#") {
            code_seen = true;
            continue;
        }
        match words(i) {
            (Some("if" | "ifdef" | "ifndef"), _) => depth += 1,
            (Some("endif"), _) => depth -= 1,
            (Some("version"), _) => version_line = Some(line),
            (Some("pragma"), _) => code_seen = true,
            // Inside an `#if`, one the driver meets (its branch is taken).
            (Some("extension"), name) if code_seen && (depth == 0 || name.is_some_and(|n| met.contains(&n))) => moved_lines.push(line),
            _ => {}
        }
    }
    if moved_lines.is_empty() && added.is_empty() {
        return (text.to_string(), Vec::new());
    }
    let lines: Vec<&str> = text.split('\n').collect();
    let moved: Vec<&str> = moved_lines.iter().map(|&l| lines[l - 1].trim()).collect();
    let inserted: Vec<String> = moved.iter().map(|l| l.to_string()).chain(added.iter().cloned()).collect();
    let mut out: Vec<String> = Vec::with_capacity(lines.len() + inserted.len());
    if version_line.is_none() {
        out.extend(inserted.iter().cloned());
    }
    for (k, line) in lines.iter().enumerate() {
        let number = k + 1;
        out.push(if moved_lines.contains(&number) { String::new() } else { line.to_string() });
        if Some(number) == version_line {
            out.extend(inserted.iter().cloned());
        }
    }
    let rewrites = moved_lines
        .iter()
        .zip(&moved)
        .map(|(&line, text)| Rewrite { line: line as u32, what: format!("`{text}` after code moved up to follow #version") })
        .collect();
    (out.join("\n"), rewrites)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_extension_after_code_moves_up_unless_in_a_branch_not_taken() {
        let text = "#version 120\nuniform float a;\n#extension GL_EXT_gpu_shader4 : enable\n#ifdef X\n#extension GL_ARB_shader_texture_lod : enable\n#endif\nvoid main() {}\n";
        let without_x = "#version 120\nuniform float a;\n#extension GL_EXT_gpu_shader4 : enable\nvoid main() {}\n";
        let (out, rewrites) = for_strict_drivers(text, without_x, Stage::Fragment, &[]);
        assert_eq!(out, "#version 120\n#extension GL_EXT_gpu_shader4 : enable\nuniform float a;\n\n#ifdef X\n#extension GL_ARB_shader_texture_lod : enable\n#endif\nvoid main() {}\n");
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 3);
        // With X defined the driver meets the second one too.
        let with_x = "#version 120\nuniform float a;\n#extension GL_EXT_gpu_shader4 : enable\n#extension GL_ARB_shader_texture_lod : enable\nvoid main() {}\n";
        let (out, rewrites) = for_strict_drivers(text, with_x, Stage::Fragment, &[]);
        assert!(out.starts_with("#version 120\n#extension GL_EXT_gpu_shader4 : enable\n#extension GL_ARB_shader_texture_lod : enable\nuniform float a;\n"), "{out}");
        assert_eq!(rewrites.iter().map(|r| r.line).collect::<Vec<_>>(), [3, 5]);
        // Before any code it is where it belongs.
        let clean = "#version 120\n#extension GL_EXT_gpu_shader4 : enable\nvoid main() {}\n";
        assert_eq!(for_strict_drivers(clean, clean, Stage::Fragment, &[]), (clean.to_string(), Vec::new()));
    }

    #[test]
    fn a_paste_before_a_bracket_is_removed() {
        let text = "#version 330\n#define CONVERT(a, b, x) convert_ ## a ## _to_ ## b ##(x)\nvec3 convert_1_to_2(vec3 c) { return c; }\nvoid main() { gl_FragColor = vec4(CONVERT(1, 2, vec3(1.0)), 1.0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert!(out.contains("#define CONVERT(a, b, x) convert_ ## a ## _to_ ## b (x)"), "{out}");
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 2);
        assert!(rewrites[0].what.contains("`CONVERT`"), "{}", rewrites[0].what);
    }

    #[test]
    fn varying_on_a_block_member_is_removed_and_a_plain_varying_kept() {
        let text = "#version 430 compatibility\nout VertexData {\n    vec2 uv;\n    varying vec3 shadowPos;\n} v;\nvarying vec3 loose;\nvoid main() { v.uv = vec2(0.0); v.shadowPos = vec3(0.0); loose = vec3(0.0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Vertex, &[]);
        assert!(out.contains("out VertexData {\n    vec2 uv;\n     vec3 shadowPos;\n} v;\nvarying vec3 loose;"), "{out}");
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 4);
    }

    #[test]
    fn an_endif_with_no_if_open_is_removed() {
        let text = "#version 120\n#ifdef A\nfloat a;\n#endif\nfloat b;\n#endif\nvoid main() {}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, "#version 120\n#ifdef A\nfloat a;\n#endif\nfloat b;\n\nvoid main() {}\n");
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 6);
    }

    #[test]
    fn a_local_const_from_a_variable_loses_its_const() {
        // As Ebin writes it: `cfloat` is `const float`, and the parameter is no constant.
        let text = "#version 120\n#define cfloat const float\nconst float halfway = 0.5;\nfloat f(cfloat depth) {\n    cfloat centre = depth * halfway;\n    const float scale = 2.0 * halfway;\n    const float twice = centre * 2.0;\n    return twice * scale;\n}\nvoid main() { gl_FragColor = vec4(f(1.0)); }\n";
        let met = "#version 120\n\nconst float halfway = 0.5;\nfloat f(const float depth) {\n    const float centre = depth * halfway;\n    const float scale = 2.0 * halfway;\n    const float twice = centre * 2.0;\n    return twice * scale;\n}\nvoid main() { gl_FragColor = vec4(f(1.0)); }\n";
        let (out, rewrites) = for_strict_drivers(text, met, Stage::Fragment, &[]);
        assert!(out.contains("    float centre = depth * halfway;"), "{out}");
        assert!(out.contains("     float twice = centre * 2.0;"), "{out}");
        assert!(out.contains("const float scale = 2.0 * halfway;") && out.contains("float f(cfloat depth)"), "{out}");
        assert_eq!(rewrites.len(), 1, "{rewrites:?}");
        assert_eq!(rewrites[0].line, 5);
        assert!(rewrites[0].what.contains("(2 declarations)"), "{}", rewrites[0].what);
    }

    #[test]
    fn a_core_stage_with_fixed_function_built_ins_is_compiled_as_compatibility() {
        // As zombye/Ozius writes its sky: `#version 420` (core) and `gl_FragColor`.
        let text = "#version 420\nuniform sampler2D color;\nin vec2 uv;\nvoid main() {\n    gl_FragColor.rgb = texture2D(color, uv).rgb;\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert!(out.starts_with("#version 420 compatibility\n") && out.contains("texture2D(color, uv)"), "{out}");
        assert_eq!(rewrites.len(), 1, "{rewrites:?}");
        assert_eq!(rewrites[0].line, 1);
        assert!(rewrites[0].what.starts_with("`gl_FragColor`, which a core profile lacks"), "{}", rewrites[0].what);
        // Mesa keeps `gl_FragColor` in core stages before 4.20, not the fixed-function state.
        let kept = text.replace("#version 420", "#version 330 core");
        let (out, rewrites) = for_strict_drivers(&kept, &kept, Stage::Fragment, &[]);
        assert!(out.starts_with("#version 330 core\n"), "{out}");
        assert!(rewrites.iter().all(|r| r.what.starts_with("texture2D() & co.")), "{rewrites:?}");
        let vertex = "#version 330 core\nin vec3 position;\nvoid main() { gl_Position = gl_ModelViewMatrix * vec4(position, 1.0); }\n";
        let (out, _) = for_strict_drivers(vertex, vertex, Stage::Vertex, &[]);
        assert!(out.starts_with("#version 330 compatibility\n"), "{out}");
    }

    #[test]
    fn a_file_scope_const_from_a_uniform_loses_its_const_and_so_do_those_it_gives() {
        // As zombye/Ozius writes its time: a file-scope `const` from a uniform, which NVIDIA
        // takes and Mesa refuses; Mesa takes a plain global with that initializer.
        let text = "#version 420 compatibility\nuniform float sunAngle;\nconst float globalTime = fract(sunAngle) * 12e2;\nconst float twice = globalTime * 2.0;\nconst float half_ = 0.5;\nconst bool colortex2MipmapEnabled = true;\nconst int _A = 0x64bd29, _B = _A, _C = int(sunAngle);\nvoid main() { const int digits[2] = int[2](_A, _B); gl_FragColor = vec4(twice * half_ * float(digits[1] + _C)); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert!(out.contains("\n float globalTime = fract(sunAngle) * 12e2;\n float twice = globalTime * 2.0;\nconst float half_ = 0.5;"), "{out}");
        assert!(out.contains("\nconst bool colortex2MipmapEnabled = true;"), "{out}");
        // As espen96/Loop declares its glyphs: one `const` for many names, each judged alone;
        // the one from a uniform takes the declaration's `const` with it.
        assert!(out.contains("\n int _A = 0x64bd29, _B = _A, _C = int(sunAngle);"), "{out}");
        assert_eq!(rewrites.len(), 1, "{rewrites:?}");
        assert_eq!(rewrites[0].line, 3);
        assert!(out.contains("void main() {  int digits[2]"), "{out}");
        assert!(rewrites[0].what.contains("`globalTime`"), "{}", rewrites[0].what);
    }

    #[test]
    fn a_const_from_a_variable_given_by_a_macro_loses_its_const() {
        // As HalcyonShaders writes it: `cv(float)` is `const float`, and `cRCP(float, total)`
        // declares `const float totalRCP = 1.0 / total`, from a parameter both.
        let text = "#version 120\n#define cv(type) const type\n#define cRCP(type, name) const type name##RCP = 1.0 / name\nfloat f(float angle, float total) {\n    cv(float) c = cos(angle);\n    cRCP(float, total);\n    return c * totalRCP;\n}\nvoid main() { gl_FragColor = vec4(f(1.0, 2.0)); }\n";
        let met = "#version 120\n\n\nfloat f(float angle, float total) {\n    const float c = cos(angle);\n    const float totalRCP = 1.0 / total;\n    return c * totalRCP;\n}\nvoid main() { gl_FragColor = vec4(f(1.0, 2.0)); }\n";
        let (out, rewrites) = for_strict_drivers(text, met, Stage::Fragment, &[]);
        assert!(out.contains("    float c = cos(angle);"), "{out}");
        assert!(out.contains("    float totalRCP = 1.0 / total ;"), "{out}");
        assert_eq!(rewrites.len(), 2, "{rewrites:?}");
        assert_eq!((rewrites[0].line, rewrites[1].line), (5, 6));
        assert!(rewrites[1].what.starts_with("`cRCP(…)`, which declares `totalRCP`"), "{}", rewrites[1].what);
        // A directive's line between the statement before and the declaration.
        let after_directive = text.replace("    cv(float) c", "    #ifdef NEVER\n    #endif\n    cv(float) c");
        let met_after_directive = met.replace("    const float c", "\n\n    const float c");
        let (out, _) = for_strict_drivers(&after_directive, &met_after_directive, Stage::Fragment, &[]);
        assert!(out.contains("    #endif\n    float c = cos(angle);"), "{out}");
        // A constant of that name in another function keeps its `const`.
        let other = text.replace("void main()", "float g() { cv(vec3) c = vec3(1.0); return c.x; }\nvoid main()");
        let met_other = met.replace("void main()", "float g() { const vec3 c = vec3(1.0); return c.x; }\nvoid main()");
        let (out, _) = for_strict_drivers(&other, &met_other, Stage::Fragment, &[]);
        assert!(out.contains("    float c = cos(angle);") && out.contains("{ cv(vec3) c = vec3(1.0);"), "{out}");
        // A call outside a function stays as written.
        let global = text.replace("float f(", "const float size = 2.0;\ncRCP(float, size);\nfloat f(");
        let met_global = met.replace("float f(", "const float size = 2.0;\nconst float sizeRCP = 1.0 / size;\nfloat f(");
        let (out, _) = for_strict_drivers(&global, &met_global, Stage::Fragment, &[]);
        assert!(out.contains("\ncRCP(float, size);\n"), "{out}");
    }

    #[test]
    fn the_fragment_depth_read_and_never_written_reads_as_the_fragments_own() {
        // As jbritain/glint-shaders' shadow pass reads it.
        let text = "#version 450 compatibility\nout vec4 data;\nvoid main() {\n    float depthToOpaque = gl_FragDepth - 0.5;\n    data = vec4(depthToOpaque);\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("gl_FragDepth", "gl_FragCoord.z"));
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 4);
        let written = text.replace("    data =", "    gl_FragDepth = 0.5;\n    data =");
        assert_eq!(for_strict_drivers(&written, &written, Stage::Fragment, &[]), (written.clone(), Vec::new()));
    }

    #[test]
    fn nvidia_only_functions_are_spelled_out() {
        // As saadam1n/MinecraftShaders writes them: a function returning a sampler, one
        // definition per branch, and parameters with default values.
        let text = "#version 120\nuniform sampler2D gaux4;\nuniform sampler2D depthtex1;\n#ifdef GBUFFERS\nsampler2D depthSource() {\n    return gaux4;\n}\n#else\nsampler2D depthSource() {\n    return depthtex1;\n}\n#endif\n\
                    vec4 move(in vec3 at = vec3(0.0), in float by = 1.0) { return vec4(at * by, 1.0); }\n\
                    void main() {\n    #endif\n    for (float i = 0.0; i < 2.0; i++) {}\n    gl_FragColor = texture2D(depthSource(), move().xy) + move(vec3(1.0)) + move(vec3(1.0), 2.0);\n}\n";
        let met = "#version 120\nuniform sampler2D gaux4;\nuniform sampler2D depthtex1;\n\n\n\n\n\nsampler2D depthSource() {\n    return depthtex1;\n}\n\n\
                   vec4 move(in vec3 at = vec3(0.0), in float by = 1.0) { return vec4(at * by, 1.0); }\n\
                   void main() {\n\n    for (float i = 0.0; i < 2.0; i++) {}\n    gl_FragColor = texture2D(depthSource(), move().xy) + move(vec3(1.0)) + move(vec3(1.0), 2.0);\n}\n";
        let (out, rewrites) = for_strict_drivers(text, met, Stage::Fragment, &[]);
        assert!(out.contains("\n#define depthSource() gaux4 ") && out.contains("\n#define depthSource() depthtex1 "), "{out}");
        assert!(out.contains("vec4 move(in vec3 at  , in float by  ) {"), "{out}");
        assert!(out.contains("move(vec3 ( 0.0 ), 1.0).xy) + move(vec3(1.0), 1.0) + move(vec3(1.0), 2.0)"), "{out}");
        assert!(out.contains("for (float i = 0.0;"), "{out}");
        assert_eq!(out.lines().count(), text.lines().count());
        assert!(rewrites.iter().any(|r| r.what.starts_with("default values of parameters")), "{rewrites:?}");
        assert_eq!(rewrites.iter().filter(|r| r.what.contains("made a macro")).count(), 2, "{rewrites:?}");
    }

    #[test]
    fn a_function_named_without_a_call_is_removed() {
        let text = "#version 430 compatibility\nvoid commons() {}\nvoid main() {\n    commons;\n    commons();\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Vertex, &[]);
        assert_eq!(out, text.replace("    commons;", "    ;"));
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 4);
        // A variable of that name is a statement drivers take.
        let variable = "#version 430 compatibility\nvoid main() {\n    float commons = 1.0;\n    commons;\n}\n";
        assert_eq!(for_strict_drivers(variable, variable, Stage::Vertex, &[]), (variable.to_string(), Vec::new()));
    }

    #[test]
    fn a_bias_in_a_vertex_stage_is_read_as_the_level() {
        let text = "#version 120\nuniform sampler2D tex;\nvec2 f(vec2 a, float b) { return a * b; }\n\
                    vec4 reflected(vec2 uv) { return texture2D(tex, f(uv, 2.0), 0.0) + texture2D(tex, uv); }\n\
                    void main() { gl_Position = vec4(0.0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Vertex, &[]);
        assert!(out.contains("texture2DLod(tex, f(uv, 2.0), 0.0) + texture2D(tex, uv)"), "{out}");
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 4);
        assert!(rewrites[0].what.starts_with("`texture2D()` with a bias in a vertex stage"), "{}", rewrites[0].what);
        // A fragment stage has a level to bias.
        assert_eq!(for_strict_drivers(text, text, Stage::Fragment, &[]), (text.to_string(), Vec::new()));
        // From 1.30, `texture()` too.
        let core = "#version 330 core\nuniform sampler2D tex;\nin vec2 uv;\nvoid main() { gl_Position = texture(tex, uv, 1.0); }\n";
        let (out, _) = for_strict_drivers(core, core, Stage::Vertex, &[]);
        assert!(out.contains("textureLod(tex, uv, 1.0)"), "{out}");
    }

    #[test]
    fn a_sampler_named_texture_is_renamed_where_it_hides_the_function() {
        let text = "#version 130\nuniform sampler2D texture;\nin vec2 uv;\nvoid main() { gl_FragColor = texture2D(texture, uv) + texture(texture, uv); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert!(out.contains("uniform sampler2D gtexture;"), "{out}");
        assert!(out.contains("texture2D(gtexture, uv) + texture(gtexture, uv)"), "{out}");
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 2);
        // Under 1.20 there is no function to hide: left alone.
        let old = "#version 120\nuniform sampler2D texture;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(texture, uv); }\n";
        assert_eq!(for_strict_drivers(old, old, Stage::Fragment, &[]), (old.to_string(), Vec::new()));
    }

    #[test]
    fn a_glsl_120_stage_calling_a_130_function_is_compiled_as_130() {
        let text = "#version 120\nuniform sampler2D tex;\nvarying vec2 uv;\nvoid main() { gl_FragData[0] = texture(tex, uv); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("#version 120", "#version 130"));
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].what, "#version 120 raised to 130 for `texture()`, a GLSL 1.30 function");
        // A call the preprocessor leaves out (a branch for 1.30 and later) does not count.
        let guarded = "#version 120\nuniform sampler2D tex;\nvarying vec2 uv;\nvoid main() {\n#if __VERSION__ >= 130\ngl_FragData[0] = texture(tex, uv);\n#endif\n}\n";
        let preprocessed = "#version 120\nuniform sampler2D tex;\nvarying vec2 uv;\nvoid main() {\n\n\n\n}\n";
        assert_eq!(for_strict_drivers(guarded, preprocessed, Stage::Fragment, &[]), (guarded.to_string(), Vec::new()));
        let plain = "#version 120\nuniform sampler2D tex;\nvarying vec2 uv;\nvoid main() { gl_FragData[0] = texture2D(tex, uv); }\n";
        assert_eq!(for_strict_drivers(plain, plain, Stage::Fragment, &[]), (plain.to_string(), Vec::new()));
    }

    #[test]
    fn a_120_stage_with_level_lookups_gets_the_extension_that_allows_them() {
        let text = "#version 120\nuniform sampler2D tex;\nvarying vec2 uv;\nvoid main() { gl_FragData[0] = texture2DLod(tex, uv, 0.0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("#version 120\n", "#version 120\n#extension GL_ARB_shader_texture_lod : enable\n"));
        assert_eq!(rewrites, [Rewrite { line: 1, what: "GL_ARB_shader_texture_lod enabled after #version for `texture2DLod()`".into() }]);
        // Already enabled, or not called: left alone.
        let enabled = text.replace("#version 120\n", "#version 120\n#extension GL_ARB_shader_texture_lod : enable\n");
        assert_eq!(for_strict_drivers(&enabled, &enabled, Stage::Fragment, &[]), (enabled.clone(), Vec::new()));
    }

    #[test]
    fn a_120_stage_with_integer_operations_gets_gpu_shader4() {
        let text = "#version 120\nuniform sampler2D s;\nvoid main() { gl_FragColor = texelFetch2D(s, ivec2(7 % 3, 0), 0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("#version 120\n", "#version 120\n#extension GL_EXT_gpu_shader4 : enable\n"));
        assert_eq!(rewrites, [Rewrite { line: 1, what: "GL_EXT_gpu_shader4 enabled after #version for `texelFetch2D()`".into() }]);
        let operator_only = "#version 120\nvoid main() { gl_FragColor = vec4(float(7 % 3)); }\n";
        assert_eq!(for_strict_drivers(operator_only, operator_only, Stage::Fragment, &[]).1[0].what, "GL_EXT_gpu_shader4 enabled after #version for `%`");
        let flat = "#version 120\nflat varying float id;\nvoid main() {}\n";
        assert_eq!(for_strict_drivers(flat, flat, Stage::Fragment, &[]).1[0].what, "GL_EXT_gpu_shader4 enabled after #version for `flat`");
        let enabled = text.replace("#version 120\n", "#version 120\n#extension GL_EXT_gpu_shader4 : enable\n");
        assert_eq!(for_strict_drivers(&enabled, &enabled, Stage::Fragment, &[]).1, []);
    }

    #[test]
    fn a_glsl_es_100_stage_is_compiled_as_desktop_120() {
        let text = "#version 100\nprecision mediump float;\nuniform sampler2D tex;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(tex, uv); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        // ES's precision statement is a reserved word in desktop 1.20, so it goes too.
        assert_eq!(out, "#version 120\n  \nuniform sampler2D tex;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(tex, uv); }\n");
        assert_eq!(rewrites[0].what, "#version 100 (GLSL ES 1.00) compiled as desktop #version 120, as NVIDIA compiles it in a desktop context");
        assert_eq!(rewrites.len(), 2);
    }

    #[test]
    fn extension_lookups_a_130_stage_lacks_are_enabled_or_renamed() {
        let text = "#version 130\nuniform sampler2D s;\nin vec2 uv;\nvoid main() { gl_FragData[0] = texture2DGradARB(s, uv, uv, uv) + texture2DGrad(s, uv, uv, uv) + texelFetch2D(s, ivec2(0), 0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert!(out.starts_with("#version 130\n#extension GL_ARB_shader_texture_lod : enable\n"), "{out}");
        assert!(out.contains("texture2DGradARB(s, uv, uv, uv) + textureGrad(s, uv, uv, uv) + texelFetch(s, ivec2(0), 0)"), "{out}");
        let whats: Vec<&str> = rewrites.iter().map(|r| r.what.as_str()).collect();
        assert_eq!(
            whats,
            [
                "GL_ARB_shader_texture_lod enabled after #version for `texture2DGradARB()`",
                "GL_EXT_gpu_shader4's lookups (texture2DGrad() & co.), which GLSL 130 lacks, renamed to its own (2 calls)"
            ]
        );
        assert_eq!(glsl130_name("texture2DArrayLod"), "textureLod");
        assert_eq!(glsl130_name("textureSizeCube"), "textureSize");
        assert_eq!(glsl130_name("texelFetch2DOffset"), "texelFetchOffset");
        assert!(is_texture_lod_arb("shadow2DProjGradARB") && !is_texture_lod_arb("texture2DARB"));
    }

    #[test]
    fn a_120_stage_with_a_switch_is_compiled_as_130() {
        let text = "#version 120\nuniform int mode;\nvoid main() { switch (mode) { default: gl_FragColor = vec4(1.0); } }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("#version 120", "#version 130"));
        assert_eq!(rewrites, [Rewrite { line: 1, what: "#version 120 raised to 130 for `switch`, a GLSL 1.30 statement".into() }]);
    }

    #[test]
    fn a_flat_varying_of_a_stage_raised_to_130_is_declared_in_or_out() {
        let vertex = "#version 120\nuniform int mode;\nflat varying vec3 n;\nvarying vec2 uv;\nvoid main() { switch (mode) { default: break; } n = gl_Normal; uv = vec2(0.0); gl_Position = ftransform(); }\n";
        let (out, rewrites) = for_strict_drivers(vertex, vertex, Stage::Vertex, &[]);
        assert_eq!(out, vertex.replace("#version 120", "#version 130").replace("flat varying", "flat out"));
        assert_eq!(rewrites[1], Rewrite { line: 3, what: "`varying` after an interpolation qualifier, which GLSL 1.30 refuses, made `out` (1 declarations)".into() });
        let fragment = "#version 120\nflat varying vec3 n;\nvoid main() { gl_FragColor = vec4(round(n), 1.0); }\n";
        let (out, _) = for_strict_drivers(fragment, fragment, Stage::Fragment, &[]);
        assert_eq!(out, fragment.replace("#version 120", "#version 130").replace("flat varying", "flat in"));
    }

    #[test]
    fn a_120_stage_declaring_in_or_out_is_compiled_as_130() {
        let text = "#version 120\nattribute vec4 mc_Entity;\nin vec3 at_velocity;\nvarying vec2 uv;\nvoid main() { uv = at_velocity.xy; gl_Position = ftransform(); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Vertex, &[]);
        assert_eq!(out, text.replace("#version 120", "#version 130"));
        assert_eq!(rewrites, [Rewrite { line: 1, what: "#version 120 raised to 130 for `in` declarations, GLSL 1.30 storage qualifiers".into() }]);
        // A parameter's `in` is GLSL 1.10.
        let parameter = "#version 120\nvarying vec2 uv;\nfloat f(in float x, out float y) { y = x; return x; }\nvoid main() { float y; gl_FragColor = vec4(f(uv.x, y)); }\n";
        assert_eq!(for_strict_drivers(parameter, parameter, Stage::Fragment, &[]), (parameter.to_string(), Vec::new()));
    }

    #[test]
    fn a_460_stage_using_nothing_of_460_is_compiled_as_450() {
        let text = "#version 460 core\nout vec4 colour;\nvoid main() { colour = vec4(1.0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("#version 460", "#version 450"));
        assert_eq!(rewrites, [Rewrite { line: 1, what: "#version 460 lowered to 450: the stage uses nothing GLSL 4.60 added".into() }]);
        // What 4.60 took from ARB extensions: under their names, the extensions enabled.
        let draw_id = "#version 460 core\nflat out int id;\nvoid main() { id = gl_DrawID; gl_Position = vec4(anyInvocation(id > 0) ? 1.0 : 0.0); }\n";
        let (out, rewrites) = for_strict_drivers(draw_id, draw_id, Stage::Vertex, &[]);
        assert_eq!(
            out,
            "#version 450 core\n#extension GL_ARB_shader_draw_parameters : enable\n#extension GL_ARB_shader_group_vote : enable\nflat out int id;\n\
             void main() { id = gl_DrawIDARB; gl_Position = vec4(anyInvocationARB(id > 0) ? 1.0 : 0.0); }\n"
        );
        assert_eq!(rewrites.len(), 1);
        assert!(rewrites[0].what.contains("(gl_DrawID, anyInvocation)"), "{}", rewrites[0].what);
    }

    #[test]
    fn fragment_inputs_the_vertex_stage_lacks_are_declared_there_and_zeroed() {
        let vertex = "#version 120\nvarying vec2 uv;\nvoid main() {\n    uv = gl_MultiTexCoord0.xy;\n}\n";
        let fragment = "#version 120\nvarying vec2 uv;\nvarying vec3 lightColor;\nvoid main() { gl_FragColor = vec4(lightColor, uv.x); }\n";
        let (out, what) = vertex_outputs_completed(vertex, fragment).expect("one input missing");
        assert_eq!(out, "#version 120\nvarying vec2 uv;\nvarying vec3 lightColor; void main() { lightColor = vec3(0);\n    uv = gl_MultiTexCoord0.xy;\n}\n");
        assert!(what.ends_with("`lightColor`"), "{what}");
        let modern = "#version 330\nflat in int id;\nin float fog;\nnoperspective in vec2 screen;\nflat in mat3 unread;\nvoid main() { gl_FragColor = vec4(id, fog, screen); }\n";
        let (out, _) = vertex_outputs_completed("#version 330\nvoid main() {}\n", modern).expect("three inputs missing");
        assert_eq!(out, "#version 330\nflat out int id; out float fog; noperspective out vec2 screen; void main() { id = int(0); fog = float(0); screen = vec2(0);}\n");
        assert_eq!(vertex_outputs_completed(vertex, "varying vec2 uv;\nvoid main() {}\n"), None);
    }

    #[test]
    fn a_version_after_directives_is_moved_first() {
        let text = "#define BONUS\n#ifndef PATCHED\n#version 430 compatibility\n#endif\nvoid main() {}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, "#version 430 compatibility\n#define BONUS\n#ifndef PATCHED\n#endif\nvoid main() {}\n");
        assert_eq!(rewrites, [Rewrite { line: 3, what: "`#version 430 compatibility`, after directives, moved to the first line as NVIDIA takes it".into() }]);
        let commented = "// a pack\n#version 120\nvoid main() {}\n";
        assert_eq!(for_strict_drivers(commented, commented, Stage::Fragment, &[]).1, []);
    }

    #[test]
    fn an_output_placed_by_layout_before_330_enables_its_extension() {
        let text = "#version 120\nlayout(location = 1) out vec4 extra;\nvoid main() { gl_FragData[0] = vec4(1.0); extra = vec4(0.5); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert!(out.starts_with("#version 130\n#extension GL_ARB_explicit_attrib_location : enable\n"), "{out}");
        assert!(rewrites.iter().any(|r| r.what == "GL_ARB_explicit_attrib_location enabled after #version for `layout(location = …)`"), "{rewrites:?}");
    }

    #[test]
    fn an_extension_after_a_pragma_is_moved_up() {
        let text = "#version 120\n#pragma optimize (on)\n#ifdef MC_GL_ARB_gpu_shader5\n#extension GL_ARB_gpu_shader5 : require\n#endif\nvoid main() {}\n";
        let preprocessed = "#version 120\n#pragma optimize (on)\n#extension GL_ARB_gpu_shader5 : require\nvoid main() {}\n";
        let (out, rewrites) = for_strict_drivers(text, preprocessed, Stage::Fragment, &[]);
        assert_eq!(out, "#version 120\n#extension GL_ARB_gpu_shader5 : require\n#pragma optimize (on)\n#ifdef MC_GL_ARB_gpu_shader5\n\n#endif\nvoid main() {}\n");
        assert_eq!(rewrites, [Rewrite { line: 4, what: "`#extension GL_ARB_gpu_shader5 : require` after code moved up to follow #version".into() }]);
    }

    #[test]
    fn a_sampler_chosen_by_a_condition_becomes_a_choice_of_lookups() {
        let text = "uniform sampler2D a, b;\nvarying vec2 uv;\nuniform bool light;\nvoid main() {\n    gl_FragColor = texture2D(light ? a :\n        b, uv * 0.5);\n}\n";
        let (out, rewrites) = lenient_expressions(text).expect("one rewrite");
        assert_eq!(out.lines().nth(4), Some("    gl_FragColor = (light ? texture2D(a, uv * 0.5) : texture2D(b, uv * 0.5))"));
        assert_eq!(out.lines().nth(5), Some(";"));
        assert_eq!(out.lines().count(), text.lines().count(), "lines stay where they were");
        assert_eq!(rewrites[0].line, 5);
        assert!(rewrites[0].what.contains("`texture2D()` of a sampler chosen by `?:`"), "{}", rewrites[0].what);
        let suffixed = "void main() { vec2 l = vec2(1.0) * 37f / 32.0 - 1.05f / 32.0 + 0x1F; }";
        let (out, rewrites) = lenient_expressions(suffixed).expect("one rewrite");
        assert_eq!(out, "void main() { vec2 l = vec2(1.0) * 37.0 / 32.0 - 1.05f / 32.0 + 0x1F; }");
        assert_eq!(rewrites[0].what, "`37f`, an integer with a float suffix, which NVIDIA reads as a float, written `37.0` (1 literals)");
        // Both at once: the literal is written as a float in each of the two lookups.
        let (out, rewrites) = lenient_expressions("void main() { vec4 c = texture2D(b ? s : t, uv * 2f); }").expect("two rewrites");
        assert_eq!(out, "void main() { vec4 c = (b ? texture2D(s, uv * 2.0) : texture2D(t, uv * 2.0)); }");
        assert_eq!(rewrites.len(), 2);
        // A choice of coordinates, or of samplers in an index, is GLSL.
        for kept in ["texture2D(a, light ? uv : -uv)", "texture2D(s[light ? 0 : 1], uv)", "texture2D(light ? a : b[0], uv)"] {
            assert_eq!(lenient_expressions(&format!("void main() {{ vec4 c = {kept}; }}")), None, "{kept}");
        }
    }

    #[test]
    fn directives_naming_no_macro_are_read_as_iris_reads_them() {
        let text = "#version 330 compatibility\n#define 2D_CLOUDS\n#ifdef 2D_CLOUDS\nint clouds;\n#endif\nvoid main() {}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, "#version 330 compatibility\n \n#if 1\nint clouds;\n#endif\nvoid main() {}\n");
        assert_eq!(rewrites.iter().map(|r| r.line).collect::<Vec<_>>(), [2, 3]);
        assert_eq!(rewrites[0].what, "`#define 2D_CLOUDS`, which names no macro, removed as Iris's preprocessor skips it");
    }

    #[test]
    fn a_local_read_before_anything_writes_it_is_set_to_0() {
        let text = "#version 120\nvoid main() {\n    vec3 col;\n    float kept;\n    kept = 1.0;\n    for (int i = 0; i < 2; i++) { col += vec3(kept); }\n    gl_FragColor = vec4(col, 1.0);\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("vec3 col;", "vec3 col = vec3(0);"));
        assert_eq!(rewrites.len(), 1);
        assert_eq!(rewrites[0].line, 3);
        assert!(rewrites[0].what.starts_with("`col`, which may be read before it is written whole"), "{}", rewrites[0].what);
        // A struct's member of the same name is not a local.
        let member = "#version 120\nstruct Light { vec3 col; };\nvoid main() {\n    Light l;\n    l.col = vec3(1.0);\n    gl_FragColor = vec4(l.col, 1.0);\n}\n";
        assert_eq!(for_strict_drivers(member, member, Stage::Fragment, &[]), (member.to_string(), Vec::new()));
        // Written in part first: the rest is undefined.
        let part = "#version 120\nvoid main() {\n    vec2 v;\n    v.x = 1.0;\n    gl_FragColor = vec4(v, 0.0, 1.0);\n}\n";
        assert_eq!(for_strict_drivers(part, part, Stage::Fragment, &[]).0, part.replace("vec2 v;", "vec2 v = vec2(0);"));
        // Written by each branch of an `if`, or through an `out` parameter: left as it is.
        let branches = "#version 120\nuniform float u;\nvoid set(out float y) { y = 1.0; }\nvoid main() {\n    float x;\n    if (u > 0.0) { x = 1.0; } else { x = 2.0; }\n    float y;\n    set(y);\n    gl_FragColor = vec4(x, y, 0.0, 1.0);\n}\n";
        assert_eq!(for_strict_drivers(branches, branches, Stage::Fragment, &[]), (branches.to_string(), Vec::new()));
        // Handed to an `inout` parameter, it is read (Cynun/CRShaders' bloom); to a built-in
        // that may write it, left as it is.
        // Another function's local of the same name and another type counts on its own.
        let inout = "#version 120\nvec3 blur() { vec3 bloom; bloom += vec3(1.0); return bloom; }\n\
                     void add(inout vec4 sum, float x) { sum.rgb += vec3(x); }\nvoid main() {\n    vec4 bloom;\n    add(bloom, 1.0);\n\
                     float whole;\n    float part = modf(1.5, whole);\n    gl_FragColor = bloom + vec4(whole + blur(), 1.0);\n}\n";
        let (out, rewrites) = for_strict_drivers(inout, inout, Stage::Fragment, &[]);
        assert_eq!(out, inout.replace("vec4 bloom;", "vec4 bloom = vec4(0);").replace("vec3 bloom;", "vec3 bloom = vec3(0);"));
        assert_eq!(rewrites.len(), 1, "{rewrites:?}");
    }

    #[test]
    fn tokens_after_a_directive_that_ignores_them_are_removed() {
        let text = "#version 120\n#ifndef BASIC && defined NORMALS\nfloat a;\n#else if defined SHADOW\nfloat b;\n#endif\nvoid main() {}\n";
        let (out, rewrites) = for_strict_drivers(text, "#version 120\nfloat a;\nvoid main() {}\n", Stage::Fragment, &[]);
        assert_eq!(out, text.replace("#ifndef BASIC && defined NORMALS", "#ifndef BASIC   ").replace("#else if defined SHADOW", "#else   "));
        assert_eq!(
            rewrites,
            [
                Rewrite { line: 2, what: "`#ifndef BASIC` ignores what follows: `&& defined NORMALS` removed".into() },
                Rewrite { line: 4, what: "`#else` ignores what follows: `if defined SHADOW` removed".into() },
            ]
        );
    }

    #[test]
    fn a_value_is_converted_where_it_appears_or_as_the_lines_right_hand_side() {
        let text = "float a = 2.0 * texture2D(depth, uv);\nif (d < x) return i / STEPS;\nfloat b = f(1, 2), c = f(1, 2);\n";
        let converted = |line, value| convert_on_line(text, line, "float", value, None).map(|(text, converted)| (text.lines().nth(line as usize - 1).unwrap().to_string(), converted));
        assert_eq!(
            converted(1, "2.0 * texture2D(depth, uv)"),
            Some(("float a = float(2.0 * texture2D(depth, uv));".to_string(), "2.0 * texture2D(depth, uv)".to_string()))
        );
        // naga saw the macro expanded: the return's value is taken whole.
        assert_eq!(converted(2, "i / 16u"), Some(("if (d < x) return float(i / STEPS);".to_string(), "i / STEPS".to_string())));
        // Twice on the line, with two assignments: nothing to go by.
        assert_eq!(convert_on_line(text, 3, "float", "f(1, 2)", None), None);
        // Told by the operator beside it.
        let compared = "void main() {\n    if (a > 0 || c != 0) {}\n}\n";
        let (text, value) = convert_on_line(compared, 2, "vec2", "0", Some("!=")).unwrap();
        assert_eq!((text.lines().nth(1).unwrap(), value.as_str()), ("    if (a > 0 || c != vec2(0)) {}", "0"));
    }

    #[test]
    fn a_lookup_offset_becomes_a_moved_coordinate() {
        assert_eq!(
            offset_as_coordinate("textureOffset(tx, uv, curOffset * live)", 2, false).as_deref(),
            Some("texture(tx, uv + vec2(curOffset * live) / vec2(textureSize(tx, 0)))")
        );
        assert_eq!(
            offset_as_coordinate("textureLodOffset(sampler2D(tx, s), f(a, b), 2.0, ivec2(i, 1))", 2, false).as_deref(),
            Some("textureLod(sampler2D(tx, s), f(a, b) + vec2(ivec2(i, 1)) / vec2(textureSize(sampler2D(tx, s), int(2.0))), 2.0)")
        );
        assert_eq!(
            offset_as_coordinate("textureOffset(tx, uv, o)", 2, true).as_deref(),
            Some("textureLod(tx, uv + vec2(o) / vec2(textureSize(tx, 0)), 0.0)")
        );
        assert_eq!(offset_as_coordinate("texture(tx, uv)", 2, false), None);
        let text = "vec4 a = textureOffset(tx, uv, o) + textureOffset(tx, uv, -o);\nvec4 b = textureOffset(tx, uv, o);\n";
        let (out, n) = offsets_as_coordinates_on_line(text, 1, 2, false).unwrap();
        assert_eq!(n, 2);
        assert_eq!(out.lines().next(), Some("vec4 a = texture(tx, uv + vec2(o) / vec2(textureSize(tx, 0))) + texture(tx, uv + vec2(-o) / vec2(textureSize(tx, 0)));"));
        assert_eq!(out.lines().nth(1), Some("vec4 b = textureOffset(tx, uv, o);"));
    }

    #[test]
    fn a_redefined_macro_is_undefined_first() {
        let text = "#version 120\n#define PI 3.14\n#define PI 3.14159\nvoid main() { gl_FragColor = vec4(PI); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[(3, "PI".into())]);
        assert_eq!(out, text.replace("#define PI 3.14159", "#undef PI\n#define PI 3.14159"));
        assert_eq!(rewrites, [Rewrite { line: 3, what: "`PI` redefined with another body: `#undef PI` inserted before it".into() }]);
    }

    #[test]
    fn a_function_without_return_returns_zero() {
        let text = "#version 120\nfloat remap(float x) {\n    mix(0.0, 1.0, x);\n}\nvec2 kept(vec2 a) { if (a.x > 0.0) { return a; } }\nvoid main() { gl_FragColor = vec4(remap(0.5)); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("    mix(0.0, 1.0, x);\n}", "    mix(0.0, 1.0, x);\nreturn float(0); }"));
        assert_eq!(rewrites, [Rewrite { line: 2, what: "`remap` returns float but has no `return`: `return float(0);` added at its end".into() }]);
    }

    /// Before GLSL 1.40 Mesa refuses to link a vertex stage that never writes `gl_Position`
    /// (MichuuMichuu18/minecraft-shaders' composite6 writes it only under an option that is
    /// off); from 1.40 on it links.
    #[test]
    fn a_position_nothing_writes_is_set_to_zero_before_glsl_140() {
        let text = "#version 120\nvarying vec2 uv;\nvoid main() {\n#ifdef GLOW\n    gl_Position = ftransform();\n#endif\n    uv = vec2(0.0);\n}\n";
        let preprocessed = "#version 120\nvarying vec2 uv;\nvoid main() {\n\n\n\n    uv = vec2(0.0);\n}\n";
        let (out, rewrites) = for_strict_drivers(text, preprocessed, Stage::Vertex, &[]);
        assert_eq!(out, text.replace("void main() {", "void main() { gl_Position = vec4(0);"));
        assert_eq!(rewrites, [Rewrite { line: 3, what: "outputs nothing writes set to 0 at the start of main: `gl_Position`".into() }]);
        let core = preprocessed.replace("#version 120", "#version 140").replace("varying", "out");
        assert_eq!(for_strict_drivers(&core, &core, Stage::Vertex, &[]).1, []);
    }

    /// An input declared `out` in a fragment stage that writes `gl_FragData`
    /// (YaoYaoSiLin/fflap-shader's shadow `out float blockID`): Mesa refuses the mix; the
    /// output, never written, becomes a global holding 0.
    #[test]
    fn an_output_only_read_beside_frag_data_becomes_a_global() {
        let text = "#version 130\n#extension GL_ARB_explicit_attrib_location : enable\nout float blockID;\nout vec4 written;\nlayout(location = 8) out vec4 placed;\nvoid main() {\n    gl_FragData[0] = vec4(blockID);\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("out float blockID;", " float blockID = float(0);").replace("out vec4 written;", " vec4 written = vec4(0);"));
        // An output placed by `layout` stays one (DrDesten/Groundwork's locations 8 and 9).
        assert_eq!(rewrites.len(), 2, "{rewrites:?}");
        assert!(rewrites[0].what.starts_with("`out float blockID`, read and never written beside `gl_FragData`"), "{rewrites:?}");
        let writing = text.replace("gl_FragData[0] = vec4(blockID);", "gl_FragData[0] = vec4(1.0); written.x = 1.0;");
        let rewrites = for_strict_drivers(&writing, &writing, Stage::Fragment, &[]).1;
        assert!(!rewrites.iter().any(|r| r.what.starts_with("`out vec4 written`")), "{rewrites:?}");
    }

    /// texture2D() of an integer sampler (YaoYaoSiLin/fflap-shader's `gaux3`, a usampler2D),
    /// which NVIDIA takes and Mesa refuses, becomes texture(); the float sampler's call stays.
    #[test]
    fn a_legacy_lookup_of_an_integer_sampler_becomes_texture() {
        let text = "#version 130\nuniform usampler2D bits;\nuniform sampler2D colour;\nvoid main() {\n    gl_FragData[0] = vec4(texture2D(bits, vec2(0.5)).r) + texture2D(colour, vec2(0.5));\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("texture2D(bits", "texture(bits"));
        assert_eq!(rewrites.len(), 1, "{rewrites:?}");
        assert!(rewrites[0].what.starts_with("texture2D() & co. of an integer sampler"), "{rewrites:?}");
    }

    #[test]
    fn a_vertex_output_nothing_writes_is_set_to_zero() {
        let text = "#version 130\nflat out vec2 offsets;\nout float used;\n#ifdef NEVER\nvoid f() { offsets = vec2(1.0); }\n#endif\nvoid main() {\n    used = 1.0; gl_Position = vec4(used);\n}\n";
        let preprocessed = "#version 130\nflat out vec2 offsets;\nout float used;\n\n\n\nvoid main() {\n    used = 1.0; gl_Position = vec4(used);\n}\n";
        let (out, rewrites) = for_strict_drivers(text, preprocessed, Stage::Vertex, &[]);
        assert_eq!(out, text.replace("void main() {", "void main() { offsets = vec2(0);"));
        assert_eq!(rewrites, [Rewrite { line: 7, what: "outputs nothing writes set to 0 at the start of main: `offsets`".into() }]);
        assert_eq!(for_strict_drivers(text, preprocessed, Stage::Fragment, &[]).1, []);
    }

    #[test]
    fn a_vertex_output_written_on_some_paths_is_set_to_zero_first() {
        // `ray` is added to before it is first assigned whole: its first value is undefined.
        let text = "#version 120\nattribute vec4 mc_Entity;\nvarying float isWater;\nvarying vec4 color;\nvarying vec2 uv;\nvarying float fog;\nvarying vec3 ray;\nvoid setUv() { uv = vec2(0.5); }\nvoid setFog() { if (mc_Entity.y > 0.0) { fog = 1.0; } }\nvoid main() {\n    color.rgb = vec3(1.0);\n    if (mc_Entity.x == 8.0) isWater = 1.0;\n    setUv();\n    setFog();\n    ray += vec3(0.5);\n    ray = ray * 2.0;\n    gl_Position = ftransform();\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Vertex, &[]);
        assert_eq!(out, text.replace("void main() {", "void main() { isWater = float(0); color = vec4(0); fog = float(0); ray = vec3(0);"));
        assert_eq!(rewrites.len(), 1);
        assert!(rewrites[0].what.contains("not written whole on every path") && rewrites[0].what.ends_with("`isWater`, `color`, `fog`, `ray`"), "{rewrites:?}");
    }

    #[test]
    fn a_fragment_output_written_on_some_paths_is_set_to_zero_first() {
        // As Makenbo/pretty-aesthetic-minecraft-shader's water writes its normal: Mesa's
        // compiler took the undefined value as the one written, wgpu's is 0.
        let text = "#version 330 compatibility\nvarying vec3 normal;\nvarying float water;\nlayout(location = 2) out vec4 extra;\nvoid main() {\n    if (water > 0.5) gl_FragData[1] = vec4(normal, 1.0);\n    gl_FragData[0] = vec4(1.0);\n    if (water > 0.5) { extra = vec4(water); }\n}\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("void main() {", "void main() { extra = vec4(0); gl_FragData[1] = vec4(0);"));
        assert_eq!(rewrites.len(), 1);
        assert!(rewrites[0].what.ends_with("`extra`, `gl_FragData[1]`"), "{rewrites:?}");
        // After an early `return`, as Matyanson/boxeh-shader's water leaves non-water: what
        // `main` assigns later is left unwritten on the path that returned.
        let returning = "#version 120\nvarying float water;\nvoid main() {\n    gl_FragData[1] = vec4(1.0);\n    if (water < 0.5) { gl_FragData[0] = vec4(0.5); return; }\n    gl_FragData[2] = vec4(water);\n}\n";
        let (out, rewrites) = for_strict_drivers(returning, returning, Stage::Fragment, &[]);
        assert_eq!(out, returning.replace("void main() {", "void main() { gl_FragData[0] = vec4(0); gl_FragData[2] = vec4(0);"));
        assert!(rewrites[0].what.ends_with("`gl_FragData[0]`, `gl_FragData[2]`"), "{rewrites:?}");
        // Outputs handed whole to `out` parameters, as our own water writes them, are written.
        let handed = "#version 330 compatibility\nout vec4 colour;\nout vec4 data;\nvoid outputs(in float a, out vec4 c, out vec4 d) { c = vec4(a); d = vec4(a); }\nvoid main() {\n    outputs(0.5, colour, data);\n}\n";
        assert_eq!(for_strict_drivers(handed, handed, Stage::Fragment, &[]), (handed.to_string(), Vec::new()));
    }

    #[test]
    fn precision_qualifiers_before_130_are_removed() {
        let text = "#version 120\nprecision mediump float;\nlowp float hash(lowp vec2 p) { return p.x; }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, "#version 120\n  \n float hash( vec2 p) { return p.x; }\n");
        assert_eq!(rewrites, [Rewrite { line: 2, what: "precision qualifiers, reserved words in GLSL 120, removed (3)".into() }]);
        let modern = text.replace("#version 120", "#version 130");
        assert_eq!(for_strict_drivers(&modern, &modern, Stage::Fragment, &[]).1, []);
    }

    #[test]
    fn deprecated_lookups_in_a_core_profile_become_their_successors() {
        let text = "#version 420\nuniform sampler2D colortex0;\nin vec2 uv;\nout vec4 o;\nvoid main() { o = texture2D(colortex0, uv) + texture2DLod(colortex0, uv, 1.0); }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, text.replace("texture2D(", "texture(").replace("texture2DLod(", "textureLod("));
        assert_eq!(rewrites, [Rewrite { line: 5, what: "texture2D() & co., which a core profile lacks, renamed to texture() & co. (2 calls)".into() }]);
        let compatibility = text.replace("#version 420", "#version 420 compatibility");
        assert_eq!(for_strict_drivers(&compatibility, &compatibility, Stage::Fragment, &[]).1, []);
    }

    #[test]
    fn reserved_words_used_as_names_get_a_suffix_everywhere() {
        let text = "#version 330\nvec3 output;\nvoid main() { output = vec3(1.0); float filter = 2.0; output *= filter; }\n";
        let (out, rewrites) = for_strict_drivers(text, text, Stage::Fragment, &[]);
        assert_eq!(out, "#version 330\nvec3 output_;\nvoid main() { output_ = vec3(1.0); float filter_ = 2.0; output_ *= filter_; }\n");
        assert_eq!(rewrites.iter().map(|r| r.line).collect::<Vec<_>>(), [2, 3]);
        // A taken name is not reused.
        let (out, _) = for_strict_drivers("#version 120\nfloat input_;\nfloat input;\n", "#version 120\nfloat input_;\nfloat input;\n", Stage::Fragment, &[]);
        assert!(out.contains("float input__;"), "{out}");
    }
}
