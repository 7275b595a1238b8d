#version 440 compatibility
// Two outputs packed into one render target by component.
/* RENDERTARGETS: 5 */
layout(location = 0, component = 1) out float detail;
layout(location = 0, component = 0) out float coverage;
in vec2 uv;
void main() {
	coverage = uv.x;
	detail = uv.y;
}
