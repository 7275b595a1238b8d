#version 120
varying vec2 uv;
void main() {
	mat4 frame = mat4(1.0);
	frame[1].xy = uv;
	frame[0].xyz = uv;
	gl_FragData[0] = frame * vec4(uv, 0.0, 1.0);
}
