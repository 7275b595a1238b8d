#version 120
// Every listed buffer is written, through the out parameters of a helper.
uniform sampler2D colortex0;
varying vec2 texcoord;
void split(vec4 color, out vec4 first, out vec4 second) {
	first = color;
	second = vec4(color.a);
}
/* DRAWBUFFERS:01 */
void main() {
	split(texture2D(colortex0, texcoord), gl_FragData[0], gl_FragData[1]);
}
