//! Compute, geometry and tessellation stages:
//! - compute stages (`.csh`) go through the lowering and naga like vertex and fragment stages,
//!   errors located at their file and line;
//! - geometry and tessellation stages are preprocessed (include errors, `#error`) and, without
//!   `--driver`, reported as only preprocessed; with `--driver` Mesa compiles and links them
//!   with the program's vertex and fragment stages, its errors located at their file and line.
//!
//! The `--driver` tests need Mesa's EGL/GL (tools/test installs them); without it they fail,
//! they never skip.

use tidepack_loader::input::pack_from_memory;
use tidepack_validate::{Options, Report, Status, validate_pack};

fn validate(files: &[(&str, &str)], driver: bool) -> Report {
    let pack = pack_from_memory("test/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    validate_pack(pack, &Options { threads: 2, driver, ..Options::default() }).unwrap()
}

fn show(report: &Report) -> String {
    report.diagnostics.iter().map(|d| format!("\n    {d}")).collect()
}

fn has(report: &Report, error: bool, path: &str, line: u32, needle: &str) -> bool {
    report.diagnostics.iter().any(|d| {
        d.is_error() == error && d.location.as_ref().is_some_and(|l| l.path == path && l.line == line) && d.message.contains(needle)
    })
}

fn status(report: &Report, program: &str) -> Status {
    report.programs.iter().find(|p| p.id == program).unwrap_or_else(|| panic!("no program {program}")).status.clone()
}

const COMPUTE: &str = "#version 430 compatibility
layout(local_size_x = 16, local_size_y = 16) in;
const vec2 workGroupsRender = vec2(1.0, 1.0);
layout(rgba16f) uniform image2D colorimg0;
uniform writeonly image2D colorimg1;
uniform sampler2D colortex2;
uniform float frameTimeCounter;
uniform vec2 viewSize;
shared uint count;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (gl_LocalInvocationIndex == 0u) count = 0u;
    barrier();
    memoryBarrierShared();
    atomicAdd(count, 1u);
    vec4 c = imageLoad(colorimg0, p) + texelFetch(colortex2, p, 0) * frameTimeCounter;
    imageStore(colorimg1, p, c);
}
";

const COMPUTE_A: &str = "#version 430
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include \"/lib/common.glsl\"
layout(rgba8) uniform image2D colorimg3;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(colorimg3, p, vec4(brighten(imageLoad(colorimg3, p).rgb), 1.0));
}
";

const COMMON: &str = "vec3 brighten(vec3 c) {
    return c * 1.5;
}
";

const FINAL: &str = "#version 120
uniform sampler2D colortex0;
varying vec2 uv;
void main() { gl_FragColor = texture2D(colortex0, uv); }
";

const FINAL_VSH: &str = "#version 120
varying vec2 uv;
void main() { gl_Position = ftransform(); uv = gl_MultiTexCoord0.xy; }
";

/// A pack of one compute stage, `composite.csh`, that includes lib/common.glsl.
fn with_common(composite: String) -> Vec<(&'static str, String)> {
    vec![("composite.csh", composite), ("lib/common.glsl", COMMON.to_string())]
}

fn compute_pack(composite_a: &str) -> Vec<(&'static str, String)> {
    vec![
        ("composite.csh", COMPUTE.replace("uniform vec2 viewSize;\n", "\n")),
        ("composite_a.csh", composite_a.to_string()),
        ("lib/common.glsl", COMMON.to_string()),
        ("final.vsh", FINAL_VSH.to_string()),
        ("final.fsh", FINAL.to_string()),
    ]
}

