#version 120
varying vec2 uv;
void main() {
	float b = uv.x;
	(b + 1.0) = 2.0;
	gl_FragData[0] = vec4(b, 0.0, 0.0, 1.0);
}
