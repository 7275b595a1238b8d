#version 330 compatibility
// textureLod on an unsigned-integer sampler, which OpenGL allows and naga refuses (Vulkan
// samples integer textures only through texelFetch): wgpu cannot draw this program, OpenGL
// can. What the lookup reads is masked away; the screen is green.
uniform usampler2D colortex1;
in vec2 uv;
/* DRAWBUFFERS:0 */
void main() {
    uint bits = textureLod(colortex1, uv, 0.0).x;
    gl_FragData[0] = vec4(0.0, 1.0, float(bits & 0u), 1.0);
}
