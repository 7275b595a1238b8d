#version 330 compatibility
// The water model (docs/water-model.md) over the finished scene, one of five cases per pixel:
//   1. camera above water, pixel not behind water: passed through unchanged;
//   2. camera under water, pixel under water: absorption over the distance, caustics;
//   3. camera under water, pixel seen through the surface: refraction, total internal
//      reflection, absorption up to the surface;
//   4. camera above water, water pixel nearer than the drawn distance: wave surface,
//      refraction, absorption, caustics, reflections, highlights, foam, the game's fog;
//   5. camera above water, water pixel at or beyond the drawn distance (the game's, or with
//      Distant Horizons its LODs'): the fog colour only.
// Distant Horizons' water (dh_water) is shaded as the game's, from its own depth buffers.
// Stained glass and ice get no water effects of their own.
#include "/lib/settings.glsl"
#include "/lib/common.glsl"
#include "/lib/space.glsl"
#include "/lib/generated.glsl"
#include "/lib/waves.glsl"
#include "/lib/optics.glsl"
#include "/lib/reflections.glsl"
#include "/lib/caustics.glsl"

/*
const int colortex4Format = RGBA16;
const int colortex5Format = RGBA8;
const int colortex6Format = RGBA8;
*/

uniform sampler2D colortex0; // the scene behind the water, glass blended in; alpha 0 under translucents
uniform sampler2D colortex3; // rain, clouds and the translucent hand: premultiplied colour, coverage
uniform sampler2D colortex4; // water mark (r, weakened by each glass in front), the water's sky light (g) and distance (b)
uniform sampler2D colortex5; // the water's tint (rgb)
uniform sampler2D colortex6; // the water's plain colour (rgb), kept where glass covers the water
uniform sampler2D colortex7; // water texture (texture.composite.colortex7): height in three octaves, foam
uniform sampler2D colortex1; // height cross textures (texture.composite.colortex1, colortex2): the normal's
uniform sampler2D colortex2; // height samples per octave, generated from colortex7's height
uniform sampler2D depthtex0;
uniform sampler2D depthtex1;
#ifdef DISTANT_HORIZONS
// Distant Horizons' depth buffers, with and without its water, under its own projection.
uniform sampler2D dhDepthTex0;
uniform sampler2D dhDepthTex1;
uniform mat4 dhProjection;
uniform mat4 dhProjectionInverse;
#endif
#if CAUSTICS_MODE == 1
uniform sampler2D noisetex;
// OptiFine binds noisetex only for a pack that declares its size (or a texture.noise).
const int noiseTextureResolution = 256;
#endif

uniform mat4 gbufferProjection;
uniform mat4 gbufferProjectionInverse;
uniform mat4 gbufferModelView;
uniform mat4 gbufferModelViewInverse;
uniform vec3 cameraPosition;
uniform vec3 shadowLightPosition;
uniform vec3 sunPosition;
uniform float rainStrength;
uniform float far;
uniform vec3 skyColor;
uniform vec3 fogColor;
uniform float frameTimeCounter;
uniform int isEyeInWater;
uniform ivec2 eyeBrightnessSmooth;

in vec2 screenUv;
// ripplePulse(frameTimeCounter), the same at every pixel (composite.vsh).
in vec2 ripple;

/* RENDERTARGETS: 0 */
out vec4 outColor0;

// Vanilla's default water colour, for pixels under water with no surface of their own.
const vec3 DEFAULT_WATER_TINT = vec3(0.247, 0.463, 0.894);
const vec3 CAUSTIC_COLOR = vec3(1.0, 0.97, 0.9);
const vec3 FOAM_COLOR = vec3(0.9, 0.95, 1.0);
// The moon's glint against the sun's.
const float MOON_GLINT = 0.1;
// Below this, a contribution is invisible in an 8-bit image.
const float INVISIBLE = 1.0 / 255.0;

