//! `const` declarations of a program's text, line by line as OptiFine's parsers read them: the
//! settings a pack declares in GLSL (`const int shadowMapResolution = 2048;`,
//! `const int colortex2Format = RGBA16F;`, `const bool colortex3Clear = false;`,
//! `const vec4 colortex0ClearColor = vec4(0.0);`) and the `const` options of
//! [`crate::option_lines`]. A declaration counts where a line starts with it, whatever
//! conditionals surround it in the unpreprocessed text; callers hand preprocessed text when only
//! active lines should count.

/// The names OptiFine accepts as `const` options (its shader-pack parser's list): only these
/// become in-game options; other `const` lines are plain GLSL.
pub const OPTION_NAMES: [&str; 36] = [
    "shadowMapResolution",
    "shadowMapFov",
    "shadowDistance",
    "shadowDistanceRenderMul",
    "shadowIntervalSize",
    "generateShadowMipmap",
    "generateShadowColorMipmap",
    "shadowHardwareFiltering",
    "shadowHardwareFiltering0",
    "shadowHardwareFiltering1",
    "shadowtex0Mipmap",
    "shadowtexMipmap",
    "shadowtex1Mipmap",
    "shadowcolor0Mipmap",
    "shadowColor0Mipmap",
    "shadowcolor1Mipmap",
    "shadowColor1Mipmap",
    "shadowtex0Nearest",
    "shadowtexNearest",
    "shadow0MinMagNearest",
    "shadowtex1Nearest",
    "shadow1MinMagNearest",
    "shadowcolor0Nearest",
    "shadowColor0Nearest",
    "shadowColor0MinMagNearest",
    "shadowcolor1Nearest",
    "shadowColor1Nearest",
    "shadowColor1MinMagNearest",
    "wetnessHalflife",
    "drynessHalflife",
    "eyeBrightnessHalflife",
    "centerDepthHalflife",
    "sunPathRotation",
    "ambientOcclusionLevel",
    "superSamplingLevel",
    "noiseTextureResolution",
];

/// One `const <type> <name> = <value>;` line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConstDecl<'t> {
    pub ty: &'t str,
    pub name: &'t str,
    /// The initialiser as written, trimmed (`2048`, `RGBA16F`, `vec4(0.0, 0.0, 0.0, 1.0)`).
    pub value: &'t str,
    /// Byte offset of the value in the line (for rewriting it in place).
    pub value_offset: usize,
    /// The `//` comment after the `;`, if any, with its slashes.
    pub comment: Option<&'t str>,
    /// Whether code follows the `;` on the line (OptiFine's settings patterns allow it, its
    /// option patterns do not).
    pub code_after: bool,
    /// 1-based line.
    pub line: u32,
}

/// Every `const` declaration of `text` that fills one line.
pub fn declarations(text: &str) -> impl Iterator<Item = ConstDecl<'_>> {
    text.lines().enumerate().filter_map(|(index, line)| declaration(line, index as u32 + 1))
}

/// The declaration `line` holds: `const`, a type, a name, `=`, a value up to the first `;`.
pub fn declaration(line: &str, number: u32) -> Option<ConstDecl<'_>> {
    let rest = line.trim_start().strip_prefix("const")?;
    if !rest.starts_with([' ', '\t']) {
        return None;
    }
    let rest = rest.trim_start();
    let (ty, rest) = word(rest)?;
    let (name, rest) = word(rest.trim_start())?;
    let rest = rest.trim_start().strip_prefix('=')?;
    let (value_part, after) = rest.split_once(';')?;
    let after = after.trim();
    let comment = after.starts_with("//").then_some(after);
    let code_after = !after.is_empty() && comment.is_none();
    let value = value_part.trim();
    if value.is_empty() {
        return None;
    }
    let value_offset = line.len() - rest.len() + (value_part.len() - value_part.trim_start().len());
    Some(ConstDecl { ty, name, value, value_offset, comment, code_after, line: number })
}

