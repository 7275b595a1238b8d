#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
void tint() {
	return 1.0;
}
void main() {
	tint();
	gl_FragData[0] = texture2D(colortex0, texcoord);
}
