#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { vec3 fogColor; float fogStart; float fogEnd; }; layout(location = 0) out vec4 tp_FragData0; 


layout(set = 1, binding = 1) uniform texture2D lightmap; layout(set = 1, binding = 2) uniform sampler tp_sampler_lightmap;
layout(set = 1, binding = 3) uniform texture2D gtexture; layout(set = 1, binding = 4) uniform sampler tp_sampler_gtexture;




layout(location = 1) in vec2 lmcoord;
layout(location = 2) in vec2 texcoord;
layout(location = 0) in vec4 glcolor;

void main() {
	vec4 color = texture(sampler2D(gtexture, tp_sampler_gtexture), texcoord) * glcolor;
	color *= texture(sampler2D(lightmap, tp_sampler_lightmap), lmcoord);

	float fog = clamp((gl_FragCoord.z / gl_FragCoord.w - fogStart) / (fogEnd - fogStart), 0.0, 1.0);
	color.rgb = mix(color.rgb, fogColor, fog);



	tp_FragData0 = color; 
}
