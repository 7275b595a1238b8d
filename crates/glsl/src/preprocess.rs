//! OptiFine's GLSL preprocessor: `#include`, macros and conditionals, with a source map.
//!
//! The output keeps exactly one output line per source line it came from: directives and
//! inactive lines become empty lines, an `#include` line is replaced by the included file's
//! lines. `Preprocessed::lines` maps every output line back to its file and line, so an error
//! that a later stage reports at an output line can be shown where the author wrote it.
//! Comments are dropped (their line breaks kept); the loader's comment directives
//! (`/* DRAWBUFFERS:.. */`, `/* RENDERTARGETS: .. */`) are recorded when they are active.

use crate::Code;
use std::collections::{BTreeSet, HashMap};
use std::fmt::Write as _;
use std::sync::Arc;

use rustc_hash::FxHashMap;

use crate::diagnostic::{Diagnostic, Location};
use crate::token::{Token, TokenKind, punctuator_len, tokenize};

/// OptiFine's limit on `#include` nesting.
pub const MAX_INCLUDE_DEPTH: usize = 10;
/// The `#include` nesting followed for Iris, which has no limit of its own (Luna5ama/Alpha-Piscium
/// nests 13 deep); a bound on this tool's recursion.
pub const MAX_IRIS_INCLUDE_DEPTH: usize = 32;
/// Largest preprocessed text of one stage, in bytes: includes repeated many times over, or
/// macros that expand exponentially, stop here with an error instead of exhausting memory.
pub const MAX_OUTPUT_BYTES: usize = 8 << 20;
/// Largest text of one stage with its `#include`s spliced in, before any `#if` is read. Iris
/// splices every include whatever its guards say (its `IncludeProcessor`), so a released pack
/// that includes its libraries from many files reaches tens of MB here (Luna5ama/Alpha-Piscium:
/// 24 MB) and a few hundred KB once its guards are read.
pub const MAX_SPLICED_BYTES: usize = 64 << 20;
/// Largest number of tokens one macro invocation may expand to.
pub const MAX_EXPANSION_TOKENS: usize = 1 << 18;
/// Deepest nesting of parentheses and operators in an `#if` expression.
pub const MAX_EXPRESSION_DEPTH: usize = 256;

/// Reads pack files by their pack-relative path (`lib/water.glsl`, `world-1/composite.fsh`).
pub trait FileProvider {
    fn read(&self, path: &str) -> Result<Arc<str>, String>;
}

impl FileProvider for HashMap<String, Arc<str>> {
    fn read(&self, path: &str) -> Result<Arc<str>, String> {
        self.get(path).cloned().ok_or_else(|| "no such file in the pack".to_string())
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SourceLine {
    /// Index into [`Preprocessed::files`].
    pub file: u32,
    /// 1-based line in that file.
    pub line: u32,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VersionDirective {
    pub number: u32,
    /// `core`, `compatibility` or `es`, as written.
    pub profile: Option<String>,
}

impl VersionDirective {
    /// A core profile: GLSL 1.50 or later without `compatibility`, where the deprecated built-ins
    /// are gone. GLSL 1.40 has no profiles: in the compatibility contexts OptiFine and Iris draw
    /// with, ARB_compatibility keeps them there (Mesa compiles them).
    pub fn is_core(&self) -> bool {
        self.number >= 150 && self.profile.as_deref() != Some("compatibility")
    }

    /// GLSL ES: `#version 100`, or a version with the `es` profile.
    pub fn is_es(&self) -> bool {
        self.number == 100 || self.profile.as_deref() == Some("es")
    }
}

/// Which outputs of a fragment shader go to which colour buffers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RenderTargets {
    /// `true` for `RENDERTARGETS` (outputs `outColor<i>`), `false` for `DRAWBUFFERS`.
    pub modern: bool,
    /// Buffer numbers in output order; `None` for an `N`, an output drawn into no buffer
    /// (OptiFine's directive pattern takes it; Iris's parser reads integers only).
    pub buffers: Vec<Option<u8>>,
    pub line: SourceLine,
}

#[derive(Clone, Debug)]
pub struct Preprocessed {
    pub text: String,
    /// One entry per line of `text`.
    pub lines: Vec<SourceLine>,
    /// Pack-relative paths, indexed by [`SourceLine::file`].
    pub files: Vec<String>,
    pub version: Option<VersionDirective>,
    pub render_targets: Option<RenderTargets>,
    /// Macro names that decided a conditional or were expanded into the text. Tests of
    /// conditionals with nothing inside (the pattern OptiFine needs to show an option) do not
    /// count: they cannot change the text.
    pub consulted_macros: BTreeSet<String>,
    /// The subset of `consulted_macros` that decided a conditional (rather than only being
    /// substituted into the text).
    pub tested_macros: BTreeSet<String>,
    pub warnings: Vec<Diagnostic>,
    /// With [`PreprocessOptions::lenient`]: the `#define` lines that redefined a macro with
    /// another body, and the macro's name.
    pub redefinitions: Vec<(Location, String)>,
    /// Read as lenient drivers read it ([`PreprocessOptions::lenient`]): naga's checks then
    /// convert values as NVIDIA does where GLSL converts nothing.
    pub lenient: bool,
}

impl Preprocessed {
    /// Where output line `line` (1-based) came from.
    pub fn location(&self, line: u32) -> Option<Location> {
        let src = self.lines.get(line.checked_sub(1)? as usize)?;
        Some(Location::line(self.files[src.file as usize].clone(), src.line))
    }

    /// The 1-based output line that holds `#version`, if one does.
    pub fn version_line(&self) -> Option<u32> {
        self.text.lines().position(|l| l.trim_start().starts_with("#version")).map(|i| i as u32 + 1)
    }
}

#[derive(Clone, Debug, Default)]
pub struct PreprocessOptions {
    /// Macros defined before the first line, in order (OptiFine's standard macros).
    pub predefined: Vec<(String, String)>,
    /// How the loader reads an `#include` line's path.
    pub include_rules: IncludeRules,
    /// Take what NVIDIA's compiler takes and Mesa and AMD refuse: an `#extension` after code, a
    /// macro redefined with another body (the last definition holds; each is recorded in
    /// [`Preprocessed::redefinitions`]). The renderer draws what lenient drivers run, and
    /// `compat::for_strict_drivers` rewrites the text for OpenGL; `validate` leaves this off.
    pub lenient: bool,
    /// Where a run that preprocesses the same files many times over (every program under every
    /// option set) keeps their tokens.
    pub token_cache: Option<Arc<TokenCache>>,
}

/// The tokens of the files one run has read, by their text. A file is tokenized once however
/// many programs and option sets include it; past [`TOKEN_CACHE_BYTES`] new files are no
/// longer kept.
#[derive(Default)]
pub struct TokenCache {
    files: std::sync::Mutex<FxHashMap<u64, Vec<TokenizedFile>>>,
    bytes: std::sync::atomic::AtomicUsize,
}

/// The most a [`TokenCache`] keeps: the texts and 16 bytes per token.
pub const TOKEN_CACHE_BYTES: usize = 256 << 20;

struct TokenizedFile {
    text: Arc<str>,
    tokens: Arc<[CachedToken]>,
}

#[derive(Clone, Copy)]
struct CachedToken {
    kind: TokenKind,
    offset: u32,
    len: u32,
    line: u32,
}

impl std::fmt::Debug for TokenCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TokenCache({} bytes)", self.bytes.load(std::sync::atomic::Ordering::Relaxed))
    }
}

impl TokenCache {
    /// The tokens of `text`, from the cache when it holds them.
    fn tokens<'t>(&self, text: &'t Arc<str>) -> Result<Vec<Token<'t>>, crate::token::TokenizeError> {
        use std::hash::Hasher;
        let mut hasher = rustc_hash::FxHasher::default();
        hasher.write(text.as_bytes());
        let hash = hasher.finish();
        let view = |cached: &[CachedToken]| {
            cached
                .iter()
                .map(|t| Token { kind: t.kind, text: &text[t.offset as usize..(t.offset + t.len) as usize], offset: t.offset as usize, line: t.line })
                .collect()
        };
        let found = self.files.lock().unwrap_or_else(|e| e.into_inner()).get(&hash).and_then(|files| {
            files.iter().find(|f| *f.text == **text).map(|f| f.tokens.clone())
        });
        if let Some(cached) = found {
            return Ok(view(&cached));
        }
        let tokens = tokenize(text)?;
        let size = text.len() + tokens.len() * std::mem::size_of::<CachedToken>();
        // Offsets past 4 GiB do not fit; no text comes near that (MAX_SPLICED_BYTES). Threads
        // adding at once may pass the budget by a file each.
        if text.len() < u32::MAX as usize && self.bytes.load(std::sync::atomic::Ordering::Relaxed) + size <= TOKEN_CACHE_BYTES {
            self.bytes.fetch_add(size, std::sync::atomic::Ordering::Relaxed);
            let cached: Arc<[CachedToken]> =
                tokens.iter().map(|t| CachedToken { kind: t.kind, offset: t.offset as u32, len: t.text.len() as u32, line: t.line }).collect();
            self.files.lock().unwrap_or_else(|e| e.into_inner()).entry(hash).or_default().push(TokenizedFile { text: text.clone(), tokens: cached });
        }
        Ok(tokens)
    }
}

/// How the loader reads `#include`s. OptiFine takes `#include "path"` only (any other line
/// reaches the compiler as written) and stops at 10 levels; Iris also takes `#include path`,
/// dropping a quote at either end, and follows any depth, of which this tool follows
/// [`MAX_IRIS_INCLUDE_DEPTH`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum IncludeRules {
    #[default]
    OptiFine,
    Iris,
}

impl IncludeRules {
    /// The deepest nesting of includes followed, and what it is.
    fn depth_limit(self) -> (usize, &'static str) {
        match self {
            IncludeRules::OptiFine => (MAX_INCLUDE_DEPTH, "OptiFine's limit"),
            IncludeRules::Iris => (MAX_IRIS_INCLUDE_DEPTH, "Iris has none; this tool follows no deeper"),
        }
    }

    /// The path an `#include` line names, given the rest of the line after `include`.
    fn target(self, rest: &str) -> Option<&str> {
        let rest = rest.trim();
        match self {
            IncludeRules::OptiFine => rest.strip_prefix('"').and_then(|r| r.split('"').next()),
            IncludeRules::Iris => {
                let rest = rest.strip_prefix('"').unwrap_or(rest);
                Some(rest.strip_suffix('"').unwrap_or(rest)).filter(|t| !t.is_empty())
            }
        }
    }
}

/// Preprocesses `entry` and everything it includes.
pub fn preprocess(
    provider: &dyn FileProvider,
    entry: &str,
    options: &PreprocessOptions,
) -> Result<Preprocessed, Diagnostic> {
    let mut pp = Preprocessor {
        provider,
        macros: FxHashMap::default(),
        out: Preprocessed {
            text: String::new(),
            lines: Vec::new(),
            files: Vec::new(),
            version: None,
            render_targets: None,
            consulted_macros: BTreeSet::new(),
            tested_macros: BTreeSet::new(),
            warnings: Vec::new(),
            redefinitions: Vec::new(),
            lenient: options.lenient,
        },
        include_stack: Vec::new(),
        seen_code: false,
        directive_before_version: None,
        include_rules: options.include_rules,
        lenient: options.lenient,
        token_cache: options.token_cache.as_deref(),
    };
    for (name, value) in &options.predefined {
        let body = owned_tokens(&tokenize(value).map_err(|e| {
            Diagnostic::error(Code::Preprocessor, format!("predefined macro {name}: {}", e.message), None)
        })?);
        pp.macros.insert(name.clone(), Macro { params: None, body });
    }
    // A shader without `#version` is GLSL 1.10.
    pp.define_version_macros(&VersionDirective { number: 110, profile: None });
    let text = provider.read(entry).map_err(|e| Diagnostic::error(Code::PackInput, format!("cannot read {entry}: {e}"), None))?;
    pp.process_file(entry, &text)?;
    debug_assert_eq!(pp.out.text.matches('\n').count(), pp.out.lines.len(), "one source line per output line");
    Ok(pp.out)
}

