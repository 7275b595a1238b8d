#version 150 compatibility
// `tint` is read here and the vertex stage never declares it: Mesa links it (GLSL 1.50), GLSL 4.20 calls it a link error.
uniform sampler2D colortex0;
varying vec2 uv;
varying vec3 tint;
void main() {
    gl_FragData[0] = texture(colortex0, uv) * vec4(tint, 1.0);
}
