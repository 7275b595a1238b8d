//! Where a fragment stage's implicit derivatives are undefined.
//!
//! GLSL defines an implicit derivative (the mipmap level `texture2D` picks, `dFdx`, `fwidth`)
//! only where the four fragments of a 2x2 quad compute it together. Inside an `if` or a loop
//! that the quad's fragments take differently, it is undefined, and two correct compilers fill
//! it from different values (a bloom pass's `texture2D` inside the `if` that picks its tile, on
//! the quads straddling the tile's edge). [`traced`] rewrites a fragment stage so that, instead
//! of its colours, it writes 1 on the quads whose fragments ran different sequences of such
//! calls and 0 elsewhere: there the stage's result is not GLSL's to define. A call is told
//! apart by its site and by the path of function calls it was reached through: a bloom pass
//! calls one `tile` function per tile, and the fragments of a quad straddling two tiles' edge
//! run the same lookup site as often, each inside another call.

use std::collections::BTreeMap;

use tidepack_glsl::lower::is_statement_keyword;
use tidepack_glsl::token::{TokenKind, function_definitions, matching_close, tokenize};

/// Lookups that pick their level from implicit derivatives (those without an explicit level or
/// gradient).
const IMPLICIT_LEVEL_LOOKUPS: &[&str] = &[
    "texture1D", "texture1DProj", "texture2D", "texture2DProj", "texture3D", "texture3DProj", "textureCube",
    "shadow1D", "shadow1DProj", "shadow2D", "shadow2DProj", "texture", "textureProj", "textureOffset",
    "textureProjOffset", "textureQueryLod",
];

/// The derivative functions.
const DERIVATIVES: &[&str] = &["dFdx", "dFdy", "fwidth", "dFdxFine", "dFdyFine", "fwidthFine", "dFdxCoarse", "dFdyCoarse", "fwidthCoarse"];

/// The global the traced stage accumulates each fragment's sequence of derivative calls in.
const TRACE: &str = "tp_derivative_trace";

/// The global a call of a function of the stage sets to the hash of its call path, which the
/// function keeps in its local [`CONTEXT_HERE`] on entry.
const CONTEXT: &str = "tp_derivative_context";

/// Each function's copy of [`CONTEXT`] as it was entered: the path of calls that reached it.
const CONTEXT_HERE: &str = "tp_context_here";

