#version 120
#define TAPS 3
varying vec2 uv;
varying vec2 taps[TAPS * TAPS];
varying vec3 tint;
void main() {
	gl_Position = ftransform();
	uv = gl_MultiTexCoord0.xy;
	for (int i = 0; i < TAPS * TAPS; i++) {
		taps[i] = uv + vec2(float(i));
	}
	tint = vec3(1.0);
}
