#version 120
// Reads what composite.csh left and sets blue to one half: the terrain is (1, 1, 0.5) after it.
// What Iris's begin pass stored in colortex1 is added; colortex1 is cleared to zero otherwise.
const vec4 colortex1ClearColor = vec4(0.0, 0.0, 0.0, 0.0);
uniform sampler2D colortex0;
uniform sampler2D colortex1;
varying vec2 uv;
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(texture2D(colortex0, uv).rg, 0.5, 1.0) + vec4(texture2D(colortex1, uv).rgb, 0.0);
}
