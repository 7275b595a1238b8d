#version 450
layout(location = 0) out vec4 tp_FragData0; layout(location = 1) out vec4 tp_FragData1; layout(set = 1, binding = 1) uniform texture2D colortex0; layout(set = 1, binding = 2) uniform sampler tp_sampler_colortex0; layout(set = 1, binding = 3) uniform texture2D colortex1; layout(set = 1, binding = 4) uniform sampler tp_sampler_colortex1;

layout(location = 1) in vec2 texcoord; layout(location = 0) in vec2 lmcoord;

void main() {
	tp_FragData0 = texture(sampler2D(colortex0, tp_sampler_colortex0), texcoord) + texture(sampler2D(colortex1, tp_sampler_colortex1), lmcoord);
	tp_FragData1 = vec4(texcoord, lmcoord);
}
