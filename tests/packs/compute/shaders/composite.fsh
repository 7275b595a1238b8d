#version 120
// Reads what composite.csh left and sets blue to one half: the terrain is (1, 1, 0.5) after it.
uniform sampler2D colortex0;
varying vec2 uv;
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(texture2D(colortex0, uv).rg, 0.5, 1.0);
}
