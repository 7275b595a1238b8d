#version 130
// From GLSL 1.30 precision qualifiers are legal on globals, parameters and locals, and change
// nothing on desktop drivers.
precision mediump float;
uniform highp sampler2D colortex0;
in vec2 texcoord;
lowp float plantHash(lowp vec2 coord) {
    highp float seed = dot(coord, vec2(12.9898, 78.233));
    return fract(sin(seed) * 43758.547);
}
/* DRAWBUFFERS:0 */
void main() {
    mediump vec3 color = texture(colortex0, texcoord).rgb;
    gl_FragData[0] = vec4(color * plantHash(texcoord), 1.0);
}
