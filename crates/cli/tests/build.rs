//! End-to-end tests of `tidepack build` on the repository's pack, as a user runs it.

use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Arc;

use tidepack_glsl::preprocess::expand_includes;
use tidepack_loader::macros::StandardMacros;
use tidepack_loader::programs;
use tidepack_pack::dialect::Dialect;
use tidepack_pack::shipped::ShippedPack;
use tidepack_pack::source::PackSource;
use tidepack_pack::{option_sets, pack_options};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

fn tidepack(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tidepack")).args(args).current_dir(cwd).output().expect("run tidepack")
}

fn build_into(source: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["build", "--source", source.to_str().unwrap(), "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    tidepack(&args, &repo_root())
}

fn zip_entries(path: &Path) -> HashMap<String, String> {
    let mut archive = zip::ZipArchive::new(std::fs::File::open(path).unwrap()).unwrap();
    (0..archive.len())
        .map(|i| {
            let mut file = archive.by_index(i).unwrap();
            let mut bytes = Vec::new();
            file.read_to_end(&mut bytes).unwrap();
            (file.name().unwrap().to_string(), String::from_utf8_lossy(&bytes).into_owned())
        })
        .collect()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn build_writes_one_zip_per_dialect_in_the_optifine_layout() {
    let out = tempfile::tempdir().unwrap();
    let output = build_into(&repo_root().join("shaderpack"), out.path(), &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    let summary = String::from_utf8_lossy(&output.stdout);
    assert!(summary.contains("option sets") && summary.contains("skipped as identical"), "{summary}");
    for (dialect, version) in [("glsl120", "#version 120"), ("glsl330", "#version 330 compatibility")] {
        let zip = out.path().join(format!("Tidepack-0.1.0-{dialect}.zip"));
        let entries = zip_entries(&zip);
        let mut names: Vec<&str> = entries.keys().map(String::as_str).collect();
        names.sort();
        for required in [
            "shaders/shaders.properties",
            "shaders/block.properties",
            "shaders/lang/en_us.lang",
            "shaders/gbuffers_water.vsh",
            "shaders/gbuffers_water.fsh",
            "shaders/dh_terrain.vsh",
            "shaders/dh_terrain.fsh",
            "shaders/dh_water.vsh",
            "shaders/dh_water.fsh",
            "shaders/composite.vsh",
            "shaders/composite.fsh",
            "shaders/lib/generated.glsl",
            "shaders/textures/water.png",
            "shaders/textures/water.png.mcmeta",
        ] {
            assert!(names.contains(&required), "{dialect}: {required} missing from {names:?}");
        }
        assert!(names.iter().all(|n| n.starts_with("shaders/")), "{names:?}");
        // What OptiFine needs to draw the water at all (docs/loaders.md): no alpha test on the
        // translucent layer, whose colortex0 alpha is 0, and noisetex bound where it is read.
        let properties = &entries["shaders/shaders.properties"];
        assert!(properties.lines().any(|l| l.trim() == "alphaTest.gbuffers_water=off"), "{dialect}: {properties}");
        // One program-wide blend mode: OptiFine before 1.16.5 and Iris without OpenGL 4.0 have
        // no per-buffer blending, and would draw no water with it.
        assert!(properties.lines().any(|l| l.trim() == "blend.gbuffers_water=SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO"), "{dialect}: {properties}");
        assert!(properties.lines().any(|l| l.trim() == "blend.dh_water=SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO"), "{dialect}: {properties}");
        assert!(!properties.lines().any(|l| l.starts_with("blend.") && l.split('=').next().unwrap().split('.').count() == 3), "{dialect}: {properties}");
        let water_vertex = &entries["shaders/gbuffers_water.vsh"];
        assert!(water_vertex.lines().any(|l| l.trim() == "attribute vec4 mc_Entity;"), "{dialect}: OptiFine <= 1.16.5 would not bind mc_Entity");
        let composite = &entries["shaders/composite.fsh"];
        if composite.contains("uniform sampler2D noisetex;") {
            assert!(composite.contains("const int noiseTextureResolution"), "{dialect}: noisetex is never bound on OptiFine");
        }
        // OptiFine shows a lang value as written, Iris reads it as Java properties: no escapes.
        let lang = &entries["shaders/lang/en_us.lang"];
        assert!(!lang.contains('\\'), "{dialect}: a backslash OptiFine would show: {lang}");
        assert!(lang.contains("=\u{a0}blocks"), "{dialect}: the unit's leading space must survive Iris: {lang}");
        for (name, text) in &entries {
            if name.ends_with(".vsh") || name.ends_with(".fsh") {
                assert_eq!(text.lines().next(), Some(version), "{name}");
                assert!(text.lines().nth(1).unwrap().contains("Generated by tidepack"), "{name}");
            }
        }
        let properties = &entries["shaders/shaders.properties"];
        assert!(properties.contains("profile.LOW=") && properties.contains("profile.HIGH="), "{properties}");
        let blocks = &entries["shaders/block.properties"];
        assert!(blocks.contains("block.10008=minecraft:water minecraft:flowing_water"), "{blocks}");
        let fsh = &entries["shaders/gbuffers_water.fsh"];
        match dialect {
            "glsl120" => assert!(fsh.contains("/* DRAWBUFFERS:0456 */") && fsh.contains("gl_FragData[3]"), "{fsh}"),
            // Every OptiFine reads DRAWBUFFERS; before 1.16.5 G8 only an explicit location binds outColorN.
            _ => assert!(fsh.contains("/* DRAWBUFFERS:0456 */") && fsh.contains("layout(location = 3) out vec4 outColor3;"), "{fsh}"),
        }
    }
}

#[test]
fn identical_inputs_give_byte_identical_zips() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let source = repo_root().join("shaderpack");
    assert!(build_into(&source, a.path(), &["--dialect", "120"]).status.success());
    assert!(build_into(&source, b.path(), &["--dialect", "120"]).status.success());
    let name = "Tidepack-0.1.0-glsl120.zip";
    assert_eq!(std::fs::read(a.path().join(name)).unwrap(), std::fs::read(b.path().join(name)).unwrap());
    assert!(!a.path().join("Tidepack-0.1.0-glsl330.zip").exists(), "--dialect 120 builds only 120");
}

#[test]
fn profile_sets_the_shipped_defaults() {
    let out = tempfile::tempdir().unwrap();
    let output = build_into(&repo_root().join("shaderpack"), out.path(), &["--profile", "LOW", "--dialect", "330"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let entries = zip_entries(&out.path().join("Tidepack-0.1.0-glsl330.zip"));
    let settings = &entries["shaders/lib/settings.glsl"];
    assert!(settings.contains("//#define CAUSTICS //"), "{settings}");
    assert!(settings.contains("#define WAVE_REFINE_STEPS 0 //"), "{settings}");
    assert!(settings.contains("//#define REFLECTIONS //"), "{settings}");
    let output = build_into(&repo_root().join("shaderpack"), out.path(), &["--profile", "NOPE"]);
    assert_eq!(output.status.code(), Some(2), "an unknown profile is a usage error");
    assert!(stderr(&output).contains("no profile named NOPE"), "{}", stderr(&output));
}

/// glslangValidator, the Khronos reference front-end, compiles every shipped stage of both
/// dialects under every profile, after OptiFine-style include expansion, with the macros (and
/// the declarations) of each loader that runs it: OptiFine, and Iris with Distant Horizons.
#[test]
fn glslang_accepts_every_shipped_stage() {
    let glslang = which("glslangValidator").expect(
        "glslangValidator is missing: install the Debian package glslang-tools (tools/test does this)",
    );
    let source = PackSource::load(&repo_root().join("shaderpack")).unwrap();
    let options = pack_options::collect(&source).unwrap();
    let work = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for profile in source.manifest.profiles.iter().map(|p| p.name.clone()) {
        let defaults = pack_options::profile_set(&source, &options, &profile).unwrap();
        for dialect in Dialect::ALL {
            let pack = ShippedPack::generate(&source, &options, dialect, &defaults).unwrap();
            let files: HashMap<String, Arc<str>> = pack.files.iter().map(|(k, v)| (k.clone(), v.text.clone())).collect();
            for (_, macros, loader, distant_horizons) in option_sets::loaders() {
                let macros = macros.define_lines();
                for program in pack.programs() {
                    let name = program.name.rsplit('/').next().unwrap();
                    if !programs::runs_with(name, loader, distant_horizons) {
                        continue;
                    }
                    for (stage, path) in &program.stages {
                        let expanded = expand_includes(&files, path, &macros).unwrap();
                        let text = programs::with_loader_declarations(name, *stage == tidepack_glsl::Stage::Vertex, &expanded);
                        let file = work.path().join(format!("{profile}-{}-{}-{}", dialect.slug(), loader.name(), path.replace('/', "_")));
                        std::fs::write(&file, text.as_bytes()).unwrap();
                        let kind = if *stage == tidepack_glsl::Stage::Vertex { "vert" } else { "frag" };
                        let result = Command::new(&glslang).args(["-S", kind]).arg(&file).output().unwrap();
                        assert!(
                            result.status.success(),
                            "glslangValidator rejects {path} ({dialect}, profile {profile}):\n{}\n{text}",
                            String::from_utf8_lossy(&result.stdout)
                        );
                        checked += 1;
                    }
                }
            }
        }
    }
    // gbuffers_water, the six programs that draw as the game does (basic, textured,
    // textured_lit, weather, clouds, hand_water), composite and the Nether's and the End's
    // composites, two stages each; under Iris with Distant Horizons also dh_terrain (at the
    // root, in the Nether, in the End) and dh_water.
    assert_eq!(checked, source.manifest.profiles.len() * Dialect::ALL.len() * (10 + 14) * 2);
}

fn which(program: &str) -> Option<PathBuf> {
    std::env::var_os("PATH")?.to_str()?.split(':').map(|d| Path::new(d).join(program)).find(|p| p.is_file())
}

/// Copies the pack's sources to a temporary folder, applies `edit` to one template and
/// builds; returns the build's output and the folder the zips would go to.
fn build_mutated(template: &str, edit: impl Fn(&str) -> String) -> (Output, tempfile::TempDir, PathBuf) {
    let work = tempfile::tempdir().unwrap();
    let source = work.path().join("pack");
    copy_dir(&repo_root().join("shaderpack"), &source);
    let file = source.join("shaders").join(template);
    let text = std::fs::read_to_string(&file).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text, "the mutation must change {template}");
    std::fs::write(&file, edited).unwrap();
    let out = work.path().join("dist");
    let output = build_into(&source, &out, &[]);
    (output, work, file)
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

fn line_containing(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).unwrap_or_else(|| panic!("`{needle}` not in template")) + 1
}

/// Each planted mistake is reported at the template's own file and line, and nothing is zipped.
#[test]
fn mistakes_in_templates_are_reported_at_the_template_line_and_no_zip_is_written() {
    struct Mutation {
        template: &'static str,
        anchor: &'static str,
        replace: (&'static str, &'static str),
        message: &'static str,
    }
    let mutations = [
        Mutation {
            template: "composite.fsh",
            anchor: "float distance0 = length(view0);",
            replace: ("float distance0 = length(view0);", "float distance0 = length(viewZero);"),
            message: "viewZero",
        },
        Mutation {
            template: "lib/caustics.glsl",
            anchor: "vec3 c = clamp(1.0 - abs(a + b - 1.0), 0.0, 1.0);",
            replace: ("vec3 c = clamp(1.0 - abs(a + b - 1.0), 0.0, 1.0);", "vec3 c = clamp(1.0 - abs(a + b - 1.0), 0.0, 1.0) + vec2(1.0);"),
            message: "error",
        },
        Mutation {
            template: "gbuffers_water.vsh",
            anchor: "tint = gl_Color;",
            replace: ("tint = gl_Color;", "tint = gl_Color"),
            message: "error",
        },
        Mutation {
            template: "gbuffers_water.fsh",
            anchor: "#include \"/lib/translucent.glsl\"",
            replace: ("#include \"/lib/translucent.glsl\"", "#include \"/lib/missing.glsl\""),
            message: "cannot include `lib/missing.glsl`",
        },
        Mutation {
            template: "composite.fsh",
            anchor: "float cosView = clamp(dot(-rayDir, normal), 0.0, 1.0);",
            replace: ("float cosView = clamp(dot(-rayDir, normal), 0.0, 1.0);", "float cosView = clamp(dot(-rayDir, normal.xy), 0.0, 1.0);"),
            message: "error",
        },
        Mutation {
            template: "composite.fsh",
            anchor: "outColor0 = vec4(scene.rgb, 1.0);",
            replace: ("outColor0 = vec4(scene.rgb, 1.0);", "outColor0 = scene.rgb;"),
            message: "error",
        },
    ];
    for m in mutations {
        let (output, _work, file) = build_mutated(m.template, |t| t.replacen(m.replace.0, m.replace.1, 1));
        let original = std::fs::read_to_string(repo_root().join("shaderpack/shaders").join(m.template)).unwrap();
        let line = line_containing(&original, m.anchor);
        let err = stderr(&output);
        assert!(!output.status.success(), "{}: the build should fail", m.template);
        let expected = format!("{}:{line}", file.display());
        assert!(err.contains(&expected), "{}: expected a diagnostic at {expected}:\n{err}", m.template);
        assert!(err.contains(m.message), "{}: expected `{}` in:\n{err}", m.template, m.message);
        assert!(err.contains("no zip was written"), "{err}");
        assert!(!_work.path().join("dist").exists(), "{}: a failed build wrote output", m.template);
    }
}

/// An error that only some option values reach names those options.
#[test]
fn errors_under_non_default_options_name_the_options() {
    let (output, _work, file) = build_mutated("composite.fsh", |t| {
        t.replacen("#else\n    return lit;\n#endif", "#else\n    return unlit;\n#endif", 1)
    });
    let err = stderr(&output);
    assert!(!output.status.success());
    assert!(err.contains(&file.display().to_string()), "{err}");
    assert!(err.contains("CAUSTICS=off"), "the note should name the option set: {err}");
    // Only the option the error needs, not the rest of the set that first showed it.
    let notes: Vec<&str> = err.lines().filter(|l| l.contains("= with ")).collect();
    assert!(!notes.is_empty() && notes.iter().all(|l| l.trim() == "= with options CAUSTICS=off"), "{err}");
}

/// An error in an included file names the programs that include it, and through what.
#[test]
fn errors_in_included_files_name_the_including_program() {
    let (output, _work, _) = build_mutated("lib/caustics.glsl", |t| {
        t.replacen("vec3 c = clamp(1.0 - abs(a + b - 1.0), 0.0, 1.0);", "vec3 c = clamp(1.0 - abs(a + b - 1.0), 0.0, 1.0) + vec2(1.0);", 1)
    });
    let err = stderr(&output);
    assert!(!output.status.success());
    assert!(err.contains("included by program composite: composite.fsh includes lib/caustics.glsl"), "{err}");
}

/// An option no program's text depends on is built with a warning.
#[test]
fn an_option_no_program_reads_is_warned_about() {
    let work = tempfile::tempdir().unwrap();
    let source = work.path().join("pack");
    copy_dir(&repo_root().join("shaderpack"), &source);
    let settings = source.join("shaders/lib/settings.glsl");
    let text = std::fs::read_to_string(&settings).unwrap();
    std::fs::write(&settings, format!("{text}#define UNUSED_KNOB 2 // [1 2 3] Reads nowhere.\n")).unwrap();
    let manifest = source.join("pack.toml");
    let mut toml = std::fs::read_to_string(&manifest).unwrap();
    toml = toml.replacen("\"EARLY_OUTS\"]", "\"EARLY_OUTS\", \"UNUSED_KNOB\"]", 1);
    toml = toml.replace("EARLY_OUTS = true\n", "EARLY_OUTS = true\nUNUSED_KNOB = \"2\"\n");
    toml.push_str("\n[options.UNUSED_KNOB]\nlabel = \"Unused\"\ncomment = \"Nothing reads it.\"\n");
    std::fs::write(&manifest, toml).unwrap();
    let output = build_into(&source, &work.path().join("dist"), &[]);
    let err = stderr(&output);
    assert!(output.status.success(), "{err}");
    let line = text.lines().count() + 1;
    assert!(err.contains("option UNUSED_KNOB changes no program"), "{err}");
    assert!(err.contains(&format!("settings.glsl:{line}")), "{err}");
    assert!(!err.contains("option EARLY_OUTS changes no program"), "{err}");
}

#[test]
fn bad_manifests_and_missing_sources_are_clear_errors() {
    let out = tempfile::tempdir().unwrap();
    let output = build_into(Path::new("/nonexistent/pack"), out.path(), &[]);
    assert_eq!(output.status.code(), Some(2));
    let err = stderr(&output);
    assert!(err.contains("/nonexistent/pack holds no pack.toml") && err.contains("--source PATH"), "{err}");

    let work = tempfile::tempdir().unwrap();
    let source = work.path().join("pack");
    copy_dir(&repo_root().join("shaderpack"), &source);
    let manifest = source.join("pack.toml");
    let text = std::fs::read_to_string(&manifest).unwrap();
    std::fs::write(&manifest, text.replacen("columns = 2", "columns = two", 1)).unwrap();
    let output = build_into(&source, out.path(), &[]);
    let err = stderr(&output);
    assert!(!output.status.success());
    let line = line_containing(&text, "columns = 2");
    assert!(err.contains(&format!("pack.toml:{line}")), "{err}");

    std::fs::write(&manifest, text.replacen("label = \"Caustics\"\n", "", 1)).unwrap();
    let err = stderr(&build_into(&source, out.path(), &[]));
    assert!(err.contains("label"), "{err}");

    std::fs::write(&manifest, &text).unwrap();
    std::fs::write(source.join("shaders/lib/water.glsl"), b"float a;\n\xff\xfe bad\n").unwrap();
    let err = stderr(&build_into(&source, out.path(), &[]));
    assert!(err.contains("water.glsl:2") && err.contains("UTF-8"), "{err}");
    assert!(std::fs::read_dir(out.path()).unwrap().next().is_none(), "no zip after failures");
}

/// Every option in the shipped GLSL appears in shaders.properties (a screen and every profile)
/// and in the lang file (label and comment), and every option those files name is in the GLSL.
#[test]
fn options_properties_and_lang_agree() {
    use std::collections::BTreeSet;
    use tidepack_loader::option_lines::scan;

    let out = tempfile::tempdir().unwrap();
    assert!(build_into(&repo_root().join("shaderpack"), out.path(), &["--dialect", "330"]).status.success());
    let entries = zip_entries(&out.path().join("Tidepack-0.1.0-glsl330.zip"));
    let glsl: BTreeSet<String> = entries
        .iter()
        .filter(|(name, _)| name.ends_with(".glsl") || name.ends_with(".vsh") || name.ends_with(".fsh"))
        .flat_map(|(_, text)| scan(text).into_iter().map(|o| o.name))
        .collect();
    assert!(glsl.len() >= 20, "{glsl:?}");
    let properties = &entries["shaders/shaders.properties"];
    let value_of = |line: &str| line.split_once('=').map(|(_, v)| v.to_string()).unwrap_or_default();
    let words = |prefix: &str| -> Vec<Vec<String>> {
        properties
            .lines()
            .filter(|l| l.starts_with(prefix))
            .map(|l| value_of(l).split_whitespace().map(|w| w.trim_start_matches('!').split(':').next().unwrap().to_string()).collect())
            .collect()
    };
    let on_screens: BTreeSet<String> = words("screen")
        .into_iter()
        .flatten()
        .filter(|w| !w.starts_with('[') && !w.starts_with('<') && w.parse::<u32>().is_err())
        .collect();
    assert_eq!(on_screens, glsl, "options on screens vs options in the GLSL");
    let profiles = words("profile.");
    assert_eq!(profiles.len(), 4, "LOW, MEDIUM, HIGH, ULTRA");
    for profile in profiles {
        assert_eq!(profile.into_iter().collect::<BTreeSet<_>>(), glsl, "a profile sets every option");
    }
    let lang = &entries["shaders/lang/en_us.lang"];
    let labelled: BTreeSet<String> = lang
        .lines()
        .filter_map(|l| l.strip_prefix("option.")?.split_once('=').map(|(k, _)| k.to_string()))
        .filter(|k| !k.ends_with(".comment"))
        .collect();
    assert_eq!(labelled, glsl, "lang labels vs options");
    for option in &glsl {
        assert!(lang.contains(&format!("option.{option}.comment=")), "{option} has no comment");
    }
}

/// The Nether (world-1) has no water, and the End (world1) no sun or sky light for the model:
/// their programs carry none of the water model's code. Their dh_terrain draws Distant
/// Horizons' LODs as the game draws its terrain.
#[test]
fn the_nether_and_the_end_get_no_water_code() {
    let out = tempfile::tempdir().unwrap();
    assert!(build_into(&repo_root().join("shaderpack"), out.path(), &["--dialect", "120"]).status.success());
    let entries = zip_entries(&out.path().join("Tidepack-0.1.0-glsl120.zip"));
    for world in ["world-1", "world1"] {
        let prefix = format!("shaders/{world}/");
        let programs: Vec<(&String, &String)> = entries.iter().filter(|(name, _)| name.starts_with(&prefix)).collect();
        let mut names: Vec<&str> = programs.iter().map(|(n, _)| n.as_str()).collect();
        names.sort();
        let expected: Vec<String> = ["composite.fsh", "composite.vsh", "dh_terrain.fsh", "dh_terrain.vsh"].iter().map(|n| format!("{prefix}{n}")).collect();
        assert_eq!(names, expected);
        for (name, text) in programs {
            let includes: Vec<&str> = text.lines().filter(|l| l.starts_with("#include")).collect();
            let allowed: &[&str] = if name.contains("dh_terrain") { &["#include \"/lib/vanilla_vertex.glsl\"", "#include \"/lib/vanilla.glsl\""] } else { &[] };
            assert!(includes.iter().all(|l| allowed.contains(l)), "{name} includes shared water code: {includes:?}");
            for water_word in ["colortex4", "colortex5", "colortex6", "colortex7", "depthtex", "isEyeInWater", "wave"] {
                assert!(!text.contains(water_word), "{name} mentions {water_word}");
            }
        }
    }
}

#[test]
fn build_for_a_scene_folds_its_uniforms_validates_and_measures_the_speedup() {
    let out = tempfile::tempdir().unwrap();
    let scene = repo_root().join("tests/scenes/case2_under_down.toml");
    let output = build_into(&repo_root().join("shaderpack"), out.path(), &["--scene", scene.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(output.status.success(), "{stdout}\n{}", stderr(&output));
    let glslang = which("glslangValidator").expect("glslangValidator is missing: install the Debian package glslang-tools");
    for dialect in Dialect::ALL {
        let zip = out.path().join(format!("Tidepack-0.1.0-{}-case2_under_down.zip", dialect.slug()));
        let entries = zip_entries(&zip);
        let water_vertex = &entries["shaders/gbuffers_water.vsh"];
        assert!(water_vertex.lines().any(|l| l.trim() == "attribute vec4 mc_Entity;"), "{dialect}: OptiFine <= 1.16.5 would not bind mc_Entity");
        let composite = &entries["shaders/composite.fsh"];
        // The camera of this scene is under water; the animation clock stays a uniform.
        assert!(composite.contains("const int isEyeInWater = 1; // uniform folded for"), "{composite}");
        assert!(composite.contains("uniform float frameTimeCounter;"), "{composite}");
        // What ships specialised is still GLSL a driver accepts.
        let files: HashMap<String, Arc<str>> = entries
            .iter()
            .filter_map(|(k, v)| Some((k.strip_prefix("shaders/")?.to_string(), Arc::from(v.as_str()))))
            .collect();
        let macros = StandardMacros::default().define_lines();
        let text = expand_includes(&files, "composite.fsh", &macros).unwrap();
        let file = out.path().join(format!("composite-{}.fsh", dialect.slug()));
        std::fs::write(&file, &text).unwrap();
        let result = Command::new(&glslang).args(["-S", "frag"]).arg(&file).output().unwrap();
        assert!(result.status.success(), "{}\n{text}", String::from_utf8_lossy(&result.stdout));
    }
    // The speedup is measured (a figure, never asserted) and the picture is unchanged.
    assert!(
        ["x faster, median of", "x slower, median of"].iter().any(|said| stdout.contains(said)),
        "{stdout}"
    );
    let images = stdout.lines().find(|l| l.contains("images differ by at most")).expect("image comparison line");
    let differences: Vec<f64> = images
        .split_whitespace()
        .skip_while(|w| *w != "R")
        .filter_map(|w| w.parse().ok())
        .take(4)
        .collect();
    assert_eq!(differences.len(), 4, "{images}");
    assert!(differences.iter().all(|d| *d <= 1.0), "specialising changed the image: {images}");
}

/// Copies the pack's sources, applies `edit` to pack.toml and builds into `<work>/out/dist`;
/// returns the build's output, the work folder and the pack.toml path.
fn build_with_manifest(edit: impl Fn(&str) -> String) -> (Output, tempfile::TempDir, PathBuf) {
    let work = tempfile::tempdir().unwrap();
    let source = work.path().join("pack");
    copy_dir(&repo_root().join("shaderpack"), &source);
    let manifest = source.join("pack.toml");
    let text = std::fs::read_to_string(&manifest).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text, "the edit must change pack.toml");
    std::fs::write(&manifest, edited).unwrap();
    let output = build_into(&source, &work.path().join("out/dist"), &[]);
    (output, work, manifest)
}

/// Every file under `dir`, relative to it.
fn files_under(dir: &Path) -> Vec<String> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(folder) = pending.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else {
                found.push(path.strip_prefix(dir).unwrap().display().to_string());
            }
        }
    }
    found.sort();
    found
}

/// A pack name or version that is not plain file-name text would put the zips elsewhere.
#[test]
fn pack_names_and_versions_that_leave_the_output_folder_are_refused() {
    for (field, bad) in [("name", "../escaped"), ("name", "a/b"), ("version", "..\\\\x"), ("version", ""), ("name", "tab\\there")] {
        let (output, work, manifest) = build_with_manifest(|t| {
            let line = if field == "name" { "name = \"Tidepack\"" } else { "version = \"0.1.0\"" };
            t.replacen(line, &format!("{field} = \"{bad}\""), 1)
        });
        let err = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{field} = {bad:?}: {err}");
        let line = if field == "name" { 5 } else { 6 };
        assert!(err.contains(&format!("{}:{line}", manifest.display())), "{field} = {bad:?}: {err}");
        assert!(err.contains(&format!("[pack] {field}")), "{field} = {bad:?}: {err}");
        let written: Vec<String> = files_under(work.path()).into_iter().filter(|f| !f.starts_with("pack/")).collect();
        assert!(written.is_empty(), "{field} = {bad:?} wrote {written:?}");
    }
}

/// When one dialect's zip cannot be written, the other is not written either.
#[test]
fn a_zip_that_cannot_be_written_leaves_no_zip_at_all() {
    let out = tempfile::tempdir().unwrap();
    let blocked = out.path().join("Tidepack-0.1.0-glsl330.zip");
    std::fs::create_dir(&blocked).unwrap();
    let output = build_into(&repo_root().join("shaderpack"), out.path(), &[]);
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.contains(&blocked.display().to_string()) && err.contains("no zip was written"), "{err}");
    assert_eq!(files_under(out.path()), Vec::<String>::new(), "nothing but the folder in the way: {err}");
    assert!(blocked.is_dir());
}

