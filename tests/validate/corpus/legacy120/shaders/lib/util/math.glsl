#ifndef MATH_GLSL
#define MATH_GLSL
#include "constants.glsl"

#define saturate(x) clamp(x, 0.0, 1.0)
#define LUMA(c) dot(c, \
	vec3(0.2126, 0.7152, 0.0722))

float pow2(float x) { return x * x; }
vec3 pow2(vec3 x) { return x * x; }

mat2 rotate2(float a) {
	float c = cos(a), s = sin(a);
	return mat2(c, -s, s, c);
}
#endif
