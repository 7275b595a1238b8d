#version 100
// GLSL ES 1.00: NVIDIA compiles it as desktop GLSL, Mesa wants a float precision first.
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
    gl_FragData[0] = texture2D(colortex0, texcoord);
}
