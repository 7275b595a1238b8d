//! The reader of a pack's `.properties` files (shaders.properties, block.properties, …) as the
//! loaders read them, in two steps:
//!
//! 1. Conditional lines, as OptiFine's macro processor runs them before anything else reads
//!    the file: `#define`, `#undef`, `#ifdef`, `#ifndef`, `#if`, `#elif`, `#else`, `#endif`
//!    over the loader's standard macros and the configuration's `#define` options. `#if`
//!    conditions substitute macro values, read a name that is no macro as 0, and evaluate in
//!    OptiFine's expression language ([`crate::custom_uniforms::evaluate_condition`]); a
//!    condition that does not evaluate is false, as in OptiFine, and is reported. Lines of inactive branches are dropped; other
//!    lines starting with `#` are comments.
//! 2. Java's properties syntax on the lines that remain: `#` and `!` start a comment line, a
//!    line ending in an odd number of `\` continues on the next (whose leading blanks are
//!    dropped), the key ends at the first unescaped `=`, `:` or blank, escapes are resolved. A
//!    key given twice keeps its first place with the later value, as OptiFine's ordered
//!    properties map does.
//!
//! Iris runs a C preprocessor over the file instead (JCPP, IrisShaders/Iris
//! `PropertiesPreprocessor`): a `#define` or `#undef` in a branch not taken does nothing there,
//! where OptiFine records it (clorece/Allium's `#ifdef MC_OS_MAC` `#define COLORED_LIGHTING 0`
//! turns its colored lighting off everywhere under OptiFine, on macOS alone under Iris). It
//! also substitutes macros inside values; packs write conditionals that read the same both
//! ways, and that substitution is not imitated.

use std::collections::{BTreeMap, HashMap};

use crate::custom_uniforms::evaluate_condition;
use crate::loader::Loader;

/// The path of shaders.properties inside `shaders/`.
pub const PATH: &str = "shaders.properties";

/// Macro names and values the conditional lines see (`""` for a name defined without a value).
pub type Macros = BTreeMap<String, String>;

/// One key and value of a properties file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    pub key: String,
    pub value: String,
    /// 1-based line where the entry (its last occurrence) starts.
    pub line: u32,
}

/// A properties file after the loader's conditionals, entries in file order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Properties {
    entries: Vec<Entry>,
    /// Position of each key in `entries`.
    index: HashMap<String, usize>,
    /// Conditional lines that did not evaluate (taken as false), with their line.
    pub problems: Vec<(u32, String)>,
}

/// The most macro substitutions one `#if` gets before OptiFine gives up on it.
const MAX_SUBSTITUTIONS: usize = 100;

/// The directive names OptiFine's macro processor acts on; other `#` lines are comments.
const DIRECTIVES: [&str; 8] = ["define", "undef", "ifdef", "ifndef", "if", "else", "elif", "endif"];

impl Properties {
    /// Reads `text` as `loader` reads it, with `macros` defined for its conditionals.
    pub fn parse(text: &str, macros: &Macros, loader: Loader) -> Properties {
        let (active, problems) = active_lines(text, macros, loader);
        let mut entries: Vec<Entry> = Vec::new();
        let mut index: HashMap<String, usize> = HashMap::new();
        for (line, logical) in logical_lines(&active) {
            let (key, value) = split_key_value(&logical);
            match index.get(&key) {
                Some(&at) => entries[at] = Entry { key, value, line },
                None => {
                    index.insert(key.clone(), entries.len());
                    entries.push(Entry { key, value, line });
                }
            }
        }
        Properties { entries, index, problems }
    }

    /// Reads `text` with no macro defined: every `#ifdef` false, every `#ifndef` true.
    pub fn parse_plain(text: &str) -> Properties {
        Properties::parse(text, &Macros::new(), Loader::default())
    }

    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    pub fn get(&self, key: &str) -> Option<&Entry> {
        self.index.get(key).map(|&at| &self.entries[at])
    }

    /// The entries whose key starts with `prefix`, with the rest of the key.
    pub fn with_prefix<'a>(&'a self, prefix: &'a str) -> impl Iterator<Item = (&'a str, &'a Entry)> + 'a {
        self.entries.iter().filter_map(move |e| e.key.strip_prefix(prefix).map(|rest| (rest, e)))
    }
}

