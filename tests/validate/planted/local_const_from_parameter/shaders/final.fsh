#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
float scatter(float transmittance, const float coeff) {
	const float a = -1.0 / coeff;
	return transmittance * a - a;
}
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) * scatter(0.5, 2.0);
}
