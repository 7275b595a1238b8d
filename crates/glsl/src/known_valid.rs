//! Functions naga has accepted, remembered by their text and the text of every declaration they
//! use, so that a later stage holding the same function in the same surroundings gives naga its
//! prototype in its place. The covering sets of a pack repeat most of a program's functions
//! under every set: naga then reads each of them once, and the functions a set changes every
//! time.
//!
//! What a function's verdict depends on, and so its key: the stage (vertex, fragment,
//! compute), the `#version` and `#extension` lines, the function's own text, and each top-level
//! declaration that declares a name the function uses (globals, structs, blocks, the signatures
//! of the functions it calls, every overload), with the declarations those use in turn, each
//! with whether it comes before the function or after. A function stays out of it where leaving
//! it out would change the stage's interface (`main`, a function that writes `gl_Position`) or
//! where a stub body cannot be written (a return type that is not one word).

use std::collections::BTreeSet;
use std::sync::Mutex;

use rustc_hash::{FxHashMap, FxHashSet};
use sha2::{Digest, Sha256};

use crate::token::{Token, TokenKind, brace_depths, function_definitions, tokenize};

type Key = [u8; 32];

/// The keys of the functions naga accepted during one validation run; shared by its threads.
#[derive(Debug, Default)]
pub struct KnownValid {
    keys: Mutex<FxHashSet<Key>>,
    /// Functions whose prototype naga refused, as it declares a built-in of the same signature.
    no_prototype: Mutex<FxHashSet<Key>>,
    /// Digests of the texts (known functions left as prototypes) naga accepted whole.
    texts: Mutex<FxHashSet<Key>>,
}

/// One function definition of a lowered stage.
#[derive(Clone, Debug)]
pub(crate) struct Function {
    /// Byte offsets of its `{` and `}`.
    open: usize,
    close: usize,
    /// Lines of its first token and of its `}`.
    pub first_line: u32,
    pub last_line: u32,
    /// `None` for a function never stubbed.
    key: Option<Key>,
    /// The one-word return type (`void`, `vec3`, a struct's name).
    return_type: String,
    /// The stage declares a prototype of its name, or naga a built-in of its signature, so that
    /// a prototype in its place would be refused.
    prototyped: bool,
}

impl KnownValid {
    pub fn new() -> KnownValid {
        KnownValid::default()
    }

    fn contains(&self, key: &Key) -> bool {
        self.keys.lock().unwrap_or_else(|e| e.into_inner()).contains(key)
    }

    /// `text` with every function known valid left as its prototype, or, where the stage has a
    /// prototype of its name already, with a body that returns a value of its type. Line breaks
    /// stay, so lines and the other functions' columns do too. naga reads a prototype without a
    /// definition as a function without a body, and parses a body in a context holding every
    /// global: the prototype is what saves its time.
    pub(crate) fn stubbed(&self, text: &str, functions: &[Function]) -> String {
        let no_prototype = self.no_prototype.lock().unwrap_or_else(|e| e.into_inner());
        let mut out = String::with_capacity(text.len());
        let mut from = 0;
        for f in functions.iter().filter(|f| f.key.as_ref().is_some_and(|k| self.contains(k))) {
            if f.prototyped || f.key.is_some_and(|k| no_prototype.contains(&k)) {
                out.push_str(&text[from..=f.open]);
                if f.return_type != "void" {
                    out.push_str(&format!(" {} ", crate::lower::undefined_return(&f.return_type)));
                }
                out.extend(text[f.open + 1..f.close].chars().filter(|&c| c == '\n'));
                from = f.close;
            } else {
                out.push_str(&text[from..f.open]);
                out.push(';');
                out.extend(text[f.open..=f.close].chars().filter(|&c| c == '\n'));
                from = f.close + 1;
            }
        }
        out.push_str(&text[from..]);
        out
    }

    /// The digest of a stage's text as naga reads it, for [`KnownValid::accepted`].
    pub(crate) fn text_digest(&self, stage: &str, text: &str) -> Key {
        Sha256::new().chain_update(stage.as_bytes()).chain_update([0]).chain_update(text.as_bytes()).finalize().into()
    }

    /// Whether naga accepted a stage of this digest whole, with no repair needing a report.
    pub(crate) fn accepted(&self, digest: &Key) -> bool {
        self.texts.lock().unwrap_or_else(|e| e.into_inner()).contains(digest)
    }

    pub(crate) fn remember_text(&self, digest: Key) {
        self.texts.lock().unwrap_or_else(|e| e.into_inner()).insert(digest);
    }

