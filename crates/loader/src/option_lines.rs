//! OptiFine's in-game options, read from and written into shader sources the way OptiFine
//! does it: line by line.
//!
//! - Switch: `#define NAME // tooltip` (on) or `//#define NAME // tooltip` (off). OptiFine shows
//!   it only when the same file tests it (`#ifdef NAME`, `#ifndef NAME`, `defined NAME`).
//! - Value: `#define NAME 0.5 // [0.25 0.5 1.0] tooltip`. The default joins the list when missing.
//! - `const` options: `const int shadowMapResolution = 2048; // [1024 2048 4096]` and
//!   `const bool generateShadowMipmap = true;`, for the names OptiFine lists
//!   ([`crate::consts::OPTION_NAMES`]). A number without a value list has no other value a
//!   player could pick, so it is no option here.
//!
//! Changing an option rewrites its declaration line in place, as OptiFine does when a player
//! picks a value; no line is added or removed.

use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};

use tidepack_glsl::token::{Token, TokenKind, tokenize};

use crate::consts::{self, ConstDecl};

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OptionKind {
    Switch { default: bool },
    Value { default: String, values: Vec<String> },
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OptionDecl {
    pub name: String,
    pub kind: OptionKind,
    /// 1-based line of the declaration.
    pub line: u32,
    /// Text after the value list (or after `//` for switches), trimmed.
    pub tooltip: String,
}

#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum OptionValue {
    Switch(bool),
    Value(String),
}

impl std::fmt::Display for OptionValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OptionValue::Switch(on) => f.write_str(if *on { "on" } else { "off" }),
            OptionValue::Value(v) => f.write_str(v),
        }
    }
}

impl OptionKind {
    pub fn default_value(&self) -> OptionValue {
        match self {
            OptionKind::Switch { default } => OptionValue::Switch(*default),
            OptionKind::Value { default, .. } => OptionValue::Value(default.clone()),
        }
    }

    /// Every value a player can pick, default included.
    pub fn all_values(&self) -> Vec<OptionValue> {
        match self {
            OptionKind::Switch { .. } => vec![OptionValue::Switch(false), OptionValue::Switch(true)],
            OptionKind::Value { values, .. } => values.iter().cloned().map(OptionValue::Value).collect(),
        }
    }
}

/// Option values by name; names not present keep the default written in the source.
pub type OptionSet = BTreeMap<String, OptionValue>;

/// One `#define` line as OptiFine's line patterns see it.
struct DefineLine<'a> {
    commented_out: bool,
    name: &'a str,
    value: Option<Token<'a>>,
    comment: Option<&'a str>,
}

fn parse_define_line(line: &str) -> Option<DefineLine<'_>> {
    // Most lines are code: decided without tokenizing.
    if !line.contains("define") {
        return None;
    }
    let tokens = tokenize(line).ok()?;
    let sig: Vec<Token<'_>> = tokens.iter().copied().filter(|t| t.kind != TokenKind::Whitespace).collect();
    // `//#define X` tokenizes as one line comment: look inside it.
    if let [first] = sig.as_slice()
        && first.kind == TokenKind::LineComment
    {
        let inner = first.text[2..].trim_start();
        if !inner.starts_with("#define") {
            return None;
        }
        let parsed = parse_define_line(inner)?;
        return (parsed.value.is_none()).then_some(DefineLine { commented_out: true, ..parsed });
    }
    let (hash, define, name) = (sig.first()?, sig.get(1)?, sig.get(2)?);
    if !hash.is_punct("#") || !define.is_ident("define") || name.kind != TokenKind::Ident {
        return None;
    }
    let rest = &sig[3..];
    let (value, comment) = match rest {
        [] => (None, None),
        [c] if c.kind == TokenKind::LineComment => (None, Some(c.text)),
        [v] if matches!(v.kind, TokenKind::Number | TokenKind::Ident) => (Some(*v), None),
        [v, c] if matches!(v.kind, TokenKind::Number | TokenKind::Ident) && c.kind == TokenKind::LineComment => {
            (Some(*v), Some(c.text))
        }
        // `-0.5` is two tokens.
        [m, v, tail @ ..] if m.is_punct("-") && v.kind == TokenKind::Number && tail.len() <= 1 => {
            let text = &line[m.offset..v.offset + v.text.len()];
            let comment = tail.first().filter(|c| c.kind == TokenKind::LineComment).map(|c| c.text);
            if tail.len() == 1 && comment.is_none() {
                return None;
            }
            (Some(Token { kind: TokenKind::Number, text, offset: m.offset, line: 1 }), comment)
        }
        _ => return None,
    };
    Some(DefineLine { commented_out: false, name: name.text, value, comment })
}

/// Splits `// tooltip [a b c] more` into the list and the tooltip: OptiFine takes the first
/// `[...]` anywhere in the comment and the rest of the comment as the tooltip.
fn value_list(comment: &str) -> Option<(Vec<String>, String)> {
    let body = comment.strip_prefix("//")?;
    let open = body.find('[')?;
    let close = open + body[open..].find(']')?;
    let values: Vec<String> = body[open + 1..close].split_whitespace().map(str::to_string).collect();
    if values.is_empty() {
        return None;
    }
    let tooltip = format!("{} {}", body[..open].trim(), body[close + 1..].trim());
    Some((values, tooltip.trim().to_string()))
}