/// `fragment` (a stage as OpenGL compiles it) rewritten to write, into each of `outputs` (by
/// location: `gl_FragData[1]`, `gl_FragColor` or a declared output, whose type `output_type`
/// gives), 1.0 where the fragment's 2x2 quad ran different sequences of implicit-derivative
/// calls and 0.0 elsewhere. Each call adds its site and its function's call path to a running
/// hash of the fragment's sequence; after the stage's own `main`, `fwidth` of the hash, taken
/// in uniform flow, is nonzero exactly on such quads. A lookup in a sampler named directly that `level_free` says
/// reads the same at every level (no mipmaps, one filter) is no such call. None where the text
/// cannot be traced (it does not tokenize, has no `main`, or an output's type is unknown).
pub fn traced(
    fragment: &str,
    outputs: &BTreeMap<u32, String>,
    output_type: impl Fn(u32) -> Option<String>,
    level_free: impl Fn(&str) -> bool,
) -> Option<String> {
    let tokens = tokenize(fragment).ok()?;
    let sig: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect();
    let definitions = function_definitions(&tokens);
    let mains: Vec<usize> = definitions.iter().map(|d| d.name).filter(|&i| tokens[i].is_ident("main")).collect();
    if mains.is_empty() {
        return None;
    }
    // The first definition's return type (the significant token before its name).
    let first_name = definitions[0].name;
    let return_type = sig.iter().rev().find(|&&i| i < first_name).map_or(first_name, |&i| i);
    let mut writes = String::new();
    for (&location, name) in outputs {
        let ty = if name.starts_with("gl_Frag") { "vec4".to_string() } else { output_type(location)? };
        writes.push_str(&format!(" {name} = {ty}(tp_undefined);"));
    }
    // Insertions by byte offset; at one offset, in the order they are to appear.
    let mut insertions: Vec<(usize, String)> = Vec::new();
    let defined: Vec<&str> = definitions.iter().map(|d| tokens[d.name].text).collect();
    for definition in &definitions {
        let open = &tokens[definition.open];
        insertions.push((open.offset + open.text.len(), format!(" float {CONTEXT_HERE} = {CONTEXT};")));
    }
    let in_body = |i: usize| definitions.iter().any(|d| d.open < i && i < d.close);
    let mut site = 0u32;
    for (k, &i) in sig.iter().enumerate() {
        let t = &tokens[i];
        let lookup = IMPLICIT_LEVEL_LOOKUPS.contains(&t.text);
        let derivative = lookup || DERIVATIVES.contains(&t.text);
        if t.kind != TokenKind::Ident || !(derivative || defined.contains(&t.text)) {
            continue;
        }
        let before = k.checked_sub(1).map(|p| &tokens[sig[p]]);
        // A member (`.texture`) or a declaration of a function of that name (after its return
        // type) is no call.
        let declared = before.is_some_and(|b| b.kind == TokenKind::Ident && !is_statement_keyword(b.text));
        if declared || before.is_some_and(|b| b.is_punct(".")) || !sig.get(k + 1).is_some_and(|&n| tokens[n].is_punct("(")) {
            continue;
        }
        let Some(close) = matching_close(&sig, &tokens, k + 1) else { continue };
        let sampler = sig.get(k + 2).map(|&i| &tokens[i]).filter(|s| s.kind == TokenKind::Ident && sig.get(k + 3).is_some_and(|&n| tokens[n].is_punct(",")));
        if lookup && sampler.is_some_and(|s| level_free(s.text)) {
            continue;
        }
        // Outside a function (a global's initializer) there is no call path to keep.
        let context_here = if in_body(i) { CONTEXT_HERE } else { "0.0" };
        site += 1;
        let marked = if derivative {
            format!("({TRACE} = mod({TRACE} * 31.0 + mod({context_here} * 37.0 + {site}.0, 65521.0), 65521.0), ")
        } else if in_body(i) {
            format!("({CONTEXT} = mod({context_here} * 31.0 + {site}.0, 65521.0), ")
        } else {
            continue;
        };
        insertions.push((t.offset, marked));
        let end = &tokens[sig[close]];
        insertions.push((end.offset + end.text.len(), ")".to_string()));
    }
    for &i in &mains {
        insertions.push((tokens[i].offset, "tp_".to_string()));
        insertions.push((tokens[i].offset + tokens[i].text.len(), "_traced".to_string()));
    }
    insertions.push((declaration_offset(fragment, tokens[return_type].offset), format!("float {TRACE};\nfloat {CONTEXT};\n")));
    let mut text = fragment.to_string();
    // From the end, so that earlier offsets stay valid; a stable sort keeps the order at one offset.
    insertions.sort_by_key(|(offset, _)| *offset);
    for (offset, insertion) in insertions.iter().rev() {
        text.insert_str(*offset, insertion);
    }
    text.push_str(&format!(
        "\nvoid main() {{ {TRACE} = 0.0; {CONTEXT} = 0.0; tp_main_traced(); float tp_undefined = fwidth({TRACE}) > 0.0 ? 1.0 : 0.0;{writes} }}\n"
    ));
    Some(text)
}

