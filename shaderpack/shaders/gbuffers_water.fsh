#version 330 compatibility
// Translucent terrain. Every buffer blends by the output's alpha with the result's alpha set
// to 0 (blend.gbuffers_water in shaders.properties), so an output with alpha 1 replaces what is
// there, alpha 0 leaves it, and colortex0's alpha ends at 0 wherever a translucent drew.
// Water leaves colortex0's colour alone (composite shades it over the scene behind it) and
// writes its mark, sky light and distance to colortex4, its tint to colortex5 and its plain colour to
// colortex6. Glass and ice blend into colortex0 as usual, weaken the water mark and keep the
// water's tint and colour: what composite shows of water seen through glass.
#include "/lib/common.glsl"

uniform sampler2D gtexture;
uniform sampler2D lightmap;
uniform float far;

in vec2 texUv;
in vec2 lightUv;
in vec4 tint;
in float waterBlock;
in vec3 viewPosition;

/* RENDERTARGETS: 0,4,5,6 */
out vec4 outColor0;
out vec4 outColor1;
out vec4 outColor2;
out vec4 outColor3;

void main() {
    vec4 albedo = texture(gtexture, texUv) * tint;
    vec3 light = texture(lightmap, lightUv).rgb;
    if (waterBlock > 0.5) {
        // Lightmap coordinates run from 1/32 (dark) to 31/32 (full sky light).
        float skyLight = clamp((lightUv.y - 1.0 / 32.0) * (16.0 / 15.0), 0.0, 1.0);
        outColor0 = vec4(0.0);
        float distanceFraction = length(viewPosition) / (WATER_DISTANCE_RANGE * max(far, 1.0));
        outColor1 = vec4(WATER_MARK, skyLight, distanceFraction, 1.0);
        outColor2 = vec4(tint.rgb, 1.0);
        outColor3 = vec4(albedo.rgb * light, 1.0);
    } else {
        // A clear texel covers nothing: it must not mark the pixel as translucent.
        if (albedo.a < 1.0 / 255.0) {
            discard;
        }
        outColor0 = vec4(albedo.rgb * light, albedo.a);
        outColor1 = vec4(0.0, 0.0, 0.0, 1.0 - MARK_KEPT_BEHIND_TRANSLUCENT);
        outColor2 = vec4(0.0);
        outColor3 = vec4(0.0);
    }
}
