#version 430 compatibility
uniform sampler2D colortex0;
in vec2 texcoord;
struct Light { vec3 colour; int count; };
void main() {
	// Local constants sizing local arrays, as gri573/rethinking-voxels's light gathering does.
	const int side = int(2.0 + 0.001);
	const int cells = side * side;
	Light lights[side * side];
	float weights[cells];
	for (int i = 0; i < cells; i++) {
		lights[i] = Light(vec3(float(i) / float(cells)), i);
		weights[i] = float(lights[i].count + 1);
	}
	gl_FragData[0] = texture(colortex0, texcoord) * vec4(lights[cells - 1].colour * weights[side], 1.0);
}