fn as_refs<'a>(files: &'a [(&'static str, String)]) -> Vec<(&'static str, &'a str)> {
    files.iter().map(|(p, t)| (*p, t.as_str())).collect()
}

#[test]
fn valid_compute_stages_validate_through_naga() {
    let files = compute_pack(COMPUTE_A);
    let report = validate(&as_refs(&files), false);
    assert!(report.diagnostics.is_empty(), "{}", show(&report));
    assert_eq!(status(&report, "composite"), Status::Valid);
    let composite = report.programs.iter().find(|p| p.id == "composite").unwrap();
    assert_eq!(composite.stages, ["composite.csh", "composite_a.csh"]);
    // final.vsh, final.fsh and both compute stages.
    assert_eq!(report.stages_validated, 4);
}

#[test]
fn a_type_error_in_a_compute_stage_is_reported_at_its_line() {
    let broken = COMPUTE_A.replace("    ivec2 p = ivec2(gl_GlobalInvocationID.xy);", "    ivec2 p = gl_GlobalInvocationID.xy;");
    let files = compute_pack(&broken);
    let report = validate(&as_refs(&files), false);
    assert!(has(&report, true, "composite_a.csh", 6, ""), "{}", show(&report));
    assert_eq!(status(&report, "composite"), Status::Invalid);
    assert_eq!(status(&report, "final"), Status::Valid);
    // A mismatched imageStore is explained.
    let broken = COMPUTE_A.replace("vec4(brighten(imageLoad(colorimg3, p).rgb), 1.0)", "brighten(imageLoad(colorimg3, p).rgb)");
    let files = compute_pack(&broken);
    let report = validate(&as_refs(&files), false);
    assert!(
        report.diagnostics.iter().any(|d| d.location.as_ref().is_some_and(|l| l.line == 7) && d.notes.iter().any(|n| n.contains("no form of imageStore()"))),
        "{}",
        show(&report)
    );
    // An error in an included function is reported in the included file.
    let files = vec![("composite.csh", COMPUTE_A.to_string()), ("lib/common.glsl", COMMON.replace("c * 1.5", "c * vec2(1.5)"))];
    let report = validate(&as_refs(&files), false);
    assert!(has(&report, true, "lib/common.glsl", 2, ""), "{}", show(&report));
}

#[test]
fn image_atomics_naga_lacks_are_warnings_not_errors() {
    let text = COMPUTE_A.replace("layout(rgba8) uniform image2D colorimg3;", "layout(r32ui) uniform uimage2D colorimg3;").replace(
        "    imageStore(colorimg3, p, vec4(brighten(imageLoad(colorimg3, p).rgb), 1.0));",
        "    imageAtomicAdd(colorimg3, p, 1u);",
    );
    let files = with_common(text);
    let report = validate(&as_refs(&files), false);
    assert_eq!(report.errors(), 0, "{}", show(&report));
    assert!(has(&report, false, "composite.csh", 7, "imageAtomicAdd() is not checked"), "{}", show(&report));
    let report = validate(&as_refs(&files), true);
    assert_eq!(report.driver.as_ref().unwrap().both_accept, 1, "{}", show(&report));
}

#[test]
fn subgroup_built_ins_are_not_checked_by_naga_and_their_extension_is_refused_where_drivers_lack_it() {
    let text = COMPUTE_A.replace("#version 430\n", "#version 460 compatibility\n#extension GL_KHR_shader_subgroup_basic : enable\n").replace(
        "    ivec2 p = ivec2(gl_GlobalInvocationID.xy);",
        "    ivec2 p = ivec2(gl_GlobalInvocationID.xy) + int(gl_SubgroupSize);",
    );
    let files = with_common(text);
    let report = validate(&as_refs(&files), false);
    assert!(has(&report, false, "composite.csh", 7, "gl_SubgroupSize is not checked"), "{}", show(&report));
    // The one error: Mesa's llvmpipe and macOS do not offer the extension.
    assert_eq!(report.errors(), 1, "{}", show(&report));
    let refused = report.diagnostics.iter().find(|d| d.is_error()).expect("an error");
    assert!(refused.message.contains("needs an extension that Mesa's llvmpipe"), "{}", show(&report));
    assert_eq!(refused.refused_by, tidepack_glsl::Drivers::MESA.union(tidepack_glsl::Drivers::MACOS));
}

#[test]
fn iris_custom_images_are_known() {
    let text = COMPUTE_A.replace("colorimg3", "imgDepthQ");
    let mut files = with_common(text);
    let report = validate(&as_refs(&files), false);
    assert!(has(&report, false, "composite.csh", 4, "`imgDepthQ` is not an image"), "{}", show(&report));
    files.push(("shaders.properties", "image.imgDepthQ = texDepthQ RED R16F HALF_FLOAT false true 0.25 0.25\n".to_string()));
    let report = validate(&as_refs(&files), false);
    assert!(report.diagnostics.is_empty(), "{}", show(&report));
}

#[test]
fn a_compute_stage_below_glsl_430_is_an_error_naga_and_mesa_agree_on() {
    let old = COMPUTE_A.replace("#version 430\n", "#version 330 compatibility\n");
    let files = with_common(old.clone());
    for driver in [false, true] {
        let report = validate(&as_refs(&files), driver);
        assert!(has(&report, true, "composite.csh", 1, "compute shaders need `#version 430`"), "{}", show(&report));
        if driver {
            assert_eq!(report.driver.as_ref().unwrap().both_reject, 1, "{}", show(&report));
        }
    }
    let with_extension = old.replace("compatibility\n", "compatibility\n#extension GL_ARB_compute_shader : require\n");
    let files = with_common(with_extension);
    let report = validate(&as_refs(&files), false);
    assert_eq!(report.errors(), 0, "{}", show(&report));
}

#[test]
fn compute_stages_get_the_resource_checks() {
    let files = [("composite.csh", COMPUTE), ("composite1.csh", &COMPUTE.replace("colorimg1", "outputimg") as &str)];
    let report = validate(&files, false);
    assert!(has(&report, false, "composite.csh", 8, "`viewSize` is not a uniform OptiFine sets"), "{}", show(&report));
    assert!(has(&report, false, "composite1.csh", 5, "`outputimg` is not an image OptiFine binds"), "{}", show(&report));
    assert_eq!(report.errors(), 0, "{}", show(&report));
}

const GEOMETRY_VSH: &str = "#version 150 compatibility
out vec2 texcoord_v;
void main() {
    gl_Position = ftransform();
    texcoord_v = gl_MultiTexCoord0.xy;
}
";

const GEOMETRY: &str = "#version 150 compatibility
#include \"/lib/geometry.glsl\"
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec2 texcoord_v[];
out vec2 texcoord;
void main() {
    for (int i = 0; i < 3; i++) {
        gl_Position = gl_in[i].gl_Position;
        texcoord = shift(texcoord_v[i]);
        EmitVertex();
    }
    EndPrimitive();
}
";

const GEOMETRY_LIB: &str = "vec2 shift(vec2 v) {
    return v + vec2(0.5);
}
";

