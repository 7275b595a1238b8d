#version 450
layout(location = 0) in vec4 tp_FrontColor; layout(location = 1) in vec4 tp_TexCoord0; layout(location = 2) in vec4 tp_TexCoord1; layout(location = 0) out vec4 tp_FragData0; 
layout(set = 1, binding = 1) uniform texture2D gtexture; layout(set = 1, binding = 2) uniform sampler tp_sampler_gtexture;
layout(set = 1, binding = 3) uniform texture2D lightmap; layout(set = 1, binding = 4) uniform sampler tp_sampler_lightmap;

void main() {
	vec4 color = tp_FrontColor * texture(sampler2D(gtexture, tp_sampler_gtexture), tp_TexCoord0.st);
	color.rgb *= texture(sampler2D(lightmap, tp_sampler_lightmap), tp_TexCoord1.st).rgb;
	tp_FragData0 = color;
}
