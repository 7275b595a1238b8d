//! What GLSL forbids and naga does not say in GLSL terms, each checked against Mesa
//! (`--driver`): the mistake is reported once, at its line, in the rule's words rather than
//! naga's, and Mesa refuses the program too. Needs Mesa's EGL/GL (tools/test installs them);
//! without it the tests fail, they never skip.

use tidepack_loader::input::pack_from_memory;
use tidepack_validate::{Options, Report, Status, validate_pack};

const VERTEX: &str = "#version 120\nvarying vec2 uv;\nvoid main() { gl_Position = ftransform(); uv = gl_MultiTexCoord0.xy; }\n";

fn validate(fragment: &str) -> Report {
    validate_program(VERTEX, fragment)
}

fn validate_program(vertex: &str, fragment: &str) -> Report {
    let files = [("composite.vsh", vertex), ("composite.fsh", fragment)];
    let pack = pack_from_memory("test/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    validate_pack(pack, &Options { threads: 2, driver: true, ..Options::default() }).unwrap()
}

/// The errors of the report at `composite.fsh`, as `line: message`.
fn errors(report: &Report) -> Vec<String> {
    report
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| format!("{}: {}", d.location.as_ref().map_or(0, |l| l.line), d.message))
        .collect()
}

#[test]
fn each_mistake_is_one_error_at_its_line_and_mesa_agrees() {
    let cases = [
        ("#version 120\nvarying vec2 uv;\nvoid main() {\n vec4 output = vec4(uv, 0.0, 1.0);\n gl_FragData[0] = output;\n}\n", 4, "`output` is a reserved word"),
        ("#version 120\nvarying vec2 uv;\nfloat twice(float x) {\n x *= 2.0;\n}\nvoid main() { gl_FragData[0] = vec4(twice(uv.x)); }\n", 3, "twice() returns float but its body has no `return`"),
        ("#version 120\nvarying vec2 uv;\nvoid main() {\n uv *= 2.0;\n gl_FragData[0] = vec4(uv, 0.0, 1.0);\n}\n", 4, "`uv` is an input of this fragment shader"),
        ("#version 120\nvarying vec2 uv;\nuniform sampler2DShadow shadowtex0;\nvoid main() {\n gl_FragData[0] = vec4(texture2D(shadowtex0, uv).r);\n}\n", 5, "no overload of texture2D() takes a sampler2DShadow"),
        ("#version 120\nvarying vec2 uv;\nuniform float viewWidth;\nvoid main() {\n const float pixel = 1.0 / viewWidth;\n gl_FragData[0] = vec4(uv * pixel, 0.0, 1.0);\n}\n", 5, "the uniform `viewWidth` is not one"),
        ("#version 330 compatibility\nin vec2 uv;\nlayout(location = 1) out vec4 extra;\nvoid main() {\n gl_FragData[0] = vec4(uv, 0.0, 1.0);\n extra = vec4(1.0);\n}\n", 5, "writes gl_FragData and its own output `extra`"),
        ("#version 330 compatibility\nin vec2 uv;\nout vec4 colour;\nvoid main() {\n uint n = 3;\n colour = vec4(float(n) * uv.x);\n}\n", 5, "mixes the uint `n` with the int literal 3"),
    ];
    for (fragment, line, needle) in cases {
        let report = validate(fragment);
        let found = errors(&report);
        let ours: Vec<&String> = found.iter().filter(|e| !e.contains("OpenGL driver")).collect();
        assert!(ours.len() == 1 && ours[0].starts_with(&format!("{line}: ")) && ours[0].contains(needle), "{needle}: {found:#?}");
        assert!(!ours[0].contains("tp_"), "{ours:?}");
        let driver = report.driver.as_ref().expect("the driver ran");
        assert_eq!((driver.both_reject, driver.only_tidepack_rejects.len()), (1, 0), "{needle}: Mesa accepts it: {found:#?}");
        assert_eq!(report.programs[0].status, Status::Invalid);
    }
}

#[test]
fn what_drivers_accept_passes() {
    let fragment = "#version 120\nvarying vec2 uv;\nuniform sampler2DShadow shadowtex0;\nuniform float viewWidth;\nfloat scale(float x) { if (x > 0.0) return x; }\nvec2 moved(vec2 uv) { uv *= 2.0; return uv; }\nvoid main() {\n vec2 at = uv;\n at.x += 1.0 / viewWidth;\n const float k = 2.0;\n float output_ = shadow2D(shadowtex0, vec3(moved(at), 0.5)).r;\n gl_FragData[0] = vec4(output_ * k * scale(at.y));\n}\n";
    let report = validate(fragment);
    assert!(errors(&report).is_empty(), "{:#?}", errors(&report));
    let driver = report.driver.as_ref().expect("the driver ran");
    assert_eq!(driver.both_accept, 1);
}

#[test]
fn a_vertex_shader_may_leave_gl_position_unwritten_from_glsl_140() {
    let vertex = "#version 150 compatibility\nout vec2 uv;\nvoid main() {\n uv = gl_MultiTexCoord0.xy;\n}\n";
    let fragment = "#version 150 compatibility\nin vec2 uv;\nvoid main() { gl_FragData[0] = vec4(uv, 0.0, 1.0); }\n";
    let report = validate_program(vertex, fragment);
    assert!(errors(&report).is_empty(), "{:#?}", errors(&report));
    let warned = report.diagnostics.iter().any(|d| {
        !d.is_error() && d.message.contains("never writes gl_Position") && d.location.as_ref().is_some_and(|l| l.path == "composite.vsh" && l.line == 3)
    });
    assert!(warned, "{:#?}", report.diagnostics);
    assert_eq!(report.driver.as_ref().expect("the driver ran").both_accept, 1);
}
