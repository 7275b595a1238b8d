// Caustics on surfaces under water (docs/water-model.md A6 and D), as a brightness factor.

// A6: two scrolled samples of the water height texture, the second 1.5x finer and moving
// the other way; bright where they cancel. Each further sample pair is twice as fine.
float causticsFromHeight(sampler2D waterTexture, vec2 worldXZ, float time) {
    float sum = 0.0;
    float scale = 1.0;
    for (int i = 0; i < CAUSTIC_SAMPLES; i++) {
        vec2 uv = 0.5 + scale * vec2(worldXZ.x, -worldXZ.y) / WAVE_TILE;
        float a = texture(waterTexture, fract(uv + time * WAVE_DRIFT)).r;
        float b = texture(waterTexture, fract(uv * 1.5 - time * WAVE_DRIFT.yx)).r;
        float c = clamp(1.0 - abs(a + b - 1.0), 0.0, 1.0);
        float c3 = c * c * c;
        sum += c3 * c3 * c3;
        scale *= 2.0;
    }
    return sum / float(CAUSTIC_SAMPLES);
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
