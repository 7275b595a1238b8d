#include "math.glsl"
vec3 grade(vec3 c) {
	vec3 graded = c * 1.1;
	return saturate3(colr);
}
