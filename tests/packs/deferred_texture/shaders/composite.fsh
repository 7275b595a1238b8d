#version 120
// colortex6 is the composite stage's custom texture here: blue; colortex0 holds the deferred
// program's red.
uniform sampler2D colortex0;
uniform sampler2D colortex6;
varying vec2 uv;
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(texture2D(colortex0, uv).r, 0.0, texture2D(colortex6, uv).b, 1.0);
}
