#version 420 compatibility
uniform sampler2D colortex0;
in vec2 texcoord;
float weights[3] = { 0.25, 0.5, 0.25 };
void main() {
	const vec2 offsets[] = { { -1.0, 0.0 }, { 0.0, 0.0 }, { 1.0, 0.0 } };
	vec4 sum = vec4(0.0);
	for (int i = 0; i < 3; i++) sum += texture(colortex0, texcoord + offsets[i] * 0.001) * weights[i];
	gl_FragData[0] = sum;
}
