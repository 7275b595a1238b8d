//! Stable names for what a diagnostic is about, so a pack author can allow or deny each kind
//! (`--allow unknown-uniform`) the way compilers' and linters' lint names work. A name, once
//! released, keeps its meaning; docs/diagnostics.md lists them all (written from this table by
//! `tidepack codes --markdown`).

use std::fmt;

macro_rules! codes {
    ($($variant:ident $name:literal $summary:literal,)*) => {
        /// What a diagnostic is about. Each has a kebab-case name and a one-line summary.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum Code {
            $($variant,)*
        }

        impl Code {
            /// Every code, in the order docs list them.
            pub const ALL: &'static [Code] = &[$(Code::$variant,)*];

            pub const fn name(self) -> &'static str {
                match self {
                    $(Code::$variant => $name,)*
                }
            }

            pub const fn summary(self) -> &'static str {
                match self {
                    $(Code::$variant => $summary,)*
                }
            }
        }
    };
}

codes! {
    // What a compiler or linker refuses.
    Glsl "glsl" "the GLSL compiler refuses the stage: a type, a name or a construct it does not accept",
    Syntax "syntax" "a syntax error GLSL compilers report that naga's parser lets by",
    ReservedWord "reserved-word" "a word GLSL reserves (such as `output` or `input`) names a variable or function",
    MissingReturn "missing-return" "a function with a return type has no `return` statement",
    InputWritten "input-written" "a shader assigns to one of its own inputs, which are read-only",
    NoMatchingOverload "no-matching-overload" "a built-in function is called with arguments none of its overloads takes",
    MixedOutputs "mixed-outputs" "a fragment shader writes both gl_FragColor/gl_FragData and its own `out` variables",
    Version "version" "a `#version` line a driver refuses, or one above what the configuration's driver compiles",
    VersionFeature "version-feature" "a built-in or construct that the stage's `#version` does not have",
    ConstInitializer "const-initializer" "a `const` initialised from something that is not a constant expression (outside functions, or inside them before GLSL 4.20)",
    HiddenBuiltin "hidden-builtin" "a variable hides a built-in function of the same name, which is then called",
    ImplicitConversion "implicit-conversion" "an implicit conversion the stage's GLSL version does not have (int to uint before 4.00)",
    EmptyDeclaration "empty-declaration" "a `;` after a function body, which GLSL allows only from 4.60 on",
    Extension "extension" "an `#extension` line naming an extension no driver has, or a behaviour it does not take",
    Macos "macos" "what macOS's OpenGL 4.1 refuses: compute, storage blocks, images, `#version` above 410",
    NoGlPosition "no-gl-position" "a vertex shader never writes gl_Position",
    Link "link" "the stages of a program do not link: an input no output matches, or one declared differently",
    InputUndeclared "input-undeclared" "a fragment input is read that the vertex shader does not declare",
    InputNeverWritten "input-never-written" "a fragment input is read that the vertex shader declares but never writes",
    UninitialisedRead "uninitialised-read" "a local variable is read but nothing ever assigns it: its value is undefined",
    DrawBuffers "draw-buffers" "a DRAWBUFFERS/RENDERTARGETS list that does not match what the shader writes",
    Driver "driver" "the real OpenGL driver (`--driver`) refuses a stage or a program",
    // What the loader does that the pack does not expect.
    UnknownUniform "unknown-uniform" "a uniform no loader sets and shaders.properties does not define: it reads 0",
    UniformType "uniform-type" "a uniform declared with another type than the loader or shaders.properties gives it",
    UnknownSampler "unknown-sampler" "a sampler the loader binds nothing to: it reads texture unit 0",
    UnknownImage "unknown-image" "an image uniform the loader binds nothing to",
    UndefinedInIf "undefined-in-if" "a macro `#if` reads that is not defined there: it reads as 0",
    FloatInIf "float-in-if" "a number with a fraction or an exponent in `#if`, which Iris reads as its integer part and drivers refuse",
    Properties "properties" "a line of shaders.properties the loader cannot use",
    Profile "profile" "a profile that names something missing, sets a value an option does not have, or loops",
    // What the pack is, as files.
    PackInput "pack-input" "the pack, or one of its files, cannot be read (a damaged zip, a missing include)",
    Preprocessor "preprocessor" "the preprocessor refuses a directive: `#include`, `#if`, `#error`, a macro",
    BadUtf8 "bad-utf8" "a file that is not valid UTF-8; the loader reads its bad bytes as U+FFFD",
    SkippedFile "skipped-file" "a file of the pack that is not read (too large, or not a regular file)",
    DuplicateEntry "duplicate-entry" "a zip holding two entries of the same name, of which the loader reads the last",
    // What tidepack could or did not check.
    NotCompiled "not-compiled" "a stage that is only preprocessed: naga, or the OpenGL driver, has no such stage",
    NotChecked "not-checked" "a construct or a stage naga cannot check (valid GLSL it does not implement, or a naga crash)",
    Budget "budget" "an input larger than a budget of tidepack's (profiles, globals), so part of it is not checked",
    DriverAccepts "driver-accepts" "the OpenGL driver accepts a program in which tidepack reports errors",
    NothingValidated "nothing-validated" "no program the loader runs was found, so nothing was checked",
    Usage "usage" "a command-line value, or a `--cache` folder, that cannot be used",
    // tidepack's own pack sources (`tidepack build`).
    Template "template" "a mistake in a pack's template sources or pack.toml",
    UnusedOption "unused-option" "an option that changes no program's text",
    UncheckedProperty "unchecked-property" "a pack.toml property that goes into shaders.properties unchecked",
}

