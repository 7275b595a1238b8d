//! What Iris does to a stage's text before the driver compiles it (IrisShaders/Iris, its
//! preprocessor and `CommonTransformer`/`CompatibilityTransformer`), as text-to-text rewrites
//! that keep every line where it was, so that diagnostics still name the pack's lines. Each
//! returns the rewritten text and what was done, or `None` where nothing applies.

use tidepack_glsl::{Location, Stage};
use tidepack_glsl::preprocess;
use tidepack_glsl::token::{Token, TokenKind, blanked, brace_depths, function_definitions, significant, tokenize};

/// A file-scope declaration of a name: its first and last significant token (the `;`), as
/// indices into the significant tokens, whether it is a `uniform sampler2D`, and how many names
/// it declares.
#[derive(Clone, Copy)]
struct Declaration {
    first: usize,
    last: usize,
    sampler: bool,
    names: usize,
}

/// The file-scope declarations naming `name` among `tokens` (`order`: the significant ones).
fn file_scope_declarations(tokens: &[Token<'_>], order: &[usize], name: &str) -> Vec<Declaration> {
    let depths = brace_depths(tokens);
    let mut found = Vec::new();
    let mut start = 0usize;
    for (k, &i) in order.iter().enumerate() {
        if depths[i] != 0 {
            start = k + 1;
            continue;
        }
        if tokens[i].is_punct(";") || tokens[i].is_punct("}") {
            let statement = &order[start..k];
            if statement.iter().any(|&j| tokens[j].is_ident(name)) && !statement.iter().any(|&j| tokens[j].is_punct("(")) {
                let sampler = statement.iter().any(|&j| tokens[j].is_ident("uniform")) && statement.iter().any(|&j| tokens[j].is_ident("sampler2D"));
                let names = 1 + statement.iter().filter(|&&j| tokens[j].is_punct(",")).count();
                found.push(Declaration { first: start, last: k, sampler, names });
            }
            start = k + 1;
        }
    }
    found
}

/// What Iris's transformer does to a stage, as far as it is imitated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Transform {
    /// The albedo sampler named `gtexture` ([`albedo_sampler_as_gtexture`]).
    pub renames_albedo_sampler: bool,
    /// Functions nothing calls removed ([`unused_functions_removed`]).
    pub removes_unused_functions: bool,
    /// `#version` raised to 3.30 ([`version_raised_to_330`]).
    pub raises_version: bool,
}

impl Transform {
    /// All of it, as Iris does it to every stage of the world's programs.
    pub const ALL: Transform = Transform { renames_albedo_sampler: true, removes_unused_functions: true, raises_version: true };
}

/// `text` with the rewrites of Iris's transformer `transform` asks for, each decided on `seen`,
/// the stage as Iris's preprocessor leaves it, of `stage` (`None`: a geometry or other stage);
/// and what was done.
pub fn as_transformed(mut text: String, seen: &str, transform: Transform, stage: Option<Stage>) -> (String, Vec<String>) {
    let mut done = Vec::new();
    if transform.renames_albedo_sampler && let Some((rewritten, what)) = albedo_sampler_as_gtexture(&text, seen) {
        text = rewritten;
        done.push(what);
    }
    if transform.removes_unused_functions && let Some((rewritten, what)) = unused_functions_removed(&text, seen) {
        text = rewritten;
        done.push(what);
    }
    if transform.raises_version && let Some((rewritten, what)) = version_raised_to_330(&text, stage) {
        text = rewritten;
        done.push(what);
    }
    (text, done)
}

