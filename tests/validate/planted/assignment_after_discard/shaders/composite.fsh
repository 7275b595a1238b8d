#version 120
uniform float rainStrength;
varying vec2 uv;
void main() {
	if (uv.x < 0.5) {
		discard;
		rainStrength = 1.0;
	}
	gl_FragData[0] = vec4(uv, rainStrength, 1.0);
}
