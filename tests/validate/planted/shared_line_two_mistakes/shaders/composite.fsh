#version 120
// Under 1.20 the shared line has two mistakes: texture() and the undeclared `tint`.
varying vec2 uv;
#include "/lib/shade.glsl"
void main() {
    gl_FragData[0] = shade(uv);
}
