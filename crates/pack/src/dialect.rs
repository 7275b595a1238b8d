//! The two GLSL dialects the pack ships, generated from one template.
//!
//! Templates are written in `#version 330 compatibility`. Both dialects turn the
//! `RENDERTARGETS` directive into `DRAWBUFFERS`, which every OptiFine reads. The 330 dialect
//! otherwise keeps the template, giving each `out vec4 outColorN` its `layout(location = N)`
//! (OptiFine before 1.16.5 G8 does not bind it by name); the 120 dialect rewrites, token by
//! token: top-level `in`/`out` to `attribute`/`varying`, `out vec4 outColorN` to
//! `gl_FragData[N]`, `texture`/`textureLod` on 2D samplers to `texture2D`/`texture2DLod`.
//! Constructs that GLSL 120 lacks are errors at the template line, so a template always means
//! the same thing in both dialects.
//!
//! Generation inserts exactly one line (the header) and changes no other line break, so a line
//! of a shipped file maps back to its template by [`template_line`].

use std::collections::HashMap;
use std::fmt;

use tidepack_glsl::token::{Token, TokenKind, tokenize};
use tidepack_glsl::{Code, Diagnostic, Location, Stage};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dialect {
    Glsl120,
    Glsl330,
}

impl Dialect {
    pub const ALL: [Dialect; 2] = [Dialect::Glsl120, Dialect::Glsl330];

    /// `glsl120` / `glsl330`, as used in zip names.
    pub fn slug(self) -> &'static str {
        match self {
            Dialect::Glsl120 => "glsl120",
            Dialect::Glsl330 => "glsl330",
        }
    }

    pub fn version_line(self) -> &'static str {
        match self {
            Dialect::Glsl120 => "#version 120",
            Dialect::Glsl330 => "#version 330 compatibility",
        }
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Dialect::Glsl120 => "GLSL 120",
            Dialect::Glsl330 => "GLSL 330 compatibility",
        })
    }
}

/// The version line every program template starts with.
pub const TEMPLATE_VERSION: &str = "#version 330 compatibility";

/// The line of a shipped file that holds the generated-by header: after `#version` in
/// programs, first in other files.
pub fn header_line(template_text: &str) -> u32 {
    if template_text.starts_with("#version") { 2 } else { 1 }
}

/// The template line a shipped line came from; `None` for the header itself.
pub fn template_line(shipped_line: u32, header_line: u32) -> Option<u32> {
    match shipped_line.cmp(&header_line) {
        std::cmp::Ordering::Less => Some(shipped_line),
        std::cmp::Ordering::Equal => None,
        std::cmp::Ordering::Greater => Some(shipped_line - 1),
    }
}

/// Combined sampler types by name, over every template (uniforms and function parameters), so
/// a lookup in a lib file knows the type of a sampler its includer declares.
pub fn sampler_types<'a>(templates: impl IntoIterator<Item = &'a str>) -> HashMap<String, String> {
    let mut types = HashMap::new();
    for text in templates {
        let Ok(tokens) = tokenize(text) else { continue };
        let sig: Vec<&Token<'_>> = tokens.iter().filter(|t| !t.is_trivia()).collect();
        for pair in sig.windows(2) {
            if pair[0].kind == TokenKind::Ident && pair[0].text.contains("sampler") && pair[1].kind == TokenKind::Ident {
                types.insert(pair[1].text.to_string(), pair[0].text.to_string());
            }
        }
    }
    types
}

/// GLSL words and operators a template may not use because GLSL 120 lacks them.
const NOT_IN_120: [&str; 22] = [
    "flat", "smooth", "noperspective", "centroid", "layout", "switch", "case", "uint", "uvec2", "uvec3",
    "uvec4", "texelFetch", "textureSize", "textureGrad", "%", "<<", ">>", "&", "|", "^", "~", "%=",
];

