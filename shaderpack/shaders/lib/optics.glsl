// How light meets the water: Fresnel, absorption, highlights and the sky
// (docs/water-model.md A4, A5, B).

// Reflectance of water at normal incidence, n = 1.333 (exactly 0.0204).
const float WATER_F0 = 0.02;
const float WATER_IOR = 1.333;

// Schlick's approximation; cosTheta is the cosine between the view ray and the normal.
float fresnelSchlick(float cosTheta) {
    float m = 1.0 - clamp(cosTheta, 0.0, 1.0);
    float m2 = m * m;
    return WATER_F0 + (1.0 - WATER_F0) * m2 * m2 * m;
}

// Exact Fresnel reflectance of unpolarised light at a dielectric boundary with relative index
// `eta` (1.333 from air, 1/1.333 from water; total internal reflection gives 1).
float fresnelExact(float cosTheta, float eta) {
    float c = clamp(cosTheta, 0.0, 1.0);
    float g2 = eta * eta - 1.0 + c * c;
    if (g2 <= 0.0) {
        return 1.0;
    }
    float g = sqrt(g2);
    // g + c > 0 here, and c * (g - c) + 1 >= 1 - c * c >= 0 with equality only at c = 1, g = 0,
    // which g2 > 0 excludes.
    float a = (g - c) / (g + c);
    float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

float fresnel(float cosTheta, bool fromAbove) {
#ifdef FRESNEL_EXACT
    return fresnelExact(cosTheta, fromAbove ? WATER_IOR : 1.0 / WATER_IOR);
#else
    if (!fromAbove) {
        // From below, Schlick applies to the angle on the air side; past the critical angle
        // there is none: total internal reflection.
        float sinT2 = WATER_IOR * WATER_IOR * (1.0 - cosTheta * cosTheta);
        return sinT2 >= 1.0 ? 1.0 : fresnelSchlick(sqrt(1.0 - sinT2));
    }
    return fresnelSchlick(cosTheta);
#endif
}

// Fraction of light per channel that survives a path of `pathLength` blocks of water.
vec3 transmittance(float pathLength) {
    float L = clamp(pathLength, 0.0, 1e4);
#if ABSORPTION_MODEL == 0
    // Clamped ramp: red dies first, then green, then blue (A5).
    float lmax = DEPTH_FADE_DISTANCE;
    float b = clamp((lmax - L) / lmax, 0.0, 1.0);
    float g = clamp(b * (1.0 - L * (1.5 / lmax)), 0.0, 1.0);
    float r = clamp(b * (1.0 - L * (3.0 / lmax)), 0.0, 1.0);
    return vec3(r * r, g * g, b * b);
#else
    // Beer-Lambert with pure water's absorption per block (Pope & Fry 1997: 0.40 /m at
    // red, 0.057 /m at green, 0.009 /m at blue), times ABSORPTION_DENSITY. At 1 the floor
    // keeps its colour a few blocks down and blue lasts as far as the game's water fog
    // (which ends 96 blocks away).
    const vec3 PURE_WATER_ABSORPTION = vec3(0.40, 0.057, 0.009);
    return exp(-PURE_WATER_ABSORPTION * ABSORPTION_DENSITY * L);
#endif
}

// The water's own colour seen where light is absorbed: in-scattered sky light.
vec3 scatteredColor(vec3 waterTint, float skyLight, vec3 skyColor) {
    float daylight = 0.25 + 0.75 * clamp(luminance(skyColor) * 1.5, 0.0, 1.0);
    return waterTint * 0.35 * (0.15 + 0.85 * skyLight) * daylight;
}

// Sky seen in a direction (world axes), for reflections that miss the screen.
vec3 skyRadiance(vec3 dir, vec3 skyColor, vec3 fogColor) {
    return mix(fogColor, skyColor, smoothstep(-0.05, 0.35, dir.y));
}

// Phong highlights of the sun or moon, at `glint` of the sun's strength, and a broad lobe of
// the sky (A4); the light is below the horizon half the time, so its strength follows its
// height.
vec3 specularLight(vec3 reflected, vec3 lightDir, float glint, vec3 skyColor, float skyLight) {
    float visibility = smoothstep(-0.05, 0.15, lightDir.y) * skyLight * glint;
    // Powers by squaring: pow() is exp2(log2()) on a CPU renderer.
    float sun = max(dot(reflected, lightDir), 0.0);
    sun *= sun; sun *= sun; sun *= sun; sun *= sun;
    sun *= sun; sun *= sun; sun *= sun; sun *= sun;
    sun *= 8.0;
    float up = max(reflected.y, 0.0);
    float sky = up * up * up * up * 0.15;
    return vec3(1.0, 0.95, 0.85) * sun * visibility + skyColor * sky * skyLight;
}
