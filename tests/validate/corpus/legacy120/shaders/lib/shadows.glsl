#include "/lib/common.glsl"

uniform sampler2DShadow shadowtex0;
uniform mat4 shadowModelView;
uniform mat4 shadowProjection;

float shadowTap(sampler2DShadow map, vec3 coord, vec2 offset) {
	return shadow2D(map, coord + vec3(offset, 0.0)).r;
}

float sampleShadow(vec3 shadowCoord) {
#ifdef SHADOWS
	float lit = 0.0;
#if SHADOW_SAMPLES == 1
	lit = shadowTap(shadowtex0, shadowCoord, vec2(0.0));
#else
	for (int i = 0; i < SHADOW_SAMPLES; i++) {
		vec2 offset = vec2(mod(float(i), 2.0), floor(float(i) / 2.0)) / float(shadowMapResolution);
		lit += shadowTap(shadowtex0, shadowCoord, offset);
	}
	lit /= float(SHADOW_SAMPLES);
#endif
	return lit;
#else
	return 1.0;
#endif
}