/// Generates the shipped text of one template (`path` is pack-relative, e.g. `composite.fsh`).
pub fn generate(
    template_path: &str,
    path: &str,
    text: &str,
    dialect: Dialect,
    samplers: &HashMap<String, String>,
    header: &str,
) -> Result<String, Diagnostic> {
    let stage = Stage::from_path(path);
    let err = |line: u32, message: String| Diagnostic::error(Code::Template, message, Some(Location::line(template_path, line)));
    if stage.is_some() && !text.starts_with(TEMPLATE_VERSION) {
        return Err(err(1, format!("a program template starts with `{TEMPLATE_VERSION}`")));
    }
    let body = match dialect {
        Dialect::Glsl330 => for_every_loader_330(text, stage).map_err(|(line, m)| err(line, m))?,
        Dialect::Glsl120 => downlevel_to_120(text, stage, samplers).map_err(|(line, m)| err(line, m))?,
    };
    let mut out = String::with_capacity(body.len() + header.len() + 2);
    if header_line(text) == 2 {
        let (first, rest) = body.split_once('\n').unwrap_or((&body, ""));
        out.push_str(first);
        out.push('\n');
        out.push_str(header);
        out.push('\n');
        out.push_str(rest);
    } else {
        out.push_str(header);
        out.push('\n');
        out.push_str(&body);
    }
    Ok(out)
}

fn downlevel_to_120(
    text: &str,
    stage: Option<Stage>,
    samplers: &HashMap<String, String>,
) -> Result<String, (u32, String)> {
    let tokens = tokenize(text).map_err(|e| (e.line, e.message))?;
    let sig: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect();
    let mut replaced: HashMap<usize, String> = HashMap::new();
    let mut skip_until = 0;
    let mut brace_depth = 0;
    let mut paren_depth = 0;
    let mut statement_start = true;
    let mut line_of_directive = 0;
    let mut version_blocks = VersionBlocks::default();
    for (k, &i) in sig.iter().enumerate() {
        let t = &tokens[i];
        if i < skip_until {
            continue;
        }
        if t.is_punct("#") {
            line_of_directive = t.line;
        }
        let in_directive = t.line == line_of_directive;
        let directive_name = in_directive && k >= 1 && tokens[sig[k - 1]].is_punct("#");
        if directive_name {
            version_blocks.enter(t.text, &tokens, &sig[k + 1..]);
        }
        if version_blocks.skipped_in_120() {
            // Text GLSL 120's preprocessor never reads: it stays as written.
            continue;
        }
        if directive_name && t.is_ident("version") {
            // Replace the whole `#version …` line.
            let end = (i..tokens.len()).find(|&j| tokens[j].kind == TokenKind::Newline).unwrap_or(tokens.len());
            replaced.insert(sig[k - 1], Dialect::Glsl120.version_line().to_string());
            for j in sig[k - 1] + 1..end {
                replaced.insert(j, String::new());
            }
            skip_until = end;
            continue;
        }
        if NOT_IN_120.contains(&t.text) && matches!(t.kind, TokenKind::Ident | TokenKind::Punct) {
            return Err((t.line, format!("`{}` is not available in GLSL 120; the template must work in both dialects", t.text)));
        }
        match t.text {
            "{" => brace_depth += 1,
            "}" => brace_depth -= 1,
            "(" => paren_depth += 1,
            ")" => paren_depth -= 1,
            _ => {}
        }
        let top_level = brace_depth == 0 && paren_depth == 0 && !in_directive;
        let was_start = statement_start;
        statement_start = !in_directive && (t.is_punct(";") || t.is_punct("}")) || (in_directive && statement_start);
        if top_level && was_start && (t.is_ident("in") || t.is_ident("out")) {
            let Some(stage) = stage else {
                return Err((t.line, "in/out declarations belong in program files, not in lib files".into()));
            };
            let end = (k..sig.len()).find(|&j| tokens[sig[j]].is_punct(";")).ok_or((t.line, "declaration without `;`".to_string()))?;
            let name = tokens[sig[end - 1]].text;
            match (stage, t.text) {
                (Stage::Vertex, "in") => {
                    replaced.insert(i, "attribute".into());
                }
                (Stage::Fragment, "out") => {
                    let index = output_index(name)
                        .ok_or((t.line, format!("fragment outputs are named outColor<N> (OptiFine's naming), not `{name}`")))?;
                    replaced.insert(i, format!("// {name} is gl_FragData[{index}] in GLSL 120"));
                    for &j in &sig[k + 1..=end] {
                        replaced.insert(j, String::new());
                    }
                    for j in (i + 1..=sig[end]).filter(|&j| tokens[j].kind == TokenKind::Whitespace) {
                        replaced.insert(j, String::new());
                    }
                    skip_until = sig[end] + 1;
                    statement_start = true;
                }
                _ => {
                    replaced.insert(i, "varying".into());
                }
            }
            continue;
        }
        match t.kind {
            TokenKind::Ident if output_index(t.text).is_some() && stage == Some(Stage::Fragment) => {
                replaced.insert(i, format!("gl_FragData[{}]", output_index(t.text).unwrap()));
            }
            TokenKind::Ident if matches!(t.text, "texture" | "textureLod") => {
                let is_call = sig.get(k + 1).is_some_and(|&j| tokens[j].is_punct("("));
                if !is_call {
                    continue;
                }
                let sampler = sig.get(k + 2).map(|&j| &tokens[j]).filter(|a| a.kind == TokenKind::Ident);
                let ty = sampler.and_then(|s| samplers.get(s.text));
                if ty.map(String::as_str) != Some("sampler2D") {
                    return Err((
                        t.line,
                        format!("`{}` must take a sampler2D by name so it can be written as texture2D in GLSL 120", t.text),
                    ));
                }
                if t.text == "textureLod" && stage == Some(Stage::Fragment) {
                    return Err((t.line, "textureLod is not available in GLSL 120 fragment shaders".into()));
                }
                replaced.insert(i, if t.text == "texture" { "texture2D" } else { "texture2DLod" }.into());
            }
            _ => {}
        }
    }
    replaced.extend(drawbuffers_directives(&tokens)?);
    let mut out = String::with_capacity(text.len());
    for (i, t) in tokens.iter().enumerate() {
        match replaced.get(&i) {
            Some(r) => out.push_str(r),
            None => out.push_str(t.text),
        }
    }
    Ok(out)
}