const GEOMETRY_FSH: &str = "#version 150 compatibility
uniform sampler2D gtexture;
in vec2 texcoord;
/* RENDERTARGETS: 0 */
out vec4 outColor0;
void main() {
    outColor0 = texture(gtexture, texcoord);
}
";

fn geometry_pack(geometry: &str, lib: &str) -> Vec<(&'static str, String)> {
    vec![
        ("gbuffers_terrain.vsh", GEOMETRY_VSH.to_string()),
        ("gbuffers_terrain.gsh", geometry.to_string()),
        ("gbuffers_terrain.fsh", GEOMETRY_FSH.to_string()),
        ("lib/geometry.glsl", lib.to_string()),
    ]
}

#[test]
fn a_geometry_stage_without_driver_is_preprocessed_and_says_so() {
    let files = geometry_pack(GEOMETRY, GEOMETRY_LIB);
    let report = validate(&as_refs(&files), false);
    assert_eq!(report.errors(), 0, "{}", show(&report));
    assert!(has(&report, false, "gbuffers_terrain.gsh", 1, "only preprocessed"), "{}", show(&report));
    assert_eq!(report.warnings(), 1, "{}", show(&report));
    // Vertex and fragment stages still go through naga, each alone.
    assert_eq!(report.stages_validated, 2);
    // The program is valid as far as it was checked, and the report says how far.
    let program = report.programs.iter().find(|p| p.id == "gbuffers_terrain").unwrap();
    assert_eq!(program.only_preprocessed, ["gbuffers_terrain.gsh"]);
    let json: serde_json::Value = serde_json::from_str(&tidepack_validate::output::json(&report)).unwrap();
    let listed = json["programs"].as_array().unwrap().iter().find(|p| p["program"] == "gbuffers_terrain").unwrap();
    assert_eq!(listed["only_preprocessed"], serde_json::json!(["gbuffers_terrain.gsh"]), "{json}");
    let mut sink = codespan_reporting::term::termcolor::NoColor::new(Vec::new());
    let summary = tidepack_validate::output::human(&report, &mut sink).unwrap();
    assert!(summary.contains("only preprocessed, not compiled") && summary.contains("gbuffers_terrain.gsh"), "{summary}");
}

