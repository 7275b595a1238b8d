#define SHADOW_SAMPLES 4 // [0 1 2 4 8]
#define SHADOW_SOFTNESS 0.5 // [0.0 0.5 1.0]
float shadowRadius() {
#if SHADOW_SOFTNESS < 0.01
	return 0.0;
#else
	return SHADOW_SOFTNESS / float(SHADOW_SAMPLES);
#endif
}
