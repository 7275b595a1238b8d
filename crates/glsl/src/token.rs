//! A lossless GLSL tokenizer.
//!
//! Concatenating the text of every token gives back the input exactly, so rewriting passes
//! (dialect generation, lowering) can replace single tokens and keep everything else, line
//! breaks included. Line continuations (`\` before a line break) are kept inside the
//! whitespace token they appear in; every token records the 1-based line it starts on.

use std::borrow::Borrow;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TokenKind {
    Ident,
    /// Integer or floating-point literal, suffixes included (`1.0f`, `0x1Fu`, `1e-3`).
    Number,
    /// An operator or punctuation mark, possibly several characters (`<<=`, `##`).
    Punct,
    /// Spaces, tabs and line continuations; never a line break.
    Whitespace,
    Newline,
    LineComment,
    BlockComment,
    /// A character that has no place in GLSL outside comments.
    Unknown,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Token<'a> {
    pub kind: TokenKind,
    pub text: &'a str,
    /// Byte offset of the token in the tokenized text.
    pub offset: usize,
    /// 1-based line the token starts on.
    pub line: u32,
}

impl Token<'_> {
    /// Whitespace, line breaks and comments: tokens that only separate others.
    pub fn is_trivia(&self) -> bool {
        matches!(
            self.kind,
            TokenKind::Whitespace | TokenKind::Newline | TokenKind::LineComment | TokenKind::BlockComment
        )
    }

    pub fn is_punct(&self, p: &str) -> bool {
        self.kind == TokenKind::Punct && self.text == p
    }

    /// Whether a statement starts after this token: it is `{`, `}` or `;`.
    pub fn ends_statement(&self) -> bool {
        self.kind == TokenKind::Punct && matches!(self.text, "{" | "}" | ";")
    }

    pub fn is_ident(&self, name: &str) -> bool {
        self.kind == TokenKind::Ident && self.text == name
    }

    /// Line breaks inside the token (block comments and continuations span lines).
    pub fn newlines(&self) -> u32 {
        self.text.bytes().filter(|&b| b == b'\n').count() as u32
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TokenizeError {
    pub line: u32,
    pub message: String,
}

impl fmt::Display for TokenizeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for TokenizeError {}

/// Single characters GLSL uses as operators or punctuation (`"` for `#include` paths).
const GLSL_PUNCTUATION: &[u8] = b"+-*/%<>=!&|^~?:;,.()[]{}#\"";

/// The length of the punctuator `rest` starts with (its first byte is in [`GLSL_PUNCTUATION`]):
/// the longest of `<<=`, `>>=`, the two-character operators (`++`, `<=`, `&&`, `^^`, `+=`, ...),
/// `##`, `::`, `->` and `..`, else 1.
pub(crate) fn punctuator_len(rest: &[u8]) -> usize {
    match rest {
        [b'<', b'<', b'=', ..] | [b'>', b'>', b'=', ..] => 3,
        [b'+', b'+' | b'=', ..]
        | [b'-', b'-' | b'=' | b'>', ..]
        | [b'<', b'<' | b'=', ..]
        | [b'>', b'>' | b'=', ..]
        | [b'=' | b'!' | b'*' | b'/' | b'%', b'=', ..]
        | [b'&', b'&' | b'=', ..]
        | [b'|', b'|' | b'=', ..]
        | [b'^', b'^' | b'=', ..]
        | [b'#', b'#', ..]
        | [b':', b':', ..]
        | [b'.', b'.', ..] => 2,
        _ => 1,
    }
}

/// Splits `src` into tokens. Fails only on an unterminated block comment; a stray character
/// becomes an [`TokenKind::Unknown`] token so the caller can report it where it matters.
pub fn tokenize(src: &str) -> Result<Vec<Token<'_>>, TokenizeError> {
    let bytes = src.as_bytes();
    let mut tokens = Vec::with_capacity(src.len() / 3);
    let mut pos = 0;
    let mut line = 1u32;
    while pos < bytes.len() {
        let start = pos;
        let c = bytes[pos];
        let kind = match c {
            b'\n' => {
                pos += 1;
                TokenKind::Newline
            }
            b'\r' if bytes.get(pos + 1) == Some(&b'\n') => {
                pos += 2;
                TokenKind::Newline
            }
            b' ' | b'\t' | b'\r' | b'\x0b' | b'\x0c' | b'\\' => {
                if c == b'\\' && !is_continuation(bytes, pos) {
                    pos += 1;
                    TokenKind::Unknown
                } else {
                    while pos < bytes.len() {
                        match bytes[pos] {
                            b' ' | b'\t' | b'\x0b' | b'\x0c' => pos += 1,
                            b'\r' if bytes.get(pos + 1) != Some(&b'\n') => pos += 1,
                            b'\\' if is_continuation(bytes, pos) => {
                                pos += 1;
                                if bytes[pos] == b'\r' {
                                    pos += 1;
                                }
                                pos += 1;
                            }
                            _ => break,
                        }
                    }
                    TokenKind::Whitespace
                }
            }
            b'/' if bytes.get(pos + 1) == Some(&b'/') => {
                while pos < bytes.len() && bytes[pos] != b'\n' {
                    // A continuation extends a line comment onto the next line, as in C.
                    if bytes[pos] == b'\\' && is_continuation(bytes, pos) {
                        pos += 1;
                    }
                    pos += 1;
                }
                if src[start..pos].ends_with('\r') {
                    pos -= 1;
                }
                TokenKind::LineComment
            }
            b'/' if bytes.get(pos + 1) == Some(&b'*') => match src[pos + 2..].find("*/") {
                Some(end) => {
                    pos += 2 + end + 2;
                    TokenKind::BlockComment
                }
                None => {
                    return Err(TokenizeError { line, message: "unterminated block comment".into() });
                }
            },
            b'0'..=b'9' => {
                pos = scan_number(bytes, pos);
                TokenKind::Number
            }
            b'.' if bytes.get(pos + 1).is_some_and(u8::is_ascii_digit) => {
                pos = scan_number(bytes, pos);
                TokenKind::Number
            }
            b'a'..=b'z' | b'A'..=b'Z' | b'_' => {
                while pos < bytes.len() && (bytes[pos].is_ascii_alphanumeric() || bytes[pos] == b'_') {
                    pos += 1;
                }
                TokenKind::Ident
            }
            _ if GLSL_PUNCTUATION.contains(&c) => {
                pos += punctuator_len(&bytes[pos..]);
                TokenKind::Punct
            }
            _ => {
                // One whole UTF-8 character, so the token text stays valid UTF-8.
                pos += src[pos..].chars().next().map_or(1, char::len_utf8);
                TokenKind::Unknown
            }
        };
        let token = Token { kind, text: &src[start..pos], offset: start, line };
        // Only these kinds can hold a line break (comments and whitespace through continuations).
        line += match kind {
            TokenKind::Newline => 1,
            TokenKind::Whitespace | TokenKind::LineComment | TokenKind::BlockComment => token.newlines(),
            _ => 0,
        };
        tokens.push(token);
    }
    Ok(tokens)
}

