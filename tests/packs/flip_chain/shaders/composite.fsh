#version 120
// colortex0 read and written: the loader flips it, so composite1 reads this pass's output.
uniform sampler2D colortex0;
uniform sampler2D colortex3;
varying vec2 texcoord;
void main() {
    vec3 color = texture2D(colortex0, texcoord).rgb;
    float up = texture2D(colortex3, texcoord).r;
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(mix(color, vec3(max(up, 0.0)), 0.25), 1.0);
}