/// The conditional blocks of a template that GLSL 120 skips: the branch of `#if __VERSION__ >= N`
/// (N > 120) or the `#else` of `#if __VERSION__ < N`. A template may use GLSL 130+ words there,
/// with its GLSL 120 alternative in the other branch.
#[derive(Default)]
struct VersionBlocks {
    /// One entry per open `#if`/`#ifdef`/`#ifndef`: for a version test, whether it holds in
    /// GLSL 120; None for any other condition (both branches are read as GLSL 120).
    open: Vec<Option<bool>>,
}

impl VersionBlocks {
    /// Follows the directive named `name`; `rest` are the significant tokens after the name.
    fn enter(&mut self, name: &str, tokens: &[Token], rest: &[usize]) {
        match name {
            "if" => self.open.push(Self::version_test(tokens, rest)),
            "ifdef" | "ifndef" => self.open.push(None),
            "else" => {
                if let Some(Some(holds)) = self.open.last_mut() {
                    *holds = !*holds;
                }
            }
            // A chain of conditions: read the rest as GLSL 120, to be safe.
            "elif" => {
                if let Some(last) = self.open.last_mut() {
                    *last = None;
                }
            }
            "endif" => {
                self.open.pop();
            }
            _ => {}
        }
    }

    fn skipped_in_120(&self) -> bool {
        self.open.contains(&Some(false))
    }

    /// For `__VERSION__ >= N` or `__VERSION__ < N` alone on the line: whether it holds in GLSL 120.
    fn version_test(tokens: &[Token], rest: &[usize]) -> Option<bool> {
        let line = tokens[*rest.first()?].line;
        let words: Vec<&str> = rest.iter().map(|&j| &tokens[j]).take_while(|t| t.line == line).map(|t| t.text).collect();
        let [name, op, number] = words.as_slice() else { return None };
        let version: u32 = number.parse().ok()?;
        match (*name, *op) {
            ("__VERSION__", ">=") => Some(120 >= version),
            ("__VERSION__", "<") => Some(120 < version),
            _ => None,
        }
    }
}

