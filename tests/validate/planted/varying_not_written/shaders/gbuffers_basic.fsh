#version 120
varying vec4 color;
varying vec2 lmcoord;
void main() {
	gl_FragData[0] = color * lmcoord.x;
}
