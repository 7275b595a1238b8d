#version 120
// A one-pixel checker over the scene, for composite1 to read through its mipmaps.
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
    float checker = mod(floor(gl_FragCoord.x) + floor(gl_FragCoord.y), 2.0);
/* DRAWBUFFERS:1 */
    gl_FragData[0] = vec4(texture2D(colortex0, texcoord).rgb * checker, 1.0);
}
