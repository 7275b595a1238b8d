#version 120
#extension GL_EXT_gpu_shader4 : enable
uniform sampler2D colortex0;
uniform sampler2D depthtex0;
flat varying int id;
void main() {
	ivec2 size = textureSize2D(colortex0, 0);
	vec4 c = texelFetch2D(colortex0, ivec2(gl_FragCoord.xy) % size, 0) * float(id);
	gl_FragColor = c + texture2DLod(depthtex0, gl_FragCoord.xy / vec2(size), 0.0).rrrr;
}