// This pixel's own texel of a full-screen buffer. texelFetch skips the filtering and
// coordinate arithmetic of texture(): on a CPU renderer that is a fifth of the cost of a pixel
// passed through. GLSL 120 has no texelFetch and samples the texel's centre instead.
vec4 ownTexel(sampler2D source) {
#if __VERSION__ >= 130
    return texelFetch(source, ivec2(gl_FragCoord.xy), 0);
#else
    return texture(source, screenUv);
#endif
}

// Caustics on an opaque surface at a wrapped world position, weighted by how much light the
// water above lets through.
vec3 withCaustics(vec3 lit, vec2 worldXZ, float visibility) {
#ifdef CAUSTICS
    if (!NEEDED(visibility >= INVISIBLE)) {
        return lit;
    }
#if CAUSTICS_MODE == 0
    float intensity = causticsFromHeight(colortex7, worldXZ, frameTimeCounter) * CAUSTICS_STRENGTH;
    return lit + CAUSTIC_COLOR * intensity * maxComponent(lit) * visibility;
#else
    float pattern = causticsFromNoise(noisetex, worldXZ, frameTimeCounter);
    return lit * max(1.0 + CAUSTICS_STRENGTH * pattern * visibility, 0.0);
#endif
#else
    return lit;
#endif
}

// Light lost and gained along a path through water whose transmittance is t.
vec3 throughWater(vec3 color, vec3 t, vec3 scattered) {
#ifdef DEPTH_FADE
    return t * color + (1.0 - t) * scattered;
#else
    return color;
#endif
}

vec3 eyePosition() {
    return gbufferModelViewInverse[3].xyz;
}

// The glint of the sun, or of the moon (the shadow light at night) at a tenth of it; rain
// clouds hide both.
float glintStrength() {
    bool moon = dot(shadowLightPosition, sunPosition) < 0.0;
    return (moon ? MOON_GLINT : 1.0) * (1.0 - clamp(rainStrength, 0.0, 1.0));
}

vec3 lightDirection() {
    return safeNormalize(mat3(gbufferModelViewInverse) * shadowLightPosition, vec3(0.0, 1.0, 0.0));
}

// Whether rain, clouds or the translucent hand may lie over a pixel whose colortex0 alpha is
// sceneAlpha. From Minecraft 1.13 on they are drawn after the water, which left that alpha at 0,
// and add their coverage to it: where it is still 0 colortex3 holds nothing and need not be
// read. Older versions draw rain before the water, so colortex3 is always read there.
bool overlayMayCover(float sceneAlpha) {
#if MC_VERSION >= 11300
    return NEEDED(sceneAlpha > 0.0);
#else
    return true;
#endif
}

// The scene at uv without the rain, clouds and translucent hand drawn over it: they lie in
// colortex0 and, alone, in colortex3 (premultiplied colour, coverage in alpha).
vec3 sceneBehindOverlay(vec2 uv) {
    vec4 scene = texture(colortex0, uv);
    vec4 over = vec4(0.0);
    if (overlayMayCover(scene.a)) {
        over = texture(colortex3, uv);
    }
    return (scene.rgb - over.rgb) / max(1.0 - over.a, INVISIBLE);
}