#[derive(Clone, Debug)]
struct Macro {
    /// `Some` for function-like macros.
    params: Option<Vec<String>>,
    body: Vec<OwnedToken>,
}

impl Macro {
    /// The C and GLSL rule for a redefinition that is allowed: the same parameters and the same
    /// body tokens, any run of white space counting as one.
    fn same_definition(&self, other: &Macro) -> bool {
        fn words(body: &[OwnedToken]) -> Vec<&str> {
            let mut out = Vec::new();
            for t in body {
                let text = if t.kind == TokenKind::Whitespace { " " } else { t.text.as_str() };
                if !(text == " " && out.last() == Some(&" ")) {
                    out.push(text);
                }
            }
            out
        }
        self.params == other.params && words(&self.body) == words(&other.body)
    }
}

#[derive(Clone, Debug, PartialEq)]
struct OwnedToken {
    kind: TokenKind,
    text: String,
}

/// A macro body's tokens: comments dropped, and a line continuation (white space holding a
/// line break) read as a space, so that an expansion never adds a line.
fn owned_tokens(tokens: &[Token<'_>]) -> Vec<OwnedToken> {
    tokens
        .iter()
        .filter(|t| !matches!(t.kind, TokenKind::LineComment | TokenKind::BlockComment | TokenKind::Newline))
        .map(|t| {
            let text = if t.kind == TokenKind::Whitespace && t.text.contains('\n') { " " } else { t.text };
            OwnedToken { kind: t.kind, text: text.to_string() }
        })
        .collect()
}

/// State of [`Preprocessor::scan_macro_call`] across lines.
#[derive(Default)]
struct MacroCallScan {
    depth: i32,
    in_call: bool,
    pending_macro: bool,
}

struct Conditional {
    /// Lines in this branch are emitted.
    active: bool,
    /// Some branch of this group was taken already.
    taken: bool,
    /// The enclosing group is active.
    parent_active: bool,
    seen_else: bool,
    line: u32,
}

struct Preprocessor<'p> {
    provider: &'p dyn FileProvider,
    macros: FxHashMap<String, Macro>,
    out: Preprocessed,
    /// Paths of the files being processed, outermost first, with the including line.
    include_stack: Vec<(String, u32)>,
    /// A line of code (not a directive) has been emitted.
    seen_code: bool,
    /// The first directive other than `#include` met before `#version`, as file, line and
    /// name: the driver meets its line before `#version` in the text OptiFine hands it.
    directive_before_version: Option<(String, u32, String)>,
    include_rules: IncludeRules,
    lenient: bool,
    token_cache: Option<&'p TokenCache>,
}

/// A logical line: tokens up to a line break, continuations included.
struct LogicalLine<'t, 'a> {
    tokens: &'t [Token<'a>],
    first_line: u32,
    /// Physical lines it covers (block comments and continuations add lines).
    span: u32,
}

fn logical_lines<'t, 'a>(tokens: &'t [Token<'a>]) -> Vec<LogicalLine<'t, 'a>> {
    let mut lines = Vec::new();
    let mut start = 0;
    let mut line = 1;
    for (i, t) in tokens.iter().enumerate() {
        if t.kind == TokenKind::Newline {
            let tokens = &tokens[start..i];
            let span = 1 + tokens.iter().map(Token::newlines).sum::<u32>();
            lines.push(LogicalLine { tokens, first_line: line, span });
            line += span;
            start = i + 1;
        }
    }
    let tokens = &tokens[start..];
    if !tokens.is_empty() {
        let span = 1 + tokens.iter().map(Token::newlines).sum::<u32>();
        lines.push(LogicalLine { tokens, first_line: line, span });
    }
    lines
}

fn first_significant<'t, 'a>(tokens: &'t [Token<'a>]) -> Option<(usize, &'t Token<'a>)> {
    tokens.iter().enumerate().find(|(_, t)| !t.is_trivia())
}