/// `text`, a stage of `stage`, with its first `#version` below 3.30 raised to 3.30, as Iris's
/// `TransformPatcher` raises every stage before the driver sees it; and what was done. A core
/// stage (`core`, or 1.50 and later without a profile) stays core; an older or compatibility
/// stage becomes `#version 330 compatibility`, where the legacy built-ins it reads
/// (`gl_FragData`, `texture2D`, `ftransform`) still exist, as Iris's transformer keeps them
/// working by replacing them; its `attribute` and `varying` become `in` and `out`, as Iris's
/// transformer writes them (3.30 refuses `flat varying`). Lines are kept. `None` where no
/// `#version` is below 3.30.
pub fn version_raised_to_330(text: &str, stage: Option<Stage>) -> Option<(String, String)> {
    let tokens = tokenize(text).ok()?;
    let order = significant(&tokens);
    let at = order.windows(2).position(|w| tokens[w[0]].is_punct("#") && tokens[w[1]].is_ident("version"))?;
    let number_at = *order.get(at + 2)?;
    let number: u32 = tokens[number_at].text.parse().ok()?;
    let profile_at = order.get(at + 3).copied().filter(|&i| tokens[i].line == tokens[number_at].line && tokens[i].kind == TokenKind::Ident);
    let profile = profile_at.map(|i| tokens[i].text);
    let written = preprocess::VersionDirective { number, profile: profile.map(str::to_string) };
    let raised = raised_to_330(&written)?;
    let raised = format!("330 {}", raised.profile.unwrap_or_default());
    let mut out = String::with_capacity(text.len() + 16);
    let mut end = 0;
    let mut storage = 0;
    for (k, &i) in order.iter().enumerate() {
        let t = &tokens[i];
        let declares = k > at + 2 && (t.is_ident("varying") || t.is_ident("attribute"));
        let replacement = match (stage, t.text) {
            _ if i == number_at => raised.as_str(),
            _ if Some(i) == profile_at => "",
            (Some(Stage::Vertex), "varying") if declares => "out",
            (Some(Stage::Vertex), "attribute") | (Some(Stage::Fragment), "varying") if declares => "in",
            _ => continue,
        };
        storage += usize::from(declares);
        out.push_str(&text[end..t.offset]);
        out.push_str(replacement);
        end = t.offset + t.text.len();
    }
    out.push_str(&text[end..]);
    let written = format!("#version {number}{}", profile.map(|p| format!(" {p}")).unwrap_or_default());
    let storage = if storage > 0 { format!(", `attribute` and `varying` written `in` and `out` ({storage})") } else { String::new() };
    Some((out, format!("`{written}` raised to `#version {raised}`, as Iris raises every stage to GLSL 3.30{storage}")))
}

/// The `#version` Iris gives the driver for a stage that declares `written`: 3.30, core where
/// the stage is (`core`, or 1.50 and later without a profile), else compatibility; `None`
/// from 3.30 on, which Iris keeps.
pub fn raised_to_330(written: &preprocess::VersionDirective) -> Option<preprocess::VersionDirective> {
    if written.number >= 330 {
        return None;
    }
    let core = written.profile.as_deref() == Some("core") || (written.number >= 150 && written.profile.is_none());
    Some(preprocess::VersionDirective { number: 330, profile: Some(if core { "core" } else { "compatibility" }.to_string()) })
}