fn is_continuation(bytes: &[u8], pos: usize) -> bool {
    match bytes.get(pos + 1) {
        Some(b'\n') => true,
        Some(b'\r') => bytes.get(pos + 2) == Some(&b'\n'),
        _ => false,
    }
}

fn scan_number(bytes: &[u8], mut pos: usize) -> usize {
    let hex = bytes[pos] == b'0' && matches!(bytes.get(pos + 1), Some(b'x' | b'X'));
    while pos < bytes.len() {
        let c = bytes[pos];
        let exponent_sign = !hex
            && matches!(c, b'+' | b'-')
            && matches!(bytes[pos - 1], b'e' | b'E')
            && bytes.get(pos + 1).is_some_and(u8::is_ascii_digit);
        if c.is_ascii_alphanumeric() || c == b'.' || c == b'_' || exponent_sign {
            pos += 1;
        } else {
            break;
        }
    }
    pos
}

/// An `#extension NAME : BEHAVIOUR` directive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ExtensionDirective<'a> {
    /// 1-based line of the `#`.
    pub line: u32,
    pub name: &'a str,
    /// `require`, `enable`, `warn` or `disable`.
    pub behaviour: &'a str,
}

impl ExtensionDirective<'_> {
    /// Whether it turns the extension on (every behaviour but `disable`).
    pub fn enables(&self) -> bool {
        self.behaviour != "disable"
    }
}

