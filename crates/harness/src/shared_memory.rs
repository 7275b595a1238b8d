//! `shared` variables kept in storage buffers, for a compute stage that needs more `shared`
//! memory than llvmpipe gives a work group (32,768 bytes, which released packs pass: NVIDIA's
//! drivers give 49,152).
//!
//! Each variable becomes a storage block of its own holding one slice per work group of the
//! dispatch, and each use of the variable reads its work group's slice. A work group's
//! invocations see each other's writes after `barrier()` as they would in `shared` memory:
//! llvmpipe runs a group's invocations on one thread, and the blocks are `coherent`.

use tidepack_glsl::token::{self, Token, TokenKind};

/// What Mesa's linker says of a stage over the limit: the bytes it uses and the bytes given.
pub(crate) fn over_limit(log: &str) -> Option<(u64, u64)> {
    let rest = log.split("Too much shared memory used (").nth(1)?;
    let (used, rest) = rest.split_once('/')?;
    let given = rest.split(')').next()?;
    Some((used.trim().parse().ok()?, given.trim().parse().ok()?))
}

/// A compute stage's text with its `shared` variables in storage blocks.
#[derive(Debug)]
pub(crate) struct MovedShared {
    pub text: String,
    /// The blocks' names, one per variable, in the order they are declared. Each has no
    /// binding of its own: the dispatch gives it one.
    pub blocks: Vec<String>,
}

/// The work group's place in the dispatch (as the driver dispatches it), which picks its slice.
const SLICE: &str = "((gl_WorkGroupID.z * gl_NumWorkGroups.y + gl_WorkGroupID.y) * gl_NumWorkGroups.x + gl_WorkGroupID.x)";

/// `text` with each top-level `shared` declaration made into storage blocks and each later use
/// of its variables indexed by the work group's slice; None where it declares none, or one this
/// reads differently from GLSL (an initialiser, which `shared` does not take). Lines keep their
/// numbers.
pub(crate) fn moved_to_buffers(text: &str) -> Option<MovedShared> {
    let tokens = token::tokenize(text).ok()?;
    let sig = token::significant(&tokens);
    let depths = token::brace_depths(&tokens);
    let mut edits = Vec::new();
    let mut moved: Vec<(&str, usize)> = Vec::new();
    let mut blocks = Vec::new();
    let mut parens = 0i32;
    let mut at = 0;
    while at < sig.len() {
        let i = sig[at];
        let t = &tokens[i];
        if t.is_punct("#") && first_on_line(&tokens, i) {
            let line_end = (i..tokens.len()).find(|&j| tokens[j].kind == TokenKind::Newline).unwrap_or(tokens.len());
            at = sig.partition_point(|&j| j <= line_end);
            continue;
        }
        if t.is_punct("(") {
            parens += 1;
        } else if t.is_punct(")") {
            parens -= 1;
        }
        if parens == 0 && depths[i] == 0 && t.is_ident("shared") {
            let end = statement_end(&tokens, &sig, at)?;
            let declaration = Declaration::read(text, &tokens, &sig[at + 1..end])?;
            let replaced = tokens[i].offset..tokens[sig[end]].offset + 1;
            let mut with = declaration.as_blocks(&mut blocks);
            let lost = text[replaced.clone()].matches('\n').count().saturating_sub(with.matches('\n').count());
            with.push_str(&"\n".repeat(lost));
            edits.push((replaced, with));
            moved.extend(declaration.declarators.iter().map(|d| (d.name, sig[end])));
            at = end + 1;
            continue;
        }
        at += 1;
    }
    if moved.is_empty() {
        return None;
    }
    let replaced: Vec<std::ops::Range<usize>> = edits.iter().map(|(range, _)| range.clone()).collect();
    for (k, &i) in sig.iter().enumerate() {
        let t = &tokens[i];
        let after_dot = k > 0 && tokens[sig[k - 1]].is_punct(".");
        // A use inside a later declaration (its array size) stays as written: that text is
        // replaced whole, and the driver names what it cannot read.
        if t.kind != TokenKind::Ident || after_dot || replaced.iter().any(|r| r.contains(&t.offset)) {
            continue;
        }
        if let Some((name, _)) = moved.iter().find(|(name, declared_at)| *name == t.text && i > *declared_at) {
            edits.push((t.offset..t.offset + t.text.len(), format!("{}[{SLICE}].{SLICE_MEMBER}", slices_of(name))));
        }
    }
    Some(MovedShared { text: token::edited(text, edits), blocks })
}

/// `log` (a driver's complaint about a moved stage) with the names the move gave said as the
/// pack's: `tp_shared_sums` is `sums`, and so are its block and slice types.
pub(crate) fn in_the_packs_names(log: &str) -> String {
    ["tp_SharedSlice_", "tp_SharedStruct_", "tp_Shared_", "tp_shared_"].iter().fold(log.to_string(), |log, prefix| log.replace(prefix, ""))
}

/// The array of slices that holds `name`.
fn slices_of(name: &str) -> String {
    format!("tp_shared_{name}")
}

