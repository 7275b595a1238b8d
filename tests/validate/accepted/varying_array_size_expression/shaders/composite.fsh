#version 120
#define TAPS 3
uniform sampler2D colortex0;
varying vec2 uv;
varying vec2 taps[TAPS * TAPS];
varying vec3 tint;
void main() {
	vec3 sum = vec3(0.0);
	for (int i = 0; i < TAPS * TAPS; i++) {
		sum += texture2D(colortex0, taps[i]).rgb;
	}
	gl_FragData[0] = vec4(sum * tint, 1.0);
}
