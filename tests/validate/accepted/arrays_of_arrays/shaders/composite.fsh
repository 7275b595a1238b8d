#version 430 compatibility
// Arrays of arrays: the first size is the outer one.
const ivec2 grid = ivec2(2, 3);
layout(std430, binding = 0) readonly buffer cellData {
	uvec4 cells[][grid.x][grid.y];
};
const float kernel[2][3] = float[2][3](float[3](0.25, 0.5, 0.25), float[3](0.5, 1.0, 0.5));
in vec2 uv;
float pick(float rows[2][3], int i) {
	return rows[1][i];
}
void main() {
	float weights[4][2];
	for (int i = 0; i < 4; i++) {
		weights[i][1] = kernel[1][2] * float(i);
	}
	uvec4 c = cells[int(uv.x)][1][2];
	gl_FragData[0] = vec4(c) * weights[3][1] * pick(kernel, 2);
}
