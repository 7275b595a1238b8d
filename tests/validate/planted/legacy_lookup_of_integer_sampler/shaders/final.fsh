#version 130
uniform usampler2D colortex4;
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	uvec4 packed_data = texture2D(colortex4, texcoord);
	gl_FragData[0] = texture2D(colortex0, texcoord) * float(packed_data.r & 255u) / 255.0;
}
