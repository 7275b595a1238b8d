#version 450
layout(location = 0) out vec4 tp_FragData0; 


layout(set = 1, binding = 1) uniform texture2D tex; layout(set = 1, binding = 2) uniform sampler tp_sampler_tex;

layout(location = 1) in vec2 texcoord;
layout(location = 0) in vec4 glcolor;

void main() {



	vec4 color = texture(sampler2D(tex, tp_sampler_tex), texcoord) * glcolor;
	tp_FragData0 = color;

}