impl Preprocessor<'_> {
    fn file_id(&mut self, path: &str) -> u32 {
        match self.out.files.iter().position(|p| p == path) {
            Some(i) => i as u32,
            None => {
                self.out.files.push(path.to_string());
                (self.out.files.len() - 1) as u32
            }
        }
    }

    fn blank_lines(&mut self, file: u32, first_line: u32, count: u32) {
        for k in 0..count {
            self.out.text.push('\n');
            self.out.lines.push(SourceLine { file, line: first_line + k });
        }
    }

    fn process_file(&mut self, path: &str, text: &Arc<str>) -> Result<(), Diagnostic> {
        let file = self.file_id(path);
        let err_at = |line: u32, msg: String| Diagnostic::error(Code::Preprocessor, msg, Some(Location::line(path, line)));
        let tokens = match self.token_cache {
            Some(cache) => cache.tokens(text),
            None => tokenize(text),
        }
        .map_err(|e| err_at(e.line, e.message))?;
        let lines = logical_lines(&tokens);
        let mut conds: Vec<Conditional> = Vec::new();
        let mut index = 0;
        while index < lines.len() {
            let line = &lines[index];
            let active = conds.last().is_none_or(|c| c.active);
            let Some((hash_pos, first)) = first_significant(line.tokens) else {
                if active {
                    for comment in line.tokens.iter().filter(|t| t.kind == TokenKind::BlockComment) {
                        self.record_comment_directive(comment.text, path, comment.line)
                            .map_err(|m| err_at(comment.line, m))?;
                    }
                }
                self.blank_lines(file, line.first_line, line.span);
                index += 1;
                continue;
            };
            if !first.is_punct("#") {
                if active {
                    // A function-like macro call may continue on the following lines.
                    let mut end = index;
                    let mut call = MacroCallScan::default();
                    self.scan_macro_call(&mut call, &lines[index]);
                    while call.in_call && end + 1 < lines.len() {
                        if lines[end + 1].tokens.iter().any(|t| t.is_punct("#")) {
                            break;
                        }
                        end += 1;
                        self.scan_macro_call(&mut call, &lines[end]);
                    }
                    let mut joined: Vec<Token<'_>> = Vec::new();
                    for l in &lines[index..=end] {
                        if !joined.is_empty() {
                            joined.push(Token { kind: TokenKind::Whitespace, text: " ", offset: 0, line: l.first_line });
                        }
                        // A line comment inside a call's arguments is a space there: kept, it
                        // would end the one line the expansion is written on.
                        joined.extend(l.tokens.iter().map(|t| match t.kind {
                            TokenKind::LineComment if end > index => Token { kind: TokenKind::Whitespace, text: " ", ..*t },
                            _ => *t,
                        }));
                    }
                    let span: u32 = lines[index..=end].iter().map(|l| l.span).sum();
                    self.seen_code = true;
                    self.emit_text_line(&joined, path, line.first_line)?;
                    self.out.lines.push(SourceLine { file, line: line.first_line });
                    self.out.text.push('\n');
                    // Keep the line count: the lines a comment or call spanned become empty.
                    let emitted_breaks = joined.iter().filter(|t| t.kind == TokenKind::BlockComment).map(Token::newlines).sum::<u32>();
                    for k in 1..span {
                        if k <= emitted_breaks {
                            self.out.lines.push(SourceLine { file, line: line.first_line + k });
                        } else {
                            self.blank_lines(file, line.first_line + k, 1);
                        }
                    }
                    index = end + 1;
                } else {
                    self.blank_lines(file, line.first_line, line.span);
                    index += 1;
                }
                continue;
            }
            let rest = &line.tokens[hash_pos + 1..];
            let directive_pos = first_significant(rest);
            let name = directive_pos.filter(|(_, t)| t.kind == TokenKind::Ident).map(|(_, t)| t.text);
            let args = directive_pos.map_or(&[][..], |(i, _)| &rest[i + 1..]);
            let at = line.first_line;
            if self.out.version.is_none() && self.directive_before_version.is_none() && !matches!(name, Some("version" | "include")) {
                self.directive_before_version = Some((path.to_string(), at, name.unwrap_or_default().to_string()));
            }
            match name {
                Some("if" | "ifdef" | "ifndef") => {
                    let consult = !group_is_empty(&lines, index);
                    let value = if active {
                        match name {
                            Some("if") => self.condition(args, consult, path, at)?,
                            // Iris's preprocessor (JCPP) reports a group whose test is not a
                            // name (`#ifdef 2D_CLOUDS`) and keeps it, whichever the directive.
                            _ if self.lenient && !first_significant(args).is_some_and(|(_, t)| t.kind == TokenKind::Ident) => true,
                            _ => {
                                // NVIDIA's preprocessor, like C's, tests the first name and
                                // ignores what follows it (`#ifndef A && defined B`).
                                let leniently = || self.lenient.then(|| first_ident(args)).flatten();
                                let macro_name = single_ident(args).or_else(leniently).ok_or_else(|| {
                                    let directive = name.unwrap_or("");
                                    let message = match first_ident(args) {
                                        Some(first) => format!(
                                            "#{directive} needs exactly one macro name; Mesa and AMD refuse what follows `{first}` (NVIDIA tests `{first}` alone)"
                                        ),
                                        None => format!("#{directive} needs exactly one macro name"),
                                    };
                                    err_at(at, message)
                                })?;
                                if consult {
                                    self.out.consulted_macros.insert(macro_name.to_string());
                                    self.out.tested_macros.insert(macro_name.to_string());
                                }
                                self.macros.contains_key(macro_name) == (name == Some("ifdef"))
                            }
                        }
                    } else {
                        false
                    };
                    conds.push(Conditional {
                        active: active && value,
                        taken: value,
                        parent_active: active,
                        seen_else: false,
                        line: at,
                    });
                }
                Some("elif") => {
                    let consult = !group_is_empty(&lines, index);
                    let Some(top) = conds.last() else {
                        return Err(err_at(at, "#elif without #if".into()));
                    };
                    if top.seen_else {
                        return Err(err_at(at, "#elif after #else".into()));
                    }
                    let (parent_active, taken) = (top.parent_active, top.taken);
                    let value = parent_active
                        && !taken
                        && self.condition(args, consult, path, at)?;
                    let top = conds.last_mut().unwrap();
                    top.active = value;
                    top.taken |= value;
                }
                Some(directive @ ("else" | "endif")) if !self.lenient && first_significant(args).is_some() => {
                    return Err(err_at(
                        at,
                        format!("#{directive} takes nothing after it; Mesa and AMD refuse the stage (NVIDIA ignores what follows)"),
                    ));
                }
                Some("else") => {
                    let Some(top) = conds.last_mut() else {
                        return Err(err_at(at, "#else without #if".into()));
                    };
                    if top.seen_else {
                        return Err(err_at(at, "second #else for the same #if".into()));
                    }
                    top.seen_else = true;
                    top.active = top.parent_active && !top.taken;
                    top.taken = true;
                }
                Some("endif") => {
                    // Iris's preprocessor (JCPP) reports an `#endif` with no `#if` open and goes
                    // on without it; so does the lenient reading.
                    if conds.pop().is_none() && !self.lenient {
                        return Err(err_at(at, "#endif without #if".into()));
                    }
                }
                Some("include") if !active => {
                    // OptiFine splices every #include into the text before the driver sees any
                    // #if, so a missing file fails the program even in a branch not taken.
                    self.check_inactive_include(path, at, args)?;
                }
                _ if !active => {}
                Some("define") => {
                    if let Some(name) = self.define(args).map_err(|m| err_at(at, m))? {
                        self.out.redefinitions.push((Location::line(path, at), name));
                    }
                }
                Some("undef") => {
                    let macro_name =
                        single_ident(args).ok_or_else(|| err_at(at, "#undef needs exactly one macro name".into()))?;
                    self.macros.remove(macro_name);
                }
                Some("include") => {
                    self.blank_lines(file, at, line.span - 1);
                    self.include(path, at, args)?;
                    index += 1;
                    continue;
                }
                Some("version") => {
                    // Includes are spliced in first (OptiFine), so `#version` may come from an
                    // included file as long as nothing but comments and blank lines precedes it.
                    if !self.out.text.trim().is_empty() {
                        return Err(err_at(at, "#version must come before anything else in a shader".into()));
                    }
                    // Iris's preprocessor runs the directives itself and puts `#version` first.
                    if let (Some((file, line, directive)), IncludeRules::OptiFine, false) =
                        (&self.directive_before_version, self.include_rules, self.lenient)
                    {
                        return Err(Diagnostic::error(
                            Code::Preprocessor,
                            format!(
                                "`#{directive}` comes before `#version` ({path}:{at}) once the includes are spliced in, and #version must \
                                 come before anything else: OptiFine hands the text to the driver as it is, and Mesa refuses it \
                                 (\"#version must appear on the first line\"); Iris puts #version first itself"
                            ),
                            Some(Location::line(file.as_str(), *line)),
                        ));
                    }
                    let version = parse_version(args).map_err(|m| err_at(at, m))?;
                    let mut text = format!("#version {}", version.number);
                    if let Some(profile) = &version.profile {
                        write!(text, " {profile}").unwrap();
                    }
                    self.define_version_macros(&version);
                    self.out.version = Some(version);
                    self.out.text.push_str(&text);
                }
                Some("extension") => {
                    // Iris's preprocessor collects every `#extension` ahead of the stage.
                    if self.seen_code && !self.lenient && self.include_rules == IncludeRules::OptiFine {
                        return Err(err_at(
                            at,
                            "#extension after code: GLSL wants it before the first declaration; Mesa and AMD refuse it \
                             (NVIDIA accepts it)"
                                .into(),
                        ));
                    }
                    let text: String = line.tokens.iter().filter(|t| !t.is_trivia()).map(|t| t.text).collect::<Vec<_>>().join(" ");
                    self.out.text.push_str(&text);
                }
                Some("error") => {
                    let message: String = args.iter().map(|t| t.text).collect();
                    return Err(err_at(at, format!("#error {}", message.trim())));
                }
                Some("pragma" | "line") => {}
                Some(other) => return Err(err_at(at, format!("unknown preprocessor directive #{other}"))),
                None if directive_pos.is_none() => {}
                None => return Err(err_at(at, "expected a directive name after #".into())),
            }
            self.out.text.push('\n');
            self.out.lines.push(SourceLine { file, line: at });
            self.blank_lines(file, at + 1, line.span - 1);
            index += 1;
        }
        if let Some(open) = conds.last() {
            return Err(err_at(open.line, "this #if has no matching #endif in the same file".into()));
        }
        Ok(())
    }

    /// Evaluates a condition, warning about undefined names (OptiFine reads them as 0, which
    /// hides typos).
    fn condition(&mut self, args: &[Token<'_>], consult: bool, path: &str, line: u32) -> Result<bool, Diagnostic> {
        let (value, undefined, truncated) =
            self.eval_condition(args, consult).map_err(|m| Diagnostic::error(Code::Preprocessor, m, Some(Location::line(path, line))))?;
        for name in undefined {
            self.out.warnings.push(Diagnostic::warning(
                Code::UndefinedInIf,
                format!("`{name}` is not defined here and reads as 0 in #if"),
                Some(Location::line(path, line)),
            ));
        }
        for (number, integer) in truncated {
            self.out.warnings.push(Diagnostic::warning(
                Code::FloatInIf,
                format!(
                    "`{number}` reads as {integer} in this #if: Iris's preprocessor keeps the integer part of a number, so the \
                     test compares integers; OptiFine hands #if to the driver, and every driver refuses a number that is not an integer"
                ),
                Some(Location::line(path, line)),
            ));
        }
        Ok(value)
    }

    fn include(&mut self, path: &str, at: u32, args: &[Token<'_>]) -> Result<(), Diagnostic> {
        let err_at = |msg: String| Diagnostic::error(Code::Preprocessor, msg, Some(Location::line(path, at)));
        let resolved = included_path(path, args, self.include_rules).map_err(err_at)?;
        let (depth, why) = self.include_rules.depth_limit();
        if self.include_stack.len() >= depth {
            return Err(err_at(format!("includes nest deeper than {depth} levels ({why})")));
        }
        if resolved == path || self.include_stack.iter().any(|(p, _)| *p == resolved) {
            let mut chain: Vec<String> = self.include_stack.iter().map(|(p, _)| p.clone()).collect();
            chain.push(path.to_string());
            chain.push(resolved.clone());
            return Err(err_at(format!("include cycle: {}", chain.join(" -> "))));
        }
        let text = self.provider.read(&resolved).map_err(|e| err_at(format!("cannot include `{resolved}`: {e}")))?;
        if self.out.text.len() + text.len() > MAX_OUTPUT_BYTES {
            return Err(err_at(format!("the preprocessed shader grows past {} MiB here", MAX_OUTPUT_BYTES >> 20)));
        }
        self.include_stack.push((path.to_string(), at));
        let result = self.process_file(&resolved, &text);
        self.include_stack.pop();
        result
    }

    /// The macros the GLSL specification defines for a version: `__VERSION__`, and from 1.50 on
    /// `GL_core_profile` or `GL_compatibility_profile`; `GL_ES` for ES.
    fn define_version_macros(&mut self, version: &VersionDirective) {
        for name in ["__VERSION__", "GL_core_profile", "GL_compatibility_profile", "GL_ES"] {
            self.macros.remove(name);
        }
        let number = |value: String| Macro { params: None, body: vec![OwnedToken { kind: TokenKind::Number, text: value }] };
        self.macros.insert("__VERSION__".into(), number(version.number.to_string()));
        let profile = match version.profile.as_deref() {
            Some("es") => Some("GL_ES"),
            Some("compatibility") => Some("GL_compatibility_profile"),
            _ if version.is_core() => Some("GL_core_profile"),
            _ => None,
        };
        if let Some(name) = profile {
            self.macros.insert(name.into(), number("1".into()));
        }
    }

    /// Defines the macro of a `#define` line; the macro's name when, leniently, it replaced a
    /// definition with another body.
    fn define(&mut self, args: &[Token<'_>]) -> Result<Option<String>, String> {
        let Some((name_pos, name)) = first_significant(args).filter(|(_, t)| t.kind == TokenKind::Ident) else {
            // Iris's preprocessor (JCPP) reports such a line and skips it.
            if self.lenient && first_significant(args).is_some() {
                return Ok(None);
            }
            return Err("#define needs a macro name".into());
        };
        let after = &args[name_pos + 1..];
        let (params, body) = if after.first().is_some_and(|t| t.is_punct("(")) {
            let close = after.iter().position(|t| t.is_punct(")")).ok_or("unclosed parameter list in #define")?;
            let mut params = Vec::new();
            for part in after[1..close].split(|t| t.is_punct(",")) {
                let idents: Vec<_> = part.iter().filter(|t| !t.is_trivia()).collect();
                match idents.as_slice() {
                    [] if params.is_empty() && close == 1 => {}
                    [t] if t.kind == TokenKind::Ident => params.push(t.text.to_string()),
                    _ => return Err(format!("malformed parameter list in #define {}", name.text)),
                }
            }
            (Some(params), &after[close + 1..])
        } else {
            (None, after)
        };
        let mut body = owned_tokens(body);
        trim_whitespace(&mut body);
        let definition = Macro { params, body };
        let redefined = self.macros.get(name.text).is_some_and(|previous| !previous.same_definition(&definition));
        if redefined && !self.lenient {
            return Err(format!(
                "macro {} is redefined with a different body (drivers refuse this; #undef it first)",
                name.text
            ));
        }
        self.macros.insert(name.text.to_string(), definition);
        Ok(redefined.then(|| name.text.to_string()))
    }

    /// Resolves an include of an inactive branch and everything it includes in turn, without
    /// preprocessing: the files must exist, as they must for OptiFine.
    fn check_inactive_include(&mut self, path: &str, at: u32, args: &[Token<'_>]) -> Result<(), Diagnostic> {
        let err_at = |msg: String| Diagnostic::error(Code::Preprocessor, msg, Some(Location::line(path, at)));
        let resolved = included_path(path, args, self.include_rules).map_err(err_at)?;
        expand_includes_mapped(self.provider, &resolved, "", self.include_rules).map(drop).map_err(|e| {
            let note = "OptiFine splices includes in before it evaluates #if, so this include is resolved although its branch is not taken";
            let e = if e.location.is_none() { Diagnostic { location: Some(Location::line(path, at)), ..e } } else { e };
            e.with_note(note)
        })
    }

    /// Advances `scan` over one more line; `scan.in_call` then tells whether the lines so far
    /// end inside the argument list of a function-like macro call.
    fn scan_macro_call(&self, scan: &mut MacroCallScan, line: &LogicalLine<'_, '_>) {
        for t in line.tokens.iter().filter(|t| !t.is_trivia()) {
            if scan.in_call {
                if t.is_punct("(") {
                    scan.depth += 1;
                } else if t.is_punct(")") {
                    scan.depth -= 1;
                    if scan.depth == 0 {
                        scan.in_call = false;
                    }
                }
            } else if scan.pending_macro && t.is_punct("(") {
                scan.in_call = true;
                scan.depth = 1;
            } else {
                scan.pending_macro = t.kind == TokenKind::Ident
                    && self.macros.get(t.text).is_some_and(|m| m.params.is_some());
            }
        }
    }

    fn emit_text_line(&mut self, tokens: &[Token<'_>], path: &str, line: u32) -> Result<(), Diagnostic> {
        let err_at = |msg: String| Diagnostic::error(Code::Preprocessor, msg, Some(Location::line(path, line)));
        let mut i = 0;
        while i < tokens.len() {
            let t = &tokens[i];
            match t.kind {
                TokenKind::LineComment => {}
                TokenKind::BlockComment => {
                    self.record_comment_directive(t.text, path, line).map_err(err_at)?;
                    // Keep the line breaks the comment spanned so line numbers stay put.
                    let breaks = t.newlines();
                    if breaks == 0 {
                        self.out.text.push(' ');
                    }
                    for _ in 0..breaks {
                        self.out.text.push('\n');
                    }
                }
                // A continuation's line break is accounted for by the caller.
                TokenKind::Whitespace if t.text.contains('\n') => self.out.text.push(' '),
                TokenKind::Newline => self.out.text.push(' '),
                TokenKind::Unknown => {
                    return Err(err_at(format!("unexpected character `{}`", t.text.escape_debug())));
                }
                TokenKind::Ident if self.macros.contains_key(t.text) => {
                    let (expansion, consumed) = self.expand_at(tokens, i).map_err(err_at)?;
                    if self.out.text.len() + expansion.len() > MAX_OUTPUT_BYTES {
                        return Err(err_at(format!("the preprocessed shader grows past {} MiB here", MAX_OUTPUT_BYTES >> 20)));
                    }
                    push_apart(&mut self.out.text, &expansion);
                    i += consumed;
                    continue;
                }
                // After an expansion, a token may meet what it ended with.
                _ => push_apart(&mut self.out.text, t.text),
            }
            i += 1;
        }
        Ok(())
    }

    /// Expands the macro invocation starting at `tokens[start]`; returns the text and the number
    /// of tokens it consumed.
    fn expand_at(&mut self, tokens: &[Token<'_>], start: usize) -> Result<(String, usize), String> {
        let owned: Vec<OwnedToken> =
            tokens[start..].iter().map(|t| OwnedToken { kind: t.kind, text: t.text.to_string() }).collect();
        let mut disabled = Vec::new();
        let (expanded, consumed) = self.expand_one(&owned, 0, &mut disabled, 0)?;
        let mut text = String::new();
        for t in &expanded {
            push_apart(&mut text, &t.text);
        }
        Ok((text, consumed))
    }

    /// Expands the invocation at `tokens[at]` (a macro name), recursively.
    fn expand_one(
        &mut self,
        tokens: &[OwnedToken],
        at: usize,
        disabled: &mut Vec<String>,
        depth: usize,
    ) -> Result<(Vec<OwnedToken>, usize), String> {
        if depth > 64 {
            return Err("macro expansion nests too deeply".into());
        }
        let name = tokens[at].text.clone();
        self.out.consulted_macros.insert(name.clone());
        let mac = self.macros[&name].clone();
        let (body, consumed) = match &mac.params {
            None => (paste_tokens(mac.body.clone(), &name, self.lenient)?, 1),
            Some(params) => {
                let Some(open) = (at + 1..tokens.len()).find(|&i| !is_trivia_kind(tokens[i].kind)) else {
                    return Ok((vec![tokens[at].clone()], 1));
                };
                if tokens[open].text != "(" {
                    return Ok((vec![tokens[at].clone()], 1));
                }
                let (args, close) = split_arguments(tokens, open).ok_or_else(|| format!("unclosed call of macro {name}"))?;
                let args = if params.is_empty() && args.len() == 1 && args[0].iter().all(|t| is_trivia_kind(t.kind)) {
                    Vec::new()
                } else {
                    args
                };
                if args.len() != params.len() {
                    return Err(format!("macro {name} takes {} arguments, {} given", params.len(), args.len()));
                }
                let mut raw_args = Vec::with_capacity(args.len());
                let mut expanded_args = Vec::with_capacity(args.len());
                for arg in args {
                    let mut arg = arg.to_vec();
                    trim_whitespace(&mut arg);
                    expanded_args.push(self.expand_all(&arg, disabled, depth + 1)?);
                    raw_args.push(arg);
                }
                let mut body = Vec::with_capacity(mac.body.len());
                for (i, t) in mac.body.iter().enumerate() {
                    match params.iter().position(|p| t.kind == TokenKind::Ident && *p == t.text) {
                        // An operand of `##` is the argument as written, not expanded; an empty
                        // one leaves a placemarker, so that `##` does not reach past it.
                        Some(p) if beside_paste(&mac.body, i) => {
                            body.extend(raw_args[p].iter().cloned());
                            if raw_args[p].is_empty() {
                                body.push(OwnedToken { kind: TokenKind::Punct, text: String::new() });
                            }
                        }
                        Some(p) => body.extend(expanded_args[p].iter().cloned()),
                        None => body.push(t.clone()),
                    }
                }
                (paste_tokens(body, &name, self.lenient)?, close + 1 - at)
            }
        };
        // An expansion that ends in the name of a function-like macro takes its arguments from
        // the text after the invocation, as C rescans it (`#define depth_of load_depth` before
        // `depth_of(texel)`, HaringPro/Revelation).
        let (mut body, mut consumed) = (body, consumed);
        let last = body.iter().rposition(|t| !is_trivia_kind(t.kind));
        let calls_on = last.is_some_and(|l| {
            let t = &body[l];
            t.kind == TokenKind::Ident && t.text != name && !disabled.contains(&t.text) && self.macros.get(&t.text).is_some_and(|m| m.params.is_some())
        });
        if calls_on
            && let Some(open) = (at + consumed..tokens.len()).find(|&i| !is_trivia_kind(tokens[i].kind))
            && tokens[open].text == "("
            && let Some((_, close)) = split_arguments(tokens, open)
        {
            body.extend(tokens[at + consumed..=close].iter().cloned());
            consumed = close + 1 - at;
        }
        disabled.push(name);
        let result = self.expand_all(&body, disabled, depth + 1);
        disabled.pop();
        Ok((result?, consumed))
    }

    fn expand_all(
        &mut self,
        tokens: &[OwnedToken],
        disabled: &mut Vec<String>,
        depth: usize,
    ) -> Result<Vec<OwnedToken>, String> {
        let mut out = Vec::with_capacity(tokens.len());
        let mut i = 0;
        while i < tokens.len() {
            let t = &tokens[i];
            if t.kind == TokenKind::Ident && self.macros.contains_key(&t.text) && !disabled.contains(&t.text) {
                let (expanded, consumed) = self.expand_one(tokens, i, disabled, depth)?;
                out.extend(expanded);
                if out.len() > MAX_EXPANSION_TOKENS {
                    return Err(format!("macro expansion produces more than {MAX_EXPANSION_TOKENS} tokens"));
                }
                i += consumed;
            } else {
                out.push(t.clone());
                i += 1;
            }
        }
        Ok(out)
    }

    /// Evaluates an `#if`/`#elif` expression; also returns the undefined names it read as 0 and,
    /// under Iris's rules, the numbers it read as their integer part.
    #[allow(clippy::type_complexity)]
    fn eval_condition(&mut self, args: &[Token<'_>], consult: bool) -> Result<(bool, Vec<String>, Vec<(String, i64)>), String> {
        // `defined X` is resolved before macro expansion, as in C.
        let mut resolved = Vec::new();
        let sig: Vec<&Token<'_>> = args.iter().filter(|t| !t.is_trivia()).collect();
        let mut i = 0;
        while i < sig.len() {
            if sig[i].is_ident("defined") {
                let (name, used) = match (sig.get(i + 1), sig.get(i + 2), sig.get(i + 3)) {
                    (Some(o), Some(n), Some(c)) if o.is_punct("(") && c.is_punct(")") => (n, 4),
                    (Some(n), _, _) => (n, 2),
                    _ => return Err("`defined` needs a macro name".into()),
                };
                if name.kind != TokenKind::Ident {
                    return Err("`defined` needs a macro name".into());
                }
                if consult {
                    self.out.consulted_macros.insert(name.text.to_string());
                    self.out.tested_macros.insert(name.text.to_string());
                }
                let value = if self.macros.contains_key(name.text) { "1" } else { "0" };
                resolved.push(OwnedToken { kind: TokenKind::Number, text: value.into() });
                i += used;
            } else {
                resolved.push(OwnedToken { kind: sig[i].kind, text: sig[i].text.to_string() });
                i += 1;
            }
        }
        let outer = std::mem::take(&mut self.out.consulted_macros);
        let expanded = self.expand_all(&resolved, &mut Vec::new(), 0);
        let in_expression = std::mem::replace(&mut self.out.consulted_macros, outer);
        let expanded = expanded?;
        if consult {
            self.out.tested_macros.extend(in_expression.iter().cloned());
            self.out.consulted_macros.extend(in_expression);
        }
        let mut undefined = Vec::new();
        let mut truncated = Vec::new();
        let iris = self.include_rules == IncludeRules::Iris;
        let values: Vec<ExprToken> = expanded
            .iter()
            .filter(|t| !is_trivia_kind(t.kind))
            .map(|t| match t.kind {
                TokenKind::Number => parse_int(&t.text).map(ExprToken::Num).or_else(|e| match integer_part(&t.text) {
                    Some(integer) if iris => {
                        truncated.push((t.text.clone(), integer));
                        Ok(ExprToken::Num(integer))
                    }
                    _ => Err(e),
                }),
                TokenKind::Ident => {
                    if consult {
                        self.out.consulted_macros.insert(t.text.clone());
                        self.out.tested_macros.insert(t.text.clone());
                    }
                    undefined.push(t.text.clone());
                    Ok(ExprToken::Num(0))
                }
                _ => Ok(ExprToken::Op(t.text.clone())),
            })
            .collect::<Result<_, _>>()?;
        if values.is_empty() {
            return Err("#if with no expression".into());
        }
        let mut parser = ExprParser { tokens: &values, pos: 0, depth: 0 };
        let value = parser.ternary()?;
        if parser.pos != values.len() {
            return Err("unexpected tokens at the end of the #if expression".into());
        }
        Ok((value != 0, undefined, truncated))
    }

    fn record_comment_directive(&mut self, comment: &str, path: &str, line: u32) -> Result<(), String> {
        let inner = comment.trim_start_matches("/*").trim_end_matches("*/").trim();
        let (modern, list) = if let Some(rest) = inner.strip_prefix("DRAWBUFFERS:") {
            (false, rest.trim())
        } else if let Some(rest) = inner.strip_prefix("RENDERTARGETS:") {
            (true, rest.trim())
        } else {
            return Ok(());
        };
        // Each entry a buffer, or `N` for none.
        let entry = |text: &str| match text {
            "N" => Some(None),
            number => number.parse::<u8>().ok().filter(|&b| b < 16).map(Some),
        };
        // An empty list draws into no colour buffer, as Iris reads it (a shadow program that
        // only discards, kolgushev/Pixel-Perfect-B).
        let buffers: Vec<Option<u8>> = if list.is_empty() {
            Some(Vec::new())
        } else if modern {
            list.split(',').map(|s| entry(s.trim())).collect::<Option<_>>()
        } else {
            list.chars().map(|c| entry(c.encode_utf8(&mut [0; 4]))).collect::<Option<_>>()
        }
        .ok_or_else(|| format!("malformed render-target list `{list}` (buffers are 0-15, or N for none)"))?;
        if buffers.len() > MAX_DRAW_BUFFERS {
            return Err(format!("a program writes at most {MAX_DRAW_BUFFERS} buffers; `{list}` lists {}", buffers.len()));
        }
        let file = self.file_id(path);
        self.out.render_targets = Some(RenderTargets { modern, buffers, line: SourceLine { file, line } });
        Ok(())
    }
}

/// Whether `body[i]` is an operand of a `##`, white space aside.
fn beside_paste(body: &[OwnedToken], i: usize) -> bool {
    let significant = |t: &&OwnedToken| !is_trivia_kind(t.kind);
    body[..i].iter().rev().find(significant).is_some_and(|t| t.text == "##") || body[i + 1..].iter().find(significant).is_some_and(|t| t.text == "##")
}

/// Appends `text` to `out`, with a space between where the two would read as other tokens
/// than they are: a macro's `-5` after a `-` is two minus signs, not a decrement (`- -5`).
fn push_apart(out: &mut String, text: &str) {
    // The word `out` ends with is a number where it starts with a digit (`1` before `.5`).
    let trailing_word = out.trim_end_matches(|c: char| c.is_ascii_alphanumeric() || c == '_');
    let ends_in_number = out[trailing_word.len()..].starts_with(|c: char| c.is_ascii_digit());
    if let (Some(a), Some(b)) = (out.chars().next_back(), text.chars().next())
        && would_join(a, b, ends_in_number)
    {
        out.push(' ');
    }
    out.push_str(text);
}

/// Whether a token ending in `a` (a number's last digit where `number`) followed directly by one
/// starting with `b` reads as other tokens: two words or numbers run together, a number and a
/// `.`, two operator characters the tokenizer reads as one (`--`, `+=`, `<<`, `&&`, `##`, …),
/// or the start or end of a comment.
fn would_join(a: char, b: char, number: bool) -> bool {
    let word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    (word(a) && word(b))
        || (a == '.' && b.is_ascii_digit())
        || (number && b == '.')
        || (a.is_ascii() && b.is_ascii() && punctuator_len(&[a as u8, b as u8]) == 2)
        || matches!((a, b), ('/', '/' | '*') | ('*', '/'))
}

/// `tokens` with the tokens either side of each `##` joined into one, as C's preprocessor (and
/// Mesa's, glslang's and Iris's) pastes them; placemarkers (empty tokens) are dropped after.
/// A paste that does not give one token (`name ## (`) is an error, which Mesa reports; read
/// `lenient`ly, as Iris's preprocessor reads it, its text is read again as the tokens it holds.
fn paste_tokens(tokens: Vec<OwnedToken>, macro_name: &str, lenient: bool) -> Result<Vec<OwnedToken>, String> {
    if !tokens.iter().any(|t| t.text == "##" || t.text.is_empty()) {
        return Ok(tokens);
    }
    let mut out: Vec<OwnedToken> = Vec::with_capacity(tokens.len());
    let mut pasting = false;
    for t in tokens {
        if t.kind == TokenKind::Punct && t.text == "##" {
            while out.last().is_some_and(|l| is_trivia_kind(l.kind)) {
                out.pop();
            }
            if out.is_empty() {
                return Err(format!("`##` cannot begin the body of macro {macro_name}"));
            }
            pasting = true;
        } else if pasting && is_trivia_kind(t.kind) {
            continue;
        } else if let (true, Some(left)) = (pasting, out.last()) {
            pasting = false;
            let text = format!("{}{}", left.text, t.text);
            out.pop();
            match tokenize(&text).as_deref() {
                Ok([]) => out.push(OwnedToken { kind: TokenKind::Punct, text }),
                Ok([one]) => out.push(OwnedToken { kind: one.kind, text }),
                Ok(several) if lenient => out.extend(several.iter().map(|t| OwnedToken { kind: t.kind, text: t.text.to_string() })),
                _ => return Err(format!("pasting `{text}` in macro {macro_name} does not give one token")),
            }
        } else {
            out.push(t);
        }
    }
    if pasting {
        return Err(format!("`##` cannot end the body of macro {macro_name}"));
    }
    out.retain(|t| !(t.kind == TokenKind::Punct && t.text.is_empty()));
    Ok(out)
}

fn is_trivia_kind(kind: TokenKind) -> bool {
    matches!(kind, TokenKind::Whitespace | TokenKind::Newline | TokenKind::LineComment | TokenKind::BlockComment)
}

fn trim_whitespace(tokens: &mut Vec<OwnedToken>) {
    while tokens.last().is_some_and(|t| is_trivia_kind(t.kind)) {
        tokens.pop();
    }
    let lead = tokens.iter().take_while(|t| is_trivia_kind(t.kind)).count();
    tokens.drain(..lead);
}

/// Splits the arguments of a call whose `(` is at `open`; returns them and the index of `)`.
fn split_arguments(tokens: &[OwnedToken], open: usize) -> Option<(Vec<&[OwnedToken]>, usize)> {
    let mut depth = 0;
    let mut args = Vec::new();
    let mut start = open + 1;
    for (i, t) in tokens.iter().enumerate().skip(open) {
        match t.text.as_str() {
            "(" => depth += 1,
            ")" => {
                depth -= 1;
                if depth == 0 {
                    args.push(&tokens[start..i]);
                    return Some((args, i));
                }
            }
            "," if depth == 1 => {
                args.push(&tokens[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    None
}

/// The first significant token of `args` when it is a name.
fn first_ident<'a>(args: &[Token<'a>]) -> Option<&'a str> {
    first_significant(args).filter(|(_, t)| t.kind == TokenKind::Ident).map(|(_, t)| t.text)
}

fn single_ident<'a>(args: &[Token<'a>]) -> Option<&'a str> {
    let sig: Vec<_> = args.iter().filter(|t| !t.is_trivia()).collect();
    match sig.as_slice() {
        [t] if t.kind == TokenKind::Ident => Some(t.text),
        _ => None,
    }
}

/// True when the conditional opened at `lines[index]` closes with nothing inside it.
fn group_is_empty(lines: &[LogicalLine<'_, '_>], index: usize) -> bool {
    for line in &lines[index + 1..] {
        if let Some((pos, first)) = first_significant(line.tokens) {
            return first.is_punct("#")
                && first_significant(&line.tokens[pos + 1..]).is_some_and(|(_, t)| t.is_ident("endif"));
        }
    }
    false
}

/// Colour buffers one draw writes at most: OpenGL's guaranteed GL_MAX_DRAW_BUFFERS, which the
/// loaders keep to and lavapipe and llvmpipe give.
pub const MAX_DRAW_BUFFERS: usize = 8;

/// The desktop GLSL versions, and the GLSL ES ones: drivers refuse any other `#version`.
pub const GLSL_VERSIONS: [u32; 13] = [110, 120, 130, 140, 150, 330, 400, 410, 420, 430, 440, 450, 460];
const GLSL_ES_VERSIONS: [u32; 4] = [100, 300, 310, 320];

fn parse_version(args: &[Token<'_>]) -> Result<VersionDirective, String> {
    let sig: Vec<_> = args.iter().filter(|t| !t.is_trivia()).collect();
    let number = sig
        .first()
        .filter(|t| t.kind == TokenKind::Number)
        .and_then(|t| t.text.parse().ok())
        .ok_or("#version needs a version number")?;
    let profile = match sig.get(1..) {
        Some([]) | None => None,
        Some([p]) if matches!(p.text, "core" | "compatibility" | "es") => Some(p.text.to_string()),
        Some(_) => return Err("#version profile must be core, compatibility or es".into()),
    };
    let es = matches!(profile.as_deref(), Some("es")) || number == 100;
    let known: &[u32] = if es { &GLSL_ES_VERSIONS } else { &GLSL_VERSIONS };
    if !known.contains(&number) {
        let list: Vec<String> = known.iter().map(u32::to_string).collect();
        return Err(format!("#version {number} is not a GLSL{} version (there are {})", if es { " ES" } else { "" }, list.join(", ")));
    }
    Ok(VersionDirective { number, profile })
}

/// Expands every `#include` textually, as OptiFine does before handing a shader to the driver
/// (includes inside inactive conditionals are expanded too), and inserts `after_version` after
/// the `#version` line. The result is what a GL driver or glslangValidator compiles.
pub fn expand_includes(provider: &dyn FileProvider, entry: &str, after_version: &str) -> Result<String, Diagnostic> {
    expand_includes_mapped(provider, entry, after_version, IncludeRules::OptiFine).map(|(text, _)| text)
}

/// [`expand_includes`] with a map from each line of the result to the pack file and line it
/// came from (`None` for the lines of `after_version`), so a driver's messages can be located.
pub fn expand_includes_mapped(
    provider: &dyn FileProvider,
    entry: &str,
    after_version: &str,
    rules: IncludeRules,
) -> Result<(String, Vec<Option<Location>>), Diagnostic> {
    fn expand(
        provider: &dyn FileProvider,
        rules: IncludeRules,
        path: &str,
        stack: &mut Vec<String>,
        out: &mut String,
        map: &mut Vec<Option<Location>>,
    ) -> Result<(), Diagnostic> {
        let text = provider.read(path).map_err(|e| Diagnostic::error(Code::PackInput, format!("cannot read {path}: {e}"), None))?;
        stack.push(path.to_string());
        for (index, line) in text.lines().enumerate() {
            let at = || Some(Location::line(path, index as u32 + 1));
            let trimmed = line.trim_start();
            let Some(rest) = trimmed.strip_prefix('#').map(str::trim_start).and_then(|r| r.strip_prefix("include")) else {
                out.push_str(line);
                out.push('\n');
                map.push(at());
                continue;
            };
            let target = rules
                .target(rest)
                .ok_or_else(|| Diagnostic::error(Code::Preprocessor, format!("#include expects a \"quoted\" path, found `{}`", rest.trim()), at()))?;
            let resolved = resolve_include(path, target).map_err(|m| Diagnostic::error(Code::Preprocessor, m, at()))?;
            if stack.contains(&resolved) {
                let chain = format!("{} -> {resolved}", stack.join(" -> "));
                return Err(Diagnostic::error(Code::Preprocessor, format!("include cycle: {chain}"), at()));
            }
            let (depth, why) = rules.depth_limit();
            if stack.len() > depth {
                return Err(Diagnostic::error(Code::Preprocessor, format!("includes nest deeper than {depth} levels ({why})"), at()));
            }
            if out.len() > MAX_SPLICED_BYTES {
                return Err(Diagnostic::error(
                    Code::Preprocessor,
                    format!("the shader with its includes spliced in grows past {} MiB here", MAX_SPLICED_BYTES >> 20),
                    at(),
                ));
            }
            expand(provider, rules, &resolved, stack, out, map)
                .map_err(|e| if e.location.is_none() { Diagnostic { location: at(), ..e } } else { e })?;
        }
        stack.pop();
        Ok(())
    }
    let mut body = String::new();
    let mut map = Vec::new();
    expand(provider, rules, entry, &mut Vec::new(), &mut body, &mut map)?;
    // After the `#version` line, wherever it is (comments may come first), as OptiFine does.
    let inserted = vec![None; after_version.matches('\n').count()];
    let version_line = body.split_inclusive('\n').position(|line| line.trim_start().starts_with("#version"));
    match version_line {
        Some(index) => {
            let split = body.split_inclusive('\n').take(index + 1).map(str::len).sum::<usize>();
            let tail = map.split_off(index + 1);
            map.extend(inserted);
            map.extend(tail);
            Ok((format!("{}{after_version}{}", &body[..split], &body[split..]), map))
        }
        None => Ok((format!("{after_version}{body}"), inserted.into_iter().chain(map).collect())),
    }
}

/// The pack path an `#include "…"` directive of file `from` names (its arguments after the
/// directive name).
fn included_path(from: &str, args: &[Token<'_>], rules: IncludeRules) -> Result<String, String> {
    let raw: String = args.iter().filter(|t| !t.is_trivia()).map(|t| t.text).collect();
    let target = rules.target(&raw).ok_or_else(|| format!("#include expects a \"quoted\" path, found `{raw}`"))?;
    resolve_include(from, target)
}

/// Resolves an `#include` target: `/x` from the pack's shader root, `x` beside `from`.
/// Refuses paths that climb out of the pack.
pub fn resolve_include(from: &str, target: &str) -> Result<String, String> {
    let mut parts: Vec<&str> = if target.starts_with('/') {
        Vec::new()
    } else {
        let mut dir: Vec<&str> = from.split('/').collect();
        dir.pop();
        dir
    };
    // Above the root is the pack folder, so `/../shaders/lib/x.glsl` climbs out of `shaders/`
    // and straight back in, which OptiFine resolves to `lib/x.glsl`.
    let mut above_root = false;
    for part in target.split('/') {
        match part {
            "" | "." => {}
            ".." => {
                if parts.pop().is_none() {
                    if above_root {
                        return Err(format!("include path `{target}` climbs out of the shader pack"));
                    }
                    above_root = true;
                }
            }
            "shaders" if above_root => above_root = false,
            _ if above_root => return Err(format!("include path `{target}` climbs out of the shader pack")),
            p if p.contains('\\') || p.contains(':') => {
                return Err(format!("include path `{target}` must use `/` separators and no drive letters"));
            }
            p => parts.push(p),
        }
    }
    if parts.is_empty() {
        return Err(format!("include path `{target}` names no file"));
    }
    Ok(parts.join("/"))
}

fn parse_int(text: &str) -> Result<i64, String> {
    let t = text.trim_end_matches(['u', 'U']);
    let parsed = if let Some(hex) = t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
        i64::from_str_radix(hex, 16)
    } else if t.len() > 1 && t.starts_with('0') {
        i64::from_str_radix(&t[1..], 8)
    } else {
        t.parse()
    };
    parsed.map_err(|_| format!("`{text}` is not an integer; #if works on integers only"))
}

/// A decimal number with a fraction or an exponent as Iris's preprocessor (JCPP's
/// `NumericValue.longValue`) reads it in `#if`: the digits before the point, times ten to the
/// exponent, truncated (`0.5` is 0, `2.0f` is 2, `1.5e1` is 10, `5e-1` is 0).
fn integer_part(text: &str) -> Option<i64> {
    let t = text.trim_end_matches(['f', 'F', 'l', 'L']);
    if t.starts_with("0x") || t.starts_with("0X") {
        return None;
    }
    let (mantissa, exponent) = match t.split_once(['e', 'E']) {
        Some((m, e)) => (m, Some(e.parse::<i32>().ok()?)),
        None => (t, None),
    };
    let (integer, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = |part: &str| part.bytes().all(|b| b.is_ascii_digit());
    if !(digits(integer) && digits(fraction)) || (!mantissa.contains('.') && exponent.is_none()) {
        return None;
    }
    let value: i64 = if integer.is_empty() { 0 } else { integer.parse().ok()? };
    Some(match exponent {
        // Java's cast of a double to long truncates toward zero and saturates.
        Some(e) => (value as f64 * 10f64.powi(e)) as i64,
        None => value,
    })
}

enum ExprToken {
    Num(i64),
    Op(String),
}

/// The value of an integer expression of literals only (`5 * 5`, what an array size is after
/// macro expansion), evaluated as `#if` evaluates; `None` when it names anything or does not
/// parse.
pub fn literal_integer_expression(text: &str) -> Option<i64> {
    let tokens = tokenize(text).ok()?;
    let values: Vec<ExprToken> = tokens
        .iter()
        .filter(|t| !t.is_trivia())
        .map(|t| match t.kind {
            TokenKind::Number => parse_int(t.text).ok().map(ExprToken::Num),
            TokenKind::Punct => Some(ExprToken::Op(t.text.to_string())),
            _ => None,
        })
        .collect::<Option<_>>()?;
    let mut parser = ExprParser { tokens: &values, pos: 0, depth: 0 };
    let value = parser.ternary().ok()?;
    (parser.pos == values.len()).then_some(value)
}

/// Precedence-climbing evaluator for `#if` expressions (C preprocessor semantics on i64).
struct ExprParser<'t> {
    tokens: &'t [ExprToken],
    pos: usize,
    /// Recursion depth, bounded by [`MAX_EXPRESSION_DEPTH`].
    depth: usize,
}

impl ExprParser<'_> {
    fn peek_op(&self) -> Option<&str> {
        match self.tokens.get(self.pos) {
            Some(ExprToken::Op(op)) => Some(op),
            _ => None,
        }
    }

    fn ternary(&mut self) -> Result<i64, String> {
        let cond = self.binary(0)?;
        if self.peek_op() == Some("?") {
            self.pos += 1;
            let a = self.ternary()?;
            if self.peek_op() != Some(":") {
                return Err("expected `:` in #if expression".into());
            }
            self.pos += 1;
            let b = self.ternary()?;
            return Ok(if cond != 0 { a } else { b });
        }
        Ok(cond)
    }

    fn binary(&mut self, min_prec: u8) -> Result<i64, String> {
        let mut lhs = self.unary()?;
        while let Some(op) = self.peek_op() {
            let prec = match op {
                "||" => 1,
                "&&" => 2,
                "|" => 3,
                "^" => 4,
                "&" => 5,
                "==" | "!=" => 6,
                "<" | ">" | "<=" | ">=" => 7,
                "<<" | ">>" => 8,
                "+" | "-" => 9,
                "*" | "/" | "%" => 10,
                _ => break,
            };
            if prec < min_prec {
                break;
            }
            let op = op.to_string();
            self.pos += 1;
            let rhs = self.binary(prec + 1)?;
            lhs = match op.as_str() {
                "||" => ((lhs != 0) || (rhs != 0)) as i64,
                "&&" => ((lhs != 0) && (rhs != 0)) as i64,
                "|" => lhs | rhs,
                "^" => lhs ^ rhs,
                "&" => lhs & rhs,
                "==" => (lhs == rhs) as i64,
                "!=" => (lhs != rhs) as i64,
                "<" => (lhs < rhs) as i64,
                ">" => (lhs > rhs) as i64,
                "<=" => (lhs <= rhs) as i64,
                ">=" => (lhs >= rhs) as i64,
                "<<" => lhs.wrapping_shl(rhs as u32),
                ">>" => lhs.wrapping_shr(rhs as u32),
                "+" => lhs.wrapping_add(rhs),
                "-" => lhs.wrapping_sub(rhs),
                "*" => lhs.wrapping_mul(rhs),
                "/" | "%" if rhs == 0 => return Err("division by zero in #if expression".into()),
                "/" => lhs.wrapping_div(rhs),
                _ => lhs.wrapping_rem(rhs),
            };
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<i64, String> {
        self.depth += 1;
        let result = self.unary_inner();
        self.depth -= 1;
        result
    }

    fn unary_inner(&mut self) -> Result<i64, String> {
        if self.depth > MAX_EXPRESSION_DEPTH {
            return Err(format!("#if expression nests deeper than {MAX_EXPRESSION_DEPTH} levels"));
        }
        match self.tokens.get(self.pos) {
            Some(ExprToken::Num(n)) => {
                self.pos += 1;
                Ok(*n)
            }
            Some(ExprToken::Op(op)) => {
                let op = op.clone();
                self.pos += 1;
                match op.as_str() {
                    "(" => {
                        let v = self.ternary()?;
                        if self.peek_op() != Some(")") {
                            return Err("missing `)` in #if expression".into());
                        }
                        self.pos += 1;
                        Ok(v)
                    }
                    "-" => Ok(self.unary()?.wrapping_neg()),
                    "+" => self.unary(),
                    "!" => Ok((self.unary()? == 0) as i64),
                    "~" => Ok(!self.unary()?),
                    other => Err(format!("unexpected `{other}` in #if expression")),
                }
            }
            None => Err("#if expression ends early".into()),
        }
    }
}

/// A stage without `#version` is GLSL 1.10 to the driver: say so on an added first line, which
/// the line map attributes to the entry's first line.
pub fn assume_glsl_110(pre: &mut Preprocessed) {
    if pre.version.is_none() && !pre.lines.is_empty() {
        pre.text.insert_str(0, "#version 110\n");
        pre.lines.insert(0, pre.lines[0]);
        pre.version = Some(VersionDirective { number: 110, profile: None });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_macro_continued_over_lines_adds_no_line_where_it_expands() {
        let text = "#version 120\n#define BLEND(a, b) \\\n    mix(a, b, \\\n        0.5)\nfloat x = BLEND(1.0, 2.0);\nfloat y = undeclared;\n";
        let out = run(&[("a.fsh", text)]).unwrap();
        assert_eq!(out.text.matches('\n').count(), out.lines.len(), "{:?}", out.text);
        let y = out.text.lines().position(|l| l.contains("undeclared")).unwrap() as u32 + 1;
        assert_eq!(out.location(y), Some(Location::line("a.fsh", 6)));
    }

    #[test]
    fn token_pasting_joins_the_operands_as_written() {
        let text = "#version 330\n#define SUFFIX _b\n#define JOIN(a, b) a ## b\n#define NAME(x) color ## x\n#define WHOLE val ## ue\n\
                    float JOIN(f, SUFFIX) = 1.0;\nfloat NAME(2) = NAME() + WHOLE;\nint x = JOIN(1, 2);\n";
        let out = run(&[("a.fsh", text)]).unwrap();
        // An operand is not expanded first: `f ## SUFFIX` is `fSUFFIX`.
        assert!(out.text.contains("float fSUFFIX = 1.0;"), "{}", out.text);
        // An empty argument pastes nothing, and no further than its own place.
        assert!(out.text.contains("float color2 = color + value;"), "{}", out.text);
        assert!(out.text.contains("int x = 12;"), "{}", out.text);
        let bad = "#version 330\n#define JOIN(a, b) a ## b\nfloat x = JOIN(+, /);\n";
        let error = run(&[("a.fsh", bad)]).unwrap_err();
        assert!(error.message.contains("pasting `+/` in macro JOIN does not give one token"), "{}", error.message);
        // Read leniently, as Iris's preprocessor reads it, the pasted text is its tokens.
        let call = "#version 330\n#define CALL(f, x) f ## (x)\nfloat y = CALL(abs, -1.0);\n";
        let lenient = PreprocessOptions { lenient: true, ..PreprocessOptions::default() };
        let out = preprocess(&files(&[("a.fsh", call)]), "a.fsh", &lenient).unwrap();
        assert!(out.text.contains("float y = abs(-1.0);"), "{}", out.text);
        assert!(run(&[("a.fsh", call)]).is_err());
    }

    #[test]
    fn include_paths_resolve_as_optifine_resolves_them() {
        assert_eq!(resolve_include("world0/composite.fsh", "/lib/a.glsl").unwrap(), "lib/a.glsl");
        assert_eq!(resolve_include("world0/composite.fsh", "../lib/a.glsl").unwrap(), "lib/a.glsl");
        assert_eq!(resolve_include("lib/x/b.glsl", "c.glsl").unwrap(), "lib/x/c.glsl");
        // Out of shaders/ and straight back in.
        assert_eq!(resolve_include("composite.fsh", "/../shaders/lib/a.glsl").unwrap(), "lib/a.glsl");
        for outside in ["/../other/a.glsl", "../../a.glsl", "/../../shaders/a.glsl", "/..", "lib\\a.glsl"] {
            assert!(resolve_include("composite.fsh", outside).is_err(), "{outside}");
        }
    }

    fn files(list: &[(&str, &str)]) -> HashMap<String, Arc<str>> {
        list.iter().map(|(p, t)| (p.to_string(), Arc::from(*t))).collect()
    }

    fn run(list: &[(&str, &str)]) -> Result<Preprocessed, Diagnostic> {
        preprocess(&files(list), list[0].0, &PreprocessOptions::default())
    }

    #[test]
    fn a_number_that_is_not_an_integer_in_if_is_an_error_but_under_iris_its_integer_part() {
        let pack = [("a.fsh", "#if 0.5 < 1.5e1\nfloat taken;\n#endif\n")];
        assert!(run(&pack).unwrap_err().message.contains("`0.5` is not an integer"));
        let iris = PreprocessOptions { include_rules: IncludeRules::Iris, ..PreprocessOptions::default() };
        let pre = preprocess(&files(&pack), "a.fsh", &iris).unwrap();
        assert!(pre.text.contains("float taken;"), "0 < 10");
        let read: Vec<&str> = pre.warnings.iter().filter(|w| w.code == Code::FloatInIf).map(|w| w.message.as_str()).collect();
        assert!(read.len() == 2 && read[0].contains("`0.5` reads as 0") && read[1].contains("`1.5e1` reads as 10"), "{read:?}");
        for (number, integer) in [("2.0f", Some(2)), (".5", Some(0)), ("5.", Some(5)), ("5e-1", Some(0)), ("12", None), ("0x1.8p1", None)] {
            assert_eq!(integer_part(number), integer, "{number}");
        }
    }

    #[test]
    fn a_token_cache_tokenizes_each_text_once_and_never_serves_another_text() {
        let options = PreprocessOptions { token_cache: Some(Arc::new(TokenCache::default())), ..PreprocessOptions::default() };
        let cached_bytes = || options.token_cache.as_ref().unwrap().bytes.load(std::sync::atomic::Ordering::Relaxed);
        let pack = files(&[("a.fsh", "#version 120\n#include \"lib.glsl\"\nvoid main() { gl_FragColor = vec4(K); }\n"), ("lib.glsl", "#define K 0.5\n")]);
        let alone = preprocess(&pack, "a.fsh", &PreprocessOptions::default()).unwrap();
        let first = preprocess(&pack, "a.fsh", &options).unwrap();
        let bytes = cached_bytes();
        assert!(bytes > 0);
        let second = preprocess(&pack, "a.fsh", &options).unwrap();
        assert_eq!((&first.text, &first.lines), (&alone.text, &alone.lines));
        assert_eq!((&second.text, &second.lines), (&alone.text, &alone.lines));
        assert_eq!(cached_bytes(), bytes, "the second run read every file from the cache");
        // The same path with other text (an option set's value) is tokenized anew.
        let mut changed = pack.clone();
        changed.insert("lib.glsl".into(), Arc::from("#define K 0.25\n"));
        assert!(preprocess(&changed, "a.fsh", &options).unwrap().text.contains("vec4(0.25)"));
        assert!(cached_bytes() > bytes);
    }

    #[test]
    fn iris_reads_an_include_path_without_quotes_optifine_does_not() {
        let list = [("a.fsh", "#version 120\n#include lib/b.glsl\nvoid main() {}\n"), ("lib/b.glsl", "float b;\n")];
        let err = run(&list).unwrap_err();
        assert!(err.message.contains("expects a \"quoted\" path") && err.location.unwrap().line == 2, "{}", err.message);
        let iris = PreprocessOptions { include_rules: IncludeRules::Iris, ..PreprocessOptions::default() };
        let out = preprocess(&files(&list), "a.fsh", &iris).unwrap();
        assert!(out.text.contains("float b;"), "{}", out.text);
        assert_eq!(IncludeRules::Iris.target(" \"lib/c.glsl\" "), Some("lib/c.glsl"));
        assert_eq!(IncludeRules::OptiFine.target(" \"lib/c.glsl\" // why"), Some("lib/c.glsl"));
    }

    #[test]
    fn iris_follows_includes_deeper_than_optifine_and_stops_at_its_own_bound() {
        // a.fsh includes l1.glsl, which includes l2.glsl, … down to l{n}.glsl.
        let chain = |n: usize| -> Vec<(String, String)> {
            let mut list = vec![("a.fsh".to_string(), "#version 120\n#include \"/l1.glsl\"\nvoid main() {}\n".to_string())];
            for k in 1..n {
                list.push((format!("l{k}.glsl"), format!("#include \"/l{}.glsl\"\n", k + 1)));
            }
            list.push((format!("l{n}.glsl"), "float deepest;\n".to_string()));
            list
        };
        let provider = |list: &[(String, String)]| list.iter().map(|(p, t)| (p.clone(), Arc::from(t.as_str()))).collect::<HashMap<String, Arc<str>>>();
        let iris = PreprocessOptions { include_rules: IncludeRules::Iris, ..PreprocessOptions::default() };
        let thirteen = provider(&chain(13));
        let err = preprocess(&thirteen, "a.fsh", &PreprocessOptions::default()).unwrap_err();
        assert!(err.message.contains("deeper than 10 levels (OptiFine's limit)"), "{}", err.message);
        assert!(preprocess(&thirteen, "a.fsh", &iris).unwrap().text.contains("float deepest;"));
        let err = preprocess(&provider(&chain(MAX_IRIS_INCLUDE_DEPTH + 2)), "a.fsh", &iris).unwrap_err();
        assert!(err.message.contains(&format!("deeper than {MAX_IRIS_INCLUDE_DEPTH} levels")), "{}", err.message);
    }

    #[test]
    fn tokens_an_expansion_brings_together_stay_apart() {
        // As RetroMaidRage/ImmersiveShaders counts a loop from `-BLOOM_QUALITY2`, itself `-5`.
        let text = "#define NEG -5\n#define MINUS(x) -x\nint i = -NEG; int j = MINUS(-1); int k = NEG-1; float f = tex0.x; vec2 v = vec2(NEG.0);\n";
        let out = preprocess(&files(&[("a.fsh", text)]), "a.fsh", &PreprocessOptions::default()).unwrap();
        assert!(out.text.contains("int i = - -5; int j = - -1; int k = -5-1; float f = tex0.x;"), "{}", out.text);
        assert!(out.text.contains("vec2(-5 .0)"), "{}", out.text);
    }

    #[test]
    fn a_macro_redefined_is_refused_and_taken_leniently_with_its_place_recorded() {
        let list = [("a.fsh", "#version 120\n#include \"/b.glsl\"\n#define PI 3.14159\nfloat x = PI;\n"), ("b.glsl", "#define PI 3.14\n")];
        let err = run(&list).unwrap_err();
        assert!(err.message.contains("macro PI is redefined") && err.location.unwrap().line == 3, "{}", err.message);
        let lenient = PreprocessOptions { lenient: true, ..PreprocessOptions::default() };
        let out = preprocess(&files(&list), "a.fsh", &lenient).unwrap();
        assert!(out.text.contains("float x = 3.14159;"), "{}", out.text);
        assert_eq!(out.redefinitions, [(Location::line("a.fsh", 3), "PI".to_string())]);
    }

    #[test]
    fn a_define_without_a_name_is_refused_and_skipped_leniently_with_its_groups_kept() {
        let list = [("a.fsh", "#define 2D_CLOUDS\n#ifdef 2D_CLOUDS\nint clouds;\n#endif\n#ifndef 2D_CLOUDS\nint more;\n#endif\n")];
        let err = preprocess(&files(&list), "a.fsh", &PreprocessOptions::default()).unwrap_err();
        assert!(err.message.contains("#define needs a macro name"), "{}", err.message);
        let lenient = PreprocessOptions { lenient: true, ..PreprocessOptions::default() };
        let out = preprocess(&files(&list), "a.fsh", &lenient).unwrap();
        assert!(out.text.contains("int clouds;") && out.text.contains("int more;"), "{}", out.text);
    }

    #[test]
    fn an_endif_with_no_if_open_is_refused_and_skipped_leniently() {
        let list = [("a.fsh", "#version 120\n#include \"/b.glsl\"\nfloat b;\n"), ("b.glsl", "#ifdef A\nfloat a;\n#endif\nfloat c;\n#endif\n")];
        let err = run(&list).unwrap_err();
        assert!(err.message.contains("#endif without #if") && err.location.unwrap().line == 5, "{}", err.message);
        let lenient = PreprocessOptions { lenient: true, ..PreprocessOptions::default() };
        let out = preprocess(&files(&list), "a.fsh", &lenient).unwrap();
        assert!(out.text.contains("float c;") && out.text.contains("float b;") && !out.text.contains("float a;"), "{}", out.text);
    }

    #[test]
    fn extra_tokens_after_an_ifndef_name_are_refused_and_ignored_leniently() {
        let list = [("a.fsh", "#version 120\n#define A\n#ifndef A && defined B\nfloat a;\n#else\nfloat b;\n#endif\n")];
        let err = run(&list).unwrap_err();
        assert!(err.message.contains("#ifndef needs exactly one macro name") && err.location.unwrap().line == 3, "{}", err.message);
        let lenient = PreprocessOptions { lenient: true, ..PreprocessOptions::default() };
        let out = preprocess(&files(&list), "a.fsh", &lenient).unwrap();
        assert!(out.text.contains("float b;") && !out.text.contains("float a;"), "{}", out.text);
    }

    #[test]
    fn tokens_after_else_are_refused_and_ignored_leniently() {
        let list = [("a.fsh", "#version 120\n#ifdef VERTEX\nfloat a;\n#else if defined FRAGMENT\nfloat b;\n#endif // comment\n")];
        let err = run(&list).unwrap_err();
        assert!(err.message.contains("#else takes nothing after it") && err.location.unwrap().line == 4, "{}", err.message);
        let lenient = PreprocessOptions { lenient: true, ..PreprocessOptions::default() };
        let out = preprocess(&files(&list), "a.fsh", &lenient).unwrap();
        assert!(out.text.contains("float b;") && !out.text.contains("float a;"), "{}", out.text);
    }

    #[test]
    fn a_version_no_glsl_has_is_an_error() {
        let err = run(&[("a.fsh", "#version 9999 compatibility\nvoid main() {}\n")]).unwrap_err();
        assert!(err.message.contains("#version 9999 is not a GLSL version"), "{}", err.message);
        assert_eq!(err.location.unwrap().line, 1);
        assert!(run(&[("a.fsh", "#version 300 es\nvoid main() {}\n")]).is_ok());
        assert!(run(&[("a.fsh", "#version 300\nvoid main() {}\n")]).unwrap_err().message.contains("not a GLSL version"));
    }

    #[test]
    fn the_version_line_defines_the_specifications_macros() {
        let text = "#if __VERSION__ >= 130\nnew\n#else\nold\n#endif\n#ifdef GL_compatibility_profile\ncompat\n#endif\n#ifdef GL_core_profile\ncore\n#endif\nint v = __VERSION__;\n";
        let words = |version: &str| {
            let out = run(&[("a.fsh", &format!("{version}{text}"))]).unwrap();
            assert!(out.warnings.is_empty(), "{:?}", out.warnings);
            out.text.split_whitespace().collect::<Vec<_>>().join(" ")
        };
        assert!(words("#version 120\n").ends_with("old int v = 120;"), "{}", words("#version 120\n"));
        assert!(words("#version 330 compatibility\n").ends_with("new compat int v = 330;"));
        assert!(words("#version 330\n").ends_with("new core int v = 330;"));
        // No #version: GLSL 1.10.
        assert!(words("").ends_with("old int v = 110;"), "{}", words(""));
    }

    #[test]
    fn keeps_one_output_line_per_source_line() {
        let out = run(&[(
            "a.fsh",
            "#version 120\n#define X 2\n#ifdef X\nfloat a = X;\n#else\nfloat a = 0;\n#endif\n/* two\nlines */ float b;\n",
        )])
        .unwrap();
        let lines: Vec<&str> = out.text.lines().collect();
        assert_eq!(lines.len(), out.lines.len());
        assert_eq!(lines[0], "#version 120");
        assert_eq!(lines[3], "float a = 2;");
        assert_eq!(lines[5], "");
        assert_eq!(lines[8].trim(), "float b;");
        assert_eq!(out.lines[8].line, 9);
    }

    #[test]
    fn includes_map_back_to_their_files() {
        let out = run(&[
            ("prog/a.fsh", "#version 120\n#include \"/lib/x.glsl\"\nvoid main() {}\n"),
            ("lib/x.glsl", "#include \"y.glsl\"\nfloat x;\n"),
            ("lib/y.glsl", "float y;\n"),
        ])
        .unwrap();
        let located: Vec<String> =
            (1..=out.lines.len() as u32).map(|l| out.location(l).unwrap().to_string()).collect();
        assert_eq!(located, ["prog/a.fsh:1", "lib/y.glsl:1", "lib/x.glsl:2", "prog/a.fsh:3"]);
        assert!(out.text.contains("float y;\nfloat x;\nvoid main"));
    }

    #[test]
    fn include_cycle_is_reported_at_the_including_line() {
        let err = run(&[
            ("a.fsh", "#version 120\n#include \"/lib/x.glsl\"\n"),
            ("lib/x.glsl", "\n\n#include \"/lib/x.glsl\"\n"),
        ])
        .unwrap_err();
        assert_eq!(err.location, Some(Location::line("lib/x.glsl", 3)));
        assert!(err.message.contains("include cycle"), "{}", err.message);
    }

    #[test]
    fn missing_include_and_escape_are_errors() {
        let err = run(&[("a.fsh", "#version 120\n\n#include \"/lib/none.glsl\"\n")]).unwrap_err();
        assert_eq!(err.location, Some(Location::line("a.fsh", 3)));
        let err = run(&[("a.fsh", "#include \"../../etc/passwd\"\n")]).unwrap_err();
        assert!(err.message.contains("climbs out"), "{}", err.message);
    }

    #[test]
    fn function_macros_and_nested_expansion() {
        let out = run(&[(
            "a.fsh",
            "#define SQ(x) ((x) * (x))\n#define TWO 2\n#define F(a, b) SQ(a) + b\nfloat v = F(TWO, SQ(3));\nfloat w = F(1,\n 2);\n",
        )])
        .unwrap();
        let lines: Vec<&str> = out.text.lines().collect();
        assert_eq!(lines[3], "float v = ((2) * (2)) + ((3) * (3));");
        assert!(lines[4].starts_with("float w = ((1) * (1)) + 2;"), "{:?}", lines[4]);
        assert_eq!(out.text.lines().count(), 6);
    }

    #[test]
    fn if_expressions_follow_c_rules() {
        let src = "#define A 3\n#if defined(A) && A * 2 == 6 && !defined B && (UNDEF == 0) && (A > 2 ? 1 : 0)\nyes\n#endif\n#if 0x10 >> 2 != 4\nno\n#elif 1\nelif\n#else\nno\n#endif\n";
        let out = run(&[("a.fsh", src)]).unwrap();
        let words: Vec<&str> = out.text.split_whitespace().collect();
        assert_eq!(words, ["yes", "elif"]);
    }

    #[test]
    fn empty_conditionals_do_not_count_as_consulted() {
        let out = run(&[("a.fsh", "#define OPT\n#ifdef OPT\n#endif\n#ifdef USED\nx\n#endif\n")]).unwrap();
        assert!(!out.consulted_macros.contains("OPT"));
        assert!(out.consulted_macros.contains("USED"));
    }

    #[test]
    fn records_active_render_targets_only() {
        let src = "#ifdef NEVER\n/* DRAWBUFFERS:0123 */\n#else\n/* RENDERTARGETS: 0,4 */\n#endif\n";
        let out = run(&[("a.fsh", src)]).unwrap();
        let targets = out.render_targets.unwrap();
        assert_eq!((targets.modern, targets.buffers), (true, vec![Some(0), Some(4)]));
        assert_eq!(targets.line.line, 4);
    }

    /// An object-like macro naming a function-like one takes the arguments written after it,
    /// as C rescans (HaringPro/Revelation's `#define loadDepthMacro loadDepth1`).
    #[test]
    fn a_macro_expanding_to_a_function_like_macro_name_takes_the_arguments_after_it() {
        let src = "#define load(t) fetch(t, 0)\n#define loader load\nfloat d = loader(ivec2(1, 2)).x;\nfloat e = loader;\n";
        let out = run(&[("a.fsh", src)]).unwrap();
        let lines: Vec<&str> = out.text.lines().collect();
        assert!(lines[2].contains("fetch(ivec2(1, 2), 0).x;") && !lines[2].contains("load"), "{}", out.text);
        assert!(lines[3].contains("float e = load;"), "{}", out.text);
    }

    /// A line comment between a multi-line macro call's arguments (Rinrin0413/Tempest-Shaders_JE's
    /// `saturate(` … `// Subtract in shadow` … `)`) does not end the line the call is written on.
    #[test]
    fn a_line_comment_inside_a_macro_call_spanning_lines_is_a_space() {
        let src = "#define S(x) clamp(x, 0.0, 1.0)\nfloat l = S(\n    a\n    // the rest\n    - b\n);\nfloat next;\n";
        let out = run(&[("a.fsh", src)]).unwrap();
        let first = out.text.lines().nth(1).unwrap();
        assert!(first.contains("clamp") && first.contains("- b") && first.trim_end().ends_with(';') && !first.contains("//"), "{first}");
        assert!(out.text.lines().nth(6).is_some_and(|l| l.contains("float next")), "{}", out.text);
    }

    /// `/* DRAWBUFFERS: */` names no buffer: the program draws into none, as Iris reads it.
    #[test]
    fn an_empty_render_target_list_draws_into_no_buffer() {
        for src in ["/* DRAWBUFFERS: */\n", "/* RENDERTARGETS: */\n"] {
            let targets = run(&[("a.fsh", src)]).unwrap().render_targets.unwrap();
            assert!(targets.buffers.is_empty(), "{src:?}");
        }
    }

    #[test]
    fn structural_errors_name_the_line() {
        for (src, line, needle) in [
            ("a\n#if 1\nb\n", 2, "no matching #endif"),
            ("#endif\n", 1, "#endif without #if"),
            ("\n#if 1 +\n#endif\n", 2, "ends early"),
            ("\n\n#error stop here\n", 3, "#error stop here"),
            ("x\n#bogus\n", 2, "unknown preprocessor directive"),
            ("#if 1 / 0\n#endif\n", 1, "division by zero"),
            ("float a;\nfloat b @;\n", 2, "unexpected character"),
            ("\nfloat a; /* open\n", 2, "unterminated block comment"),
        ] {
            let err = run(&[("a.fsh", src)]).unwrap_err();
            assert_eq!(err.location.as_ref().unwrap().line, line, "{src:?}: {err}");
            assert!(err.message.contains(needle), "{src:?}: {err}");
        }
    }

    #[test]
    fn include_depth_is_limited() {
        let mut list = vec![("a.fsh".to_string(), "#include \"/l0.glsl\"\n".to_string())];
        for i in 0..12 {
            list.push((format!("l{i}.glsl"), format!("#include \"/l{}.glsl\"\n", i + 1)));
        }
        list.push(("l12.glsl".into(), "float x;\n".into()));
        let map: HashMap<String, Arc<str>> = list.into_iter().map(|(p, t)| (p, Arc::from(t))).collect();
        let err = preprocess(&map, "a.fsh", &PreprocessOptions::default()).unwrap_err();
        assert!(err.message.contains("deeper than 10"), "{err}");
    }

    #[test]
    fn expand_includes_is_textual_and_checks_cycles() {
        let map = files(&[
            ("a.fsh", "#version 120\n#ifdef NEVER\n#include \"/lib/x.glsl\"\n#endif\nvoid main() {}\n"),
            ("lib/x.glsl", "float x;\n"),
        ]);
        let out = expand_includes(&map, "a.fsh", "#define MC_VERSION 12104\n").unwrap();
        assert_eq!(out, "#version 120\n#define MC_VERSION 12104\n#ifdef NEVER\nfloat x;\n#endif\nvoid main() {}\n");
        let (_, map) = expand_includes_mapped(&map, "a.fsh", "#define A\n", IncludeRules::OptiFine).unwrap();
        let shown: Vec<String> = map.iter().map(|l| l.as_ref().map_or("-".into(), |l| l.to_string())).collect();
        assert_eq!(shown, ["a.fsh:1", "-", "a.fsh:2", "lib/x.glsl:1", "a.fsh:4", "a.fsh:5"]);
        let late = files(&[("a.fsh", "// banner\n\n#version 150 compatibility\nvoid main() {}\n")]);
        let (text, map) = expand_includes_mapped(&late, "a.fsh", "#define A\n", IncludeRules::OptiFine).unwrap();
        assert_eq!(text, "// banner\n\n#version 150 compatibility\n#define A\nvoid main() {}\n");
        assert_eq!(map[3], None);
        assert_eq!(map[4], Some(Location::line("a.fsh", 4)));
        let cyclic = files(&[("a.fsh", "#include \"b.glsl\"\n"), ("b.glsl", "\n#include \"a.fsh\"\n")]);
        let err = expand_includes(&cyclic, "a.fsh", "").unwrap_err();
        assert_eq!(err.location, Some(Location::line("b.glsl", 2)));
    }

    #[test]
    fn hostile_inputs_stop_with_errors() {
        // Exponential macro expansion.
        let mut src = String::from("#define A0 x x\n");
        for i in 1..40 {
            src.push_str(&format!("#define A{i} A{} A{}\n", i - 1, i - 1));
        }
        src.push_str("float v = A39;\n");
        let err = run(&[("a.fsh", &src)]).unwrap_err();
        assert!(err.message.contains("more than"), "{err}");
        // An include repeated until the output is too large.
        let big = "float x; ".repeat(300_000);
        let mut list = vec![("a.fsh".to_string(), "#include \"/b.glsl\"\n".repeat(8))];
        list.push(("b.glsl".into(), big));
        let map: HashMap<String, Arc<str>> = list.into_iter().map(|(p, t)| (p, Arc::from(t))).collect();
        let err = preprocess(&map, "a.fsh", &PreprocessOptions::default()).unwrap_err();
        assert!(err.message.contains("grows past"), "{err}");
        assert_eq!(err.location.unwrap().path, "a.fsh");
        // Deeply nested #if expression.
        let src = format!("#if {}1{}\n#endif\n", "(".repeat(100_000), ")".repeat(100_000));
        let err = run(&[("a.fsh", &src)]).unwrap_err();
        assert!(err.message.contains("nests deeper"), "{err}");
        // An unclosed macro call over many lines is linear, not quadratic.
        let src = format!("#define F(x) x\nF(\n{}", "a,\n".repeat(50_000));
        let started = std::time::Instant::now();
        let _ = run(&[("a.fsh", &src)]);
        assert!(started.elapsed().as_secs() < 10);
    }

    #[test]
    fn self_referential_macro_stops() {
        let out = run(&[("a.fsh", "#define X X + 1\nfloat v = X;\n")]).unwrap();
        assert_eq!(out.text.lines().nth(1).unwrap(), "float v = X + 1;");
    }

    #[test]
    fn a_stage_without_version_is_glsl_110() {
        let files: HashMap<String, Arc<str>> =
            [("final.fsh".to_string(), Arc::from("uniform sampler2D composite;\nvoid main() {}\n"))].into();
        let mut pre = preprocess(&files, "final.fsh", &PreprocessOptions::default()).unwrap();
        assume_glsl_110(&mut pre);
        assert!(pre.text.starts_with("#version 110\nuniform sampler2D composite;\n"), "{}", pre.text);
        assert_eq!(pre.text.lines().count(), pre.lines.len());
        assert_eq!(pre.location(2), Some(Location::line("final.fsh", 1)));
    }
}
