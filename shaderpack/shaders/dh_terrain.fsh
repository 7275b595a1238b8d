#version 330 compatibility
// Distant Horizons' opaque LODs (see dh_terrain.vsh).
#define LIT

/* RENDERTARGETS: 0 */
out vec4 outColor0;

in vec2 texUv;
in vec2 lightUv;
in vec4 tint;
in float viewDistance;

#include "/lib/vanilla.glsl"

void main() {
    outColor0 = vanillaColor(texUv, lightUv, tint, viewDistance);
}
