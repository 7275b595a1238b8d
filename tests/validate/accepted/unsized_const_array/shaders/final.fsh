#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
const vec2[] offsets = vec2[](vec2(1.0, 0.0), vec2(0.0, 1.0), vec2(-1.0, 0.0));
void main() {
	vec4 sum = vec4(0.0);
	for (int i = 0; i < 3; i++) sum += texture2D(colortex0, texcoord + offsets[i] * 0.001);
	gl_FragData[0] = sum / 3.0;
}
