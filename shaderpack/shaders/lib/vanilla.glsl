// What the game itself would draw. The pack has programs for everything so that nothing is left
// to the loader: OptiFine up to Minecraft 1.16.5 writes its own drawing into every buffer, the
// water's data in colortex4 included. gbuffers_basic (lines, the sky's colour),
// gbuffers_textured (particles, the sun and moon, glints) and gbuffers_textured_lit (terrain,
// entities, the opaque hand, particles) are the ends of every fallback chain; gbuffers_weather,
// gbuffers_clouds and gbuffers_hand_water draw over the water and keep a copy of their colour
// for composite.
//
// The fragment stage of those programs; the including program defines TEXTURED (sample
// gtexture) and LIT (multiply by the lightmap) before including this.

#include "/lib/common.glsl"

uniform int fogMode;
uniform int isEyeInWater;
uniform float far;
uniform float alphaTestRef;
uniform vec3 fogColor;

// The game's distance fog. None where the game draws without fog (fogMode 0: the sun, moon
// and stars) and under water, where composite's absorption is the water's fog.
vec3 withDistanceFog(vec3 color, float viewDistance) {
    if (fogMode == 0 || isEyeInWater == 1) {
        return color;
    }
    return mix(color, fogColor, distanceFog(viewDistance, drawnDistance(far)));
}

#ifdef TEXTURED
uniform sampler2D gtexture;
#endif
#ifdef LIT
uniform sampler2D lightmap;
#endif

// The colour the game draws: the vertex colour, times the texture and the lightmap where the
// program has them, fogged. Fragments the game's alpha test would drop are discarded.
vec4 vanillaColor(vec2 texUv, vec2 lightUv, vec4 tint, float viewDistance) {
    vec4 color = tint;
#ifdef TEXTURED
    color *= texture(gtexture, texUv);
#endif
    // OptiFine from Minecraft 1.17 and Iris leave cutout textures (leaves, grass) to the program;
    // alphaTestRef is 0 where the game tests nothing.
    if (color.a < alphaTestRef) {
        discard;
    }
#ifdef LIT
    color.rgb *= texture(lightmap, lightUv).rgb;
#endif
    return vec4(withDistanceFog(color.rgb, viewDistance), color.a);
}