// Cases 4 and 5: the camera is above the water and this pixel is its surface, at window depth
// depth0 under `projection`. The opaque scene behind it is in floorDepth: the game's depthtex1,
// or for Distant Horizons' water its dhDepthTex1 under its own projection.
vec3 shadeFromAbove(vec2 uv, float depth0, sampler2D floorDepth, mat4 projection, mat4 projectionInverse, vec3 tint, float skyLight) {
    vec3 view0 = viewFromScreen(uv, depth0, projectionInverse);
    float distance0 = length(view0);
#ifdef FAR_HAZE
    // The game's fog, as lib/vanilla.glsl puts it on the terrain.
    float haze = 1.0 - distanceFog(distance0, drawnDistance(far));
    if (!NEEDED(haze > 0.0)) {
        return fogColor;
    }
#endif
    vec3 player0 = playerFromView(view0, gbufferModelViewInverse);
    vec3 rayDir = safeNormalize(player0 - eyePosition(), vec3(0.0, -1.0, 0.0));
    vec3 cameraWrap = wrappedCamera(cameraPosition, WAVE_TILE);
    float time = frameTimeCounter;

    SurfaceSample atSurface;
    vec3 surface = refineSurface(colortex1, player0, rayDir, cameraWrap, time, true, atSurface);
    vec2 surfaceXZ = surface.xz + cameraWrap.xz;
    float diffuse;
    vec3 normal = waveNormal(colortex1, colortex2, surfaceXZ, time, ripple, distance0, atSurface, diffuse);
    vec3 normalView = mat3(gbufferModelView) * normal;
    float cosView = clamp(dot(-rayDir, normal), 0.0, 1.0);
    vec3 scattered = scatteredColor(tint, skyLight, skyColor) * (0.65 + diffuse);

    // The opaque scene under the surface, refracted. The offset grows with the water's
    // opacity, so it vanishes where water meets a shore (C); a sample whose opaque point
    // lies in front of the surface would pull above-water objects in, so it is rejected.
    float depth1 = ownTexel(floorDepth).r;
    vec2 sceneUv = uv;
#ifdef REFRACTION
    float opacity = 1.0 - transmittance(length(viewFromScreen(uv, depth1, projectionInverse)) - distance0).b;
    vec2 candidate = clamp(uv + normalView.xy * REFRACTION_STRENGTH * opacity, 0.0, 1.0);
    float candidateDepth = texture(floorDepth, candidate).r;
    if (candidateDepth > depth0) {
        sceneUv = candidate;
        depth1 = candidateDepth;
    }
#endif
    vec3 view1 = viewFromScreen(sceneUv, depth1, projectionInverse);
    vec3 player1 = playerFromView(view1, gbufferModelViewInverse);
    float pathInWater = max(distance(player1, surface), 0.0);
    bool floorVisible = depth1 < 1.0;
    vec3 below = sceneBehindOverlay(sceneUv);
    vec3 belowTransmittance = transmittance(pathInWater);
    if (floorVisible) {
        below = withCaustics(below, player1.xz + cameraWrap.xz, belowTransmittance.b);
    }
    below = throughWater(below, belowTransmittance, scattered);

    vec3 reflected = reflect(rayDir, normal);
    vec3 reflection = skyRadiance(reflected, skyColor, fogColor) * (0.2 + 0.8 * skyLight);
    float reflectance = fresnel(cosView, true);
#ifdef REFLECTIONS
    // The scene reflected on screen shows at most through the reflectance and the haze: when
    // that weight is invisible, the sky stands in and the march is skipped.
    float reflectionWeight = reflectance;
#ifdef FAR_HAZE
    reflectionWeight *= haze;
#endif
    if (NEEDED(reflectionWeight >= INVISIBLE)) {
        // March with a flatter normal: the wave detail is too fine for the screen's resolution.
        vec3 marchNormal = mat3(gbufferModelView) * safeNormalize(vec3(normal.x, normal.y * (5.0 + 0.025 * distance0), normal.z), vec3(0.0, 1.0, 0.0));
        vec3 start = (gbufferModelView * vec4(surface, 1.0)).xyz;
        vec3 marchDir = reflect(safeNormalize(view0, vec3(0.0, 0.0, -1.0)), marchNormal);
        vec4 hit = traceReflection(colortex0, floorDepth, start, marchDir, dot(marchDir, marchNormal), projection, projectionInverse);
        reflection = mix(reflection, hit.rgb, hit.a);
    }
#endif
    vec3 color = mix(below, reflection, reflectance);

    float foam = 0.0;
#ifdef FOAM
    // Coastal foam where the floor is near the surface, crest foam on the highest waves.
    float waterDepth = floorVisible ? max(surface.y - player1.y, 0.0) : 1e4;
    float coastal = max(0.0, 0.8 * (1.0 - waterDepth / 1.5));
    float crest = smoothstep(0.55, 0.75, diffuse);
    float foamWeight = max(coastal, crest) * min(1.0, 32.0 / max(distance0, 1.0));
    // Most water is neither shallow nor a high crest: it skips the pattern's lookup.
    if (NEEDED(foamWeight > 0.0)) {
        vec2 foamUv = 0.5 + 4.0 * vec2(surfaceXZ.x + normal.x, -(surfaceXZ.y + normal.z)) / WAVE_TILE;
        foam = foamWeight * texture(colortex7, fract(foamUv)).a;
    }
    color = mix(color, FOAM_COLOR * (0.2 + 0.8 * skyLight) * (0.3 + 0.7 * luminance(skyColor)), foam);
#endif
#ifdef SPECULAR
    float foamFree = 1.0 - foam;
    color += specularLight(reflected, lightDirection(), glintStrength(), skyColor, skyLight) * reflectance * foamFree * foamFree * foamFree;
#endif
#ifdef FAR_HAZE
    color = mix(fogColor, color, haze);
#endif
    return color;
}

