#version 430
// One work group of one invocation per pixel, numbered along x alone: 230,400 groups at
// 640x360, more than the 65,535 llvmpipe dispatches along an axis (NVIDIA and AMD take 2^31 - 1).
// Each paints its pixel red; a group numbered wrong leaves its pixel as composite.fsh found it.
layout(local_size_x = 1) in;
const ivec3 workGroups = ivec3(230400, 1, 1);
layout(rgba8) uniform image2D colorimg0;
uniform float viewWidth;
void main() {
    int pixel = int(gl_GlobalInvocationID.x);
    int width = int(viewWidth);
    if (gl_NumWorkGroups.x == 230400u) {
        imageStore(colorimg0, ivec2(pixel % width, pixel / width), vec4(1.0, 0.0, 0.0, 1.0));
    }
}
