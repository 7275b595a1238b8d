//! Snapshot tests of the lowering, in the style of naga's own tests.
//!
//! Every program in `tests/lowering/in` (a `<name>.vsh` and/or `<name>.fsh`; when both exist
//! they are lowered together and share the varying layout) is preprocessed with no predefined
//! macros, lowered with `naga_check::lower_program`, and checked:
//!
//! 1. the lowered text equals `tests/lowering/out/<name>.<vsh|fsh>.glsl` exactly;
//! 2. it has exactly as many lines as the preprocessed text (the lowering is line-preserving);
//! 3. naga parses and validates it;
//! 4. every file in `tests/lowering/out` belongs to an input.
//!
//! After a deliberate change to the lowering, regenerate the expected outputs with
//!
//! ```text
//! TIDEPACK_BLESS=1 cargo test -p tidepack-glsl --test lowering_snapshots
//! ```
//!
//! and review the diff of `tests/lowering/out` like any other change. Blessing writes the
//! actual texts instead of comparing them; the other checks still apply.
//!
//! Inputs that expose a lowering bug are kept out of `in/` and described, with the error and a
//! diagnosis, in `tests/lowering/known-failures.md`.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use naga::front::glsl::Frontend;
use tidepack_glsl::preprocess::{self, PreprocessOptions, Preprocessed};
use tidepack_glsl::naga_check::{self, LoweredStage};
use tidepack_glsl::{Diagnostic, Stage};

type Files = HashMap<String, Arc<str>>;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/lowering")
}

/// Whether to rewrite the snapshots: `TIDEPACK_BLESS` set to anything but empty or `0`, the rule
/// every test that reads it follows (docs/ARCHITECTURE.md, "Tests").
fn blessing() -> bool {
    std::env::var("TIDEPACK_BLESS").is_ok_and(|v| !v.is_empty() && v != "0")
}

fn extension(stage: Stage) -> &'static str {
    match stage {
        Stage::Vertex => "vsh",
        Stage::Fragment => "fsh",
    }
}

/// The programs of `in/`: base name → stage files (relative to `in/`), vertex first.
fn programs(input_dir: &Path, problems: &mut Vec<String>) -> BTreeMap<String, Vec<(Stage, String)>> {
    let mut programs: BTreeMap<String, Vec<(Stage, String)>> = BTreeMap::new();
    let entries = std::fs::read_dir(input_dir).unwrap_or_else(|e| panic!("cannot read {}: {e}", input_dir.display()));
    for entry in entries {
        let name = entry.unwrap().file_name().into_string().expect("UTF-8 file name");
        let stage = Stage::from_path(&name);
        match (stage, name.rsplit_once('.')) {
            (Some(stage), Some((base, _))) => programs.entry(base.to_string()).or_default().push((stage, name)),
            _ => problems.push(format!("in/{name}: not a .vsh or .fsh file")),
        }
    }
    for stages in programs.values_mut() {
        stages.sort();
    }
    programs
}

/// Lowers one program; the files are keyed by their names in `in/` (the paths diagnostics show).
fn lower(stages: &[(Stage, String)], files: &Files) -> Result<Vec<LoweredStage>, String> {
    let mut preprocessed = Vec::new();
    for (stage, path) in stages {
        let pre = preprocess::preprocess(files, path, &PreprocessOptions::default())
            .map_err(|d| format!("preprocessing failed: {d}"))?;
        preprocessed.push((*stage, Arc::new(pre)));
    }
    naga_check::lower_program(&preprocessed).map_err(|d| format!("lowering failed: {d}"))
}

fn line_breaks(text: &str) -> usize {
    text.bytes().filter(|&b| b == b'\n').count()
}

/// A line diff of `expected` against `actual` (the `similar` crate) with `CONTEXT` lines around
/// each change: `-` lines are expected only, `+` lines actual only; each hunk starts with the
/// line numbers where it starts on either side.
fn line_diff(expected: &str, actual: &str) -> String {
    const CONTEXT: usize = 2;
    let a: Vec<&str> = expected.split('\n').collect();
    let b: Vec<&str> = actual.split('\n').collect();
    let diff = similar::TextDiff::configure().diff_slices(&a, &b);
    let mut out = String::new();
    for hunk in diff.grouped_ops(CONTEXT) {
        let Some(first) = hunk.first() else { continue };
        let (el, al) = (first.old_range().start + 1, first.new_range().start + 1);
        writeln!(out, "@@ expected line {el}, actual line {al} @@").unwrap();
        for change in hunk.iter().flat_map(|op| diff.iter_changes(op)) {
            writeln!(out, "{}{}", change.tag(), change.value()).unwrap();
        }
    }
    out
}

