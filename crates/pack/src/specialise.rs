//! Specialising the pack for one scene: uniforms whose value the scene fixes become
//! constants in the shipped text, before validation, so the compiler folds the branches and
//! arithmetic they decide (`isEyeInWater` picks the above- or under-water half once and for
//! all).
//!
//! Each declaration is rewritten on its own line, `uniform int isEyeInWater;` becoming
//! `const int isEyeInWater = 0; // uniform folded for <scene>`, so every line keeps its number
//! and diagnostics still point at the template.

use std::collections::BTreeMap;
use std::sync::Arc;

use tidepack_glsl::token::{TokenKind, tokenize};

use crate::pack_options::is_glsl;
use crate::shipped::{ShippedFile, ShippedPack};

/// What to fold: uniform name → GLSL initialiser valid in both dialects (`0`,
/// `vec3(0.5, 0.6, 1.0)`, `mat4(...)`).
#[derive(Clone, Debug, Default)]
pub struct Specialisation {
    /// The scene the values come from, as the folded lines name it.
    pub scene: String,
    pub constants: BTreeMap<String, String>,
}

impl Specialisation {
    /// The scene's file stem, which names the specialised zip.
    pub fn variant_name(&self) -> String {
        let stem = self.scene.rsplit(['/', '\\']).next().unwrap_or(&self.scene);
        stem.strip_suffix(".toml").unwrap_or(stem).to_string()
    }
}

/// Rewrites, in every GLSL file of `pack`, the declarations of uniforms `spec` has a value
/// for, and records the names folded in `pack.folded_uniforms`.
pub fn specialise(pack: &mut ShippedPack, spec: &Specialisation) {
    let mut folded = Vec::new();
    for (path, file) in pack.files.iter_mut() {
        if !is_glsl(path) {
            continue;
        }
        if let Some((text, names)) = specialise_text(&file.text, spec) {
            *file = ShippedFile { text: Arc::from(text), origin: file.origin.clone() };
            folded.extend(names);
        }
    }
    folded.sort();
    folded.dedup();
    pack.folded_uniforms = folded;
}

/// Scalars, vectors and matrices: the types a constant can stand in for (never samplers).
fn is_plain_type(name: &str) -> bool {
    let vector = |prefix: &str| name.strip_prefix(prefix).is_some_and(|n| matches!(n, "2" | "3" | "4"));
    matches!(name, "float" | "int" | "uint" | "bool")
        || ["vec", "ivec", "uvec", "bvec", "mat"].into_iter().any(vector)
        || name.strip_prefix("mat").is_some_and(|n| matches!(n.as_bytes(), [b'2'..=b'4', b'x', b'2'..=b'4']))
}

/// The text with its foldable declarations rewritten and the names folded, or `None` when
/// nothing in it is folded. Only a plain `uniform TYPE NAME;` is folded: a declaration with
/// several names, an array or a qualifier stays a uniform.
pub fn specialise_text(text: &str, spec: &Specialisation) -> Option<(String, Vec<String>)> {
    // Text the tokenizer rejects is left alone: validation reports it with its location.
    let tokens = tokenize(text).ok()?;
    let significant: Vec<usize> = (0..tokens.len()).filter(|&i| !tokens[i].is_trivia()).collect();
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    let mut names = Vec::new();
    for (k, window) in significant.windows(4).enumerate() {
        let [keyword, ty, name, end] = [window[0], window[1], window[2], window[3]].map(|i| &tokens[i]);
        let first_on_line = k == 0 || tokens[significant[k - 1]].line < keyword.line;
        if !first_on_line
            || !keyword.is_ident("uniform")
            || ty.kind != TokenKind::Ident
            || !is_plain_type(ty.text)
            || name.kind != TokenKind::Ident
            || !end.is_punct(";")
            || end.line != keyword.line
        {
            continue;
        }
        let Some(value) = spec.constants.get(name.text) else { continue };
        let statement_end = end.offset + end.text.len();
        edits.push((keyword.offset, statement_end, format!("const {} {} = {value};", ty.text, name.text)));
        names.push(name.text.to_string());
        // The note ends the line, inside the comment already there if there is one.
        let mut line_end = text[statement_end..].find('\n').map_or(text.len(), |n| statement_end + n);
        if text[..line_end].ends_with('\r') {
            line_end -= 1;
        }
        let rest = text[statement_end..line_end].trim();
        let note = if rest.is_empty() {
            format!(" // uniform folded for {}", spec.scene)
        } else if rest.starts_with("//") {
            format!(" (uniform folded for {})", spec.scene)
        } else {
            edits.push((statement_end, statement_end, format!(" /* uniform folded for {} */", spec.scene)));
            continue;
        };
        edits.push((line_end, line_end, note));
    }
    if edits.is_empty() {
        return None;
    }
    let mut out = String::with_capacity(text.len() + 64 * names.len());
    let mut at = 0;
    for (start, end, replacement) in edits {
        out.push_str(&text[at..start]);
        out.push_str(&replacement);
        at = end;
    }
    out.push_str(&text[at..]);
    Some((out, names))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(pairs: &[(&str, &str)]) -> Specialisation {
        Specialisation {
            scene: "tests/scenes/pool.toml".into(),
            constants: pairs.iter().map(|(n, v)| (n.to_string(), v.to_string())).collect(),
        }
    }

    #[test]
    fn folds_plain_declarations_on_their_own_line() {
        let text = "#version 120\nuniform int isEyeInWater;\nuniform vec3 skyColor; // the sky\nuniform float far;\nvoid main() {}\n";
        let (out, names) = specialise_text(text, &spec(&[("isEyeInWater", "0"), ("skyColor", "vec3(0.5, 0.6, 1.0)")])).unwrap();
        assert_eq!(names, ["isEyeInWater", "skyColor"]);
        assert_eq!(
            out,
            "#version 120\n\
             const int isEyeInWater = 0; // uniform folded for tests/scenes/pool.toml\n\
             const vec3 skyColor = vec3(0.5, 0.6, 1.0); // the sky (uniform folded for tests/scenes/pool.toml)\n\
             uniform float far;\n\
             void main() {}\n"
        );
        assert_eq!(out.lines().count(), text.lines().count());
    }

    #[test]
    fn leaves_samplers_arrays_lists_and_mentions_alone() {
        let text = "uniform sampler2D colortex0;\nuniform mat4 m[2];\nuniform float a, b;\nfloat f() { return isEyeInWater; }\n";
        let folded = specialise_text(text, &spec(&[("colortex0", "0"), ("m", "0"), ("a", "0"), ("isEyeInWater", "1")]));
        assert!(folded.is_none(), "{folded:?}");
    }
}
