//! `tidepack validate` end to end: exit codes (0 clean, 1 shader errors, 2 unreadable input)
//! and the three output formats.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn tests_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/validate")
}

fn validate(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tidepack")).arg("validate").args(args).output().expect("run tidepack")
}

/// A pack folder with a pass-through `final.vsh` and the given `final.fsh`.
fn pack_with_fragment(fragment: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let shaders = dir.path().join("pack/shaders");
    std::fs::create_dir_all(&shaders).unwrap();
    std::fs::write(shaders.join("final.vsh"), "#version 120\nvoid main() { gl_Position = ftransform(); }\n").unwrap();
    std::fs::write(shaders.join("final.fsh"), fragment).unwrap();
    let pack = dir.path().join("pack");
    (dir, pack)
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn exit_codes_follow_the_verdict() {
    let clean = tests_dir().join("corpus/legacy120");
    let out = validate(&[clean.to_str().unwrap(), "--all-profiles"]);
    assert_eq!(out.status.code(), Some(0), "{}{}", text(&out.stdout), text(&out.stderr));
    assert!(text(&out.stdout).contains("0 errors, 0 warnings"), "{}", text(&out.stdout));

    let planted = tests_dir().join("planted/undeclared_identifier");
    let out = validate(&[planted.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("error[glsl]: undeclared identifier `colr`"), "{stderr}");
    assert!(stderr.contains("undeclared_identifier/shaders/lib/color.glsl:4:"), "{stderr}");
    assert!(stderr.contains("return saturate3(colr);"), "snippet missing: {stderr}");

    let dir = tempfile::tempdir().unwrap();
    let garbage = dir.path().join("pack.zip");
    std::fs::write(&garbage, b"not a zip at all").unwrap();
    for bad in [garbage.to_str().unwrap(), "/nonexistent/pack"] {
        let out = validate(&[bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}: {}", text(&out.stderr));
    }
    let out = validate(&[clean.to_str().unwrap(), "--profile", "NOPE"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no profile `NOPE`"), "{}", text(&out.stderr));
}

#[test]
fn json_and_github_formats() {
    let planted = tests_dir().join("planted/varying_type_mismatch");
    let out = validate(&[planted.to_str().unwrap(), "--format", "json"]);
    assert_eq!(out.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    let errors: Vec<&serde_json::Value> = json["diagnostics"].as_array().unwrap().iter().filter(|d| d["severity"] == "error").collect();
    assert!(
        errors.iter().any(|d| d["file"].as_str().unwrap().ends_with("varying_type_mismatch/shaders/gbuffers_basic.fsh") && d["line"] == 2),
        "{json}"
    );
    let program = json["programs"].as_array().unwrap().iter().find(|p| p["program"] == "gbuffers_basic").unwrap();
    assert_eq!(program["status"], "invalid");
    // The program lists the diagnostics found in it.
    let listed: Vec<usize> = program["diagnostics"].as_array().unwrap().iter().map(|i| i.as_u64().unwrap() as usize).collect();
    assert!(listed.iter().any(|&i| json["diagnostics"][i]["severity"] == "error"), "{json}");

    // Annotations name files from the working directory, where GitHub resolves them.
    let out = Command::new(env!("CARGO_BIN_EXE_tidepack"))
        .current_dir(tests_dir())
        .args(["validate", "--format", "github", planted.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let annotations = text(&out.stdout);
    let line = annotations.lines().find(|l| l.starts_with("::error ")).unwrap_or_else(|| panic!("{annotations}"));
    assert!(line.contains("file=planted/varying_type_mismatch/shaders/gbuffers_basic.fsh,line=2"), "{line}");

    // A warning (an output the render-target list drops) fails only with --deny-warnings.
    let drawbuffers = tests_dir().join("planted/wrong_drawbuffers");
    let out = validate(&[drawbuffers.to_str().unwrap(), "--format", "github"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(text(&out.stdout).lines().any(|l| l.starts_with("::warning ") && l.contains("gbuffers_terrain.fsh,line=8")), "{}", text(&out.stdout));
    let out = validate(&[drawbuffers.to_str().unwrap(), "--deny-warnings"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("--deny-warnings: 1 warning"), "the failure says why: {}", text(&out.stderr));
}

#[test]
fn json_is_the_same_on_every_run() {
    // Programs share includes, and naga's results arrive in thread order.
    let pack = tests_dir().join("corpus/legacy120");
    let runs: Vec<Vec<u8>> = (0..4).map(|_| validate(&[pack.to_str().unwrap(), "--all-profiles", "--format", "json"]).stdout).collect();
    assert!(runs.iter().all(|r| r == &runs[0]), "JSON differs between runs");
    let planted = tests_dir().join("planted/undeclared_identifier");
    let runs: Vec<Vec<u8>> = (0..4).map(|_| validate(&[planted.to_str().unwrap(), "--format", "json"]).stdout).collect();
    assert!(runs.iter().all(|r| r == &runs[0]), "JSON differs between runs");
}

#[test]
fn control_characters_from_a_pack_do_not_reach_the_terminal() {
    let (_dir, pack) = pack_with_fragment("#version 120\nvoid main() { gl_FragColor = vec4(\u{1b}[31m); }\n");
    let out = validate(&[pack.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(!out.stderr.contains(&0x1b) && !out.stdout.contains(&0x1b), "{}", text(&out.stderr));
}

#[test]
fn the_template_source_folder_points_at_the_built_zip() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaderpack");
    let out = validate(&[source.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("template source") && stderr.contains("tidepack validate dist/"), "{stderr}");
}

#[test]
fn expressions_too_long_for_naga_are_errors_not_crashes() {
    let bodies = [
        format!("vec4 x = vec4(1.0); gl_FragColor = x{};", ".xyzw".repeat(100_000)),
        format!("float x = 1.0; gl_FragColor = vec4({});", vec!["x"; 50_000].join(" + ")),
        format!("float x = 1.0; gl_FragColor = vec4({}x);", "- ".repeat(100_000)),
    ];
    for body in bodies {
        let (_dir, pack) = pack_with_fragment(&format!("#version 120\nvoid main() {{\n{body}\n}}\n"));
        let out = validate(&[pack.to_str().unwrap(), "--format", "json"]);
        assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON even for hostile input");
        let error = json["diagnostics"].as_array().unwrap().iter().find(|d| d["severity"] == "error").unwrap();
        assert_eq!((error["file"].as_str().unwrap().ends_with("final.fsh"), error["line"].as_u64()), (true, Some(3)), "{error}");
        assert!(error["message"].as_str().unwrap().contains("operators"), "{error}");
    }
}

#[test]
fn a_configuration_is_named_as_render_names_it() {
    let (_dir, pack) = pack_with_fragment(
        "#version 120\n//#define GLOW\n#ifdef GLOW\nfloat glow() { return glowStrength; }\n#else\nfloat glow() { return 1.0; }\n#endif\nvoid main() { gl_FragData[0] = vec4(glow()); }\n",
    );
    let path = pack.to_str().unwrap();
    assert_eq!(validate(&[path]).status.code(), Some(0));
    let out = validate(&[path, "--set", "GLOW=on", "--loader", "iris"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("glowStrength"), "{}", text(&out.stderr));
    for (args, needle) in [
        (&["--set", "GLOW=maybe"][..], "on or off"),
        (&["--set", "NOPE=1"][..], "no option NOPE"),
        (&["--set", "=1"][..], "OPTION=VALUE"),
        (&["--dimension", "moon"][..], "overworld, nether, end"),
    ] {
        let out = validate(&[&[path][..], args].concat());
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", text(&out.stderr));
        assert!(text(&out.stderr).contains(needle), "{args:?}: {}", text(&out.stderr));
    }
}

/// A mistake behind one toggle: the defaults pass, `--covering` fails and prints the `--set`
/// line that shows it; a shard and a cache folder work from the command line.
#[test]
fn covering_finds_a_mistake_behind_a_toggle_and_says_how_to_show_it() {
    let (_dir, pack) = pack_with_fragment(
        "#version 120\n//#define GLOW // Glow\n#ifdef GLOW\nfloat glow() { return glowAmount; }\n#endif\nvoid main() { gl_FragColor = vec4(1.0); }\n",
    );
    let path = pack.to_str().unwrap();
    assert_eq!(validate(&[path]).status.code(), Some(0));
    let out = validate(&[path, "--covering"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("final.fsh:4") && stderr.contains("shown with: --set GLOW=on"), "{stderr}");
    assert!(text(&out.stdout).contains("option sets cover every combination"), "{}", text(&out.stdout));
    let cache = _dir.path().join("cache");
    for _ in 0..2 {
        let out = validate(&[path, "--covering", "--cache", cache.to_str().unwrap(), "--format", "json"]);
        assert_eq!(out.status.code(), Some(1));
    }
    assert!(std::fs::read_dir(&cache).unwrap().count() > 0, "the cache folder holds entries");
    let shards: Vec<i32> = ["1/2", "2/2"].iter().map(|s| validate(&[path, "--covering", "--shard", s]).status.code().unwrap()).collect();
    assert!(shards.contains(&1), "one shard holds the failing text: {shards:?}");
    let out = validate(&[path, "--covering", "--shard", "3/2"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("K/N"), "{}", text(&out.stderr));
}

/// macOS gives Minecraft before 1.17 OpenGL 2.1: a `#version 330` stage does not load there,
/// while GLSL 1.20 packs and later Minecraft versions are fine.
#[test]
fn an_os_and_minecraft_version_imply_their_glsl_limit() {
    let core330 = tests_dir().join("corpus/core330");
    let core330 = core330.to_str().unwrap();
    let old_mac = validate(&[core330, "--os", "mac", "--mc-version", "1.16.5"]);
    let stderr = String::from_utf8_lossy(&old_mac.stderr);
    assert_eq!(old_mac.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("above GLSL 120") && stderr.contains("MC_GLSL_VERSION 120"), "{stderr}");
    assert_eq!(validate(&[core330, "--os", "mac", "--mc-version", "1.20.1"]).status.code(), Some(0));
    let legacy = tests_dir().join("corpus/legacy120");
    assert_eq!(validate(&[legacy.to_str().unwrap(), "--os", "mac", "--mc-version", "1.16.5"]).status.code(), Some(0));
    let explicit = validate(&[core330, "--glsl-version", "1.5"]);
    assert!(String::from_utf8_lossy(&explicit.stderr).contains("above GLSL 150"));
}

/// A pack with `count` fragment uniforms no loader sets, each read (an `unknown-uniform`
/// warning apiece), and one `#if` on an undefined macro (an `undefined-in-if` warning).
fn pack_with_unknown_uniforms(count: usize) -> (tempfile::TempDir, PathBuf) {
    let declared: String = (0..count).map(|i| format!("uniform float mystery{i};\n")).collect();
    let read: String = (0..count).map(|i| format!(" + mystery{i}")).collect();
    pack_with_fragment(&format!(
        "#version 120\n{declared}#if SOMETHING_UNDEFINED\n#endif\nvoid main() {{ gl_FragColor = vec4(0.0{read}); }}\n"
    ))
}

#[test]
fn codes_are_shown_counted_allowed_and_denied() {
    let (_dir, pack) = pack_with_unknown_uniforms(3);
    let path = pack.to_str().unwrap();
    let out = validate(&[path]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("warning[unknown-uniform]: `mystery0` is not a uniform"), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("by code: unknown-uniform 3 warnings, undefined-in-if 1 warning"), "{}", text(&out.stdout));

    let out = validate(&[path, "--allow", "unknown-uniform"]);
    assert_eq!(out.status.code(), Some(0));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("allowed, not shown: unknown-uniform 3") && stdout.contains("0 errors, 1 warning\n"), "{stdout}");
    assert!(!text(&out.stderr).contains("mystery"), "{}", text(&out.stderr));

    let out = validate(&[path, "--deny", "undefined-in-if,unknown-uniform", "--format", "json"]);
    assert_eq!(out.status.code(), Some(1), "a denied warning fails the check");
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let codes: Vec<(&str, &str)> =
        json["diagnostics"].as_array().unwrap().iter().map(|d| (d["code"].as_str().unwrap(), d["severity"].as_str().unwrap())).collect();
    assert_eq!(codes.iter().filter(|c| **c == ("unknown-uniform", "error")).count(), 3, "{codes:?}");
    assert!(codes.contains(&("undefined-in-if", "error")), "{codes:?}");

    for (args, said) in [
        (vec!["--allow", "unknown-uniforms"], "did you mean unknown-uniform"),
        (vec!["--allow", "link", "--deny", "link"], "contradict"),
    ] {
        let out = validate(&[&[path][..], &args].concat());
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(text(&out.stderr).contains(said), "{args:?}: {}", text(&out.stderr));
    }
}

#[test]
fn a_tidepack_toml_beside_the_pack_sets_the_levels_and_the_command_line_goes_over_it() {
    let (_dir, pack) = pack_with_unknown_uniforms(2);
    let path = pack.to_str().unwrap();
    std::fs::write(pack.join("tidepack.toml"), "[validate]\ndeny = [\"unknown-uniform\"]\n").unwrap();
    assert_eq!(validate(&[path]).status.code(), Some(1));
    assert_eq!(validate(&[path, "--allow", "unknown-uniform"]).status.code(), Some(0));

    // A mistake in the file is a usage error at its line, whichever way the file is found.
    std::fs::write(pack.join("tidepack.toml"), "[validate]\ndeny = [\n  \"unknown-uniform\",\n  \"no-such-code\",\n]\n").unwrap();
    let config = pack.join("tidepack.toml");
    for args in [vec![path], vec![path, "--config", config.to_str().unwrap()]] {
        let out = validate(&args);
        assert_eq!(out.status.code(), Some(2));
        assert!(text(&out.stderr).contains("tidepack.toml:4"), "{}", text(&out.stderr));
    }
    let out = validate(&[path, "--config", "/nonexistent/tidepack.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("/nonexistent/tidepack.toml"), "{}", text(&out.stderr));
}

#[test]
fn github_annotates_every_error_ten_warnings_and_the_summary_has_them_all() {
    let (dir, pack) = pack_with_unknown_uniforms(25);
    let summary = dir.path().join("summary.md");
    std::fs::write(&summary, "earlier step\n").unwrap();
    let out = validate(&[pack.to_str().unwrap(), "--format", "github", "--summary", summary.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0));
    let annotations = text(&out.stdout);
    let warnings: Vec<&str> = annotations.lines().filter(|l| l.starts_with("::warning ")).collect();
    assert_eq!(warnings.len(), 10, "{annotations}");
    // Taken a code at a time: the one undefined-in-if warning is among the ten.
    assert!(warnings.iter().any(|l| l.contains("title=tidepack validate [undefined-in-if]")), "{annotations}");
    assert!(annotations.lines().any(|l| l.starts_with("::notice ") && l.contains("16 more warnings")), "{annotations}");

    let markdown = std::fs::read_to_string(&summary).unwrap();
    assert!(markdown.starts_with("earlier step\n### tidepack validate"), "appended: {markdown}");
    assert!(markdown.contains("| `unknown-uniform` | 0 | 25 |"), "{markdown}");
    assert_eq!((0..25).filter(|i| markdown.contains(&format!("`mystery{i}`"))).count(), 25, "{markdown}");
}

#[test]
fn the_codes_command_lists_every_code() {
    let out = Command::new(env!("CARGO_BIN_EXE_tidepack")).arg("codes").output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    let listed = text(&out.stdout);
    for code in tidepack_glsl::Code::ALL {
        assert!(listed.lines().any(|l| l.split_whitespace().next() == Some(code.name())), "{code} missing: {listed}");
    }
}
