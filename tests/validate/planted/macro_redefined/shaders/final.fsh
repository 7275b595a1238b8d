#version 120
#define STRENGTH 0.5
uniform sampler2D colortex0;
varying vec2 texcoord;
#define STRENGTH 0.75
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) * STRENGTH;
}
