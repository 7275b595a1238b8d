#version 120
// The left half of the screen shows shadowcolor0 at the middle of the shadow map, the right
// half shadowcolor1 there: both hold the complement of what the shadow pass drew once shadowcomp
// and shadowcomp1.csh have run.
uniform sampler2D shadowcolor0;
uniform sampler2D shadowcolor1;
varying vec2 uv;
void main() {
    vec2 middle = vec2(0.5);
    vec3 shown = uv.x < 0.5 ? texture2D(shadowcolor0, middle).rgb : texture2D(shadowcolor1, middle).rgb;
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(shown, 1.0);
}
