#version 330 compatibility
// Rain and snow: drawn as the game draws it (lib/vanilla.glsl), over the water. Besides colortex0,
// it adds its colour to colortex3 (premultiplied, with its coverage in alpha, by the blend mode
// in shaders.properties), so composite can shade the water behind it and put it back on top.
// Nothing else writes colortex3, so it holds the same whether the loader draws this before the
// water (OptiFine up to Minecraft 1.12 draws rain then) or after it.
#define TEXTURED
#define LIT

/* RENDERTARGETS: 0,3 */
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
    outColor1 = color;
}
