#version 120
// What NVIDIA compiles and Mesa refuses: texture() under 1.20, an #extension after code (also
// inside an #if), a reserved word as a name, and words after the name of #ifndef and after
// #else. dot() of two floats is GLSL's own (naga has it for vectors alone).
uniform sampler2D colortex0;
varying vec2 texcoord;
#extension GL_EXT_gpu_shader4 : enable
float luma(vec3 color) {
    return dot(color, vec3(0.2126, 0.7152, 0.0722));
}
void main() {
    vec3 output = texture(colortex0, texcoord).rgb;
    float weight = dot(luma(output), 0.5);
    gl_FragData[0] = vec4(sqrt(output) * (0.75 + weight), 1.0);
}
#ifndef WARM && defined COLD
const float tone = 1.0;
#else if defined WARM
const float tone = 0.5;
#endif
#ifndef WARM
#extension GL_ARB_shader_texture_lod : enable
#endif
