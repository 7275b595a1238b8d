#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
vec3 tonemap(const in vec3 color) {
	return color / (color + 1.0);
}
// Control can reach the end without a return: the value is undefined, drivers compile it.
int brightest(vec3 c) {
	for (int i = 0; i < 2; i++) {
		if (c[i] >= c[2]) return i;
	}
}
void main() {
	gl_FragData[0] = vec4(tonemap(texture2D(colortex0, texcoord).rgb), float(brightest(vec3(0.5))));
}
