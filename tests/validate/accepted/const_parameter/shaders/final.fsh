#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
vec3 tonemap(const in vec3 color) {
	return color / (color + 1.0);
}
void main() {
	gl_FragData[0] = vec4(tonemap(texture2D(colortex0, texcoord).rgb), 1.0);
}
