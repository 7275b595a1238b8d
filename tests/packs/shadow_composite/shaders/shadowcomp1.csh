#version 430
// After shadowcomp, through shadowcolor1's image: what shadowcomp kept there becomes its
// complement too, plus colortex10, which no other program names (transparent black).
layout(local_size_x = 16, local_size_y = 16) in;
const ivec3 workGroups = ivec3(16, 16, 1);
layout(rgba8) uniform image2D shadowcolorimg1;
uniform sampler2D colortex10;
void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    vec4 kept = imageLoad(shadowcolorimg1, texel);
    imageStore(shadowcolorimg1, texel, vec4(1.0 - kept.rgb, 1.0) + texelFetch(colortex10, ivec2(0), 0));
}
