#version 120
uniform sampler2D colortex0;
uniform float frameTimeCountr;
uniform sampler2D colortx1;
varying vec2 texcoord;
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord) * frameTimeCountr + texture2D(colortx1, texcoord);
}
