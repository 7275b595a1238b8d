#version 430
// Iris's begin pass, at the start of the frame: pixels 32 to 39 of colortex1's bottom row
// turn white, for composite to copy to the screen under Iris. OptiFine runs no begin pass.
layout(local_size_x = 8) in;
const ivec3 workGroups = ivec3(1, 1, 1);
layout(rgba8) uniform image2D colorimg1;
void main() {
    imageStore(colorimg1, ivec2(32 + int(gl_GlobalInvocationID.x), 0), vec4(1.0));
}