/// `text` with its `uniform sampler2D gcolor;` or `texture;` declaration named `gtexture`, and
/// every use of that name that is not a call, as Iris's transformer has it (where both are
/// declared, `texture`'s single-name declaration goes); and what was done. Iris decides on the
/// stage as its preprocessor left it, `seen`; `text` may hold branches that left out (each
/// declaration there is renamed or dropped alike). `None` where `seen` declares neither as a
/// sampler at file scope, declares one twice or as something else, or declares `gtexture`.
pub fn albedo_sampler_as_gtexture(text: &str, seen: &str) -> Option<(String, String)> {
    let seen_tokens = tokenize(seen).ok()?;
    let seen_order = significant(&seen_tokens);
    let in_seen = |name: &str| file_scope_declarations(&seen_tokens, &seen_order, name);
    if !in_seen("gtexture").is_empty() {
        return None;
    }
    let declared = |name: &str| {
        let found = in_seen(name);
        (found.len() == 1 && found[0].sampler).then(|| found[0])
    };
    let (gcolor, texture) = (declared("gcolor"), declared("texture"));
    let dropped_name = match (gcolor, texture) {
        (Some(_), Some(t)) if t.names == 1 => Some("texture"),
        (Some(_), Some(_)) | (None, None) => return None,
        _ => None,
    };
    let renamed: Vec<&str> = [gcolor.map(|_| "gcolor"), texture.map(|_| "texture")].into_iter().flatten().collect();
    let tokens = tokenize(text).ok()?;
    let order = significant(&tokens);
    let dropped: Vec<Declaration> = dropped_name
        .map(|name| file_scope_declarations(&tokens, &order, name).into_iter().filter(|d| d.sampler && d.names == 1).collect())
        .unwrap_or_default();
    let mut out = String::with_capacity(text.len());
    for (k, &i) in order.iter().enumerate() {
        let previous_end = if k == 0 { 0 } else { tokens[order[k - 1]].offset + tokens[order[k - 1]].text.len() };
        out.push_str(&text[previous_end..tokens[i].offset]);
        if dropped.iter().any(|d| (d.first..=d.last).contains(&k)) {
            continue;
        }
        let call = order.get(k + 1).is_some_and(|&n| tokens[n].is_punct("("));
        if tokens[i].kind == TokenKind::Ident && renamed.contains(&tokens[i].text) && !call {
            out.push_str("gtexture");
        } else {
            out.push_str(tokens[i].text);
        }
    }
    let end = order.last().map_or(0, |&i| tokens[i].offset + tokens[i].text.len());
    out.push_str(&text[end..]);
    Some((out, format!("`{}` named `gtexture`, as Iris's transformer names the albedo sampler", renamed.join("` and `"))))
}

/// `text` with the definition of every function but `main` whose name occurs only once in
/// `seen` (the stage as Iris's transformer parses it) blanked, lines kept, as Iris's
/// transformer removes them; and what was removed. A definition with a preprocessor directive
/// inside, or in its return type, is kept. `None` where nothing is removed.
pub fn unused_functions_removed(text: &str, seen: &str) -> Option<(String, String)> {
    let tokens = tokenize(text).ok()?;
    let seen = tokenize(seen).ok()?;
    let uses = |name: &str| seen.iter().filter(|t| t.is_ident(name)).count();
    // Tokens of directives, to the line break that ends each (continuations included): their
    // words are not a return type.
    let mut in_directive = vec![false; tokens.len()];
    let mut line_start = true;
    let mut directive = false;
    for (i, t) in tokens.iter().enumerate() {
        if t.kind == TokenKind::Newline {
            (line_start, directive) = (true, false);
        } else if !t.is_trivia() {
            directive |= line_start && t.is_punct("#");
            line_start = false;
        }
        in_directive[i] = directive;
    }
    let mut ranges = Vec::new();
    let mut removed = Vec::new();
    for definition in function_definitions(&tokens) {
        let name = tokens[definition.name].text;
        if name == "main" || uses(name) > 1 || definition.close >= tokens.len() {
            continue;
        }
        // The return type and qualifiers: the words and array sizes before the name.
        let mut start = definition.name;
        for i in (0..definition.name).rev() {
            let t = &tokens[i];
            if t.is_trivia() {
                continue;
            }
            if in_directive[i] || !(t.kind == TokenKind::Ident || t.kind == TokenKind::Number || t.is_punct("[") || t.is_punct("]")) {
                break;
            }
            start = i;
        }
        if (start..=definition.close).any(|i| in_directive[i]) {
            continue;
        }
        ranges.push(tokens[start].offset..tokens[definition.close].offset + 1);
        let named = format!("`{name}`");
        if !removed.contains(&named) {
            removed.push(named);
        }
    }
    if ranges.is_empty() {
        return None;
    }
    let what = format!("functions nothing calls removed, as Iris's transformer removes them: {}", removed.join(", "));
    Some((blanked(text, &ranges), what))
}

