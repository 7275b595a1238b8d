#version 120
uniform sampler3D colortex0;
varying vec2 texcoord;
void main() {
	vec4 c = texture2D(colortex0, texcoord);
	gl_FragData[0] = c;
}
