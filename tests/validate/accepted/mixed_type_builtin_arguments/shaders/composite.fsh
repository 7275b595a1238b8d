#version 400 compatibility
// From GLSL 4.00 an int argument beside a uint one converts to uint.
uniform sampler2D colortex0;
uniform int frameCounter;
in vec2 uv;
void main() {
	uint frame = uint(frameCounter);
	uint a = max(frame, 4);
	uint b = min(3, frame);
	uvec2 size = uvec2(textureSize(colortex0, 0));
	bvec2 inside = lessThan(size, ivec2(gl_FragCoord.xy));
	vec2 c = clamp(uv, 0, 1u);
	uvec3 d = clamp(uvec3(frame), 0, 255);
	gl_FragData[0] = vec4(float(a + b), any(inside) ? 1.0 : 0.0, c + vec2(d.xy));
}
