#version 120
// A lookup with a bias in a vertex stage, which has no derivatives and so no level to bias
// (Cynun/CRShaders reads the depth buffer so in its gbuffers' vertex stages).
uniform sampler2D depthtex1;
varying vec2 uv;
varying float depth;
void main() {
    gl_Position = ftransform();
    uv = gl_MultiTexCoord0.xy;
    depth = texture2D(depthtex1, uv, 0.0).x;
}
