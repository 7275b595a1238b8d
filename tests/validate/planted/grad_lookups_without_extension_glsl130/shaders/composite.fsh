#version 130
// Gradient lookups by their extension names, with no extension enabled: GLSL 1.30 has
// textureGrad(), the ARB names need GL_ARB_shader_texture_lod, the 2D names GL_EXT_gpu_shader4.
uniform sampler2D colortex0;
in vec2 uv;
void main() {
    vec2 dx = dFdx(uv);
    vec2 dy = dFdy(uv);
    vec4 a = texture2DGradARB(colortex0, uv, dx, dy);
    vec4 b = texture2DGrad(colortex0, uv, dx, dy);
    gl_FragData[0] = a + b;
}
