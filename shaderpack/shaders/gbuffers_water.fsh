#version 330 compatibility
// Translucent terrain: water marked for composite, glass and ice blended (lib/translucent.glsl).
#include "/lib/translucent.glsl"

uniform sampler2D gtexture;

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
    translucentOutputs(albedo, lightUv, tint, waterBlock > 0.5, length(viewPosition), outColor0, outColor1, outColor2, outColor3);
}
