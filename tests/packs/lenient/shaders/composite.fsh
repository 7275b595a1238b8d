#version 120
// Three things NVIDIA compiles and Mesa refuses: texture() under 1.20, an #extension after
// code, and a reserved word as a name.
uniform sampler2D colortex0;
varying vec2 texcoord;
#extension GL_EXT_gpu_shader4 : enable
void main() {
    vec3 output = texture(colortex0, texcoord).rgb;
    gl_FragData[0] = vec4(sqrt(output), 1.0);
}