/// The lines of `text` the macro processor of `loader` keeps, with their 1-based numbers, and
/// the conditions it could not evaluate.
fn active_lines<'t>(text: &'t str, predefined: &Macros, loader: Loader) -> (Vec<(u32, &'t str)>, Vec<(u32, String)>) {
    let mut macros = predefined.clone();
    // Per open conditional: whether its current branch is taken, and whether any was.
    let mut open: Vec<(bool, bool)> = Vec::new();
    let mut kept = Vec::new();
    let mut problems = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line = index as u32 + 1;
        let active = open.iter().all(|(taken, _)| *taken);
        let Some((name, param)) = directive(raw) else {
            if active {
                kept.push((line, raw));
            }
            continue;
        };
        let param = param.split("//").next().unwrap_or("").trim();
        let mut words = param.split_whitespace();
        let word = words.next().unwrap_or("");
        let condition = |macros: &Macros, problems: &mut Vec<(u32, String)>| match evaluate_directive(param, macros) {
            Ok(value) => value,
            Err(e) => {
                problems.push((line, format!("#{name} {param}: {e} (taken as false)")));
                false
            }
        };
        match name {
            // OptiFine's processor records definitions in inactive branches too; Iris's does not.
            "define" | "undef" if !active && loader == Loader::Iris => {}
            "define" => {
                macros.insert(word.to_string(), param[word.len()..].trim().to_string());
            }
            "undef" => {
                macros.remove(word);
            }
            "ifdef" => {
                let taken = macros.contains_key(word);
                open.push((taken, taken));
            }
            "ifndef" => {
                let taken = !macros.contains_key(word);
                open.push((taken, taken));
            }
            "if" => {
                let taken = condition(&macros, &mut problems);
                open.push((taken, taken));
            }
            "elif" => {
                if let Some((_, resolved)) = open.pop() {
                    let taken = !resolved && condition(&macros, &mut problems);
                    open.push((taken, resolved || taken));
                }
            }
            "else" => {
                if let Some((_, resolved)) = open.pop() {
                    open.push((!resolved, true));
                }
            }
            "endif" => {
                open.pop();
            }
            _ => {}
        }
    }
    (kept, problems)
}

/// The name and parameter of a directive line OptiFine acts on (`#ifdef X`, `# if A > 1`).
fn directive(line: &str) -> Option<(&str, &str)> {
    let rest = line.trim_start().strip_prefix('#')?.trim_start();
    let end = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
    let name = &rest[..end];
    DIRECTIVES.contains(&name).then(|| (name, rest[end..].trim()))
}

/// An `#if`/`#elif` condition: `defined X` and `defined(X)` become `defined_X`, macro names are
/// replaced by their values (a name without a value by 1) until none is left, then the
/// expression is evaluated; a number is true when it is not zero.
fn evaluate_directive(condition: &str, macros: &Macros) -> Result<bool, String> {
    let mut text = replace_defined(condition);
    for _ in 0..MAX_SUBSTITUTIONS {
        let Some((start, end, value)) = first_macro(&text, macros) else {
            let defined: BTreeMap<String, bool> =
                identifiers(&text).filter_map(|(_, name)| name.strip_prefix("defined_").map(|m| (name.to_string(), macros.contains_key(m)))).collect();
            return evaluate_condition(&unknown_names_as_zero(&text), &defined);
        };
        let value = if value.is_empty() { "1" } else { value };
        text = format!("{} {value} {}", &text[..start], &text[end..]);
    }
    Err(format!("more than {MAX_SUBSTITUTIONS} macro substitutions"))
}

/// `text` with every name that is no macro, no `defined_X` and no function call replaced by
/// `0`, as OptiFine's macro resolver values an unknown name (it warns and reads 0).
fn unknown_names_as_zero(text: &str) -> String {
    let mut out = String::new();
    let mut last = 0;
    for (at, name) in identifiers(text) {
        let end = at + name.len();
        let call = text[end..].trim_start().starts_with('(');
        if call || name.starts_with("defined_") || name == "true" || name == "false" {
            continue;
        }
        out.push_str(&text[last..at]);
        out.push('0');
        last = end;
    }
    out.push_str(&text[last..]);
    out
}