/// The GLSL 330 text, made to work on every loader: `RENDERTARGETS` (OptiFine 1.16.5 G8 and
/// later) becomes `DRAWBUFFERS`, which every OptiFine reads, and each `out vec4 outColorN;` of a
/// fragment program gets `layout(location = N)`, since OptiFine before G8 does not bind
/// `outColorN` to draw buffer N. Line breaks stay as written.
fn for_every_loader_330(text: &str, stage: Option<Stage>) -> Result<String, (u32, String)> {
    let tokens = tokenize(text).map_err(|e| (e.line, e.message))?;
    let mut replaced = drawbuffers_directives(&tokens)?;
    if stage == Some(Stage::Fragment) {
        let sig: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect();
        let mut depth = 0i32;
        let mut line_of_directive = 0;
        let mut statement_start = true;
        for (k, &i) in sig.iter().enumerate() {
            let t = &tokens[i];
            if t.is_punct("#") {
                line_of_directive = t.line;
            }
            if t.line == line_of_directive {
                continue;
            }
            match t.text {
                "{" | "(" => depth += 1,
                "}" | ")" => depth -= 1,
                _ => {}
            }
            if depth == 0 && statement_start && t.is_ident("out") {
                let end = (k..sig.len()).find(|&j| tokens[sig[j]].is_punct(";")).ok_or((t.line, "declaration without `;`".to_string()))?;
                let name = tokens[sig[end - 1]].text;
                let index = output_index(name)
                    .ok_or((t.line, format!("fragment outputs are named outColor<N> (OptiFine's naming), not `{name}`")))?;
                replaced.insert(i, format!("layout(location = {index}) out"));
            }
            statement_start = t.is_punct(";") || t.is_punct("}");
        }
    }
    let mut out = String::with_capacity(text.len() + 64);
    for (i, t) in tokens.iter().enumerate() {
        out.push_str(replaced.get(&i).map_or(t.text, String::as_str));
    }
    Ok(out)
}

/// `/* RENDERTARGETS: a,b */` comments as `/* DRAWBUFFERS:ab */`, which older loaders read
/// (buffers 0-9 only).
fn drawbuffers_directives(tokens: &[Token]) -> Result<HashMap<usize, String>, (u32, String)> {
    let mut replaced = HashMap::new();
    for (i, t) in tokens.iter().enumerate() {
        if t.kind == TokenKind::BlockComment
            && let Some(list) = t.text.trim_start_matches("/*").trim_end_matches("*/").trim().strip_prefix("RENDERTARGETS:")
        {
            let buffers: Vec<&str> = list.split(',').map(str::trim).collect();
            if buffers.iter().any(|b| b.len() != 1 || !b.chars().all(|c| c.is_ascii_digit())) {
                return Err((t.line, format!("DRAWBUFFERS can only name buffers 0-9, not `{}`", list.trim())));
            }
            replaced.insert(i, format!("/* DRAWBUFFERS:{} */", buffers.concat()));
        }
    }
    Ok(replaced)
}

