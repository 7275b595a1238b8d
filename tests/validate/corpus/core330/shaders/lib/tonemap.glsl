#if !defined TONEMAP_GLSL
#define TONEMAP_GLSL
#define TONEMAP 1 // [0 1 2] Tonemapping operator
#define EXPOSURE 1.0 // [0.5 1.0 2.0]

vec3 reinhard(vec3 c) { return c / (1.0 + c); }
vec3 aces(vec3 c) {
	const float a = 2.51, b = 0.03, cc = 2.43, d = 0.59, e = 0.14;
	return clamp((c * (a * c + b)) / (c * (cc * c + d) + e), 0.0, 1.0);
}
vec3 tonemap(vec3 c) {
	c *= EXPOSURE;
	switch (TONEMAP) {
		case 0: return c;
		case 1: return reinhard(c);
		default: return aces(c);
	}
}
#endif
