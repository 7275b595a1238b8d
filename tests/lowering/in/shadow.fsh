#version 120
#extension GL_EXT_gpu_shader4 : enable
#extension GL_ARB_shader_texture_lod : enable

uniform sampler2D tex;

varying vec2 texcoord;
varying vec4 glcolor;

void main() {
#if defined(WATER_SHADOW) || 0
	discard;
#else
	vec4 color = texture2D(tex, texcoord) * glcolor;
	gl_FragData[0] = color;
#endif
}