/// Where a global can be declared ahead of every function: the start of the line that holds
/// the first function definition's return type (`at`), or, where `#if`s enclose that line, of
/// the outermost one's line.
fn declaration_offset(text: &str, at: usize) -> usize {
    let mut depth = 0usize;
    let mut offset = 0;
    let mut chosen = 0;
    for line in text.split_inclusive('\n') {
        if offset > at {
            break;
        }
        if depth == 0 {
            chosen = offset;
        }
        let directive = line.trim_start().strip_prefix('#').map(|rest| rest.trim_start().split(|c: char| !c.is_ascii_alphanumeric()).next().unwrap_or(""));
        match directive {
            Some("if" | "ifdef" | "ifndef") => depth += 1,
            Some("endif") => depth = depth.saturating_sub(1),
            _ => {}
        }
        offset += line.len();
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_call_adds_its_site_and_call_path_and_main_writes_the_quads_that_ran_others() {
        let fragment = "#version 120\n#ifdef A\n#extension GL_EXT_gpu_shader4 : enable\n#endif\nuniform sampler2D tex;\n\
            vec4 tile(vec2 uv) { return texture2D(tex, uv * 2.0); }\n\
            void main() {\n    vec4 c = uv.x > 0.5 ? tile(texture2D(tex, uv).xy) : vec4(dFdx(uv.x));\n    gl_FragData[1] = c;\n}\n";
        let outputs = BTreeMap::from([(1, "gl_FragData[1]".to_string())]);
        let traced = traced(fragment, &outputs, |_| None, |_| false).expect("traced");
        let expected = "#version 120\n#ifdef A\n#extension GL_EXT_gpu_shader4 : enable\n#endif\nuniform sampler2D tex;\n\
            float tp_derivative_trace;\nfloat tp_derivative_context;\n\
            vec4 tile(vec2 uv) { float tp_context_here = tp_derivative_context; return (tp_derivative_trace = mod(tp_derivative_trace * 31.0 + mod(tp_context_here * 37.0 + 1.0, 65521.0), 65521.0), texture2D(tex, uv * 2.0)); }\n\
            void tp_main_traced() { float tp_context_here = tp_derivative_context;\n    vec4 c = uv.x > 0.5 ? \
            (tp_derivative_context = mod(tp_context_here * 31.0 + 2.0, 65521.0), tile((tp_derivative_trace = mod(tp_derivative_trace * 31.0 + mod(tp_context_here * 37.0 + 3.0, 65521.0), 65521.0), texture2D(tex, uv)).xy)) : \
            vec4((tp_derivative_trace = mod(tp_derivative_trace * 31.0 + mod(tp_context_here * 37.0 + 4.0, 65521.0), 65521.0), dFdx(uv.x)));\n    gl_FragData[1] = c;\n}\n\n\
            void main() { tp_derivative_trace = 0.0; tp_derivative_context = 0.0; tp_main_traced(); float tp_undefined = fwidth(tp_derivative_trace) > 0.0 ? 1.0 : 0.0; \
            gl_FragData[1] = vec4(tp_undefined); }\n";
        assert_eq!(traced, expected);
    }

    #[test]
    fn declared_outputs_take_their_type_and_an_unknown_one_traces_nothing() {
        let fragment = "#version 330 compatibility\nlayout(location = 0) out vec3 colour;\nvoid main() { colour = vec3(1.0); }\n";
        let outputs = BTreeMap::from([(0, "colour".to_string())]);
        let traced = traced(fragment, &outputs, |location| (location == 0).then(|| "vec3".to_string()), |_| false).expect("traced");
        assert!(traced.ends_with("colour = vec3(tp_undefined); }\n"), "{traced}");
        assert!(traced.contains("out vec3 colour;\nfloat tp_derivative_trace;\nfloat tp_derivative_context;\nvoid tp_main_traced()"), "{traced}");
        assert_eq!(super::traced(fragment, &outputs, |_| None, |_| false), None);
    }

    #[test]
    fn the_trace_is_declared_ahead_of_the_conditional_holding_the_first_function() {
        let fragment = "#version 120\nuniform sampler2D tex;\n#ifdef B\n#define X 1\nvec4\nlookup(vec2 uv) { return texture2D(tex, uv); }\n#endif\nvoid main() {}\n";
        let traced = traced(fragment, &BTreeMap::new(), |_| None, |_| false).expect("traced");
        assert!(traced.starts_with("#version 120\nuniform sampler2D tex;\nfloat tp_derivative_trace;\nfloat tp_derivative_context;\n#ifdef B\n"), "{traced}");
    }

    #[test]
    fn a_lookup_in_a_sampler_without_levels_is_no_call() {
        let fragment = "void main() { if (gl_FragCoord.x > 3.0) gl_FragColor = texture2D(colortex1, vec2(0.5)) + texture2D(colortex2, vec2(0.5)); }\n";
        let traced = traced(fragment, &BTreeMap::from([(0, "gl_FragColor".to_string())]), |_| None, |name| name == "colortex1").expect("traced");
        assert!(traced.contains("texture2D(colortex1, vec2(0.5)) + (tp_derivative_trace = mod(tp_derivative_trace * 31.0 + mod(tp_context_here * 37.0 + 1.0, 65521.0), 65521.0), texture2D(colortex2"), "{traced}");
    }

    #[test]
    fn a_function_named_like_a_lookup_and_a_member_are_not_calls() {
        let fragment = "vec4 texture2D(sampler2D s, vec2 uv);\nvoid main() { gl_FragColor = vec4(s.texture(1.0)); }\n";
        let traced = traced(fragment, &BTreeMap::from([(0, "gl_FragColor".to_string())]), |_| None, |_| false).expect("traced");
        assert!(!traced.contains("31.0"), "{traced}");
    }
}
