#version 330 compatibility
// Water shading over the finished scene. Pixels with no water in front of them, stained
// glass included, pass through unchanged; water pixels fade the scene behind them by the
// depth of water it lies under, gain caustics, and reflect the sky at grazing angles; with
// the camera under water, everything fades with its distance from the camera.
#include "/lib/settings.glsl"
#include "/lib/common.glsl"
#include "/lib/space.glsl"
#include "/lib/water.glsl"

/*
const int colortex4Format = RGBA16;
*/

uniform sampler2D colortex0;
uniform sampler2D colortex4;
uniform sampler2D depthtex0;
uniform sampler2D depthtex1;
uniform sampler2D noisetex;

uniform mat4 gbufferProjectionInverse;
uniform mat4 gbufferModelViewInverse;
uniform vec3 cameraPosition;
uniform vec3 skyColor;
uniform float frameTimeCounter;
uniform int isEyeInWater;

in vec2 screenUv;

/* RENDERTARGETS: 0 */
out vec4 outColor0;

// Caustic brightening of a surface at a view-space position, weighted by how much of it
// the water lets through.
vec3 withCaustics(vec3 color, vec3 viewPos, float visibility) {
#ifdef CAUSTICS
    vec3 playerPos = playerFromView(viewPos, gbufferModelViewInverse);
    vec2 worldXZ = playerPos.xz + wrappedCamera(cameraPosition, NOISE_TILE).xz;
    float pattern = causticPattern(noisetex, worldXZ, frameTimeCounter);
    return color * max(1.0 + CAUSTICS_STRENGTH * pattern * visibility, 0.0);
#else
    return color;
#endif
}

void main() {
    vec4 scene = texture(colortex0, screenUv);
    vec4 surface = texture(colortex4, screenUv);
    bool eyeInWater = isEyeInWater == 1;
    bool waterPixel = isWaterMaterial(surface.a);
    if (!waterPixel && !eyeInWater) {
        outColor0 = scene;
        return;
    }

    float depth0 = texture(depthtex0, screenUv).r;
    float depth1 = texture(depthtex1, screenUv).r;
    vec3 viewPos0 = viewFromScreen(screenUv, depth0, gbufferProjectionInverse);
    vec3 viewPos1 = viewFromScreen(screenUv, depth1, gbufferProjectionInverse);
    vec3 viewDir = safeNormalize(viewPos0, vec3(0.0, 0.0, -1.0));
    vec3 color = scene.rgb;

    if (eyeInWater) {
        // Under water: light fades along the whole way from the camera to the nearest surface.
        float visibility = 1.0;
#ifdef DEPTH_FADE
        visibility = depthFade(length(viewPos0), DEPTH_FADE_DISTANCE);
#endif
        // Caustics fall on opaque surfaces only, never on the sky, water or glass.
        bool opaque = surface.a < 0.25 && depth0 < 1.0;
        if (opaque) {
            color = withCaustics(color, viewPos0, visibility);
        }
        color = mix(WATER_FOG_COLOR, color, visibility);
    } else {
        // Above water, looking into it: the scene behind lies under the water surface.
        vec3 normal = decodeNormal(surface.rgb);
        float cosView = clamp(abs(dot(viewDir, normal)), 0.0, 1.0);
        float visibility = 1.0;
#ifdef DEPTH_FADE
        // The path through the water times the cosine approximates the depth below the surface.
        float pathInWater = max(length(viewPos1) - length(viewPos0), 0.0);
        visibility = depthFade(pathInWater * cosView, DEPTH_FADE_DISTANCE);
#endif
        if (depth1 < 1.0) {
            color = withCaustics(color, viewPos1, visibility);
        }
        color = mix(WATER_FOG_COLOR, color, visibility);
        // Schlick-like sky reflection, strongest at grazing angles.
        float reflectance = pow(1.0 - cosView, 4.0);
        color = mix(color, skyColor, reflectance);
    }
    outColor0 = vec4(color, scene.a);
}
