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
// dot of two scalars, in a function naga resolves while validating.
float lengthSquared(float x) { return dot(x, x); }
float lengthSquared(vec2 x) { return dot(x, x); }
void main() {
	gl_FragData[0] = vec4(tonemap(texture2D(colortex0, texcoord).rgb), float(brightest(vec3(0.5))) + lengthSquared(0.5) + lengthSquared(texcoord));
}