/// A geometry stage naming a fragment shader's built-in (`gl_FragCoord`, through an include),
/// which every driver refuses as undeclared, is an error at its line without `--driver` too.
#[test]
fn a_fragment_built_in_in_a_geometry_stage_is_an_error_at_its_line() {
    let lib = "vec2 shift(vec2 v) {\n    return v + gl_FragCoord.xy;\n}\n";
    let report = validate(&as_refs(&geometry_pack(GEOMETRY, lib)), false);
    assert_eq!(report.errors(), 1, "{}", show(&report));
    assert!(has(&report, true, "lib/geometry.glsl", 2, "`gl_FragCoord` is a fragment shader built-in: a geometry shader has no such variable"), "{}", show(&report));
}

#[test]
fn an_include_cycle_in_a_geometry_stage_is_reported() {
    let cyclic = format!("#include \"/lib/geometry.glsl\"\n{GEOMETRY_LIB}");
    let files = geometry_pack(GEOMETRY, &cyclic);
    for driver in [false, true] {
        let report = validate(&as_refs(&files), driver);
        assert!(has(&report, true, "lib/geometry.glsl", 1, "include cycle"), "driver {driver}: {}", show(&report));
        assert_eq!(status(&report, "gbuffers_terrain"), Status::Invalid);
    }
}

#[test]
fn an_error_directive_in_a_geometry_stage_is_reported() {
    let files = geometry_pack(&GEOMETRY.replace("layout(triangles) in;", "#error no geometry today"), GEOMETRY_LIB);
    let report = validate(&as_refs(&files), false);
    assert!(has(&report, true, "gbuffers_terrain.gsh", 3, "no geometry today"), "{}", show(&report));
}

#[test]
fn a_clean_geometry_program_validates_under_the_driver() {
    let files = geometry_pack(GEOMETRY, GEOMETRY_LIB);
    let report = validate(&as_refs(&files), true);
    assert!(report.diagnostics.is_empty(), "{}", show(&report));
    assert_eq!(status(&report, "gbuffers_terrain"), Status::Valid);
    assert!(report.programs.iter().all(|p| p.only_preprocessed.is_empty()));
    let driver = report.driver.as_ref().unwrap();
    assert_eq!(driver.both_accept, 1, "{driver:?}");
}