/// The `#extension` directives among `tokens`, in order: the one reader of them, for the
/// lowering, the rewrites for OpenGL and validation alike.
pub fn extension_directives<'a, T: Borrow<Token<'a>>>(tokens: &[T]) -> Vec<ExtensionDirective<'a>> {
    let sig: Vec<&Token<'a>> = tokens.iter().map(Borrow::borrow).filter(|t| !t.is_trivia()).collect();
    sig.windows(5)
        .filter(|w| w[0].is_punct("#") && w[1].is_ident("extension") && w[2].kind == TokenKind::Ident && w[3].is_punct(":") && w[4].kind == TokenKind::Ident)
        .map(|w| ExtensionDirective { line: w[0].line, name: w[2].text, behaviour: w[4].text })
        .collect()
}

/// Indices of the tokens that are not trivia, in order.
pub fn significant(tokens: &[Token<'_>]) -> Vec<usize> {
    (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect()
}

/// The brace depth at each token of `tokens`, counted from the start (the `{` and `}`
/// themselves count as inside). Stray `}` make it negative, so that what follows them is not
/// taken for top level.
pub fn brace_depths<'a, T: Borrow<Token<'a>>>(tokens: &[T]) -> Vec<i32> {
    let mut depth = 0;
    tokens
        .iter()
        .map(|t| {
            let t = t.borrow();
            if t.is_punct("{") {
                depth += 1;
            } else if t.is_punct("}") {
                depth -= 1;
                return depth + 1;
            }
            depth
        })
        .collect()
}

/// A function definition at top level; indices into the tokens given to
/// [`function_definitions`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FunctionDefinition {
    /// The function's name.
    pub name: usize,
    /// The `{` that opens the body.
    pub open: usize,
    /// The `}` that closes the body, or the number of tokens if nothing closes it.
    pub close: usize,
}

/// The precision qualifiers of `tokens` (`lowp`, `mediump`, `highp`) and default precision
/// statements (`precision mediump float;`), each as the first and last index of its tokens.
pub fn precision_qualifiers(tokens: &[Token<'_>]) -> Vec<(usize, usize)> {
    let mut found = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let t = &tokens[i];
        if t.is_ident("precision") {
            let end = (i..tokens.len()).find(|&j| tokens[j].is_punct(";")).unwrap_or(i);
            found.push((i, end));
            i = end + 1;
            continue;
        }
        if t.kind == TokenKind::Ident && matches!(t.text, "lowp" | "mediump" | "highp") {
            found.push((i, i));
        }
        i += 1;
    }
    found
}

/// `text` with the byte ranges in `ranges` blanked out: every character in them but a line
/// break becomes a space, so lines and the columns after them stay where they were.
pub fn blanked(text: &str, ranges: &[std::ops::Range<usize>]) -> String {
    text.char_indices().map(|(at, c)| if c != '\n' && ranges.iter().any(|r| r.contains(&at)) { ' ' } else { c }).collect()
}

/// `text` with each byte range of `edits` (none overlapping) replaced by its text.
pub fn edited(text: &str, mut edits: Vec<(std::ops::Range<usize>, String)>) -> String {
    edits.sort_by_key(|(range, _)| range.start);
    let mut out = String::with_capacity(text.len());
    let mut from = 0;
    for (range, with) in edits {
        out.push_str(&text[from..range.start]);
        out.push_str(&with);
        from = range.end;
    }
    out.push_str(&text[from..]);
    out
}

/// Where a fragment stage reads `gl_FragDepth` and never writes it: the positions in `sig`
/// (significant tokens) of its uses; empty where it writes it or names it nowhere. Unwritten,
/// its value is undefined and the fragment keeps the depth it was rasterised at, which
/// `gl_FragCoord.z` holds.
pub fn depth_read_never_written(sig: &[&Token]) -> Vec<usize> {
    // A redeclaration (`out float gl_FragDepth;`) is no use.
    let uses: Vec<usize> = (0..sig.len()).filter(|&k| sig[k].is_ident("gl_FragDepth") && (k == 0 || sig[k - 1].kind != TokenKind::Ident)).collect();
    let written = uses.iter().any(|&k| {
        let assigned = sig.get(k + 1).is_some_and(|n| n.kind == TokenKind::Punct && ["=", "+=", "-=", "*=", "/=", "++", "--"].contains(&n.text));
        let stepped = k > 0 && (sig[k - 1].is_punct("++") || sig[k - 1].is_punct("--"));
        let handed_out = argument_qualifiers(sig, k).is_some_and(|q| q.iter().any(|q| *q == "out" || *q == "inout"));
        assigned || stepped || handed_out
    });
    if written { Vec::new() } else { uses }
}

/// For the argument that starts at `sig[at]` (significant tokens) of a call: the qualifier of the
/// parameter it goes to (`in`, `out`, `inout`, or `""` for none) in each definition of the called
/// function among `sig`. `None` where `sig[at]` is in no call's parentheses; empty where the
/// function is not defined there (a built-in).
pub fn argument_qualifiers<'a>(sig: &[&Token<'a>], at: usize) -> Option<Vec<&'a str>> {
    // The call's `(`: the nearest unmatched one before the argument, counting commas on the way.
    let (mut depth, mut index, mut open) = (0usize, 0usize, None);
    for k in (0..at).rev() {
        match sig[k].text {
            ")" | "]" => depth += 1,
            "(" | "[" if depth > 0 => depth -= 1,
            "(" => {
                open = Some(k);
                break;
            }
            "," if depth == 0 => index += 1,
            _ => {}
        }
    }
    let callee = open.and_then(|o| o.checked_sub(1)).map(|c| sig[c]).filter(|c| c.kind == TokenKind::Ident)?;
    let qualifiers = function_definitions(sig).into_iter().filter(|d| sig[d.name].text == callee.text).map(|definition| {
        // The parameter list from the `(` after the name to its `)`, split at top-level commas.
        let (mut parameter, mut depth) = (0usize, 0usize);
        for t in &sig[definition.name + 2..definition.open] {
            match t.text {
                "(" | "[" => depth += 1,
                ")" | "]" if depth > 0 => depth -= 1,
                ")" => break,
                "," if depth == 0 => parameter += 1,
                q @ ("in" | "out" | "inout") if parameter == index => return q,
                _ => {}
            }
        }
        ""
    });
    Some(qualifiers.collect())
}

