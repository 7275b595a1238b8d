#version 400 compatibility
// gl_FragCoord redeclared, as GLSL allows (with or without a layout qualifier): a built-in,
// not an input the vertex stage must write.
in vec4 gl_FragCoord;
uniform sampler2D colortex0;
uniform float viewWidth;
in vec2 uv;
void main() {
    gl_FragData[0] = texture(colortex0, uv) * (gl_FragCoord.x / viewWidth);
}
