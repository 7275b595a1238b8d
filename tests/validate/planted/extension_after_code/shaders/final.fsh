#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
#extension GL_EXT_gpu_shader4 : enable
void main() {
	gl_FragData[0] = texture2D(colortex0, texcoord);
}