    /// Gives each function that holds one of `lines` (where naga refused a prototype) a stub
    /// body from now on, in this stage and the next; whether any changed.
    pub(crate) fn stub_with_bodies(&self, functions: &mut [Function], lines: &[u32]) -> bool {
        let mut no_prototype = self.no_prototype.lock().unwrap_or_else(|e| e.into_inner());
        let mut changed = false;
        for f in functions.iter_mut().filter(|f| !f.prototyped && lines.iter().any(|l| (f.first_line..=f.last_line).contains(l))) {
            f.prototyped = true;
            no_prototype.extend(f.key);
            changed = true;
        }
        changed
    }

    /// Remembers the functions naga accepted: all of `functions` but those holding a line in
    /// `rejected` (the functions whose errors were reported and whose bodies were blanked).
    pub(crate) fn remember(&self, functions: &[Function], rejected: &[u32]) {
        let mut keys = self.keys.lock().unwrap_or_else(|e| e.into_inner());
        for f in functions {
            if let Some(key) = f.key
                && !rejected.iter().any(|line| (f.first_line..=f.last_line).contains(line))
            {
                keys.insert(key);
            }
        }
    }
}

/// A top-level declaration (a function's signature, or any other statement): its digest, where
/// it starts, the names it declares and the names it mentions.
struct Declaration<'a> {
    digest: Key,
    start: usize,
    declares: Vec<&'a str>,
    mentions: Vec<&'a str>,
    /// The name of a prototype (`float f(float x);`).
    prototype: Option<&'a str>,
}

/// The function definitions of a lowered stage, each with its key. `stage` tells the stages
/// apart (naga's verdict on a function depends on it). A text the tokenizer refuses has none.
pub(crate) fn functions_of(text: &str, stage: &str) -> Vec<Function> {
    let Ok(tokens) = tokenize(text) else { return Vec::new() };
    let depths = brace_depths(&tokens);
    let definitions = function_definitions(&tokens);
    let significant: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect();
    let directive_lines: FxHashSet<u32> = crate::compat::directive_lines(&tokens, &significant).iter().map(|&(hash, ..)| tokens[hash].line).collect();
    // First token of each definition: back from its name over the words of its return type.
    let starts: Vec<usize> = definitions
        .iter()
        .map(|d| {
            let mut start = d.name;
            for k in (0..d.name).rev() {
                let t = &tokens[k];
                if t.is_trivia() {
                    continue;
                }
                if directive_lines.contains(&t.line) || !(t.kind == TokenKind::Ident || t.kind == TokenKind::Number || t.is_punct("[") || t.is_punct("]")) {
                    break;
                }
                start = k;
            }
            start
        })
        .collect();
    let mut preamble = Sha256::new();
    let mut declarations: Vec<Declaration> = Vec::new();
    let mut in_function = vec![false; tokens.len()];
    for (d, &start) in definitions.iter().zip(&starts) {
        in_function[start..=d.close.min(tokens.len() - 1)].iter_mut().for_each(|f| *f = true);
        // A definition also declares its signature.
        let open = tokens[d.open].offset;
        declarations.push(Declaration {
            digest: Sha256::digest(&text.as_bytes()[tokens[start].offset..open]).into(),
            start: tokens[start].offset,
            declares: vec![tokens[d.name].text],
            mentions: tokens[start..d.open].iter().filter(|t| t.kind == TokenKind::Ident).map(|t| t.text).collect(),
            prototype: None,
        });
    }
    let mut statement: Vec<usize> = Vec::new();
    for (i, t) in tokens.iter().enumerate() {
        if t.is_trivia() || in_function[i] {
            continue;
        }
        if directive_lines.contains(&t.line) {
            preamble.update(t.text.as_bytes());
            preamble.update(b" ");
            continue;
        }
        statement.push(i);
        if depths[i] == 0 && t.is_punct(";") {
            declarations.push(declaration(text, &tokens, &statement));
            statement.clear();
        }
    }
    if !statement.is_empty() {
        declarations.push(declaration(text, &tokens, &statement));
    }
    let preamble: Key = preamble.finalize().into();
    let prototyped: FxHashSet<&str> = declarations.iter().filter_map(|d| d.prototype).collect();
    let mut declaring: FxHashMap<&str, Vec<usize>> = FxHashMap::default();
    for (index, declaration) in declarations.iter().enumerate() {
        for name in &declaration.declares {
            declaring.entry(*name).or_default().push(index);
        }
    }
    definitions
        .iter()
        .zip(&starts)
        .map(|(d, &start)| {
            let close = d.close.min(tokens.len() - 1);
            let own = &tokens[start..=close];
            let return_words: Vec<&Token> = tokens[start..d.name].iter().filter(|t| !t.is_trivia()).collect();
            let return_type = match return_words.as_slice() {
                [word] if word.kind == TokenKind::Ident => word.text.to_string(),
                _ => String::new(),
            };
            let stubbable = !return_type.is_empty()
                && tokens[d.name].text != "main"
                && d.close < tokens.len()
                && !own.iter().any(|t| t.is_ident("gl_Position"));
            let key = stubbable.then(|| {
                let begin = tokens[start].offset;
                let mut used: BTreeSet<(Key, bool)> = BTreeSet::new();
                let mut seen: FxHashSet<usize> = FxHashSet::default();
                let mut names: Vec<&str> = own.iter().filter(|t| t.kind == TokenKind::Ident).map(|t| t.text).collect();
                let mut asked: FxHashSet<&str> = FxHashSet::default();
                while let Some(name) = names.pop() {
                    if !asked.insert(name) {
                        continue;
                    }
                    for &index in declaring.get(name).into_iter().flatten() {
                        if seen.insert(index) {
                            let declaration = &declarations[index];
                            used.insert((declaration.digest, declaration.start < begin));
                            names.extend(&declaration.mentions);
                        }
                    }
                }
                let mut hasher = Sha256::new();
                hasher.update(stage.as_bytes());
                hasher.update(preamble);
                hasher.update(&text.as_bytes()[begin..tokens[close].offset + 1]);
                for (digest, before) in &used {
                    hasher.update(digest);
                    hasher.update([u8::from(*before)]);
                }
                hasher.finalize().into()
            });
            Function {
                open: tokens[d.open].offset,
                close: tokens[close].offset,
                first_line: tokens[start].line,
                last_line: tokens[close].line,
                key,
                return_type,
                prototyped: prototyped.contains(tokens[d.name].text),
            }
        })
        .collect()
}

