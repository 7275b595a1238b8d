#version 430 compatibility
layout(local_size_x = 16, local_size_y = 16) in;
const ivec3 workGroups = ivec3(1, 1, 1);
writeonly uniform image2D colorimg5;
shared vec3[9] sums[gl_WorkGroupSize.x * gl_WorkGroupSize.y];
void main() {
	uint i = gl_LocalInvocationIndex;
	sums[i][0] = vec3(float(i));
	barrier();
	if (i == 0u) imageStore(colorimg5, ivec2(0), vec4(sums[5][0], 1.0));
}
