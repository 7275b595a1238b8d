#version 420 compatibility
// As zombye/Ozius keeps its time: a `const` outside functions read from a uniform, which
// NVIDIA takes and Mesa refuses. The constant from a literal is fine.
uniform float sunAngle;
uniform sampler2D colortex0;
in vec2 uv;
const float dayLength = 12e2;
const float globalTime = fract(sunAngle) * dayLength;
void main() {
    gl_FragColor = texture(colortex0, uv) * globalTime;
}