// Case 3: the camera is under water and this pixel is the surface seen from below.
vec3 shadeFromBelow(vec2 uv, float depth0, float skyLight, vec3 scattered) {
    vec3 view0 = viewFromScreen(uv, depth0, gbufferProjectionInverse);
    float distance0 = length(view0);
    vec3 player0 = playerFromView(view0, gbufferModelViewInverse);
    vec3 rayDir = safeNormalize(player0 - eyePosition(), vec3(0.0, 1.0, 0.0));
    vec3 cameraWrap = wrappedCamera(cameraPosition, WAVE_TILE);
    SurfaceSample atSurface;
    vec3 surface = refineSurface(colortex1, player0, rayDir, cameraWrap, frameTimeCounter, false, atSurface);
    float diffuse;
    vec3 normal = waveNormal(colortex1, colortex2, surface.xz + cameraWrap.xz, frameTimeCounter, ripple, distance0, atSurface, diffuse);
    float cosView = clamp(dot(rayDir, normal), 0.0, 1.0);

    // What lies above the surface, refracted more the farther it is behind the surface.
    float depth1 = texture(depthtex1, uv).r;
    vec2 sceneUv = uv;
#ifdef REFRACTION
    float behind = max(length(viewFromScreen(uv, depth1, gbufferProjectionInverse)) - distance0, 0.0);
    vec3 normalView = mat3(gbufferModelView) * normal;
    sceneUv = clamp(uv + normalView.xy * REFRACTION_STRENGTH * clamp(behind / 8.0, 0.0, 1.0), 0.0, 1.0);
#endif
    vec3 above = texture(colortex0, sceneUv).rgb;
    // Past the critical angle the surface mirrors the water below.
    vec3 color = mix(above, scattered, fresnel(cosView, false));
#ifdef FOAM
    color = mix(color, FOAM_COLOR * 0.5 * skyLight, smoothstep(0.6, 0.8, diffuse) * 0.5);
#endif
    return throughWater(color, transmittance(distance0), scattered);
}

// Case 2: the camera is under water and so is this pixel.
vec3 shadeUnderwater(vec2 uv, float depth0, vec3 color, bool opaque, vec3 scattered) {
    vec3 view0 = viewFromScreen(uv, depth0, gbufferProjectionInverse);
    float distance0 = length(view0);
    if (opaque) {
        vec3 player0 = playerFromView(view0, gbufferModelViewInverse);
        vec2 worldXZ = player0.xz + wrappedCamera(cameraPosition, WAVE_TILE).xz;
        color = withCaustics(color, worldXZ, transmittance(distance0).b);
    }
    return throughWater(color, transmittance(distance0), scattered);
}

#ifdef DISTANT_HORIZONS
// Whether the water nearest at uv, `waterDistance` from the eye, is Distant Horizons' (drawn
// by dh_water, before the game's water) rather than the game's: its LOD surface lies at that
// distance. Both record their distance in colortex4.b, to about a sixteenth of a block.
bool isLodWater(vec2 uv, float waterDistance) {
    float lodDepth = ownTexel(dhDepthTex0).r;
    if (lodDepth >= 1.0) {
        return false;
    }
    float lodDistance = length(viewFromScreen(uv, lodDepth, dhProjectionInverse));
    return abs(lodDistance - waterDistance) < 0.5 + 0.002 * waterDistance;
}
#endif

