#version 120
// Copies what composite.csh left in colortex0.
uniform sampler2D colortex0;
varying vec2 uv;
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = texture2D(colortex0, uv);
}
