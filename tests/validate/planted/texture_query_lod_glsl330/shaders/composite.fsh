#version 330 compatibility
// textureQueryLod came with GLSL 4.00 (before, GL_ARB_texture_query_lod); GL_EXT_gpu_shader4_1
// does not bring it. Found behind a Distant Horizons switch in a released pack.
#extension GL_EXT_gpu_shader4_1 : enable
uniform sampler2D colortex0;
in vec2 uv;
void main() {
    float lod = textureQueryLod(colortex0, uv).x;
    gl_FragData[0] = textureLod(colortex0, uv, lod);
}
