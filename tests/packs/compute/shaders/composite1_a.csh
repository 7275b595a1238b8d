#version 430
// A program of compute stages alone, on fixed work groups: the bottom row's first 16 pixels
// of the texture composite wrote turn blue.
layout(local_size_x = 16) in;
const ivec3 workGroups = ivec3(1, 1, 1);
layout(rgba8) uniform image2D colorimg0;
void main() {
    imageStore(colorimg0, ivec2(gl_GlobalInvocationID.x, 0), vec4(0.0, 0.0, 1.0, 1.0));
}
