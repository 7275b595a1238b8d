#version 120
#include "/lib/shadows.glsl"
#include "/lib/fog.glsl"

uniform sampler2D colortex0;
uniform sampler2D colortex2;
uniform sampler2D depthtex0;
uniform mat4 gbufferProjectionInverse;
uniform mat4 gbufferModelViewInverse;
uniform bool isDay;
uniform int isEyeInWater;

varying vec2 texcoord;

struct Material {
	vec3 albedo;
	float roughness;
};

Material readMaterial(vec2 coord) {
	Material m;
	m.albedo = texture2D(colortex0, coord).rgb;
	m.roughness = 1.0 - texture2D(colortex2, coord).a;
	return m;
}

vec3 viewPosition(vec2 coord, float depth) {
	vec4 p = gbufferProjectionInverse * vec4(vec3(coord, depth) * 2.0 - 1.0, 1.0);
	return p.xyz / p.w;
}

void main() {
	Material m = readMaterial(texcoord);
	float depth = texture2D(depthtex0, texcoord).r;
	vec3 view = viewPosition(texcoord, depth);
	vec4 world = gbufferModelViewInverse * vec4(view, 1.0);
	vec4 shadowPos = shadowProjection * (shadowModelView * world);
	vec3 shadowCoord = shadowPos.xyz / shadowPos.w * 0.5 + 0.5;
	float lit = sampleShadow(shadowCoord);
	vec3 color = m.albedo * mix(0.3, 1.0, lit) * (isDay ? 1.0 : 0.4);
	if (isEyeInWater == 1) color *= vec3(0.4, 0.7, 1.0);
	color = applyFog(color, length(view));
/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color, 1.0);
}
