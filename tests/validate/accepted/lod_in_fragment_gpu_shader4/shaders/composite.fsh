#version 120
#extension GL_EXT_gpu_shader4 : enable
// GL_EXT_gpu_shader4 makes texture2DLod available in fragment shaders.
uniform sampler2D colortex1;
varying vec2 texcoord;
void main() {
	gl_FragData[0] = texture2DLod(colortex1, texcoord, 2.0);
}
