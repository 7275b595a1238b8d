#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
#include "/lib/shadow.glsl"
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) * shadowRadius();
}
