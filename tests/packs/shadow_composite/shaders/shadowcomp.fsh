#version 120
// After the shadow pass, over the shadow map: shadowcolor0 becomes its complement, and
// shadowcolor1 keeps what shadowcolor0 held before. Both read shadowcolor0 as the shadow pass
// left it, though this program draws into it. colortex9, which no other program names, holds
// its clear colour, transparent black.
const int shadowMapResolution = 256;
uniform sampler2D shadowcolor0;
uniform sampler2D colortex9;
varying vec2 uv;
void main() {
    vec4 before = texture2D(shadowcolor0, uv);
/* DRAWBUFFERS:01 */
    gl_FragData[0] = vec4(1.0 - before.rgb + texture2D(colortex9, uv).rgb, 1.0);
    gl_FragData[1] = before;
}