/// The options OptiFine would show for one source file read alone.
pub fn scan(text: &str) -> Vec<OptionDecl> {
    scan_tested(text, &tested_names(text))
}

/// The options of one source file, a `#define NAME` line counting as a switch where `tested`
/// (the names the files it is read with test, [`tested_names`]) holds the name.
pub fn scan_tested(text: &str, tested: &BTreeSet<String>) -> Vec<OptionDecl> {
    let mut found = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let Some(def) = parse_define_line(line) else { continue };
        let line_no = index as u32 + 1;
        match def.value {
            None => {
                if !tested.contains(def.name) {
                    continue;
                }
                let tooltip = def.comment.map_or("", |c| c[2..].trim()).to_string();
                found.push(OptionDecl {
                    name: def.name.to_string(),
                    kind: OptionKind::Switch { default: !def.commented_out },
                    line: line_no,
                    tooltip,
                });
            }
            Some(value) => {
                let Some((mut values, tooltip)) = def.comment.and_then(value_list) else { continue };
                if !values.iter().any(|v| v == value.text) {
                    values.insert(0, value.text.to_string());
                }
                found.push(OptionDecl {
                    name: def.name.to_string(),
                    kind: OptionKind::Value { default: value.text.to_string(), values },
                    line: line_no,
                    tooltip,
                });
            }
        }
    }
    found.extend(consts::declarations(text).filter(ConstDecl::is_option).filter_map(|decl| const_option(&decl)));
    found
}

/// A `const` option line as an option; `None` for a number without a value list.
fn const_option(decl: &ConstDecl) -> Option<OptionDecl> {
    let (kind, tooltip) = match decl.switch() {
        Some(default) => (OptionKind::Switch { default }, decl.comment.map_or("", |c| c[2..].trim()).to_string()),
        None => {
            let (mut values, tooltip) = decl.comment.and_then(value_list)?;
            if !values.iter().any(|v| v == decl.value) {
                values.insert(0, decl.value.to_string());
            }
            (OptionKind::Value { default: decl.value.to_string(), values }, tooltip)
        }
    };
    Some(OptionDecl { name: decl.name.to_string(), kind, line: decl.line, tooltip })
}

/// The names `text` tests with `#ifdef NAME` or `#ifndef NAME` alone on a line: what makes a
/// `#define NAME` line a switch for OptiFine and Iris. `#if defined NAME` does not count, nor a
/// test with anything after the name.
pub fn tested_names(text: &str) -> BTreeSet<String> {
    text.lines()
        .filter_map(|line| {
            let line = line.trim();
            let rest = line.strip_prefix("#ifdef").or_else(|| line.strip_prefix("#ifndef"))?;
            let name = rest.strip_prefix([' ', '\t'])?.trim();
            (!name.is_empty() && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')).then(|| name.to_string())
        })
        .collect()
}

/// Rewrites the declaration lines of the options in `set`, keeping every line in place.
pub fn apply<'t>(text: &'t str, set: &OptionSet) -> Cow<'t, str> {
    if set.is_empty() {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 64);
    let mut changed = false;
    for line in text.split_inclusive('\n') {
        let (body, ending) = match line.strip_suffix('\n') {
            Some(b) => b.strip_suffix('\r').map_or((b, "\n"), |b| (b, "\r\n")),
            None => (line, ""),
        };
        let rewritten = rewrite_define_line(body, set).or_else(|| rewrite_const_line(body, set));
        match rewritten {
            Some(new_body) => {
                changed = true;
                out.push_str(&new_body);
            }
            None => out.push_str(body),
        }
        out.push_str(ending);
    }
    if changed { Cow::Owned(out) } else { Cow::Borrowed(text) }
}

/// `body` with a `#define` option line set as `set` wants, when that changes it.
fn rewrite_define_line(body: &str, set: &OptionSet) -> Option<String> {
    parse_define_line(body).and_then(|def| {
        let wanted = set.get(def.name)?;
        match (wanted, def.value) {
            (OptionValue::Switch(on), None) => {
                if *on != def.commented_out {
                    return None;
                }
                let indent = &body[..body.len() - body.trim_start().len()];
                let decl = body.trim_start();
                Some(if *on {
                    format!("{indent}{}", decl.trim_start_matches('/').trim_start())
                } else {
                    format!("{indent}//{decl}")
                })
            }
            (OptionValue::Value(v), Some(old)) if v != old.text => {
                Some(format!("{}{}{}", &body[..old.offset], v, &body[old.offset + old.text.len()..]))
            }
            _ => None,
        }
    })
}