/// The function definitions at brace depth 0, in order: a name after the return type (an
/// identifier or an array's `]`), a parenthesised parameter list and a `{`. Prototypes, structs and interface
/// blocks are not definitions. Trivia may be among the tokens or left out.
pub fn function_definitions<'a, T: Borrow<Token<'a>>>(tokens: &[T]) -> Vec<FunctionDefinition> {
    let sig: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].borrow().is_trivia()).collect();
    let token = |k: usize| sig.get(k).map(|&i| tokens[i].borrow());
    let mut found = Vec::new();
    let mut k = 0;
    while k < sig.len() {
        let t = tokens[sig[k]].borrow();
        if t.is_punct("{") {
            // A block that is not a function body (a struct, an interface block): skip it whole.
            k = matching_close(&sig, tokens, k).map_or(sig.len(), |c| c + 1);
            continue;
        }
        // A function-like macro whose body is a block (`#define print(s) { … }`) is no definition.
        let macro_name = k > 1 && token(k - 1).is_some_and(|p| p.is_ident("define")) && token(k - 2).is_some_and(|p| p.is_punct("#"));
        let header = t.kind == TokenKind::Ident
            && k > 0
            && !macro_name
            && token(k - 1).is_some_and(|p| p.kind == TokenKind::Ident || p.is_punct("]"))
            && token(k + 1).is_some_and(|n| n.is_punct("("));
        if header
            && let Some(params_end) = matching_close(&sig, tokens, k + 1)
            && token(params_end + 1).is_some_and(|n| n.is_punct("{"))
        {
            let open = params_end + 1;
            let close = matching_close(&sig, tokens, open);
            found.push(FunctionDefinition { name: sig[k], open: sig[open], close: close.map_or(tokens.len(), |c| sig[c]) });
            k = close.map_or(sig.len(), |c| c + 1);
            continue;
        }
        k += 1;
    }
    found
}

