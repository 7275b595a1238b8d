#version 330 compatibility

uniform float rainStrength;

out float starData;

void main() {
	gl_Position = ftransform();
	gl_FrontColor = gl_Color;
	starData = float(gl_Color.r == gl_Color.g && gl_Color.g == gl_Color.b && gl_Color.r > 0.0) * (1.0 - rainStrength);
}
