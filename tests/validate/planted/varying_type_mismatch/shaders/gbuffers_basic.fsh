#version 120
varying vec3 normal;
void main() {
	gl_FragData[0] = vec4(normal, 1.0);
}