/// The member of a slice that holds the variable. Each slice is a struct of its own, so that the
/// variable's array sizes stay where GLSL read them (Mesa refuses some constant sizes, such as
/// `const ivec2` components, after a runtime-sized dimension).
const SLICE_MEMBER: &str = "value";

/// Whether token `i` is the first on its line but for whitespace.
fn first_on_line(tokens: &[Token<'_>], i: usize) -> bool {
    tokens[..i].iter().rev().find(|t| t.kind != TokenKind::Whitespace).is_none_or(|t| t.kind == TokenKind::Newline)
}

/// The position in `sig` of the `;` that ends the statement whose first token is at `from`.
fn statement_end(tokens: &[Token<'_>], sig: &[usize], from: usize) -> Option<usize> {
    let mut nesting = 0i32;
    for (k, &i) in sig.iter().enumerate().skip(from) {
        match tokens[i].text {
            "(" | "[" | "{" if tokens[i].kind == TokenKind::Punct => nesting += 1,
            ")" | "]" | "}" if tokens[i].kind == TokenKind::Punct => nesting -= 1,
            ";" if nesting == 0 => return Some(k),
            _ => {}
        }
    }
    None
}

/// A `shared` declaration, read from the tokens after `shared` up to its `;`.
struct Declaration<'a> {
    /// Qualifiers written before the type (`highp`, `precise`), as written.
    qualifiers: Vec<&'a str>,
    type_of: TypeOf<'a>,
    declarators: Vec<Declarator<'a>>,
}

enum TypeOf<'a> {
    /// A type by name, with the array sizes written after it (`vec3[9]`), as written.
    Named(&'a str),
    /// A struct defined in the declaration: its name, if written, and its body from `{` to `}`.
    Struct { name: Option<&'a str>, body: &'a str },
}

struct Declarator<'a> {
    name: &'a str,
    /// The array sizes after the name (`[256][9]`), as written; empty for a single value.
    sizes: &'a str,
}

impl<'a> Declaration<'a> {
    /// Reads `sig`, the significant tokens between `shared` and `;`.
    fn read(text: &'a str, tokens: &[Token<'a>], sig: &[usize]) -> Option<Self> {
        let span = |from: usize, to: usize| &text[tokens[sig[from]].offset..tokens[sig[to]].offset + tokens[sig[to]].text.len()];
        let mut at = 0;
        let mut qualifiers = Vec::new();
        while at < sig.len() && matches!(tokens[sig[at]].text, "highp" | "mediump" | "lowp" | "precise" | "volatile" | "coherent") {
            qualifiers.push(tokens[sig[at]].text);
            at += 1;
        }
        let type_of = if tokens.get(*sig.get(at)?)?.is_ident("struct") {
            at += 1;
            let name = (tokens[*sig.get(at)?].kind == TokenKind::Ident).then(|| tokens[sig[at]].text);
            at += usize::from(name.is_some());
            if !tokens[*sig.get(at)?].is_punct("{") {
                return None;
            }
            let close = matching(tokens, sig, at)?;
            let body = span(at, close);
            at = close + 1;
            TypeOf::Struct { name, body }
        } else {
            let from = at;
            if tokens[*sig.get(at)?].kind != TokenKind::Ident {
                return None;
            }
            at += 1;
            while at < sig.len() && tokens[sig[at]].is_punct("[") {
                at = matching(tokens, sig, at)? + 1;
            }
            TypeOf::Named(span(from, at - 1))
        };
        let mut declarators = Vec::new();
        while at < sig.len() {
            let name = tokens[sig[at]].kind == TokenKind::Ident;
            if !name {
                return None;
            }
            let named = at;
            at += 1;
            while at < sig.len() && tokens[sig[at]].is_punct("[") {
                at = matching(tokens, sig, at)? + 1;
            }
            let sizes = if at > named + 1 { span(named + 1, at - 1) } else { "" };
            declarators.push(Declarator { name: tokens[sig[named]].text, sizes });
            match sig.get(at).map(|&i| &tokens[i]) {
                None => {}
                Some(t) if t.is_punct(",") => at += 1,
                // An initialiser, or what GLSL does not read as a declaration.
                Some(_) => return None,
            }
        }
        (!declarators.is_empty()).then_some(Declaration { qualifiers, type_of, declarators })
    }

    /// The declaration as storage blocks, one per variable, on one line after the struct it
    /// defines (whose body keeps its lines); their names are added to `blocks`.
    fn as_blocks(&self, blocks: &mut Vec<String>) -> String {
        let mut out = String::new();
        let type_name = match &self.type_of {
            TypeOf::Named(name) => name.to_string(),
            TypeOf::Struct { name, body } => {
                let name = name.map_or_else(|| format!("tp_SharedStruct_{}", self.declarators[0].name), str::to_string);
                out.push_str(&format!("struct {name} {body}; "));
                name
            }
        };
        let qualifiers: String = self.qualifiers.iter().map(|q| format!("{q} ")).collect();
        for d in &self.declarators {
            let (slice, block) = (format!("tp_SharedSlice_{}", d.name), format!("tp_Shared_{}", d.name));
            out.push_str(&format!("struct {slice} {{ {qualifiers}{type_name} {SLICE_MEMBER}{}; }}; ", d.sizes));
            out.push_str(&format!("layout(std430) coherent buffer {block} {{ {slice} {}[]; }}; ", slices_of(d.name)));
            blocks.push(block);
        }
        out.truncate(out.trim_end().len());
        out
    }
}