/// A default changed in settings.glsl alone says which profile setting to change, and where.
#[test]
fn a_default_out_of_step_with_the_default_profile_says_what_to_edit() {
    let (output, _work, file) =
        build_mutated("lib/settings.glsl", |t| t.replacen("#define SSR_STEPS 10 ", "#define SSR_STEPS 16 ", 1));
    let err = stderr(&output);
    assert!(!output.status.success(), "{err}");
    let manifest_text = std::fs::read_to_string(repo_root().join("shaderpack/pack.toml")).unwrap();
    let high = manifest_text.find("name = \"HIGH\"").unwrap();
    let line = manifest_text[..high].lines().count() + manifest_text[high..].lines().position(|l| l.starts_with("SSR_STEPS =")).unwrap() + 1;
    let manifest = file.parent().unwrap().parent().unwrap().parent().unwrap().join("pack.toml");
    assert!(err.contains("SSR_STEPS defaults to 16 in the GLSL but the default profile HIGH sets 10"), "{err}");
    assert!(err.contains("set SSR_STEPS = \"16\" in [profile.settings] of the profile named HIGH"), "{err}");
    assert!(err.contains(&format!("{}:{line}", manifest.display())), "expected pack.toml:{line} in {err}");
    assert!(err.contains("to keep 10, write it back on the #define line"), "{err}");
}

