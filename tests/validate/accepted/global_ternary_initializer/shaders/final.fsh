#version 120
uniform sampler2D colortex0;
uniform float rainStrength;
varying vec2 texcoord;
float rainSign = rainStrength < 0.5 ? 1.0 : -1.0;
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) * rainSign;
}
