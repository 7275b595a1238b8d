#version 330 compatibility
struct Parameters {
    float coverage;
    vec2 amounts;
};
flat in Parameters parameters;
in vec2 uv;
/* DRAWBUFFERS:0 */
void main() {
    gl_FragData[0] = vec4(parameters.coverage, parameters.amounts, 1.0);
}
