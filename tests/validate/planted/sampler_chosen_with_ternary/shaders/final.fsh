#version 120
uniform sampler2D shadowcolor0;
uniform sampler2D shadowcolor1;
uniform float rainStrength;
varying vec2 texcoord;
void main() {
	bool lightShaft = rainStrength > 0.5;
	gl_FragData[0] = texture2D(lightShaft ? shadowcolor1 : shadowcolor0, texcoord);
}
