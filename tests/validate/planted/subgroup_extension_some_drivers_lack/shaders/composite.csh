#version 430
// A reduction over the workgroup that takes its first step within a subgroup, as
// HaringPro/Revelation's compute passes do: the subgroup functions come from an extension
// NVIDIA, AMD and Intel offer, and Mesa's llvmpipe and macOS do not.
#extension GL_KHR_shader_subgroup_basic : enable
#extension GL_KHR_shader_subgroup_arithmetic : enable
layout(local_size_x = 64) in;
const ivec3 workGroups = ivec3(1, 1, 1);
layout(std430, binding = 0) buffer Exposure { float total; } exposure;
uniform sampler2D colortex0;
void main() {
    float luminance = texelFetch(colortex0, ivec2(gl_LocalInvocationID.xy), 0).g;
    float sum = subgroupAdd(luminance);
    if (subgroupElect()) exposure.total += sum;
}
