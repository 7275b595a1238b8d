#version 430
// Each work group of 64 invocations fills a table of 64 x 36 vec4, 36,864 bytes of `shared`
// memory: more than the 32,768 llvmpipe gives a group (NVIDIA's drivers give 49,152). After
// barrier() each invocation reads the row its neighbour wrote and the count of invocations
// that arrived. A group that sees another group's table, or a row not yet written, paints
// its pixels red; the others paint them green.
layout(local_size_x = 64) in;
const ivec3 workGroups = ivec3(10, 360, 1);
layout(rgba8) uniform image2D colorimg0;

shared vec4 rows[64][36];
shared struct {
    uint arrived;
} tally;

void main() {
    uint me = gl_LocalInvocationID.x;
    float group = float(gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x);
    if (me == 0u) {
        tally.arrived = 0u;
    }
    for (int k = 0; k < 36; k++) {
        rows[me][k] = vec4(group, float(me), float(k), 1.0);
    }
    memoryBarrierShared();
    barrier();
    atomicAdd(tally.arrived, 1u);
    memoryBarrierShared();
    barrier();
    uint next = (me + 1u) % 64u;
    bool seen = tally.arrived == 64u;
    for (int k = 0; k < 36; k++) {
        seen = seen && rows[next][k] == vec4(group, float(next), float(k), 1.0);
    }
    imageStore(colorimg0, ivec2(gl_GlobalInvocationID.xy), seen ? vec4(0.0, 1.0, 0.0, 1.0) : vec4(1.0, 0.0, 0.0, 1.0));
}
