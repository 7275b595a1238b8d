//! `validate` under a named configuration, as a player runs the pack: `--set` values over the
//! defaults or a profile, one dimension's programs, shaders.properties read under the options
//! in force (its conditionals evaluated), and OptiFine's `const` options. Minimal packs of our
//! own, each reproducing a pattern of released packs: a mistake behind one toggle, a dimension
//! folder of its own, a profile that sets `shadowMapResolution`.

use tidepack_loader::Dimension;
use tidepack_loader::input::pack_from_memory;
use tidepack_validate::{Options, Profiles, Report, validate_pack};

const VERTEX: &str = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";

/// A composite whose `GODRAYS` branch reads an undeclared name: clean under the defaults.
const TOGGLED: &str = "#version 120
//#define GODRAYS
#ifdef GODRAYS
float rays() { return undeclaredStrength; }
#endif
void main() { gl_FragData[0] = vec4(1.0); }
";

fn validate(files: &[(&str, &str)], options: Options) -> Result<Report, String> {
    let pack = pack_from_memory("test/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    validate_pack(pack, &Options { threads: 2, ..options }).map_err(|d| d.message)
}

fn errors(report: &Report) -> Vec<String> {
    report.diagnostics.iter().filter(|d| d.is_error()).map(|d| format!("{d}")).collect()
}

#[test]
fn a_mistake_behind_one_toggle_shows_under_set_and_says_which() {
    let files = [("composite.vsh", VERTEX), ("composite.fsh", TOGGLED)];
    let defaults = validate(&files, Options::default()).unwrap();
    assert!(errors(&defaults).is_empty(), "{:?}", errors(&defaults));
    let on = Options { overrides: vec![("GODRAYS".into(), "on".into())], ..Options::default() };
    let report = validate(&files, on).unwrap();
    let found = errors(&report);
    assert!(found.iter().any(|e| e.contains("undeclaredStrength") && e.contains("composite.fsh:4")), "{found:?}");
    assert!(report.option_sets.iter().any(|s| s.contains("GODRAYS=on")), "{:?}", report.option_sets);
    let bad = Options { overrides: vec![("GODRAYS".into(), "maybe".into())], ..Options::default() };
    assert!(validate(&files, bad).unwrap_err().contains("on or off"));
    let unknown = Options { overrides: vec![("NOPE".into(), "1".into())], ..Options::default() };
    assert!(validate(&files, unknown).unwrap_err().contains("no option NOPE"));
}

#[test]
fn a_dimension_validates_only_the_programs_it_runs() {
    let broken = "#version 120\nvoid main() { gl_FragData[0] = vec4(missingName); }\n";
    let files = [
        ("composite.vsh", VERTEX),
        ("composite.fsh", "#version 120\nvoid main() { gl_FragData[0] = vec4(1.0); }\n"),
        ("world-1/composite.vsh", VERTEX),
        ("world-1/composite.fsh", broken),
    ];
    let every = validate(&files, Options::default()).unwrap();
    assert!(errors(&every).iter().any(|e| e.contains("world-1/composite.fsh")));
    let nether = Options { dimension: Some(Dimension::parse("nether").unwrap()), ..Options::default() };
    let report = validate(&files, nether).unwrap();
    assert_eq!(report.programs.iter().map(|p| p.id.as_str()).collect::<Vec<_>>(), ["world-1/composite"]);
    let overworld = Options { dimension: Some(Dimension::default()), ..Options::default() };
    let report = validate(&files, overworld).unwrap();
    assert_eq!(report.programs.iter().map(|p| p.id.as_str()).collect::<Vec<_>>(), ["composite"]);
    assert!(errors(&report).is_empty(), "{:?}", errors(&report));
}

#[test]
fn profiles_set_const_options_and_properties_follow_their_conditionals() {
    let fragment = "#version 120
const int shadowMapResolution = 2048; // [1024 2048 4096]
#define CLOUDS
#ifdef CLOUDS
#endif
uniform float cloudFade;
void main() { gl_FragData[0] = vec4(cloudFade); }
";
    // cloudFade exists only while CLOUDS is on: under LOW it is not a custom uniform.
    let properties = "profile.LOW=shadowMapResolution:1024 !CLOUDS\nprofile.HIGH=shadowMapResolution:4096\n#ifdef CLOUDS\nuniform.float.cloudFade = 1.0\n#endif\n";
    let files = [("composite.vsh", VERTEX), ("composite.fsh", fragment), ("shaders.properties", properties)];
    let report = validate(&files, Options { profiles: Profiles::All, ..Options::default() }).unwrap();
    let warnings: Vec<String> = report.diagnostics.iter().filter(|d| !d.is_error()).map(|d| format!("{d}")).collect();
    assert!(!warnings.iter().any(|w| w.contains("which no shader file declares")), "{warnings:?}");
    let unknown: Vec<&String> = warnings.iter().filter(|w| w.contains("cloudFade")).collect();
    assert_eq!(unknown.len(), 1, "cloudFade is unknown under LOW only: {warnings:?}");
    assert!(report.diagnostics.iter().any(|d| d.message.contains("cloudFade") && d.notes.iter().any(|n| n.contains("LOW"))), "{:#?}", report.diagnostics);
}

#[test]
fn an_if_on_an_option_whose_list_follows_its_tooltip_is_read_as_optifine_reads_it() {
    // The value list after the tooltip still makes MODE an option (OptiFine finds the list
    // anywhere in the comment), and a name no file defines reads 0 in an `#if`.
    for settings in ["#define MODE 0 // Timelapse mode [0 1 2]\n#if MODE == 1\n#endif\n", ""] {
        let fragment = format!("#version 120\n{settings}uniform float shiftedTime;\nvoid main() {{ gl_FragData[0] = vec4(shiftedTime); }}\n");
        let properties = "#if MODE == 0\nuniform.float.shiftedTime = frameTimeCounter\n#endif\n";
        let files = [("composite.vsh", VERTEX), ("composite.fsh", fragment.as_str()), ("shaders.properties", properties)];
        let report = validate(&files, Options::default()).unwrap();
        assert!(!report.diagnostics.iter().any(|d| d.message.contains("shiftedTime")), "{settings:?}: {:#?}", report.diagnostics);
    }
}

#[test]
fn a_conditional_line_that_does_not_evaluate_is_a_warning_at_its_line() {
    let fragment = "#version 120\nvoid main() { gl_FragData[0] = vec4(1.0); }\n";
    let files = [("composite.vsh", VERTEX), ("composite.fsh", fragment), ("shaders.properties", "sliders=A\n#if (1 +\nx=1\n#endif\n")];
    let report = validate(&files, Options::default()).unwrap();
    let warning = report.diagnostics.iter().find(|d| d.location.as_ref().is_some_and(|l| l.path == "shaders.properties" && l.line == 2));
    assert!(warning.is_some_and(|w| !w.is_error() && w.message.contains("taken as false")), "{:#?}", report.diagnostics);
}

#[test]
fn a_program_switched_off_is_validated_only_where_it_runs() {
    let broken = "#version 120\n//#define BLOOM\n#ifdef BLOOM\n#endif\nvoid main() { gl_FragData[0] = vec4(missingBloom); }\n";
    let files = [
        ("composite.vsh", VERTEX),
        ("composite.fsh", "#version 120\nvoid main() { gl_FragData[0] = vec4(1.0); }\n"),
        ("composite1.vsh", VERTEX),
        ("composite1.fsh", broken),
        ("shaders.properties", "program.composite1.enabled=BLOOM\n"),
    ];
    let defaults = validate(&files, Options::default()).unwrap();
    assert!(errors(&defaults).is_empty(), "{:?}", errors(&defaults));
    let skipped = defaults.programs.iter().find(|p| p.id == "composite1").unwrap();
    assert!(matches!(&skipped.status, tidepack_validate::Status::Skipped(why) if why.contains("program.composite1.enabled")), "{:?}", skipped.status);
    let on = validate(&files, Options { overrides: vec![("BLOOM".into(), "on".into())], ..Options::default() }).unwrap();
    assert!(errors(&on).iter().any(|e| e.contains("missingBloom")), "{:?}", errors(&on));
}

#[test]
fn iris_uniforms_are_known_under_iris_only() {
    let fragment = "#version 120
uniform float currentPlayerHealth;
uniform bool is_sneaking;
uniform sampler2D dhDepthTex0;
void main() { gl_FragData[0] = vec4(currentPlayerHealth + float(is_sneaking) + texture2D(dhDepthTex0, vec2(0.5)).r); }
";
    let files = [("composite.vsh", VERTEX), ("composite.fsh", fragment)];
    let unknown = |report: &Report| -> Vec<String> {
        report.diagnostics.iter().filter(|d| d.message.contains("silently reads")).map(|d| d.message.clone()).collect()
    };
    let optifine = unknown(&validate(&files, Options::default()).unwrap());
    assert_eq!(optifine.len(), 3, "{optifine:?}");
    assert!(optifine.iter().all(|m| m.contains("OptiFine")), "{optifine:?}");
    let iris = Options { loader: tidepack_loader::Loader::Iris, ..Options::default() };
    let iris = unknown(&validate(&files, iris).unwrap());
    assert!(iris.is_empty(), "{iris:?}");
}

#[test]
fn a_dimension_the_pack_does_not_shade_is_a_warning_not_an_error() {
    let fragment = "#version 120\nvoid main() { gl_FragData[0] = vec4(1.0); }\n";
    let files = [("world0/composite.vsh", VERTEX), ("world0/composite.fsh", fragment)];
    let nether = Options { dimension: Some(Dimension::parse("nether").unwrap()), ..Options::default() };
    let report = validate(&files, nether).unwrap();
    assert!(errors(&report).is_empty(), "{:?}", errors(&report));
    assert!(report.diagnostics.iter().any(|d| d.message.contains("drawn without shaders") && d.message.contains("shaders/")), "{:?}", report.diagnostics);
    // A pack with no programs at all still fails: nothing was checked.
    let empty = validate(&[("shaders.properties", "")], Options { dimension: Some(Dimension::parse("nether").unwrap()), ..Options::default() }).unwrap();
    assert!(!errors(&empty).is_empty());
}

#[test]
fn iris_programs_are_validated_under_iris() {
    let fragment = "#version 120\nvoid main() { gl_FragData[0] = vec4(undeclaredTint); }\n";
    let files = [("gbuffers_terrain_cutout.vsh", VERTEX), ("gbuffers_terrain_cutout.fsh", fragment), ("composite.vsh", VERTEX), ("composite.fsh", "#version 120\nvoid main() { gl_FragData[0] = vec4(1.0); }\n")];
    let status = |report: &Report| report.programs.iter().find(|p| p.id == "gbuffers_terrain_cutout").map(|p| p.status.clone());
    let optifine = validate(&files, Options::default()).unwrap();
    assert!(matches!(status(&optifine), Some(tidepack_validate::Status::Skipped(_))), "{:?}", status(&optifine));
    let iris = validate(&files, Options { loader: tidepack_loader::Loader::Iris, ..Options::default() }).unwrap();
    assert_eq!(status(&iris), Some(tidepack_validate::Status::Invalid));
    assert!(errors(&iris).iter().any(|e| e.contains("undeclaredTint") && e.contains("gbuffers_terrain_cutout.fsh:2")), "{:?}", errors(&iris));
}

/// Iris removes a function nothing calls before the driver compiles the stage, so what only it
/// reads need not be declared there; OptiFine gives the driver the function, which refuses it.
#[test]
fn a_function_nothing_calls_is_not_compiled_under_iris() {
    let fragment = "#version 120\nvec4 noise() { return vec4(viewWidth); }\nvoid main() { gl_FragData[0] = vec4(1.0); }\n";
    let files = [("composite.vsh", VERTEX), ("composite.fsh", fragment)];
    let optifine = validate(&files, Options::default()).unwrap();
    assert!(errors(&optifine).iter().any(|e| e.contains("viewWidth") && e.contains("composite.fsh:2")), "{:?}", errors(&optifine));
    let iris = validate(&files, Options { loader: tidepack_loader::Loader::Iris, ..Options::default() }).unwrap();
    assert!(errors(&iris).is_empty(), "{:?}", errors(&iris));
}

/// `N` in a draw-buffer list: an output OptiFine draws into no buffer; Iris cannot read the
/// list and does not load the pack.
#[test]
fn an_output_drawn_into_no_buffer_is_optifines_alone() {
    let fragment = "#version 120\nvoid main() {\n/* DRAWBUFFERS:N0 */\ngl_FragData[0] = vec4(1.0);\ngl_FragData[1] = vec4(0.5);\n}\n";
    let files = [("composite.vsh", VERTEX), ("composite.fsh", fragment)];
    let optifine = validate(&files, Options::default()).unwrap();
    assert!(errors(&optifine).is_empty(), "{:?}", errors(&optifine));
    let iris = validate(&files, Options { loader: tidepack_loader::Loader::Iris, ..Options::default() }).unwrap();
    assert!(errors(&iris).iter().any(|e| e.contains("`N` in DRAWBUFFERS") && e.contains("composite.fsh:3")), "{:?}", errors(&iris));
}
