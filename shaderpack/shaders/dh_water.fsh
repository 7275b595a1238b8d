#version 330 compatibility
// Distant Horizons' translucent LODs, under Iris with the mod installed: its water marked for
// composite as gbuffers_water marks the game's, so that both are shaded alike
// (lib/translucent.glsl). LODs have no texture, only their vertex colour.
#include "/lib/translucent.glsl"

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
    translucentOutputs(tint, lightUv, tint, waterBlock > 0.5, length(viewPosition), outColor0, outColor1, outColor2, outColor3);
}
