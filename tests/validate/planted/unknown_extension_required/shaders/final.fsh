#version 120
#extension GL_ARB_shader_texture_lod : enable
#extension GL_ARB_shader_textur_lod : require
uniform sampler2D colortex0;
varying vec2 uv;
void main() {
    gl_FragColor = texture2DLod(colortex0, uv, 0.0);
}
