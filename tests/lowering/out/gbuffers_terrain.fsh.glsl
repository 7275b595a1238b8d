#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { int isEyeInWater; float rainStrength; }; layout(location = 0) out vec4 tp_FragData0; layout(location = 1) out vec4 tp_FragData1; layout(location = 2) out vec4 tp_FragData2; 
layout(set = 1, binding = 1) uniform texture2D gtexture; layout(set = 1, binding = 2) uniform sampler tp_sampler_gtexture;
layout(set = 1, binding = 3) uniform texture2D lightmap; layout(set = 1, binding = 4) uniform sampler tp_sampler_lightmap;



layout(location = 5) in vec2 texcoord;
layout(location = 2) in vec2 lmcoord;
layout(location = 1) in vec4 glcolor;
layout(location = 4) in vec3 normal;
layout(location = 0) in float blockId;
layout(location = 3) centroid in vec2 midcoord;

vec4 sampleAtlas(texture2D atlas, sampler tp_sampler_atlas, vec2 coord, float bias) {
	return texture(sampler2D(atlas, tp_sampler_atlas), coord, bias);
}

void main() {
	vec4 albedo = sampleAtlas(gtexture, tp_sampler_gtexture, texcoord, -0.5) * glcolor;
	if (albedo.a < 0.1) discard;
	vec3 light = texture(sampler2D(lightmap, tp_sampler_lightmap), lmcoord).rgb;
	if (isEyeInWater == 1) light *= vec3(0.4, 0.6, 1.0);
	light *= 1.0 - 0.3 * rainStrength;


	tp_FragData0 = vec4(albedo.rgb * light, albedo.a);
	tp_FragData1 = vec4(normal * 0.5 + 0.5, 1.0);
	tp_FragData2 = vec4(lmcoord, blockId / 255.0, midcoord.x);
}
