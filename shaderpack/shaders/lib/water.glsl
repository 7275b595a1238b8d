// The water model's pieces shared by gbuffers_water and composite.

// Angular speed of the vertex swell: 172 whole cycles per 3600 s (about 0.3 rad/s), so the
// wrap of frameTimeCounter at 3600 s does not make the waves jump.
const float SWELL_SPEED = TAU * 172.0 / 3600.0;
// The swell repeats every 4 blocks along z, a power of two the camera is wrapped by.
const float SWELL_PERIOD = 4.0;

// Vertical offset of a water vertex at world position (wrapped) and time.
float swellOffset(float worldZ, float time, float amplitude) {
    return amplitude * sin(SWELL_SPEED * time + TAU / SWELL_PERIOD * worldZ);
}

// noisetex repeats every NOISE_TILE blocks in x and z.
const float NOISE_TILE = 64.0;
// Scroll rates in tiles per second: whole repeats per 3600 s keep the timer wrap seamless.
const float NOISE_SCROLL_A = 36.0 / 3600.0;
const float NOISE_SCROLL_B = 54.0 / 3600.0;

// Two scrolled samples of the noise texture moving in opposite directions, summed, in
// [-2, 2]: the moving light pattern on an underwater floor.
float causticPattern(sampler2D noise, vec2 worldXZ, float time) {
    vec2 uv = worldXZ / NOISE_TILE;
    float a = texture(noise, fract(uv + vec2(time * NOISE_SCROLL_A, 0.0))).r;
    float b = texture(noise, fract(uv * 1.5 - vec2(0.0, time * NOISE_SCROLL_B))).r;
    return (a * 2.0 - 1.0) + (b * 2.0 - 1.0);
}

// How much of the scene behind the water remains visible after `depth` blocks of water:
// 1 at the surface, 0 from `fadeDistance` on.
float depthFade(float depth, float fadeDistance) {
    return clamp(1.0 - depth / fadeDistance, 0.0, 1.0);
}