/// A stage as Iris hands it to its transformer, and then to the driver: `text`, its
/// preprocessor's output for the stage `seen` (every directive resolved but `#version` and
/// `#extension`), with the `#version` it chose on the first line and the `#extension` lines
/// after it ([`extensions_hoisted`]); the pack location of each line; and what was moved.
pub fn as_preprocessor_leaves_it(text: &str, seen: &preprocess::Preprocessed) -> (String, Vec<Option<Location>>, Option<String>) {
    let mut map: Vec<Option<Location>> = (1..=seen.lines.len() as u32).map(|line| seen.location(line)).collect();
    let mut moved = Vec::new();
    let mut text = match version_resolved_on_top(text, seen.version.as_ref()) {
        Some((resolved, what)) => {
            map.insert(0, seen.version_line().and_then(|line| seen.location(line)));
            moved.push(what);
            resolved
        }
        None => text.to_string(),
    };
    if let Some((hoisted, from_lines, what)) = extensions_hoisted(&text) {
        let at = extensions_go_before(&text);
        let locations: Vec<Option<Location>> = from_lines.iter().map(|&line| map.get(line).cloned().flatten()).collect();
        map.splice(at..at, locations);
        text = hoisted;
        moved.push(what);
    }
    (text, map, (!moved.is_empty()).then(|| moved.join("; ")))
}

fn is_directive(line: &str, name: &str) -> bool {
    line.trim_start().strip_prefix('#').is_some_and(|rest| rest.trim_start().starts_with(name))
}

/// The 0-based line of `text` before which [`extensions_hoisted`] puts the `#extension` lines:
/// the one after `#version`, or the first where there is none.
fn extensions_go_before(text: &str) -> usize {
    text.lines().position(|l| is_directive(l, "version")).map_or(0, |at| at + 1)
}

/// `text` with its `#extension` lines moved up to follow `#version` (their old lines left
/// empty), as Iris's preprocessor collects them ahead of the stage (IrisShaders/Iris
/// `JcppProcessor`: packs written for lenient drivers put them after code, which Mesa
/// refuses); the 0-based lines they came from; and what was done. `None` where no `#extension`
/// comes after code, so nothing moves.
pub fn extensions_hoisted(text: &str) -> Option<(String, Vec<usize>, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let extensions: Vec<usize> = (0..lines.len()).filter(|&i| is_directive(lines[i], "extension")).collect();
    let is_code = |line: &str| {
        let line = line.trim();
        !line.is_empty() && !line.starts_with('#') && !line.starts_with("//")
    };
    let first_code = lines.iter().position(|l| is_code(l))?;
    let late = extensions.iter().filter(|&&i| i > first_code).count();
    if late == 0 {
        return None;
    }
    let at = extensions_go_before(text);
    let mut hoisted: Vec<&str> = Vec::with_capacity(lines.len() + extensions.len());
    for (i, line) in lines.iter().enumerate() {
        if i == at {
            hoisted.extend(extensions.iter().map(|&e| lines[e].trim()));
        }
        hoisted.push(if extensions.contains(&i) { "" } else { line });
    }
    let what = format!("{late} `#extension` lines after code moved up to follow #version, as Iris's preprocessor collects them");
    Some((hoisted.join("\n") + "\n", extensions, what))
}

/// A stage whose first directive is not `#version` (the pack chooses it in an `#if`, one per
/// profile) with the `#version` the preprocessor resolved on the first line and every other
/// `#version` line left blank, as a loader that preprocesses first gives it to the driver; and
/// what was done. `None` where `#version` already comes first or the stage has none.
pub fn version_resolved_on_top(text: &str, version: Option<&preprocess::VersionDirective>) -> Option<(String, String)> {
    let version = version?;
    let first = text.lines().map(str::trim).find(|l| !l.is_empty() && !l.starts_with("//"))?;
    if first.starts_with("#version") {
        return None;
    }
    let directive = match &version.profile {
        Some(profile) => format!("#version {} {profile}", version.number),
        None => format!("#version {}", version.number),
    };
    let mut resolved = format!("{directive}\n");
    for line in text.lines() {
        resolved.push_str(if is_directive(line, "version") { "" } else { line });
        resolved.push('\n');
    }
    Some((resolved, format!("`{directive}`, chosen inside an `#if`, put first as Iris's preprocessor leaves it")))
}

