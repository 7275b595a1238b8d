#include "/lib/noise.glsl"
vec3 sky(vec2 p) {
	return vec3(0.4, 0.6, 1.0) * hash(p);
}
