#version 430
// Runs before composite's own stages: adds red to every pixel of colortex0 in place, through
// its image, one invocation per pixel (the default workGroupsRender).
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba8) uniform image2D colorimg0;
void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    vec4 colour = imageLoad(colorimg0, pixel);
    imageStore(colorimg0, pixel, vec4(1.0, colour.gb, 1.0));
}