/// The position in `sig` of the bracket that closes the one at `sig[open]` (`(` or `{`).
pub fn matching_close<'a, T: Borrow<Token<'a>>>(sig: &[usize], tokens: &[T], open: usize) -> Option<usize> {
    let (opener, closer) = if tokens[sig[open]].borrow().is_punct("(") { ("(", ")") } else { ("{", "}") };
    let mut depth = 0usize;
    for (k, &i) in sig.iter().enumerate().skip(open) {
        let t = tokens[i].borrow();
        if t.is_punct(opener) {
            depth += 1;
        } else if t.is_punct(closer) {
            // A closer before any opener (`sig[open]` was neither bracket) closes nothing.
            depth = depth.checked_sub(1)?;
            if depth == 0 {
                return Some(k);
            }
        }
    }
    None
}

/// The number of arguments of the call whose `(` is `sig[open]`: commas outside inner brackets,
/// plus one unless the list is empty; 0 where nothing closes it.
pub fn argument_count<'a, T: Borrow<Token<'a>>>(sig: &[usize], tokens: &[T], open: usize) -> usize {
    let Some(close) = matching_close(sig, tokens, open) else { return 0 };
    let (mut depth, mut commas) = (0usize, 0usize);
    for &i in &sig[open + 1..close] {
        match tokens[i].borrow().text {
            "(" | "[" => depth += 1,
            ")" | "]" => depth = depth.saturating_sub(1),
            "," if depth == 0 => commas += 1,
            _ => {}
        }
    }
    if close == open + 1 { 0 } else { commas + 1 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<(TokenKind, &str)> {
        tokenize(src).unwrap().into_iter().map(|t| (t.kind, t.text)).collect()
    }

    #[test]
    fn extension_directives_with_their_lines_and_behaviours() {
        let src = "#version 130\n#extension GL_EXT_gpu_shader4 : enable\n  #  extension\tGL_ARB_gpu_shader5:disable\nint extension = 1;\n#extension all\n";
        let tokens = tokenize(src).unwrap();
        let found = extension_directives(&tokens);
        assert_eq!(found, vec![
            ExtensionDirective { line: 2, name: "GL_EXT_gpu_shader4", behaviour: "enable" },
            ExtensionDirective { line: 3, name: "GL_ARB_gpu_shader5", behaviour: "disable" },
        ]);
        assert!(found[0].enables() && !found[1].enables());
    }

    #[test]
    fn round_trips_exactly() {
        let src = "#version 120\r\nuniform sampler2D tex; // atlas\n/* a\n b */ float x = .5e-3f + 0x1Fu;\\\n y <<= 2;\n";
        let joined: String = tokenize(src).unwrap().iter().map(|t| t.text).collect();
        assert_eq!(joined, src);
    }

    #[test]
    fn numbers_keep_suffixes_and_exponents() {
        let nums: Vec<_> = kinds("1.0f .5 1e-3 2E+4 0x1F 10u 3.lf a-1")
            .into_iter()
            .filter(|(k, _)| *k == TokenKind::Number)
            .map(|(_, t)| t)
            .collect();
        assert_eq!(nums, ["1.0f", ".5", "1e-3", "2E+4", "0x1F", "10u", "3.lf", "1"]);
    }

    #[test]
    fn longest_punctuator_wins() {
        let puncts: Vec<_> =
            kinds("a<<=b>>c++&&d^^e##f").into_iter().filter(|(k, _)| *k == TokenKind::Punct).map(|(_, t)| t).collect();
        assert_eq!(puncts, ["<<=", ">>", "++", "&&", "^^", "##"]);
    }

    #[test]
    fn lines_count_through_comments_and_continuations() {
        let toks = tokenize("a /* x\ny */ b \\\n c\n// d\ne").unwrap();
        let line_of = |name: &str| toks.iter().find(|t| t.text == name).unwrap().line;
        assert_eq!((line_of("a"), line_of("b"), line_of("c"), line_of("e")), (1, 2, 3, 5));
    }

    #[test]
    fn unterminated_comment_names_its_line() {
        let err = tokenize("a\nb /* open\n").unwrap_err();
        assert_eq!(err.line, 2);
    }

    #[test]
    fn stray_characters_are_unknown_tokens() {
        let toks = kinds("a @ é \\ b");
        assert!(toks.contains(&(TokenKind::Unknown, "@")));
        assert!(toks.contains(&(TokenKind::Unknown, "é")));
        assert!(toks.contains(&(TokenKind::Unknown, "\\")));
    }

    #[test]
    fn function_definitions_are_the_top_level_bodies() {
        let src = "struct S { float f(); };\nvec3 g(float x);\nuniform B { int h; } b;\n#define print(s) { y(s); }\nvoid main() { if (x) { y(); } }\nfloat[2] k(int a) { return float[2](0.0, 1.0); }\n";
        let tokens = tokenize(src).unwrap();
        let defs = function_definitions(&tokens);
        let names: Vec<&str> = defs.iter().map(|d| tokens[d.name].text).collect();
        assert_eq!(names, ["main", "k"]);
        let body: String = tokens[defs[0].open..=defs[0].close].iter().map(|t| t.text).collect();
        assert_eq!(body, "{ if (x) { y(); } }");
        // Without trivia, indices are into the tokens given.
        let sig: Vec<&Token<'_>> = tokens.iter().filter(|t| !t.is_trivia()).collect();
        let defs = function_definitions(&sig);
        assert_eq!((sig[defs[0].name].text, sig[defs[0].open].text, sig[defs[0].close].text), ("main", "{", "}"));
        let unclosed = tokenize("void main() { x;").unwrap();
        assert_eq!(function_definitions(&unclosed)[0].close, unclosed.len());
    }

    #[test]
    fn the_fragment_depth_read_and_never_written_is_found() {
        let uses = |src: &str| {
            let tokens = tokenize(src).unwrap();
            let sig: Vec<&Token<'_>> = tokens.iter().filter(|t| !t.is_trivia()).collect();
            depth_read_never_written(&sig).len()
        };
        assert_eq!(uses("out float gl_FragDepth;\nvoid main() { float d = gl_FragDepth - 0.5; d += max(gl_FragDepth, 0.0); }"), 2);
        assert_eq!(uses("void main() { float d = gl_FragDepth; gl_FragDepth = d; }"), 0);
        assert_eq!(uses("void set(out float d) { d = 0.5; }\nvoid main() { float e = gl_FragDepth; set(gl_FragDepth); }"), 0);
        assert_eq!(uses("void main() { gl_FragColor = vec4(1.0); }"), 0);
    }

    #[test]
    fn a_closer_before_any_opener_closes_nothing() {
        let tokens = tokenize("a; } )").unwrap();
        let sig: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect();
        assert_eq!(matching_close(&sig, &tokens, 1), None);
    }

    #[test]
    fn brace_depths_count_the_braces_as_inside() {
        let tokens: Vec<Token<'_>> = tokenize("a { b { c } } } d").unwrap().into_iter().filter(|t| !t.is_trivia()).collect();
        assert_eq!(brace_depths(&tokens), [0, 1, 1, 2, 2, 2, 1, 0, -1]);
    }
}
