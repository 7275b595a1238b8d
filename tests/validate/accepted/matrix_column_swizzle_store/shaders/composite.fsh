#version 410 compatibility
flat in mat4 frame;
in vec2 uv;
void main() {
	mat3 local = mat3(2.0);
	local[1].yx *= uv;
	local[2].b = 0.5;
	gl_FragData[0] = frame * vec4(local * vec3(uv, 1.0), 1.0);
}