/// `defined X` and `defined ( X )` written as the single name `defined_X`.
fn replace_defined(condition: &str) -> String {
    let mut out = String::new();
    let mut rest = condition;
    while let Some(at) = find_word(rest, "defined") {
        out.push_str(&rest[..at]);
        let after = rest[at + "defined".len()..].trim_start();
        let (inner, tail) = match after.strip_prefix('(') {
            Some(open) => match open.find(')') {
                Some(close) => (open[..close].trim(), &open[close + 1..]),
                None => ("", after),
            },
            None => {
                let end = after.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(after.len());
                (&after[..end], &after[end..])
            }
        };
        if inner.is_empty() {
            out.push_str("defined");
            rest = &rest[at + "defined".len()..];
        } else {
            out.push_str("defined_");
            out.push_str(inner);
            rest = tail;
        }
    }
    out.push_str(rest);
    out
}

/// Where the whole word `word` first stands in `text`.
fn find_word(text: &str, word: &str) -> Option<usize> {
    identifiers(text).find(|(_, name)| *name == word).map(|(at, _)| at)
}

/// The identifiers of `text` with their byte offsets (names start with a letter or `_`).
fn identifiers(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let bytes = text.as_bytes();
    let mut at = 0;
    std::iter::from_fn(move || {
        while at < bytes.len() {
            let c = bytes[at];
            if c.is_ascii_alphanumeric() || c == b'_' {
                let start = at;
                while at < bytes.len() && (bytes[at].is_ascii_alphanumeric() || bytes[at] == b'_') {
                    at += 1;
                }
                let word = &text[start..at];
                if !word.as_bytes()[0].is_ascii_digit() {
                    return Some((start, word));
                }
            } else {
                at += 1;
            }
        }
        None
    })
}

/// The first macro name of `text` with its span and value.
fn first_macro<'m>(text: &str, macros: &'m Macros) -> Option<(usize, usize, &'m str)> {
    identifiers(text).find_map(|(at, name)| macros.get(name).map(|value| (at, at + name.len(), value.as_str())))
}

/// Logical lines (continuations joined) with the 1-based line each starts on; comments and
/// blank lines dropped.
fn logical_lines(lines: &[(u32, &str)]) -> Vec<(u32, String)> {
    let blank = |c: char| c == ' ' || c == '\t' || c == '\x0c';
    let mut out = Vec::new();
    let mut lines = lines.iter();
    while let Some((line, raw)) = lines.next() {
        let first = raw.trim_start_matches(blank);
        if first.is_empty() || first.starts_with('#') || first.starts_with('!') {
            continue;
        }
        let mut joined = String::new();
        let mut current = first;
        loop {
            let trailing = current.len() - current.trim_end_matches('\\').len();
            if trailing % 2 == 1 {
                joined.push_str(&current[..current.len() - 1]);
                match lines.next() {
                    Some((_, next)) => current = next.trim_start_matches(blank),
                    None => break,
                }
            } else {
                joined.push_str(current);
                break;
            }
        }
        out.push((*line, joined));
    }
    out
}

/// Splits a logical line into its key and value, resolving backslash escapes in both.
fn split_key_value(line: &str) -> (String, String) {
    let chars: Vec<char> = line.chars().collect();
    let separator = |c: char| matches!(c, ' ' | '\t' | '\x0c');
    let mut i = 0;
    let mut key_end = chars.len();
    while i < chars.len() {
        match chars[i] {
            '\\' => i += 2,
            '=' | ':' => {
                key_end = i;
                break;
            }
            c if separator(c) => {
                key_end = i;
                break;
            }
            _ => i += 1,
        }
    }
    let key_end = key_end.min(chars.len());
    let mut value_start = key_end;
    while value_start < chars.len() && separator(chars[value_start]) {
        value_start += 1;
    }
    if value_start < chars.len() && matches!(chars[value_start], '=' | ':') {
        value_start += 1;
        while value_start < chars.len() && separator(chars[value_start]) {
            value_start += 1;
        }
    }
    (unescape(&chars[..key_end]), unescape(&chars[value_start..]).trim_end().to_string())
}

