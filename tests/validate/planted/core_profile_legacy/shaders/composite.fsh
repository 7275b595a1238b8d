#version 330
uniform sampler2D colortex0;
void main() {
	gl_FragData[0] = vec4(1.0);
}
