#version 120
varying vec4 color;
varying vec4 tangent;
varying vec2 spriteCentre;
void main() {
/* DRAWBUFFERS:01 */
    gl_FragData[0] = color;
    gl_FragData[1] = vec4(tangent.xyz * 0.5 + 0.5, tangent.w * 0.25 + 0.5 + spriteCentre.x * 0.1);
}
