//! Needs Mesa's EGL and OpenGL (Debian: libegl1 libegl-mesa0 libgl1-mesa-dri; tools/test installs
//! them). Without them these tests fail with the driver's error; they never skip.

use tidepack_gldriver::{GlContext, ProgramStep, glow};

fn context() -> GlContext {
    GlContext::new().unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn context_is_a_compatibility_profile() {
    let ctx = context();
    let info = ctx.info();
    assert!(info.version.contains("Compatibility"), "not a compatibility context: {info}");
    let major: u32 = info.version.split('.').next().and_then(|m| m.parse().ok()).expect("a version number");
    assert!(major >= 3, "{info}");
}

#[test]
fn compiles_glsl_120_with_legacy_builtins() {
    let ctx = context();
    let vs = "#version 120\nattribute vec4 mc_Entity;\nvarying vec2 uv;\nvarying float id;\n\
              void main() { gl_Position = ftransform(); uv = gl_MultiTexCoord0.xy; id = mc_Entity.x; }\n";
    let fs = "#version 120\nuniform sampler2D gtexture;\nvarying vec2 uv;\nvarying float id;\n\
              void main() { gl_FragData[0] = texture2D(gtexture, uv) * id; gl_FragData[1] = vec4(1.0); }\n";
    let program = ctx.compile_program(vs, fs, &[("mc_Entity", 8)], &[]).unwrap_or_else(|e| panic!("{e}"));
    // SAFETY: the context is current on this thread.
    let location = unsafe { glow::HasContext::get_attrib_location(ctx.gl(), program.raw, "mc_Entity") };
    assert_eq!(location, Some(8));
    ctx.delete_program(program);
}

#[test]
fn compiles_glsl_330_compatibility_with_bound_outputs() {
    let ctx = context();
    let vs = "#version 330 compatibility\nin vec4 mc_Entity;\nout vec2 uv;\n\
              void main() { gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; uv = gl_MultiTexCoord0.xy + mc_Entity.xy; }\n";
    let fs = "#version 330 compatibility\nuniform sampler2D colortex0;\nin vec2 uv;\nout vec4 outColor0;\nout vec4 outColor1;\n\
              void main() { outColor0 = texture(colortex0, uv); outColor1 = vec4(uv, 0.0, 1.0); }\n";
    let program = ctx
        .compile_program(vs, fs, &[("mc_Entity", 8)], &[("outColor0", 0), ("outColor1", 1)])
        .unwrap_or_else(|e| panic!("{e}"));
    // SAFETY: the context is current on this thread.
    let location = unsafe { glow::HasContext::get_frag_data_location(ctx.gl(), program.raw, "outColor1") };
    assert_eq!(location, 1);
    ctx.delete_program(program);
}

#[test]
fn a_compile_error_returns_the_driver_log_with_its_line() {
    let ctx = context();
    let vs = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";
    let fs = "#version 120\nvoid main() {\n    gl_FragColor = vec4(undeclared, 1.0);\n}\n";
    let err = ctx.compile_program(vs, fs, &[], &[]).expect_err("undeclared identifier must fail");
    assert_eq!(err.step, ProgramStep::CompileFragment);
    let messages = err.messages();
    assert!(messages.iter().any(|m| m.line == 3 && m.severity == "error" && m.message.contains("undeclared")), "{err}");
}

#[test]
fn a_link_error_is_reported_as_such() {
    let ctx = context();
    let vs = "#version 120\nvoid helper();\nvoid main() { helper(); gl_Position = ftransform(); }\n";
    let fs = "#version 120\nvoid main() { gl_FragColor = vec4(1.0); }\n";
    let err = ctx.compile_program(vs, fs, &[], &[]).expect_err("missing function must fail to link");
    assert_eq!(err.step, ProgramStep::Link);
    assert!(!err.log.trim().is_empty());
}
