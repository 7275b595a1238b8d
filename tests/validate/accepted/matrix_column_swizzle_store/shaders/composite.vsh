#version 410 compatibility
// A matrix varying and a local matrix whose columns are assigned through swizzles.
flat out mat4 frame;
out vec2 uv;
void main() {
	gl_Position = ftransform();
	uv = gl_MultiTexCoord0.xy;
	frame = mat4(1.0);
	frame[3].xyz -= mat3(frame) * vec3(uv, 1.0);
	if (uv.x > 0.5) {
		frame[0].xyz = -frame[0].xyz;
	}
}
