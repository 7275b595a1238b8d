#version 120
// Colour to colortex0, the view-space normal to colortex2.
varying vec4 color;
varying vec3 normal;
void main() {
/* DRAWBUFFERS:02 */
    gl_FragData[0] = color;
    gl_FragData[1] = vec4(normalize(normal) * 0.5 + 0.5, 1.0);
}