#[cfg(test)]
mod tests {
    /// Iris's preprocessor collects `#extension` lines ahead of the stage: those after code move
    /// up to follow `#version`, with their old lines left empty; where none comes after code,
    /// nothing moves.
    #[test]
    fn extensions_after_code_move_up_to_follow_version() {
        let text = "#version 120\n#extension GL_EXT_gpu_shader4 : enable\nuniform float a;\n  #extension GL_ARB_shader_texture_lod : enable\nvoid main() {}\n";
        let (hoisted, from, what) = super::extensions_hoisted(text).expect("moved");
        assert_eq!(hoisted, "#version 120\n#extension GL_EXT_gpu_shader4 : enable\n#extension GL_ARB_shader_texture_lod : enable\n\nuniform float a;\n\nvoid main() {}\n");
        assert_eq!(from, [1, 3]);
        assert!(what.starts_with("1 `#extension` lines after code"), "{what}");
        assert_eq!(super::extensions_hoisted("#version 120\n#extension GL_EXT_gpu_shader4 : enable\nvoid main() {}\n"), None);
    }

    /// Iris raises every stage to GLSL 3.30: an old stage becomes 3.30 compatibility with `in`
    /// and `out` for `attribute` and `varying` (MichuuMichuu18/minecraft-shaders' `flat
    /// varying`), a core one stays core, 3.30 and later is left as written; lines are kept.
    #[test]
    fn every_stage_is_raised_to_glsl_330() {
        use tidepack_glsl::Stage;
        let vertex = "#version 120\nattribute vec4 mc_Entity;\nflat varying vec3 glow; // varying\nvoid main() { gl_Position = ftransform(); }\n";
        let (raised, what) = super::version_raised_to_330(vertex, Some(Stage::Vertex)).expect("raised");
        assert_eq!(raised, "#version 330 compatibility\nin vec4 mc_Entity;\nflat out vec3 glow; // varying\nvoid main() { gl_Position = ftransform(); }\n");
        assert_eq!(what, "`#version 120` raised to `#version 330 compatibility`, as Iris raises every stage to GLSL 3.30, `attribute` and `varying` written `in` and `out` (2)");
        let fragment = vertex.replace("attribute vec4 mc_Entity;", "");
        assert!(super::version_raised_to_330(&fragment, Some(Stage::Fragment)).expect("raised").0.contains("flat in vec3 glow;"));
        let core = "#version 150\nin vec2 uv;\nvoid main() {}\n";
        assert_eq!(super::version_raised_to_330(core, Some(Stage::Fragment)).expect("raised").0, core.replace("150", "330 core"));
        assert_eq!(super::version_raised_to_330("#version 330 compatibility\nvoid main() {}\n", Some(Stage::Vertex)), None);
        assert_eq!(super::version_raised_to_330("#version 460\nvoid main() {}\n", None), None);
    }

    /// Iris removes the definitions of functions nothing calls, so what only they reference
    /// need not be declared; a function called once, `main`, and a definition with a directive
    /// in its body stay; lines stay where they were.
    #[test]
    fn functions_nothing_calls_are_removed_as_iris_removes_them() {
        let text = "#version 330 compatibility\nvec4 noise(vec2 c) {\n    return texelFetch(noisetex, ivec2(c * viewWidth), 0);\n}\nfloat half_of(float x) { return x * 0.5; }\nfloat guarded() {\n#ifdef A\n    return 1.0;\n#endif\n    return 0.0;\n}\nvoid main() { gl_FragData[0] = vec4(half_of(1.0)); }\n";
        let (removed, what) = super::unused_functions_removed(text, text).expect("removed");
        assert_eq!(removed.lines().count(), text.lines().count());
        assert!(!removed.contains("noisetex") && removed.contains("float half_of") && removed.contains("float guarded"), "{removed}");
        assert!(removed.lines().nth(1).is_some_and(|l| l.trim().is_empty()), "{removed}");
        assert!(what.ends_with("`noise`"), "{what}");
        // Counted in the text the transformer parses: a call left out by the preprocessor does
        // not keep a function.
        let seen = text.replace("half_of(1.0)", "1.0");
        let (removed, _) = super::unused_functions_removed(text, &seen).expect("removed");
        assert!(!removed.contains("float half_of"), "{removed}");
        // A directive continued onto the next line ends there: its last word is not the return
        // type of the function after it.
        let continued = "#version 120\n#if MODE == 1 \\\n    && VIEW == VIEW_B\nvoid unused() {}\n#endif\nvoid main() {}\n";
        let (removed, _) = super::unused_functions_removed(continued, continued).expect("removed");
        assert!(removed.contains("&& VIEW == VIEW_B\n") && !removed.contains("unused"), "{removed}");
    }