/// A top-level statement as a declaration. Outside brackets, it declares each word followed by
/// `;`, `,`, `=`, `[` or `{` (a variable, a constant, a block or struct), and the word of a
/// prototype (`float f(`, after a type); it mentions every word in it (its type, the constants
/// of its sizes and initializer).
fn declaration<'a>(text: &str, tokens: &[Token<'a>], statement: &[usize]) -> Declaration<'a> {
    let first = &tokens[statement[0]];
    let last = &tokens[*statement.last().expect("a statement has a token")];
    let mut declares = Vec::new();
    let mut prototype = None;
    let mut depth = 0;
    for (k, &i) in statement.iter().enumerate() {
        let t = &tokens[i];
        if t.is_punct("(") || t.is_punct("[") {
            depth += 1;
        } else if t.is_punct(")") || t.is_punct("]") {
            depth -= 1;
        }
        let Some(next) = statement.get(k + 1).map(|&n| &tokens[n]) else { continue };
        if depth != 0 || t.kind != TokenKind::Ident {
            continue;
        }
        let after_type = k > 0 && (tokens[statement[k - 1]].kind == TokenKind::Ident || tokens[statement[k - 1]].is_punct("]"));
        if [";", ",", "=", "[", "{"].iter().any(|p| next.is_punct(p)) {
            declares.push(t.text);
        } else if next.is_punct("(") && after_type && t.text != "layout" {
            declares.push(t.text);
            prototype = Some(t.text);
        }
    }
    let mentions = statement.iter().filter(|&&i| tokens[i].kind == TokenKind::Ident).map(|&i| tokens[i].text).collect();
    Declaration {
        digest: Sha256::digest(&text.as_bytes()[first.offset..last.offset + last.text.len()]).into(),
        start: first.offset,
        declares,
        mentions,
        prototype,
    }
}


#[cfg(test)]
mod tests {
    use std::collections::HashMap;
    use std::sync::Arc;

    use super::*;
    use crate::lower::Stage;
    use crate::naga_check::{Frontend, lower_program, validate_stage, validate_stage_reusing};
    use crate::preprocess::{PreprocessOptions, preprocess};

    fn key_of(text: &str, stage: &str, name: &str) -> Option<Key> {
        let functions = functions_of(text, stage);
        let tokens = tokenize(text).unwrap();
        let line = tokens.iter().find(|t| t.is_ident(name)).map(|t| t.line).unwrap();
        functions.into_iter().find(|f| f.first_line <= line && line <= f.last_line).and_then(|f| f.key)
    }

