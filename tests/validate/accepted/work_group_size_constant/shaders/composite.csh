#version 430 compatibility
// gl_WorkGroupSize is a constant: it sizes a shared array.
layout(local_size_x = 16, local_size_y = 16) in;
const ivec3 workGroups = ivec3(1, 1, 1);
writeonly uniform image2D colorimg5;
shared float sums[gl_WorkGroupSize.x * gl_WorkGroupSize.y];
void main() {
	uint i = gl_LocalInvocationIndex;
	const int count = int(gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z);
	sums[i] = float(count);
	for (uint stride = uint(count) / 2u; stride > 0u; stride /= 2u) {
		barrier();
		if (i < stride) sums[i] += sums[i + stride];
	}
	if (i == 0u) imageStore(colorimg5, ivec2(0), vec4(sums[0]));
}