fn unescape(chars: &[char]) -> String {
    let mut out = String::with_capacity(chars.len());
    let mut i = 0;
    while i < chars.len() {
        if chars[i] != '\\' || i + 1 == chars.len() {
            out.push(chars[i]);
            i += 1;
            continue;
        }
        let c = chars[i + 1];
        i += 2;
        match c {
            't' => out.push('\t'),
            'n' => out.push('\n'),
            'r' => out.push('\r'),
            'f' => out.push('\x0c'),
            'u' => {
                let hex: String = chars[i..chars.len().min(i + 4)].iter().collect();
                match u32::from_str_radix(&hex, 16).ok().and_then(char::from_u32) {
                    Some(u) if hex.len() == 4 => {
                        out.push(u);
                        i += 4;
                    }
                    _ => out.push('u'),
                }
            }
            other => out.push(other),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn macros(pairs: &[(&str, &str)]) -> Macros {
        pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
    }

    fn keys(p: &Properties) -> Vec<(&str, &str, u32)> {
        p.entries().iter().map(|e| (e.key.as_str(), e.value.as_str(), e.line)).collect()
    }

    #[test]
    fn java_syntax_comments_continuations_separators_and_escapes() {
        let p = Properties::parse_plain("# comment\n! also\n\nprofile.LOW=A \\\n    B\nscreen : X Y\nkey value\nuni\\u0063ode=\\tx\n");
        assert_eq!(keys(&p), [("profile.LOW", "A B", 4), ("screen", "X Y", 6), ("key", "value", 7), ("unicode", "\tx", 8)]);
    }

    #[test]
    fn a_key_given_twice_keeps_its_place_with_the_later_value() {
        let p = Properties::parse_plain("a=1\nb=2\na=3\n");
        assert_eq!(keys(&p), [("a", "3", 3), ("b", "2", 2)]);
    }

    #[test]
    fn conditionals_follow_the_macros_and_keep_line_numbers() {
        let text = "#ifdef SHADOWS\nshadow=on\n#else\nshadow=off\n#endif\n#if MC_VERSION >= 11700 && defined(SHADOWS)\nnew=1\n#elif QUALITY == 2\nmid=1\n#endif\n";
        let on = Properties::parse(text, &macros(&[("SHADOWS", ""), ("MC_VERSION", "12104")]), Loader::default());
        assert_eq!(keys(&on), [("shadow", "on", 2), ("new", "1", 7)]);
        let off = Properties::parse(text, &macros(&[("MC_VERSION", "12104"), ("QUALITY", "2")]), Loader::default());
        assert_eq!(keys(&off), [("shadow", "off", 4), ("mid", "1", 9)]);
        assert!(off.problems.is_empty(), "{:?}", off.problems);
    }

    #[test]
    fn nested_branches_defines_and_comment_lines() {
        let text = "#define LOCAL\n#ifndef MISSING\n  #ifdef LOCAL // a comment\nx=1\n  #endif\n#else\ny=1\n#endif\n#undef LOCAL\n#ifdef LOCAL\nz=1\n#endif\n# just a comment\n";
        assert_eq!(keys(&Properties::parse_plain(text)), [("x", "1", 4)]);
    }

    /// OptiFine records a `#define` in a branch not taken; Iris's C preprocessor does not
    /// (clorece/Allium turns its colored lighting off in a `#ifdef MC_OS_MAC` branch).
    #[test]
    fn a_definition_in_a_branch_not_taken_counts_under_optifine_only() {
        let text = "#ifdef MC_OS_MAC\n#define LIGHTS 0\n#endif\n#if LIGHTS > 0\nfeatures=CUSTOM_IMAGES\n#endif\n";
        let options = macros(&[("LIGHTS", "256")]);
        assert!(Properties::parse(text, &options, Loader::OptiFine1_21).get("features").is_none());
        assert_eq!(Properties::parse(text, &options, Loader::Iris).get("features").map(|e| e.line), Some(5));
    }

    #[test]
    fn a_condition_that_does_not_evaluate_is_false_and_named() {
        let p = Properties::parse_plain("#if (\nx=1\n#endif\ny=2\n");
        assert_eq!(keys(&p), [("y", "2", 4)]);
        assert_eq!(p.problems.len(), 1);
        assert_eq!(p.problems[0].0, 1);
    }

    #[test]
    fn a_name_that_is_no_macro_reads_zero() {
        let p = Properties::parse_plain("#if TIMELAPSE_MODE == 0\nx=1\n#endif\n#if max(UNSET, 2) > 1\ny=1\n#endif\n");
        assert_eq!(keys(&p), [("x", "1", 2), ("y", "1", 5)]);
        assert!(p.problems.is_empty(), "{:?}", p.problems);
    }

    #[test]
    fn self_referencing_macros_stop() {
        let p = Properties::parse("#if A\nx=1\n#endif\n", &macros(&[("A", "A + 1")]), Loader::default());
        assert!(p.entries().is_empty());
        assert!(p.problems[0].1.contains("substitutions"), "{:?}", p.problems);
    }
}