fn show(diagnostics: &[Diagnostic]) -> String {
    diagnostics.iter().map(|d| format!("\n    {d}")).collect()
}

#[test]
fn lowering_snapshots() {
    let root = root();
    let (input_dir, output_dir) = (root.join("in"), root.join("out"));
    let bless = blessing();
    let mut problems = Vec::new();
    let programs = programs(&input_dir, &mut problems);
    assert!(!programs.is_empty(), "no inputs in {}", input_dir.display());
    let mut expected_outputs = std::collections::BTreeSet::new();
    let mut checked = 0;

    for (name, stages) in &programs {
        let mut files = Files::new();
        for (_, path) in stages {
            let text = std::fs::read_to_string(input_dir.join(path)).unwrap();
            files.insert(path.clone(), Arc::from(text));
        }
        for (stage, _) in stages {
            expected_outputs.insert(format!("{name}.{}.glsl", extension(*stage)));
        }
        let lowered = match lower(stages, &files) {
            Ok(lowered) => lowered,
            Err(e) => {
                problems.push(format!("{name}: {e}"));
                continue;
            }
        };
        let mut frontend = Frontend::default();
        for stage in &lowered {
            let out_name = format!("{name}.{}.glsl", extension(stage.stage));
            let actual = &stage.lowered.text;
            let pre: &Preprocessed = &stage.preprocessed;
            checked += 1;

            // (1) The snapshot.
            let out_path = output_dir.join(&out_name);
            if bless {
                let unchanged = std::fs::read_to_string(&out_path).is_ok_and(|old| old == *actual);
                if !unchanged {
                    std::fs::create_dir_all(&output_dir).unwrap();
                    std::fs::write(&out_path, actual).unwrap();
                    eprintln!("blessed out/{out_name}");
                }
            } else {
                match std::fs::read_to_string(&out_path) {
                    Ok(expected) if expected == *actual => {}
                    Ok(expected) => problems.push(format!(
                        "out/{out_name}: the lowered text differs from the snapshot \
                         (-expected +actual; TIDEPACK_BLESS=1 to accept):\n{}",
                        line_diff(&expected, actual)
                    )),
                    Err(e) => problems.push(format!(
                        "out/{out_name}: no snapshot ({e}); TIDEPACK_BLESS=1 writes it. Lowered text:\n{actual}"
                    )),
                }
            }

            // (2) The line-preserving invariant.
            let (pre_lines, lowered_lines) = (line_breaks(&pre.text), line_breaks(actual));
            if pre_lines != lowered_lines || pre.text.lines().count() != actual.lines().count() {
                problems.push(format!(
                    "{out_name}: the lowering changed the line count: {} lines preprocessed ({pre_lines} breaks), \
                     {} lowered ({lowered_lines} breaks)",
                    pre.text.lines().count(),
                    actual.lines().count(),
                ));
            }

            // (3) naga accepts it.
            if let Err(diagnostics) = naga_check::validate_stage(&mut frontend, stage, &files) {
                problems.push(format!("{out_name}: naga rejects the lowered text:{}", show(&diagnostics)));
            }
        }
    }

    // (4) No orphaned snapshots.
    if let Ok(entries) = std::fs::read_dir(&output_dir) {
        for entry in entries {
            let file = entry.unwrap().file_name().into_string().expect("UTF-8 file name");
            if !expected_outputs.contains(&file) {
                problems
                    .push(format!("out/{file}: no input in in/ produces this file; delete it or restore its input"));
            }
        }
    }

    assert!(
        problems.is_empty(),
        "{} problem(s) in {} lowered stages of {} programs:\n\n{}",
        problems.len(),
        checked,
        programs.len(),
        problems.join("\n\n")
    );
}

/// Preprocesses, lowers and validates a program given as in-memory files: every `.vsh`/`.fsh`
/// is a stage of the program, other files are only there to be included. Returns naga's
/// diagnostics.
fn naga_errors(files: &[(&str, &str)]) -> Vec<Diagnostic> {
    let map: Files = files.iter().map(|(p, t)| (p.to_string(), Arc::from(*t))).collect();
    let stages: Vec<(Stage, String)> =
        files.iter().filter_map(|(p, _)| Some((Stage::from_path(p)?, p.to_string()))).collect();
    let lowered = lower(&stages, &map).unwrap();
    let mut frontend = Frontend::default();
    let mut errors = Vec::new();
    for stage in &lowered {
        if let Err(d) = naga_check::validate_stage(&mut frontend, stage, &map) {
            errors.extend(d);
        }
    }
    errors
}

