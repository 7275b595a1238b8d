#version 120
// After the shadow pass, over the shadow map: shadowcolor0 becomes its complement, and
// shadowcolor1 keeps what shadowcolor0 held before. Both read shadowcolor0 as the shadow pass
// left it, though this program draws into it.
const int shadowMapResolution = 256;
uniform sampler2D shadowcolor0;
varying vec2 uv;
void main() {
    vec4 before = texture2D(shadowcolor0, uv);
/* DRAWBUFFERS:01 */
    gl_FragData[0] = vec4(1.0 - before.rgb, 1.0);
    gl_FragData[1] = before;
}
