#version 120
#extension GL_EXT_gpu_shader4 : enable
#include "/lib/common.glsl"
uniform sampler2D gtexture;
uniform sampler2D lightmap;
uniform sampler2D specular;
varying vec2 texcoord;
varying vec2 lmcoord;
varying vec4 glcolor;
varying vec3 normal;
flat varying int material;
void main() {
	vec4 albedo = texture2D(gtexture, texcoord) * glcolor;
	if (albedo.a < 0.1) discard;
	ivec2 size = textureSize2D(specular, 0);
	vec4 spec = texelFetch2D(specular, ivec2(texcoord * vec2(size)), 0);
	float emissive = material == 10050 ? 1.0 : spec.a;
	vec3 light = texture2D(lightmap, lmcoord).rgb + emissive;
	light *= 1.0 - 0.3 * rainStrength;
/* DRAWBUFFERS:012 */
	gl_FragData[0] = vec4(albedo.rgb * light, albedo.a);
	gl_FragData[1] = vec4(normalize(normal) * 0.5 + 0.5, 1.0);
	gl_FragData[2] = vec4(lmcoord, LUMA(albedo.rgb), 1.0);
}