/// A GLSL identifier at the start of `text`, and what follows it.
fn word(text: &str) -> Option<(&str, &str)> {
    let end = text.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(text.len());
    (end > 0 && !text.as_bytes()[0].is_ascii_digit()).then(|| (&text[..end], &text[end..]))
}

impl ConstDecl<'_> {
    /// The value as a finite number (`2048`, `-0.5f`).
    pub fn number(&self) -> Option<f64> {
        self.value.trim_end_matches(['f', 'F']).parse::<f64>().ok().filter(|v| v.is_finite())
    }

    /// The value of a `bool` declaration.
    pub fn switch(&self) -> Option<bool> {
        match (self.ty, self.value) {
            ("bool", "true") => Some(true),
            ("bool", "false") => Some(false),
            _ => None,
        }
    }

    /// The components of a `vec4(...)` initialiser: one value repeated, or four.
    pub fn vec4(&self) -> Option<[f64; 4]> {
        let parts = self.vector("vec4", 4)?;
        Some([parts[0], parts[1], parts[2], parts[3]])
    }

    /// The `components` numbers of a `constructor(...)` initialiser (`ivec3(50, 30, 1)`): one
    /// value repeated, or each.
    pub fn vector(&self, constructor: &str, components: usize) -> Option<Vec<f64>> {
        let inner = self.value.strip_prefix(constructor)?.trim_start().strip_prefix('(')?.strip_suffix(')')?;
        let parts: Vec<f64> = inner.split(',').map(|p| p.trim().trim_end_matches(['f', 'F', 'u', 'U']).parse::<f64>().ok()).collect::<Option<_>>()?;
        match parts.len() {
            1 => Some(vec![parts[0]; components]),
            n if n == components => Some(parts),
            _ => None,
        }
    }

    /// Whether OptiFine shows this declaration as an option: a listed name, a `bool` or an
    /// `int`/`float` with a plain number.
    pub fn is_option(&self) -> bool {
        !self.code_after
            && OPTION_NAMES.contains(&self.name)
            && match self.ty {
                "bool" => self.switch().is_some(),
                "int" | "float" => {
                    let digits = self.value.strip_prefix('-').unwrap_or(self.value).trim_end_matches(['f', 'F']);
                    !digits.is_empty() && digits.chars().all(|c| c.is_ascii_digit() || c == '.')
                }
                _ => false,
            }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_settings_and_skips_other_lines() {
        let text = "const int shadowMapResolution = 2048; // [1024 2048]\n\
                    const int colortex2Format = RGBA16F;\n\
                    const vec4 colortex3ClearColor = vec4(1.0, 0.5, 0.0, 1.0);\n\
                    const bool colortex4Clear = false;\n\
                    const float shadowDistance = 96.0; float y;\n\
                    constant int z = 1;\n\
                    float notconst = 1.0;\n";
        let found: Vec<(&str, &str, u32)> = declarations(text).map(|d| (d.name, d.value, d.line)).collect();
        assert_eq!(
            found,
            [
                ("shadowMapResolution", "2048", 1),
                ("colortex2Format", "RGBA16F", 2),
                ("colortex3ClearColor", "vec4(1.0, 0.5, 0.0, 1.0)", 3),
                ("colortex4Clear", "false", 4),
                ("shadowDistance", "96.0", 5)
            ]
        );
        let all: Vec<ConstDecl> = declarations(text).collect();
        assert!(all[0].is_option() && !all[1].is_option());
        // A setting may have code after it; an option may not.
        assert!(all[4].code_after && !all[4].is_option());
        assert_eq!(all[0].comment, Some("// [1024 2048]"));
        assert_eq!(all[2].vec4(), Some([1.0, 0.5, 0.0, 1.0]));
        assert_eq!(all[3].switch(), Some(false));
        assert_eq!(&text[all[0].value_offset..all[0].value_offset + 4], "2048");
    }
}
