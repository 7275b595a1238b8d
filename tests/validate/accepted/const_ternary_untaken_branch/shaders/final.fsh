#version 120
#define SUN_DIRECTION 1
uniform sampler2D colortex0;
varying vec2 texcoord;
const vec3 sunDir = SUN_DIRECTION == 1 ? vec3(0.0, 1.0, 0.0) : normalize(vec3(0.0));
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) * sunDir.y;
}