/// `N` of an output named `outColorN`.
fn output_index(name: &str) -> Option<u32> {
    name.strip_prefix("outColor").and_then(|n| n.parse().ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    const FSH: &str = "#version 330 compatibility
uniform sampler2D colortex0;
in vec2 uv;
/* RENDERTARGETS: 0,4 */
out vec4 outColor0;
out vec4 outColor1;
out vec4 outColor2;
vec4 tap(sampler2D s, in vec2 p) { return texture(s, p); }
void main() {
    outColor0 = texture(colortex0, uv);
    outColor1 = tap(colortex0, uv);
}
";

    fn samplers() -> HashMap<String, String> {
        sampler_types([FSH])
    }

    #[test]
    fn generates_120_line_for_line() {
        let out = generate("t/a.fsh", "a.fsh", FSH, Dialect::Glsl120, &samplers(), "// header").unwrap();
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines.len(), FSH.lines().count() + 1);
        assert_eq!(lines[0], "#version 120");
        assert_eq!(lines[1], "// header");
        assert_eq!(lines[3], "varying vec2 uv;");
        assert_eq!(lines[4], "/* DRAWBUFFERS:04 */");
        assert_eq!(lines[5], "// outColor0 is gl_FragData[0] in GLSL 120");
        assert_eq!(lines[6], "// outColor1 is gl_FragData[1] in GLSL 120");
        assert_eq!(lines[7], "// outColor2 is gl_FragData[2] in GLSL 120");
        assert_eq!(lines[8], "vec4 tap(sampler2D s, in vec2 p) { return texture2D(s, p); }");
        assert_eq!(lines[10], "    gl_FragData[0] = texture2D(colortex0, uv);");
        assert_eq!(lines[11], "    gl_FragData[1] = tap(colortex0, uv);");
    }

    #[test]
    fn generates_330_for_every_loader_line_for_line() {
        let out = generate("t/a.fsh", "a.fsh", FSH, Dialect::Glsl330, &samplers(), "// header").unwrap();
        let expected = FSH
            .replacen('\n', "\n// header\n", 1)
            .replace("/* RENDERTARGETS: 0,4 */", "/* DRAWBUFFERS:04 */")
            .replace("\nout vec4 outColor", "\nlayout(location = N) out vec4 outColor");
        let expected: String = expected
            .lines()
            .map(|l| match l.strip_prefix("layout(location = N) out vec4 outColor") {
                Some(rest) => format!("layout(location = {}) out vec4 outColor{rest}\n", &rest[..1]),
                None => format!("{l}\n"),
            })
            .collect();
        assert_eq!(out, expected);
        // A vertex program and lib files keep their text.
        let vsh = "#version 330 compatibility\nout vec2 uv;\nvoid main() {}\n";
        let out = generate("t/a.vsh", "a.vsh", vsh, Dialect::Glsl330, &HashMap::new(), "//").unwrap();
        assert_eq!(out, vsh.replacen('\n', "\n//\n", 1));
    }

    #[test]
    fn vertex_in_out_become_attribute_varying() {
        let vsh = "#version 330 compatibility\nin vec4 mc_Entity;\nout float material;\nvoid f(in float a, out float b) { b = a; }\n";
        let out = generate("t/a.vsh", "a.vsh", vsh, Dialect::Glsl120, &HashMap::new(), "//").unwrap();
        assert!(out.contains("\nattribute vec4 mc_Entity;\nvarying float material;\n"), "{out}");
        assert!(out.contains("void f(in float a, out float b)"), "{out}");
    }

    #[test]
    fn constructs_missing_from_120_are_errors_at_their_line() {
        for (src, needle) in [
            ("#version 330 compatibility\n\nflat in float m;\n", "`flat`"),
            ("#version 330 compatibility\n\nint a = 5 % 2;\n", "`%`"),
            ("#version 330 compatibility\nuniform sampler3D v;\nvec4 a = texture(v, vec3(0));\n", "sampler2D"),
        ] {
            let err = generate("t/a.fsh", "a.fsh", src, Dialect::Glsl120, &sampler_types([src]), "//").unwrap_err();
            let loc = err.location.clone().unwrap();
            assert_eq!((loc.path.as_str(), loc.line), ("t/a.fsh", 3), "{err}");
            assert!(err.message.contains(needle), "{err}");
        }
    }

    #[test]
    fn branches_glsl_120_skips_may_use_newer_glsl() {
        let src = "#version 330 compatibility
uniform sampler2D colortex0;
in vec2 uv;
vec4 own() {
#if __VERSION__ >= 130
    return texelFetch(colortex0, ivec2(gl_FragCoord.xy), 0);
#else
    return texture(colortex0, uv);
#endif
}
#if __VERSION__ < 130
float a = 1.0;
#else
uint b = 1u;
#endif
";
        let out = generate("t/a.fsh", "a.fsh", src, Dialect::Glsl120, &sampler_types([src]), "//").unwrap();
        let lines: Vec<&str> = out.lines().collect();
        // Kept as written where GLSL 120 never reads it, downlevelled where it does.
        assert_eq!(lines[6], "    return texelFetch(colortex0, ivec2(gl_FragCoord.xy), 0);");
        assert_eq!(lines[8], "    return texture2D(colortex0, uv);");
        assert_eq!(lines[12], "float a = 1.0;");
        assert_eq!(lines[14], "uint b = 1u;");
    }

    #[test]
    fn newer_glsl_outside_a_version_branch_is_still_an_error() {
        for src in [
            "#version 330 compatibility\n#ifdef A\nuint a;\n#endif\n",
            "#version 330 compatibility\n#if __VERSION__ >= 110\nuint a;\n#endif\n",
            "#version 330 compatibility\n#if __VERSION__ >= 130\n#else\nuint a;\n#endif\n",
            "#version 330 compatibility\n#if __VERSION__ >= 130\n#elif B\nuint a;\n#endif\n",
            "#version 330 compatibility\n#if __VERSION__ >= 130\n#endif\nuint a;\n",
        ] {
            let err = generate("t/a.fsh", "a.fsh", src, Dialect::Glsl120, &HashMap::new(), "//").unwrap_err();
            assert!(err.message.contains("`uint`"), "{src}: {err}");
        }
    }

    #[test]
    fn header_mapping() {
        assert_eq!([1, 2, 3, 10].map(|l| template_line(l, 2)), [Some(1), None, Some(2), Some(9)]);
        assert_eq!([1, 2].map(|l| template_line(l, 1)), [None, Some(1)]);
    }
}