#[test]
fn a_syntax_error_in_a_geometry_stage_is_reported_by_the_driver_at_its_line() {
    let broken = GEOMETRY.replace("        EmitVertex();", "        EmitVertex()");
    let files = geometry_pack(&broken, GEOMETRY_LIB);
    let report = validate(&as_refs(&files), true);
    // Mesa reports a missing `;` at the next token, on the following line.
    assert!(
        report.diagnostics.iter().any(|d| d.is_error()
            && d.message.contains("OpenGL driver")
            && d.location.as_ref().is_some_and(|l| l.path == "gbuffers_terrain.gsh" && (11..=12).contains(&l.line))),
        "{}",
        show(&report)
    );
    assert_eq!(report.driver.as_ref().unwrap().only_driver_rejects, ["gbuffers_terrain"]);
    // An error in an included function is located in the included file.
    let files = geometry_pack(GEOMETRY, &GEOMETRY_LIB.replace("vec2(0.5)", "vec3(0.5)"));
    let report = validate(&as_refs(&files), true);
    assert!(has(&report, true, "lib/geometry.glsl", 2, "OpenGL driver"), "{}", show(&report));
    // Without the driver the same mistake is not an error: the stage was only preprocessed.
    let files = geometry_pack(&broken, GEOMETRY_LIB);
    let report = validate(&as_refs(&files), false);
    assert_eq!(report.errors(), 0, "{}", show(&report));
    assert!(has(&report, false, "gbuffers_terrain.gsh", 1, "only preprocessed"), "{}", show(&report));
}

#[test]
fn geometry_outputs_that_do_not_link_with_the_fragment_stage_are_reported_by_the_driver() {
    let geometry = GEOMETRY.replace("out vec2 texcoord;", "out vec3 texcoord;").replace("texcoord = shift(texcoord_v[i]);", "texcoord = vec3(shift(texcoord_v[i]), 0.0);");
    let files = geometry_pack(&geometry, GEOMETRY_LIB);
    let report = validate(&as_refs(&files), true);
    assert!(report.diagnostics.iter().any(|d| d.is_error() && d.message.contains("OpenGL driver") && d.message.contains("texcoord")), "{}", show(&report));
    assert_eq!(status(&report, "gbuffers_terrain"), Status::Invalid);
}

const TESS_VSH: &str = "#version 400 compatibility
out vec3 position_v;
void main() { position_v = gl_Vertex.xyz; }
";

const TESS_CONTROL: &str = "#version 400 compatibility
layout(vertices = 3) out;
in vec3 position_v[];
out vec3 position_c[];
void main() {
    position_c[gl_InvocationID] = position_v[gl_InvocationID];
    gl_TessLevelOuter[0] = 2.0; gl_TessLevelOuter[1] = 2.0; gl_TessLevelOuter[2] = 2.0;
    gl_TessLevelInner[0] = 2.0;
}
";

const TESS_EVALUATION: &str = "#version 400 compatibility
layout(triangles, equal_spacing, ccw) in;
in vec3 position_c[];
uniform mat4 gbufferProjection;
void main() {
    vec3 p = gl_TessCoord.x * position_c[0] + gl_TessCoord.y * position_c[1] + gl_TessCoord.z * position_c[2];
    gl_Position = gbufferProjection * vec4(p, 1.0);
}
";

const TESS_FSH: &str = "#version 400 compatibility
/* RENDERTARGETS: 0 */
out vec4 outColor0;
void main() { outColor0 = vec4(1.0); }
";

fn tessellation_pack(evaluation: &str) -> Vec<(&'static str, String)> {
    vec![
        ("gbuffers_water.vsh", TESS_VSH.to_string()),
        ("gbuffers_water.tcs", TESS_CONTROL.to_string()),
        ("gbuffers_water.tes", evaluation.to_string()),
        ("gbuffers_water.fsh", TESS_FSH.to_string()),
    ]
}

#[test]
fn tessellation_stages_are_preprocessed_and_compiled_by_the_driver() {
    let files = tessellation_pack(TESS_EVALUATION);
    let report = validate(&as_refs(&files), false);
    assert_eq!(report.errors(), 0, "{}", show(&report));
    assert!(has(&report, false, "gbuffers_water.tcs", 1, "only preprocessed"), "{}", show(&report));
    assert!(has(&report, false, "gbuffers_water.tes", 1, "only preprocessed"), "{}", show(&report));
    let report = validate(&as_refs(&files), true);
    assert!(report.diagnostics.is_empty(), "{}", show(&report));
    let broken = TESS_EVALUATION.replace("vec4(p, 1.0)", "vec4(p)");
    let files = tessellation_pack(&broken);
    let report = validate(&as_refs(&files), true);
    assert!(has(&report, true, "gbuffers_water.tes", 7, "OpenGL driver"), "{}", show(&report));
}