fn assert_error_at(errors: &[Diagnostic], path: &str, line: u32, needle: &str) {
    assert!(!errors.is_empty(), "naga accepted a program with a planted error");
    let found = errors.iter().any(|d| {
        d.is_error()
            && d.location.as_ref().is_some_and(|l| l.path == path && l.line == line)
            && d.message.to_lowercase().contains(&needle.to_lowercase())
    });
    assert!(found, "expected an error mentioning `{needle}` at {path}:{line}; got:{}", show(errors));
}

/// An undeclared identifier on line 7 of a `#version 120` fragment shader, below lines the
/// lowering rewrites (a loose uniform, a varying, a combined sampler, `gl_FragData`).
#[test]
fn undeclared_identifier_is_reported_at_its_source_line() {
    let fsh = "\
#version 120
#extension GL_ARB_shader_texture_lod : enable
uniform sampler2D texture;
uniform float rainStrength;
varying vec2 texcoord;
void main() {
    vec4 color = texture2D(texture, texcoord) * wetnesss;
    /* DRAWBUFFERS:0 */
    gl_FragData[0] = color * (1.0 - rainStrength);
}
";
    let errors = naga_errors(&[("gbuffers_textured.fsh", fsh)]);
    assert_error_at(&errors, "gbuffers_textured.fsh", 7, "wetnesss");
    let error = errors.iter().find(|d| d.message.contains("wetnesss")).unwrap();
    // The column narrows to the identifier, which occurs once on the original line.
    let columns = error.location.as_ref().unwrap().columns.clone();
    let line = fsh.lines().nth(6).unwrap();
    assert_eq!(columns.map(|c| &line[c]), Some("wetnesss"), "{error}");
}

/// A `vec4` passed for a `vec3` parameter (the old `texture2D` returns a `vec4`): naga's
/// frontend finds no matching overload and reports the call at its source line.
#[test]
fn argument_type_mismatch_is_reported_at_its_source_line() {
    let fsh = "\
#version 120

uniform sampler2D colortex0;
varying vec2 texcoord;

float luma(vec3 color) {
    return dot(color, vec3(0.2126, 0.7152, 0.0722));
}

void main() {
    float brightness = luma(texture2D(colortex0, texcoord));
    gl_FragColor = vec4(vec3(brightness), 1.0);
}
";
    let errors = naga_errors(&[("composite2.fsh", fsh)]);
    assert_error_at(&errors, "composite2.fsh", 11, "luma");
}

/// A `vec4` assigned to a `vec3`, in a vertex stage with legacy inputs; the program's fragment
/// stage is valid. naga's frontend accepts the store and its validator rejects it.
#[test]
fn assignment_type_mismatch_is_reported_at_its_source_line() {
    let vsh = "\
#version 120
varying vec2 texcoord;
varying vec3 tint;
uniform sampler2D noisetex;

void main() {
    gl_Position = ftransform();
    texcoord = gl_MultiTexCoord0.st;
    tint = texture2DLod(noisetex, texcoord, 0.0);
}
";
    let fsh = "\
#version 120
varying vec2 texcoord;
varying vec3 tint;
void main() {
    gl_FragColor = vec4(tint, 1.0);
}
";
    let errors = naga_errors(&[("shadow.vsh", vsh), ("shadow.fsh", fsh)]);
    assert!(errors.iter().all(|d| d.location.as_ref().is_some_and(|l| l.path == "shadow.vsh")), "{}", show(&errors));
    let at_line_9 = errors.iter().any(|d| d.location.as_ref().is_some_and(|l| l.line == 9));
    assert!(at_line_9, "expected the type mismatch at shadow.vsh:9; got:{}", show(&errors));
}

/// An error in an included file is reported in that file, at its own line, not at the line of
/// the preprocessed text (which is shifted by the including file's lines).
#[test]
fn error_in_an_included_file_names_that_file() {
    let fsh = "\
#version 330 compatibility

#include \"/lib/fog.glsl\"

in vec2 texcoord;
uniform sampler2D colortex0;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 outColor0;
void main() {
    vec3 color = texture(colortex0, texcoord).rgb;
    outColor0 = vec4(applyFog(color, 0.5), 1.0);
}
";
    let fog = "\
uniform vec3 fogColor;

vec3 applyFog(vec3 color, float depth) {
    float amount = clamp(depth * fogDensity, 0.0, 1.0);
    return mix(color, fogColor, amount);
}
";
    let errors = naga_errors(&[("composite.fsh", fsh), ("lib/fog.glsl", fog)]);
    assert_error_at(&errors, "lib/fog.glsl", 4, "fogdensity");
}

#[test]
fn line_diff_marks_changed_lines() {
    let diff = line_diff("a\nb\nc\nd\n", "a\nB\nc\nd\n");
    assert_eq!(diff, "@@ expected line 1, actual line 1 @@\n a\n-b\n+B\n c\n d\n");
}
