#version 120
// An `#extension` after code, as packs written on NVIDIA put it: Iris's preprocessor collects
// every `#extension` ahead of the stage, so the driver meets it after `#version` (under
// OptiFine, Mesa and AMD refuse the stage).
uniform sampler2D gtexture;
varying vec2 texcoord;
varying vec4 glcolor;
#extension GL_ARB_shader_texture_lod : enable
void main() {
    gl_FragData[0] = texture2DLod(gtexture, texcoord, 0.0) * glcolor;
}
