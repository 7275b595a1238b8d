#version 330 compatibility
// Under 3.30 the same line has one: `tint`, which must be reported here too, though the line
// already holds another program's error.
in vec2 uv;
#include "/lib/shade.glsl"
void main() {
    gl_FragData[0] = shade(uv);
}
