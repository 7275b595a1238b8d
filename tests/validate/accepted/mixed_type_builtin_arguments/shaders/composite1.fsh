#version 330 compatibility
// Before GLSL 4.00 int and uint arguments both convert to float.
uniform int frameCounter;
in vec2 uv;
void main() {
	uint frame = uint(frameCounter);
	float a = max(frame, 4);
	bvec2 b = greaterThanEqual(uvec2(frame), ivec2(uv));
	gl_FragData[0] = vec4(a, any(b) ? 1.0 : 0.0, uv);
}
