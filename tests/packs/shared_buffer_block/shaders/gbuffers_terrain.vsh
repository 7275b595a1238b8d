#version 430 compatibility
// One buffer block (Iris's SSBOs) that both stages declare at binding 0, as
// Keolai/itty-bitty-shader's coloured lights: one buffer, which the vertex stage may write too.
layout(std430, binding = 0) buffer lightCounts {
    uint counted[];
};
out vec2 texcoord;
out vec4 tint;
void main() {
    gl_Position = ftransform();
    texcoord = gl_MultiTexCoord0.xy;
    tint = gl_Color * (1.0 + float(counted[0]));
}
