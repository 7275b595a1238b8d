#version 120
// gl_FragData[1] goes to an `in` parameter: nothing writes it.
uniform sampler2D colortex0;
varying vec2 texcoord;
void split(vec4 color, out vec4 first, vec4 second) {
	first = color;
}
/* DRAWBUFFERS:01 */
void main() {
	split(texture2D(colortex0, texcoord), gl_FragData[0], gl_FragData[1]);
}