/// `body` with a `const` option line set as `set` wants, when that changes it.
fn rewrite_const_line(body: &str, set: &OptionSet) -> Option<String> {
    let decl = consts::declaration(body, 0).filter(ConstDecl::is_option)?;
    let value = match set.get(decl.name)? {
        OptionValue::Switch(on) if decl.switch()? != *on => on.to_string(),
        OptionValue::Value(v) if decl.switch().is_none() && v != decl.value => v.clone(),
        _ => return None,
    };
    Some(format!("{}{}{}", &body[..decl.value_offset], value, &body[decl.value_offset + decl.value.len()..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SETTINGS: &str = "\
#define WAVES // Moving water
//#define FOAM // White crests
#define STRENGTH 0.5 // [0.25 0.5 1.0] How strong
#define STEPS 8 // [4 16] Steps
#define OFFSET -0.5 // [-1.0 -0.5 0.0]
#define MODE 0 // Timelapse mode [0 1 2]
#define BLOCK_WATER 10008
#define UNTESTED
#define COMMENTED_TEST
#ifdef WAVES
#endif
#ifndef FOAM
#endif
#if defined(UNTESTED)
#endif
#ifdef COMMENTED_TEST // a test with more on its line is no reference (Iris, after OptiFine)
#endif
";

    /// Only `#ifdef NAME` and `#ifndef NAME` alone on a line make a `#define NAME` a switch.
    #[test]
    fn scans_switches_and_values_like_optifine() {
        let found = scan(SETTINGS);
        let summary: Vec<(&str, &OptionKind, u32)> = found.iter().map(|o| (o.name.as_str(), &o.kind, o.line)).collect();
        assert_eq!(
            summary,
            [
                ("WAVES", &OptionKind::Switch { default: true }, 1),
                ("FOAM", &OptionKind::Switch { default: false }, 2),
                (
                    "STRENGTH",
                    &OptionKind::Value { default: "0.5".into(), values: vec!["0.25".into(), "0.5".into(), "1.0".into()] },
                    3
                ),
                ("STEPS", &OptionKind::Value { default: "8".into(), values: vec!["8".into(), "4".into(), "16".into()] }, 4),
                (
                    "OFFSET",
                    &OptionKind::Value { default: "-0.5".into(), values: vec!["-1.0".into(), "-0.5".into(), "0.0".into()] },
                    5
                ),
                ("MODE", &OptionKind::Value { default: "0".into(), values: vec!["0".into(), "1".into(), "2".into()] }, 6),
            ]
        );
        assert_eq!(found[0].tooltip, "Moving water");
        assert_eq!(found[2].tooltip, "How strong");
        assert_eq!(found[5].tooltip, "Timelapse mode");
    }

    #[test]
    fn apply_toggles_and_sets_in_place() {
        let set: OptionSet = [
            ("WAVES".to_string(), OptionValue::Switch(false)),
            ("FOAM".to_string(), OptionValue::Switch(true)),
            ("STRENGTH".to_string(), OptionValue::Value("1.0".into())),
            ("OFFSET".to_string(), OptionValue::Value("0.0".into())),
        ]
        .into();
        let out = apply(SETTINGS, &set);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines.len(), SETTINGS.lines().count());
        assert_eq!(lines[0], "//#define WAVES // Moving water");
        assert_eq!(lines[1], "#define FOAM // White crests");
        assert_eq!(lines[2], "#define STRENGTH 1.0 // [0.25 0.5 1.0] How strong");
        assert_eq!(lines[4], "#define OFFSET 0.0 // [-1.0 -0.5 0.0]");
        let back = scan(&out);
        assert_eq!(back[0].kind, OptionKind::Switch { default: false });
        assert_eq!(back[1].kind, OptionKind::Switch { default: true });
    }

    #[test]
    fn const_options_of_optifines_list_are_options_too() {
        let text = "const int shadowMapResolution = 2048; // [1024 2048 4096] Shadow size\nconst bool generateShadowMipmap = false;\nconst float sunPathRotation = -40.0;\nconst int notAnOption = 3; // [1 2 3]\nconst float sunPathRotation2 = 1.0; // [1.0 2.0]\n";
        let found = scan(text);
        let summary: Vec<(&str, &OptionKind)> = found.iter().map(|o| (o.name.as_str(), &o.kind)).collect();
        assert_eq!(
            summary,
            [
                ("shadowMapResolution", &OptionKind::Value { default: "2048".into(), values: vec!["1024".into(), "2048".into(), "4096".into()] }),
                ("generateShadowMipmap", &OptionKind::Switch { default: false }),
            ]
        );
        assert_eq!(found[0].tooltip, "Shadow size");
        let set: OptionSet = [
            ("shadowMapResolution".to_string(), OptionValue::Value("4096".into())),
            ("generateShadowMipmap".to_string(), OptionValue::Switch(true)),
            ("notAnOption".to_string(), OptionValue::Value("1".into())),
        ]
        .into();
        let out = apply(text, &set);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "const int shadowMapResolution = 4096; // [1024 2048 4096] Shadow size");
        assert_eq!(lines[1], "const bool generateShadowMipmap = true;");
        assert_eq!(lines[3], "const int notAnOption = 3; // [1 2 3]");
    }

    #[test]
    fn apply_with_defaults_borrows() {
        let set: OptionSet = [("WAVES".to_string(), OptionValue::Switch(true))].into();
        assert!(matches!(apply(SETTINGS, &set), Cow::Borrowed(_)));
    }
}