/// The position in `sig` of the bracket that closes the one at `open`.
fn matching(tokens: &[Token<'_>], sig: &[usize], open: usize) -> Option<usize> {
    let mut nesting = 0i32;
    for (k, &i) in sig.iter().enumerate().skip(open) {
        let t = &tokens[i];
        if t.kind != TokenKind::Punct {
            continue;
        }
        match t.text {
            "(" | "[" | "{" => nesting += 1,
            ")" | "]" | "}" => {
                nesting -= 1;
                if nesting == 0 {
                    return Some(k);
                }
            }
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn moved(text: &str) -> MovedShared {
        let moved = moved_to_buffers(text).unwrap_or_else(|| panic!("nothing moved in {text}"));
        assert_eq!(moved.text.lines().count(), text.lines().count(), "{}", moved.text);
        moved
    }

    #[test]
    fn a_complaint_about_a_moved_stage_names_the_packs_variables() {
        assert_eq!(in_the_packs_names("0:3(5): error: `tp_shared_sums' undeclared in tp_Shared_sums"), "0:3(5): error: `sums' undeclared in sums");
    }

    #[test]
    fn mesas_complaint_gives_the_bytes_used_and_given() {
        assert_eq!(over_limit("error: Too much shared memory used (36860/32768)\n"), Some((36860, 32768)));
        assert_eq!(over_limit("error: undeclared identifier"), None);
    }

    #[test]
    fn an_array_becomes_a_block_of_slices_and_its_uses_read_the_groups_slice() {
        let text = "#version 430\nlayout(local_size_x = 256) in;\nshared vec3 sums[256][9];\nvoid main() {\n    sums[0][1] = vec3(1.0);\n}\n";
        let moved = moved(text);
        assert_eq!(moved.blocks, ["tp_Shared_sums"]);
        let lines: Vec<&str> = moved.text.lines().collect();
        assert_eq!(
            lines[2],
            "struct tp_SharedSlice_sums { vec3 value[256][9]; }; layout(std430) coherent buffer tp_Shared_sums { tp_SharedSlice_sums tp_shared_sums[]; };"
        );
        assert_eq!(lines[4], format!("    tp_shared_sums[{SLICE}].value[0][1] = vec3(1.0);"));
    }

    #[test]
    fn array_types_lists_of_declarators_and_qualifiers_are_kept() {
        let moved = moved("shared highp vec3[9] coeffs[64], spare;\nvoid f() { coeffs[1][2] = spare[0]; }\n");
        assert_eq!(moved.blocks, ["tp_Shared_coeffs", "tp_Shared_spare"]);
        assert!(moved.text.starts_with(
            "struct tp_SharedSlice_coeffs { highp vec3[9] value[64]; }; layout(std430) coherent buffer tp_Shared_coeffs { tp_SharedSlice_coeffs tp_shared_coeffs[]; }; \
             struct tp_SharedSlice_spare { highp vec3[9] value; }; layout(std430) coherent buffer tp_Shared_spare { tp_SharedSlice_spare tp_shared_spare[]; };\n"
        ), "{}", moved.text);
        assert!(moved.text.contains(&format!("tp_shared_coeffs[{SLICE}].value[1][2] = tp_shared_spare[{SLICE}].value[0]")), "{}", moved.text);
    }

    #[test]
    fn a_struct_defined_in_the_declaration_is_named_and_keeps_its_lines() {
        let text = "shared struct {\n    uint count;\n    uint[4] items;\n} tally;\nvoid main() { tally.count = 0u; other.tally = 1; }\n";
        let moved = moved(text);
        let lines: Vec<&str> = moved.text.lines().collect();
        assert_eq!(lines[0], "struct tp_SharedStruct_tally {");
        assert_eq!(
            lines[3],
            "}; struct tp_SharedSlice_tally { tp_SharedStruct_tally value; }; layout(std430) coherent buffer tp_Shared_tally { tp_SharedSlice_tally tp_shared_tally[]; };"
        );
        assert!(lines[4].contains(&format!("tp_shared_tally[{SLICE}].value.count = 0u; other.tally = 1;")), "{}", lines[4]);
    }

    #[test]
    fn layouts_naming_shared_and_directives_are_left_alone() {
        let text = "#define SHARED shared float\nlayout(shared) uniform Block { float x; };\n";
        assert!(moved_to_buffers(text).is_none());
    }

    #[test]
    fn an_initialised_shared_variable_is_not_read_as_one() {
        assert!(moved_to_buffers("shared float x = 1.0;\n").is_none());
    }
}
