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
    let program = ctx.compile_program(vs, None, fs, &[("mc_Entity", 8)], &[]).unwrap_or_else(|e| panic!("{e}"));
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
        .compile_program(vs, None, fs, &[("mc_Entity", 8)], &[("outColor0", 0), ("outColor1", 1)])
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
    let err = ctx.compile_program(vs, None, fs, &[], &[]).expect_err("undeclared identifier must fail");
    assert_eq!(err.step, ProgramStep::CompileFragment);
    let messages = err.messages();
    assert!(messages.iter().any(|m| m.line == 3 && m.severity == "error" && m.message.contains("undeclared")), "{err}");
}

#[test]
fn a_link_error_is_reported_as_such() {
    let ctx = context();
    let vs = "#version 120\nvoid helper();\nvoid main() { helper(); gl_Position = ftransform(); }\n";
    let fs = "#version 120\nvoid main() { gl_FragColor = vec4(1.0); }\n";
    let err = ctx.compile_program(vs, None, fs, &[], &[]).expect_err("missing function must fail to link");
    assert_eq!(err.step, ProgramStep::Link);
    assert!(!err.log.trim().is_empty());
}

/// The harness records what a vertex stage computed with transform feedback and relies on
/// glClipControl and glProvokingVertex being there.
#[test]
fn a_capture_program_records_the_vertex_outputs_bit_for_bit() {
    use glow::HasContext as _;
    let ctx = context();
    assert!(ctx.legacy().clip_control.is_some(), "{} has no glClipControl", ctx.info());
    let vs = "#version 330 compatibility\nin vec4 p;\nout vec2 uv;\nout float k;\n\
              void main() { gl_Position = vec4(p.xy, p.z / 3.0, 1.0); uv = p.yx; k = p.w * 0.1; }\n";
    let program = ctx.compile_capture_program(vs, &[("p", 0)], &["gl_Position", "uv", "k"]).unwrap_or_else(|e| panic!("{e}"));
    let input: [f32; 12] = [1.0, 2.0, 1.0, 3.0, -4.0, 0.5, 2.0, 7.0, 0.25, -0.75, 5.0, 1.0];
    let gl = ctx.gl();
    let mut captured = [0u8; 3 * 7 * 4];
    // SAFETY: the context is current on this thread; every object is made and deleted here.
    unsafe {
        // Surfaceless: draws need a complete framebuffer even with the rasteriser off.
        let fbo = gl.create_framebuffer().unwrap();
        let rbo = gl.create_renderbuffer().unwrap();
        gl.bind_renderbuffer(glow::RENDERBUFFER, Some(rbo));
        gl.renderbuffer_storage(glow::RENDERBUFFER, glow::RGBA8, 1, 1);
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
        gl.framebuffer_renderbuffer(glow::FRAMEBUFFER, glow::COLOR_ATTACHMENT0, glow::RENDERBUFFER, Some(rbo));
        let vbo = gl.create_buffer().unwrap();
        gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
        let bytes: Vec<u8> = input.iter().flat_map(|v| v.to_le_bytes()).collect();
        gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, &bytes, glow::STATIC_DRAW);
        gl.enable_vertex_attrib_array(0);
        gl.vertex_attrib_pointer_f32(0, 4, glow::FLOAT, false, 16, 0);
        let feedback = gl.create_buffer().unwrap();
        gl.bind_buffer(glow::TRANSFORM_FEEDBACK_BUFFER, Some(feedback));
        gl.buffer_data_size(glow::TRANSFORM_FEEDBACK_BUFFER, captured.len() as i32, glow::STATIC_COPY);
        gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, Some(feedback));
        gl.use_program(Some(program.raw));
        gl.enable(glow::RASTERIZER_DISCARD);
        gl.begin_transform_feedback(glow::TRIANGLES);
        gl.draw_arrays(glow::TRIANGLES, 0, 3);
        gl.end_transform_feedback();
        gl.disable(glow::RASTERIZER_DISCARD);
        gl.get_buffer_sub_data(glow::TRANSFORM_FEEDBACK_BUFFER, 0, &mut captured);
        gl.delete_buffer(vbo);
        gl.delete_buffer(feedback);
        gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        gl.delete_framebuffer(fbo);
        gl.delete_renderbuffer(rbo);
        assert_eq!(gl.get_error(), glow::NO_ERROR);
    }
    ctx.delete_program(program);
    let out: Vec<f32> = captured.chunks_exact(4).map(|c| f32::from_le_bytes(c.try_into().unwrap())).collect();
    for (v, p) in input.chunks_exact(4).enumerate() {
        let expected = [p[0], p[1], p[2] / 3.0, 1.0, p[1], p[0], p[3] * 0.1];
        let got = &out[v * 7..v * 7 + 7];
        assert_eq!(got.iter().map(|f| f.to_bits()).collect::<Vec<_>>(), expected.map(f32::to_bits).to_vec(), "vertex {v}: {got:?}");
    }
}

/// Two contexts on one thread (a validator's driver beside a renderer's): each compiles when it
/// is used, and dropping the older one leaves the newer one working, as
/// `tools/corpus --covering` needs from one pack to the next.
#[test]
fn two_contexts_on_one_thread_each_compile_and_survive_the_other_dropped() {
    let vs = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";
    let fs = "#version 120\nvoid main() { gl_FragColor = vec4(1.0); }\n";
    let older = context();
    let newer = context();
    for ctx in [&older, &newer, &older] {
        let program = ctx.compile_program(vs, None, fs, &[], &[]).unwrap_or_else(|e| panic!("{e}"));
        ctx.delete_program(program);
    }
    drop(older);
    let program = newer.compile_program(vs, None, fs, &[], &[]).unwrap_or_else(|e| panic!("with the other context dropped: {e}"));
    newer.delete_program(program);
}