#[test]
fn the_driver_agrees_with_naga_on_compute_stages() {
    let files = compute_pack(COMPUTE_A);
    let report = validate(&as_refs(&files), true);
    assert!(report.diagnostics.is_empty(), "{}", show(&report));
    assert_eq!(report.driver.as_ref().unwrap().both_accept, 2);
    let broken = COMPUTE_A.replace("    ivec2 p = ivec2(gl_GlobalInvocationID.xy);", "    ivec2 p = gl_GlobalInvocationID.xy;");
    let files = compute_pack(&broken);
    let report = validate(&as_refs(&files), true);
    let driver = report.driver.as_ref().unwrap();
    assert_eq!(driver.both_reject, 1, "{driver:?}: {}", show(&report));
    assert!(driver.only_tidepack_rejects.is_empty() && driver.only_driver_rejects.is_empty(), "{driver:?}");
}

#[test]
fn fuzzing_compute_and_geometry_stages_finds_no_crash() {
    let packs = [compute_pack(COMPUTE_A), geometry_pack(GEOMETRY, GEOMETRY_LIB), tessellation_pack(TESS_EVALUATION)];
    let seeds: Vec<tidepack_validate::fuzz::SeedPack> =
        packs.iter().map(|files| files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())).collect()).collect();
    let stats = tidepack_validate::fuzz::run(&seeds, 3000, std::time::Duration::from_secs(30), 0x6373_6868);
    assert!(stats.executions >= 50, "{stats:?}");
    let findings: Vec<String> =
        stats.findings.iter().map(|(what, input)| format!("{what}\n--- input ---\n{}", String::from_utf8_lossy(input))).collect();
    assert_eq!(stats.crashes + stats.invariant_failures, 0, "{}", findings.join("\n\n"));
}

#[test]
fn the_driver_skips_a_program_turned_off_as_validate_does() {
    let vertex = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";
    let off = "#version 120\n#error \"turn this program off without colored lights\"\nvoid main() { gl_FragData[0] = vec4(1.0); }\n";
    let files = [
        ("composite.vsh", vertex),
        ("composite.fsh", "#version 120\nvoid main() { gl_FragData[0] = vec4(1.0); }\n"),
        ("composite1.vsh", vertex),
        ("composite1.fsh", off),
        ("shaders.properties", "program.composite1.enabled=false\n"),
    ];
    let report = validate(&files, true);
    assert!(matches!(status(&report, "composite1"), Status::Skipped(_)), "{:?}", status(&report, "composite1"));
    let driver = report.driver.as_ref().expect("the driver ran");
    assert!(driver.only_driver_rejects.is_empty() && driver.both_accept == 1, "{driver:?}{}", show(&report));
}

