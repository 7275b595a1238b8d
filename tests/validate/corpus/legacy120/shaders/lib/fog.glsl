#include "/lib/common.glsl"

uniform vec3 fogColor;
uniform float far;

vec3 applyFog(vec3 color, float dist) {
#if FOG_STYLE == 0
	return color;
#elif FOG_STYLE == 1
	return mix(color, fogColor, saturate(dist / far));
#else
	return mix(color, fogColor, 1.0 - exp(-dist / far * 3.0));
#endif
}
