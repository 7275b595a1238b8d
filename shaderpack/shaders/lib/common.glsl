// Constants and guarded math shared by every program.

const float TAU = 6.28318530718;

// The water mark in colortex4.r, written by gbuffers_water and read by composite. Water writes
// it whole; every other translucent (glass, ice) drawn over it scales it by 3/4, since the one
// blend mode OptiFine applies to all of gbuffers_water's buffers mixes by the output's alpha,
// and those translucents write it as 0 with alpha 1/4.
const float WATER_MARK = 1.0;
const float MARK_KEPT_BEHIND_TRANSLUCENT = 0.75;

// The water's distance from the eye is kept in colortex4.b as a fraction of this many drawn
// distances (drawnDistance), as far as the game's projection reaches (4 × far): composite
// reads the surface's position from it where rain, clouds or the hand wrote their depth over
// the water's, and tells Distant Horizons' water from the game's by it.
const float WATER_DISTANCE_RANGE = 4.0;

// Water is the nearest translucent at this pixel.
bool isWaterNearest(float mark) {
    return mark > 0.875;
}

// Water lies behind one to ten layers of glass or ice (mark 0.75 down to 0.75^10 = 0.056).
bool isWaterBehindTranslucent(float mark) {
    return mark > 0.04 && mark <= 0.875;
}

// normalize() of a zero vector is NaN: decoded normals and view vectors can be zero.
vec3 safeNormalize(vec3 v, vec3 fallback) {
    float lengthSquared = dot(v, v);
    return lengthSquared > 1e-12 ? v * inversesqrt(lengthSquared) : fallback;
}

float luminance(vec3 color) {
    return dot(color, vec3(0.2126, 0.7152, 0.0722));
}

float maxComponent(vec3 v) {
    return max(v.r, max(v.g, v.b));
}

#ifdef DISTANT_HORIZONS
uniform int dhRenderDistance;
#endif

// How far the world is drawn, given the game's render distance (`far`): with Distant Horizons
// its LODs go on to dhRenderDistance, so the fog and the water's distance record reach out
// there with them, and the fog has no edge where the game's chunks end and the LODs begin.
float drawnDistance(float renderDistance) {
#ifdef DISTANT_HORIZONS
    return max(renderDistance, float(dhRenderDistance));
#else
    return renderDistance;
#endif
}

// The game's distance fog: none up to three quarters of the render distance, all of it at the
// render distance.
float distanceFog(float viewDistance, float renderDistance) {
    float range = max(renderDistance, 1.0);
    return clamp((viewDistance - 0.75 * range) / (0.25 * range), 0.0, 1.0);
}
