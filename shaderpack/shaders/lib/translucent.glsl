// The fragment stage of the translucent programs: gbuffers_water for the game's blocks and
// dh_water for Distant Horizons' LODs. Every buffer blends by the output's alpha with the
// result's alpha set to 0 (blend.gbuffers_water and blend.dh_water in shaders.properties), so an
// output with alpha 1 replaces what is there, alpha 0 leaves it, and colortex0's alpha ends at 0
// wherever a translucent drew.

#include "/lib/common.glsl"

uniform sampler2D lightmap;
uniform float far;

// The outputs of a translucent fragment of colour `albedo`, for colortex0, 4, 5 and 6.
// Water leaves colortex0's colour alone (composite shades it over the scene behind it) and
// writes its mark, sky light and distance to colortex4, its tint to colortex5 and its plain
// colour to colortex6. Glass and ice blend into colortex0 as usual, weaken the water mark and
// keep the water's tint and colour: what composite shows of water seen through glass.
void translucentOutputs(vec4 albedo, vec2 lightUv, vec4 tint, bool isWater, float viewDistance,
                        out vec4 color, out vec4 waterRecord, out vec4 waterTint, out vec4 waterColor) {
    vec3 light = texture(lightmap, lightUv).rgb;
    if (isWater) {
        // Lightmap coordinates run from 1/32 (dark) to 31/32 (full sky light).
        float skyLight = clamp((lightUv.y - 1.0 / 32.0) * (16.0 / 15.0), 0.0, 1.0);
        color = vec4(0.0);
        float distanceFraction = viewDistance / (WATER_DISTANCE_RANGE * max(drawnDistance(far), 1.0));
        waterRecord = vec4(WATER_MARK, skyLight, distanceFraction, 1.0);
        waterTint = vec4(tint.rgb, 1.0);
        waterColor = vec4(albedo.rgb * light, 1.0);
    } else {
        // A clear texel covers nothing: it must not mark the pixel as translucent.
        if (albedo.a < 1.0 / 255.0) {
            discard;
        }
        color = vec4(albedo.rgb * light, albedo.a);
        waterRecord = vec4(0.0, 0.0, 0.0, 1.0 - MARK_KEPT_BEHIND_TRANSLUCENT);
        waterTint = vec4(0.0);
        waterColor = vec4(0.0);
    }
}
