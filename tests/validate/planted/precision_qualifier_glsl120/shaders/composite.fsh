#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
// Reserved words in GLSL 1.20: Mesa refuses them, NVIDIA takes them.
lowp float plantHash(vec2 coord) {
    return fract(sin(dot(coord, vec2(12.9898, 78.233))) * 43758.547);
}
void main() {
    gl_FragData[0] = texture2D(colortex0, texcoord) * plantHash(texcoord);
}
