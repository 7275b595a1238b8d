#version 330 compatibility
// Terrain, entities, the opaque hand, particles, and every program that falls back here: drawn as the game draws it (lib/vanilla.glsl).
#define TEXTURED
#define LIT

/* RENDERTARGETS: 0,4 */
out vec4 outColor0;
out vec4 outColor1;

in vec2 texUv;
in vec2 lightUv;
in vec4 tint;
in float viewDistance;

#include "/lib/vanilla.glsl"

void main() {
    vec4 color = vanillaColor(texUv, lightUv, tint, viewDistance);
    outColor0 = color;
    // Where this covers water drawn before it (particles), the water is no longer what the
    // pixel shows: its mark goes, in part where this is translucent.
    outColor1 = vec4(0.0, 0.0, 0.0, color.a);
}