    /// Iris names a `gcolor` or `texture` sampler `gtexture`: its declaration and every use
    /// that is not a call; with both declared, `texture`'s declaration goes.
    #[test]
    fn the_albedo_sampler_is_named_gtexture_as_iris_names_it() {
        let text = "#version 120\nuniform sampler2D gcolor;\nuniform sampler2D texture;\nvarying vec2 uv;\nvoid main() {\n    gl_FragData[0] = texture2D(gcolor, uv) + texture2D(texture, uv) + texture(gtexture, uv);\n}\n";
        let (renamed, what) = super::albedo_sampler_as_gtexture(text, text).expect("renamed");
        assert_eq!(
            renamed,
            "#version 120\nuniform sampler2D gtexture;\n  \nvarying vec2 uv;\nvoid main() {\n    gl_FragData[0] = texture2D(gtexture, uv) + texture2D(gtexture, uv) + texture(gtexture, uv);\n}\n"
        );
        assert!(what.contains("`gcolor` and `texture`"), "{what}");
        // A stage declaring gtexture, or gcolor as something else, is left alone.
        let both = "uniform sampler2D gtexture;\nuniform sampler2D gcolor;\n";
        assert!(super::albedo_sampler_as_gtexture(both, both).is_none());
        let other = "uniform vec4 gcolor;\nvoid main() {}\n";
        assert!(super::albedo_sampler_as_gtexture(other, other).is_none());
        // One stage of a file holding both (`#ifdef VSH` … `#ifdef FSH`): Iris decides on what its
        // preprocessor left, one declaration, and every declaration of the file is renamed.
        let file = "#ifdef VSH\nuniform sampler2D gcolor;\n#endif\n#ifdef FSH\nuniform sampler2D gcolor;\nvoid main() { gl_FragData[0] = texture2D(gcolor, vec2(0.0)); }\n#endif\n";
        let seen = "uniform sampler2D gcolor;\nvoid main() { gl_FragData[0] = texture2D(gcolor, vec2(0.0)); }\n";
        let (renamed, _) = super::albedo_sampler_as_gtexture(file, seen).expect("renamed");
        assert!(!renamed.contains("gcolor") && renamed.matches("sampler2D gtexture;").count() == 2, "{renamed}");
    }

    /// Iris gives the driver the `#version` its preprocessor chose, first; the others go.
    #[test]
    fn a_version_chosen_inside_an_if_is_put_first() {
        let version = tidepack_glsl::preprocess::VersionDirective { number: 450, profile: Some("compatibility".into()) };
        let text = "// header\n#ifdef CORE_PROFILE\n  #version 450 core\n#else\n  #version 450 compatibility\n#endif\nvoid main() {}\n";
        let (resolved, what) = super::version_resolved_on_top(text, Some(&version)).expect("rewritten");
        assert_eq!(resolved, "#version 450 compatibility\n// header\n#ifdef CORE_PROFILE\n\n#else\n\n#endif\nvoid main() {}\n");
        assert!(what.contains("#version 450 compatibility"), "{what}");
        assert!(super::version_resolved_on_top("#version 120\nvoid main() {}\n", Some(&version)).is_none());
    }
}
