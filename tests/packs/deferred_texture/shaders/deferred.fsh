#version 120
// colortex5 is the deferred stage's custom texture here: red.
uniform sampler2D colortex5;
varying vec2 uv;
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(texture2D(colortex5, uv).r, 0.0, 0.0, 1.0);
}