#[test]
fn iris_features_macos_lacks_are_refused_there_when_macos_is_a_target() {
    let files = [
        ("final.vsh", "#version 120\nvoid main() { gl_Position = ftransform(); }\n"),
        ("final.fsh", "#version 120\nvoid main() { gl_FragColor = vec4(1.0); }\n"),
        ("shaders.properties", "sliders = \niris.features.required = SSBO SEPARATE_HARDWARE_SAMPLERS COMPUTE_SHADERS\n"),
    ];
    let pack = || pack_from_memory("test/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    let iris = |target| Options { threads: 2, loader: tidepack_loader::Loader::Iris, target, ..Options::default() };
    let report = validate_pack(pack(), &iris(tidepack_glsl::Drivers::ALL)).unwrap();
    let on_macos: Vec<_> = report.diagnostics.iter().filter(|d| d.code == tidepack_glsl::Code::Macos).collect();
    assert_eq!(on_macos.len(), 2, "{}", show(&report));
    assert!(has(&report, true, "shaders.properties", 2, "SSBO (shader storage buffers, OpenGL 4.3)"), "{}", show(&report));
    assert!(has(&report, true, "shaders.properties", 2, "COMPUTE_SHADERS"), "{}", show(&report));
    assert!(on_macos.iter().all(|d| d.refused_by == tidepack_glsl::Drivers::MACOS));
    // Not a target by default; and OptiFine does not read the key.
    let report = validate_pack(pack(), &iris(tidepack_validate::DEFAULT_TARGET)).unwrap();
    assert!(report.errors() == 0, "{}", show(&report));
    let report = validate_pack(pack(), &Options { threads: 2, target: tidepack_glsl::Drivers::ALL, ..Options::default() }).unwrap();
    assert!(report.errors() == 0, "{}", show(&report));
}

/// A Distant Horizons program as packs write it: `dhMaterialId` undeclared (Iris declares it
/// in the vertex stage), `dhProjection`, legacy built-ins, and `DISTANT_HORIZONS` tested.
fn distant_horizons_pack() -> Vec<(&'static str, &'static str)> {
    vec![
        ("final.vsh", "#version 120\nvoid main() { gl_Position = ftransform(); }\n"),
        ("final.fsh", "#version 120\nvoid main() { gl_FragColor = vec4(1.0); }\n"),
        (
            "dh_water.vsh",
            "#version 330 compatibility\nuniform mat4 dhProjection;\nflat out int water;\nout vec4 tint;\n\
             void main() {\n    water = int(dhMaterialId == DH_BLOCK_WATER);\n    tint = gl_Color;\n\
                 gl_Position = dhProjection * (gl_ModelViewMatrix * gl_Vertex);\n}\n",
        ),
        (
            "dh_water.fsh",
            "#version 330 compatibility\nflat in int water;\nin vec4 tint;\n/* RENDERTARGETS: 0 */\nlayout(location = 0) out vec4 color;\n\
             void main() {\n#ifndef DISTANT_HORIZONS\n    undefined_outside_dh();\n#endif\n    color = tint * float(water);\n}\n",
        ),
    ]
}

#[test]
fn distant_horizons_programs_validate_with_what_iris_declares_and_mesa_agrees() {
    let files = distant_horizons_pack();
    let pack = || pack_from_memory("test/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    let loader = tidepack_loader::Loader::Iris;
    let with_dh = tidepack_loader::macros::StandardMacros { distant_horizons: true, ..tidepack_loader::macros::StandardMacros::for_loader(loader) };
    let report = validate_pack(pack(), &Options { threads: 2, loader, macros: with_dh, driver: true, ..Options::default() }).unwrap();
    assert_eq!(status(&report, "dh_water"), Status::Valid, "{}", show(&report));
    assert!(report.diagnostics.is_empty(), "{}", show(&report));
    let driver = report.driver.as_ref().expect("the driver ran");
    assert!(driver.only_driver_rejects.is_empty() && driver.only_tidepack_rejects.is_empty() && driver.both_accept == 2, "{driver:?}");

    // Without the mod the program is not run, and the report says how to validate it.
    let plain = Options { threads: 2, loader, macros: tidepack_loader::macros::StandardMacros::for_loader(loader), ..Options::default() };
    let report = validate_pack(pack(), &plain).unwrap();
    assert!(matches!(status(&report, "dh_water"), Status::Skipped(why) if why.contains("--distant-horizons")), "{}", show(&report));

    // A DH vertex stage that uses another undeclared name is still an error at its line.
    let mut broken = distant_horizons_pack();
    broken[2].1 = "#version 330 compatibility\nvoid main() {\n    gl_Position = vec4(float(dhMaterialId) * notDeclared);\n}\n";
    let pack = pack_from_memory("test/shaders/", broken.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    let with_dh = tidepack_loader::macros::StandardMacros { distant_horizons: true, ..tidepack_loader::macros::StandardMacros::for_loader(loader) };
    let report = validate_pack(pack, &Options { threads: 2, loader, macros: with_dh, ..Options::default() }).unwrap();
    assert!(has(&report, true, "dh_water.vsh", 3, "notDeclared"), "{}", show(&report));
}