impl Code {
    /// The code named `name`, or a message listing the codes that exist.
    pub fn parse(name: &str) -> Result<Code, String> {
        let name = name.trim();
        if let Some(code) = Code::ALL.iter().find(|c| c.name() == name) {
            return Ok(*code);
        }
        let close: Vec<&str> = Code::ALL.iter().map(|c| c.name()).filter(|n| n.contains(name) || name.contains(n)).collect();
        let hint = if close.is_empty() { String::new() } else { format!(" (did you mean {}?)", close.join(" or ")) };
        Err(format!(
            "no diagnostic code `{}`{hint}; `tidepack codes` lists them",
            crate::terminal::line(name)
        ))
    }
}

/// docs/diagnostics.md: what a code is for, how to allow or deny one, and every code.
pub fn reference_page() -> String {
    let mut page = String::from(
        "# Diagnostic codes\n\n\
         <!-- Written by `tidepack codes --markdown` from crates/glsl/src/code.rs; a test fails when they differ. -->\n\n\
         Every diagnostic `tidepack validate` and `tidepack build` print has a code, shown as\n\
         `warning[unknown-uniform]: …`, in the JSON report's `code` and in GitHub annotations' titles.\n\
         A code keeps its meaning from release to release.\n\n\
         A warning can be left out (`--allow CODE`) or made an error that fails the check (`--deny CODE`),\n\
         on the command line or in a `tidepack.toml` beside the pack (or in the folder `validate` runs in):\n\n\
         ```toml\n[validate]\nallow = [\"unknown-uniform\"]\ndeny = [\"input-never-written\"]\n```\n\n\
         The command line goes over the file. Errors cannot be allowed: an error is what a target driver\n\
         refuses, and `--target` chooses the drivers (an error only other drivers refuse is a warning of\n\
         the same code). The summary line counts what was found by code, and what was allowed.\n\n\
         | code | what it is about |\n|---|---|\n",
    );
    for code in Code::ALL {
        page.push_str(&format!("| `{}` | {} |\n", code.name(), code.summary()));
    }
    page
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_kebab_case_and_parse_back() {
        let mut seen = std::collections::HashSet::new();
        for code in Code::ALL {
            let name = code.name();
            assert!(seen.insert(name), "{name} twice");
            assert!(name.bytes().all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-'), "{name}");
            assert_eq!(Code::parse(name), Ok(*code));
            assert!(!code.summary().is_empty() && !code.summary().ends_with('.'), "{name}");
        }
    }

    #[test]
    fn the_docs_page_is_the_one_this_table_writes() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/diagnostics.md");
        let written = std::fs::read_to_string(path).unwrap_or_default();
        assert!(written == reference_page(), "docs/diagnostics.md is out of date: run `cargo run -- docs`");
    }

    #[test]
    fn an_unknown_name_lists_where_to_look_and_the_close_ones() {
        let err = Code::parse("uniform").unwrap_err();
        assert!(err.contains("unknown-uniform") && err.contains("uniform-type") && err.contains("tidepack codes"), "{err}");
        let err = Code::parse("nope\u{1b}[2J").unwrap_err();
        assert!(!err.contains('\u{1b}'), "{err}");
    }
}
