#version 120
// Reads what the terrain wrote, before the water: colortex2 and depthtex1, into a float buffer
// with a clear colour of its own.
/*
const int colortex3Format = RGBA16F;
*/
const vec4 colortex3ClearColor = vec4(0.0, 0.0, 1.0, 1.0);
uniform sampler2D colortex2;
uniform sampler2D depthtex1;
varying vec2 texcoord;
void main() {
    float up = texture2D(colortex2, texcoord).y * 2.0 - 1.0;
/* DRAWBUFFERS:3 */
    gl_FragData[0] = vec4(up, texture2D(depthtex1, texcoord).r, 0.0, 1.0);
}
