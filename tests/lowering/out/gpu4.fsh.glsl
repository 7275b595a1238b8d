#version 450
layout(location = 0) out vec4 tp_FragData0; 
layout(set = 1, binding = 1) uniform texture2D colortex0; layout(set = 1, binding = 2) uniform sampler tp_sampler_colortex0;
layout(set = 1, binding = 3) uniform texture2D depthtex0; layout(set = 1, binding = 4) uniform sampler tp_sampler_depthtex0;
layout(location = 0) flat in int id;
void main() {
	ivec2 size = textureSize(sampler2D(colortex0, tp_sampler_colortex0), 0);
	vec4 c = texelFetch(sampler2D(colortex0, tp_sampler_colortex0), ivec2(gl_FragCoord.xy) % size, 0) * float(id);
	tp_FragData0 = c + textureLod(sampler2D(depthtex0, tp_sampler_depthtex0), gl_FragCoord.xy / vec2(size), 0.0).rrrr;
}
