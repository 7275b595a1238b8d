#version 430 compatibility
// Blocks declared with a layout and no instance name, each closed by `};`.
layout(std430, binding = 0) readonly buffer cellData {
	uint cellCount;
	uvec4 cells[];
};
layout(std140, binding = 1) uniform Tints {
	vec4 tint;
};
in vec2 uv;
void main() {
	uvec4 c = cells[min(uint(uv.x), cellCount)];
	gl_FragData[0] = vec4(c) * tint;
}
