#version 120
uniform sampler2D colortex0;
uniform float rainStrength;
varying vec2 texcoord;
void main() {
	rainStrength = 0.0;
	gl_FragData[0] = texture2D(colortex0, texcoord);
}