/// Values pack.toml passes to shaders.properties are checked against what OptiFine reads.
#[test]
fn properties_optifine_would_ignore_are_refused() {
    let cases = [
        ("\"blend.gbuffers_water\" = \"SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO\"", "\"blend.gbuffers_water\" = \"SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZER\"", "ZER is not a blend factor"),
        (
            "\"texture.composite.colortex7\" = \"textures/water.png\"",
            "\"texture.composite.colortex7\" = \"textures/waves.png\"",
            "no file shaders/textures/waves.png",
        ),
        ("\"blend.gbuffers_water\" = \"SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO\"", "\"blend.gbuffers_watr\" = \"off\"", "no program gbuffers_watr"),
        ("\"blend.gbuffers_water\" = \"SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO\"", "\"blend.gbuffers_water.colortex44\" = \"off\"", "colortex44 is not a colour buffer"),
        ("\"alphaTest.gbuffers_water\" = \"off\"", "\"alphaTest.gbuffers_water\" = \"GREATER\"", "an alpha test is"),
        ("\"blend.gbuffers_water\" = \"SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO\"", "\"oldLighting\" = \"yes\"", "takes true or false"),
        ("\"blend.gbuffers_water\" = \"SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO\"", "\"iris.features.required\" = \"PER_BUFFER_BLENDS\"", "PER_BUFFER_BLENDS is not an Iris feature"),
        ("\"blend.gbuffers_water\" = \"SRC_ALPHA ONE_MINUS_SRC_ALPHA ZERO ZERO\"", "\"sliders\" = \"SSR_STEPS\"", "from [screen]"),
    ];
    for (from, to, message) in cases {
        let (output, work, manifest) = build_with_manifest(|t| t.replacen(from, to, 1));
        let err = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{to}: {err}");
        let text = std::fs::read_to_string(&manifest).unwrap();
        let line = text.lines().position(|l| l.starts_with(to)).unwrap() + 1;
        assert!(err.contains(&format!("{}:{line}", manifest.display())), "{to}: expected pack.toml:{line} in {err}");
        assert!(err.contains(message), "{to}: expected `{message}` in {err}");
        assert!(!work.path().join("out").exists(), "{to}: a failed build wrote output");
    }
    let (output, _work, _) =
        build_with_manifest(|t| t.replacen("[properties]\n", "[properties]\n\"uniform.float.tp_test\" = \"1.0\"\n", 1));
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("\"uniform.float.tp_test\" is not a key tidepack checks"), "{}", stderr(&output));
}

#[test]
fn the_generated_parts_of_the_docs_are_current() {
    let out = Command::new(env!("CARGO_BIN_EXE_tidepack")).args(["docs", "--check"]).current_dir(repo_root()).output().unwrap();
    assert!(out.status.success(), "{}{}", String::from_utf8_lossy(&out.stdout), stderr(&out));
    // A doc whose generated part was edited by hand is named.
    let docs = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(repo_root().join("docs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            std::fs::copy(&path, docs.path().join(path.file_name().unwrap())).unwrap();
        }
    }
    let skipping = docs.path().join("skipping.md");
    let text = std::fs::read_to_string(&skipping).unwrap();
    std::fs::write(&skipping, text.replace("stages validated", "stages checked")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_tidepack"))
        .args(["docs", "--check", "--docs"])
        .arg(docs.path())
        .current_dir(repo_root())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("docs/skipping.md"), "{}", stderr(&out));
}
