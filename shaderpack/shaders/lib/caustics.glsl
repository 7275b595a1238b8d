// Caustics on surfaces under water (docs/water-model.md A6 and D), as a brightness factor.

// A6: two scrolled samples of the water's height, the second 1.5x finer and moving the other
// way; bright where they cancel. The water texture holds the height at 1, 2 and 4 times its
// frequency in R, G and B, so each lookup gives a sample of every octave, each twice as fine.
float causticsFromHeight(sampler2D waterTexture, vec2 worldXZ, float time) {
    vec2 uv = 0.5 + vec2(worldXZ.x, -worldXZ.y) / WAVE_TILE;
    vec3 a = texture(waterTexture, fract(uv + time * WAVE_DRIFT)).rgb;
    vec3 b = texture(waterTexture, fract(uv * 1.5 - time * WAVE_DRIFT.yx)).rgb;
    vec3 c = clamp(1.0 - abs(a + b - 1.0), 0.0, 1.0);
    vec3 c3 = c * c * c;
    vec3 c9 = c3 * c3 * c3;
#if CAUSTIC_SAMPLES == 1
    return c9.r;
#elif CAUSTIC_SAMPLES == 2
    return (c9.r + c9.g) / 2.0;
#else
    return (c9.r + c9.g + c9.b) / 3.0;
#endif
}

// D: two samples of OptiFine's noise texture moving in opposite directions, in [-2, 2].
float causticsFromNoise(sampler2D noise, vec2 worldXZ, float time) {
    float sum = 0.0;
    float scale = 1.0;
    for (int i = 0; i < CAUSTIC_SAMPLES; i++) {
        vec2 uv = scale * worldXZ / WAVE_TILE;
        float a = texture(noise, fract(uv + time * WAVE_DRIFT)).r;
        float b = texture(noise, fract(uv - time * WAVE_DRIFT)).r;
        sum += (a * 2.0 - 1.0) + (b * 2.0 - 1.0);
        scale *= 2.0;
    }
    return sum / float(CAUSTIC_SAMPLES);
}
