#version 330 compatibility
// Unpacks the integer buffer: red from the low byte, green from the flag, and magenta wherever
// the marker did not arrive whole (a buffer stored as floats, or read through a float sampler).
uniform usampler2D colortex1;
in vec2 uv;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 color;
void main() {
    uint bits = texelFetch(colortex1, ivec2(gl_FragCoord.xy), 0).r;
    bool intact = (bits >> 16u) == 0xABCDu;
    float red = float(bits & 0xFFu) / 255.0;
    float bright = float((bits >> 8u) & 1u);
    color = intact ? vec4(red, bright, 0.0, 1.0) : vec4(1.0, 0.0, 1.0, 1.0);
}
