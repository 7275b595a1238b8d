#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	float weights[2] = {0.25, 0.75};
	gl_FragData[0] = texture2D(colortex0, texcoord) * weights[1];
}
