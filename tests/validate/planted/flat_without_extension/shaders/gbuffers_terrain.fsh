#version 120
#extension GL_EXT_gpu_shader4 : enable
flat varying int blockId;
void main() {
	gl_FragData[0] = vec4(float(blockId & 255) / 255.0);
}
