#version 120
// Global constants computed from elements of a constant array, and from each other.
varying vec2 uv;
const float weights[3] = float[3](1.0, 2.0, 3.0);
const vec2 pair = vec2(weights[1], weights[2]);
const vec2 scaled = pair * 2.0;
const vec3 axis = vec3(weights[0]) / dot(pair, pair);
void main() {
	gl_FragData[0] = vec4(uv * scaled, axis.y, 1.0);
}
