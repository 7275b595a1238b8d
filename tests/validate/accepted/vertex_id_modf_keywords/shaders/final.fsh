#version 130
uniform sampler2D colortex0;
in vec2 texcoord;
in float cycle;
void main() {
	float sample = cycle * 0.5;
	gl_FragData[0] = texture2D(colortex0, texcoord) * sample;
}
