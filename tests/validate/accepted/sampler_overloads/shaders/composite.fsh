#version 120
// Overloads taking the sampler at different positions, one calling the other.
uniform sampler2D colortex0;
varying vec2 uv;
vec4 fetch(bool sharp, vec2 p, sampler2D tex) {
	return sharp ? texture2D(tex, p) : texture2D(tex, p, 1.0);
}
vec4 fetch(vec2 p, sampler2D tex) {
	return fetch(false, p, tex);
}
void main() {
	gl_FragData[0] = fetch(uv, colortex0) + fetch(true, uv, colortex0);
}