    #[test]
    fn a_function_key_changes_with_what_it_uses_and_only_with_that() {
        let base = "#version 450\nstruct Light { vec3 colour; };\nuniform Light sun;\nuniform float unrelated;\nfloat f(float x) {\n  return x * sun.colour.r;\n}\n";
        let key = key_of(base, "Fragment", "f").expect("keyed");
        let other_unrelated = base.replace("uniform float unrelated;", "uniform vec4 unrelated;");
        assert_eq!(key_of(&other_unrelated, "Fragment", "f"), Some(key), "a global it does not use");
        let other_struct = base.replace("vec3 colour;", "float colour;");
        assert_ne!(key_of(&other_struct, "Fragment", "f"), Some(key), "the struct of a global it uses");
        let after = "#version 450\nstruct Light { vec3 colour; };\nuniform float unrelated;\nfloat f(float x) {\n  return x * sun.colour.r;\n}\nuniform Light sun;\n";
        assert_ne!(key_of(after, "Fragment", "f"), Some(key), "declared after it");
        assert_ne!(key_of(base, "Vertex", "f"), Some(key), "another stage");
        let extension = base.replace("#version 450\n", "#version 450\n#extension GL_ARB_gpu_shader5 : enable\n");
        assert_ne!(key_of(&extension, "Fragment", "f"), Some(key), "an extension line");
        let callee = "#version 450\nfloat g(float y) { return y; }\nfloat f(float x) { return g(x); }\n";
        let callee_changed = "#version 450\nfloat g(int y) { return float(y); }\nfloat f(float x) { return g(x); }\n";
        assert_ne!(key_of(callee, "Fragment", "f"), key_of(callee_changed, "Fragment", "f"), "the signature of a function it calls");
        let body_changed = "#version 450\nfloat g(float y) { return y * 2.0; }\nfloat f(float x) { return g(x); }\n";
        assert_eq!(key_of(callee, "Fragment", "f"), key_of(body_changed, "Fragment", "f"), "not the body of a function it calls");
        assert_eq!(key_of("#version 450\nvoid main() { }\n", "Fragment", "main"), None, "main is never left out");
    }

    #[test]
    fn a_function_known_valid_becomes_its_prototype_line_for_line() {
        let text = "#version 450\nfloat half_of(float x)\n{\n  return x * 0.5;\n}\nfloat twice(float x);\nfloat twice(float x) { return x * 2.0; }\nvoid main() { }\n";
        let functions = functions_of(text, "Fragment");
        let known = KnownValid::new();
        assert_eq!(known.stubbed(text, &functions), text, "nothing is known yet");
        known.remember(&functions, &[]);
        let stubbed = known.stubbed(text, &functions);
        assert_eq!(stubbed.lines().count(), text.lines().count());
        assert!(stubbed.contains("float half_of(float x)\n;\n\n\n"), "{stubbed}");
        assert!(stubbed.contains(&format!("float twice(float x) {{ {} }}", crate::lower::undefined_return("float"))), "a second prototype would be refused: {stubbed}");
        assert!(stubbed.contains("void main() { }"), "{stubbed}");
        let rejected = KnownValid::new();
        rejected.remember(&functions, &[4]);
        assert!(rejected.stubbed(text, &functions).contains("return x * 0.5;"), "a function whose errors were reported is read again");
    }

    fn fragment(text: &str) -> crate::naga_check::LoweredStage {
        let files: HashMap<String, Arc<str>> = [("composite.fsh".to_string(), Arc::from(text))].into();
        let pre = preprocess(&files, "composite.fsh", &PreprocessOptions::default()).unwrap();
        lower_program(&[(Stage::Fragment, Arc::new(pre))]).unwrap().remove(0)
    }

    fn messages<T>(result: Result<T, Vec<crate::Diagnostic>>) -> Vec<String> {
        result.err().unwrap_or_default().iter().map(|d| d.to_string()).collect()
    }

    #[test]
    fn a_stage_checked_with_known_functions_gives_what_it_gives_alone() {
        let files: HashMap<String, Arc<str>> = HashMap::new();
        let known = KnownValid::new();
        // The lowering defines `dot` of two floats, which naga's built-in prototype of it refuses
        // as a prototype.
        let valid = "#version 330\nuniform float level;\nfloat shade(float x) { return x * level; }\n\
                     out vec4 colour;\nvoid main() { colour = vec4(shade(dot(0.5, 2.0))); }\n";
        for _ in 0..3 {
            assert_eq!(messages(validate_stage_reusing(&mut Frontend::default(), &fragment(valid), &files, &known)), Vec::<String>::new());
        }
        assert_eq!(known.no_prototype.lock().unwrap().len(), 1, "the lowering's `dot` has a stub body");
        // The text as written, and the text with its functions known (which the third run found).
        assert_eq!(known.texts.lock().unwrap().len(), 2);
        // `level` is now a vector: `shade` is read again, and its error found.
        let changed = valid.replace("uniform float level;", "uniform vec3 level;");
        let alone = messages(validate_stage(&mut Frontend::default(), &fragment(&changed), &files));
        assert!(!alone.is_empty());
        assert_eq!(messages(validate_stage_reusing(&mut Frontend::default(), &fragment(&changed), &files, &known)), alone);
        // An error elsewhere in the stage, with `shade` known valid.
        let broken_main = valid.replace("vec4(shade(", "vec4(shade(undeclared + ");
        let alone = messages(validate_stage(&mut Frontend::default(), &fragment(&broken_main), &files));
        assert!(!alone.is_empty());
        assert_eq!(messages(validate_stage_reusing(&mut Frontend::default(), &fragment(&broken_main), &files, &known)), alone);
    }
}
