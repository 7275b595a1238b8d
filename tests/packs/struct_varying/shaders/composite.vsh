#version 330 compatibility
// A struct passed from the vertex stage to the fragment stage, as packs pass per-frame
// parameters computed once per vertex (cloud coverage, light colours).
struct Parameters {
    float coverage;
    vec2 amounts;
};
flat out Parameters parameters;
out vec2 uv;
void main() {
    gl_Position = ftransform();
    uv = gl_MultiTexCoord0.xy;
    parameters.coverage = 0.25;
    parameters.amounts = vec2(0.5, 0.75);
}
