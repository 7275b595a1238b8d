#version 120
#include "/lib/a.glsl"
void main() { gl_FragColor = vec4(1.0); }