void main() {
    vec4 scene = ownTexel(colortex0);
    outColor0 = vec4(scene.rgb, 1.0);
    // Case 1 on a single read: gbuffers_water's blending leaves colortex0's alpha at 0 wherever
    // a translucent drew (blend.gbuffers_water in shaders.properties), so alpha 1 means no water
    // or glass in front.
    if (isEyeInWater != 1 && !NEEDED(scene.a < 1.0)) {
        return;
    }
    vec4 waterRecord = ownTexel(colortex4);
    bool water = isWaterNearest(waterRecord.r);
    if (isEyeInWater != 1) {
        bool waterBehindGlass = isWaterBehindTranslucent(waterRecord.r);
        // Rain, clouds and the translucent hand lie in colortex0 over the water, and in
        // colortex3 alone (premultiplied, coverage in alpha): take them out to shade what lies
        // behind, then put them back on top.
        vec4 drawnOver = vec4(0.0);
        if (overlayMayCover(scene.a)) {
            drawnOver = ownTexel(colortex3);
        }
        float uncovered = 1.0 - drawnOver.a;
        vec3 behind = (scene.rgb - drawnOver.rgb) / max(uncovered, INVISIBLE);
        // Glass over water: the water behind it shows in the plain colour it left in colortex6.
        vec3 shaded = waterBehindGlass ? mix(behind, ownTexel(colortex6).rgb, 0.6) : behind;
        if (NEEDED(water)) {
            vec3 tint = ownTexel(colortex5).rgb;
            // Rain, clouds and the hand write their depth over the water's: where they drew, the
            // surface's depth comes from the distance the water kept.
            float waterDistance = waterRecord.b * WATER_DISTANCE_RANGE * max(drawnDistance(far), 1.0);
            vec3 surface;
#ifdef DISTANT_HORIZONS
            if (isLodWater(screenUv, waterDistance)) {
                float lodDepth0 = drawnOver.a > 0.0
                    ? depthAtDistance(screenUv, waterDistance, dhProjection, dhProjectionInverse)
                    : ownTexel(dhDepthTex0).r;
                surface = shadeFromAbove(screenUv, lodDepth0, dhDepthTex1, dhProjection, dhProjectionInverse, tint, waterRecord.g);
            } else
#endif
            {
                float depth0 = drawnOver.a > 0.0
                    ? depthAtDistance(screenUv, waterDistance, gbufferProjection, gbufferProjectionInverse)
                    : ownTexel(depthtex0).r;
                surface = shadeFromAbove(screenUv, depth0, depthtex1, gbufferProjection, gbufferProjectionInverse, tint, waterRecord.g);
            }
            shaded = water ? surface : shaded;
        }
        outColor0.rgb = water || waterBehindGlass ? shaded * uncovered + drawnOver.rgb : scene.rgb;
        return;
    }
    // Under water: the sky light reaching the eye stands in for the depth below the surface.
    float eyeSkyLight = clamp(float(eyeBrightnessSmooth.y) / 240.0, 0.0, 1.0);
    float depth0 = ownTexel(depthtex0).r;
    if (NEEDED(water)) {
        vec3 scattered = scatteredColor(ownTexel(colortex5).rgb, eyeSkyLight, skyColor);
        vec3 shaded = shadeFromBelow(screenUv, depth0, waterRecord.g, scattered);
        outColor0.rgb = water ? shaded : outColor0.rgb;
    }
    if (NEEDED(!water)) {
        vec3 scattered = scatteredColor(DEFAULT_WATER_TINT, eyeSkyLight, skyColor);
        // Opaque: nothing translucent drew here (colortex0's alpha is still 1) and not the sky.
        bool opaque = scene.a > 0.5 && depth0 < 1.0;
        vec3 shaded = shadeUnderwater(screenUv, depth0, scene.rgb, opaque, scattered);
        outColor0.rgb = water ? outColor0.rgb : shaded;
    }
}
