// Constants and guarded math shared by every program.

const float TAU = 6.28318530718;

// Material mask in colortex4.a, written by gbuffers_water, read by composite.
const float MATERIAL_WATER = 1.0;
const float MATERIAL_TRANSLUCENT = 0.5;

// RGBA8 stores 0.5 as 128/255, so classify with margins rather than equality.
bool isWaterMaterial(float mask) {
    return mask > 0.75;
}

bool isTranslucentMaterial(float mask) {
    return mask > 0.25 && mask <= 0.75;
}

// normalize() of a zero vector is NaN: decoded normals and view vectors can be zero.
vec3 safeNormalize(vec3 v, vec3 fallback) {
    float lengthSquared = dot(v, v);
    return lengthSquared > 1e-12 ? v * inversesqrt(lengthSquared) : fallback;
}

// Unit normals to the [0, 1] range an unsigned colour buffer can hold, and back.
vec3 encodeNormal(vec3 normal) {
    return normal * 0.5 + 0.5;
}

vec3 decodeNormal(vec3 encoded) {
    return safeNormalize(encoded * 2.0 - 1.0, vec3(0.0, 1.0, 0.0));
}

float luminance(vec3 color) {
    return dot(color, vec3(0.2126, 0.7152, 0.0722));
}

float maxComponent(vec3 v) {
    return max(v.r, max(v.g, v.b));
}
