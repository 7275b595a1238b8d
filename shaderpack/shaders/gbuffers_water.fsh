#version 330 compatibility
// Translucent terrain: the blended base colour to colortex0, and for composite the view
// normal and material mask to colortex4 (blending off for it in shaders.properties).
#include "/lib/common.glsl"

uniform sampler2D gtexture;
uniform sampler2D lightmap;

in vec2 texUv;
in vec2 lightUv;
in vec4 tint;
in vec3 viewNormal;
in float material;

/* RENDERTARGETS: 0,4 */
out vec4 outColor0;
out vec4 outColor1;

void main() {
    vec4 albedo = texture(gtexture, texUv) * tint;
    vec3 light = texture(lightmap, lightUv).rgb;
    outColor0 = vec4(albedo.rgb * light, albedo.a);
    // Interpolation can shorten the normal; re-normalise before encoding.
    outColor1 = vec4(encodeNormal(safeNormalize(viewNormal, vec3(0.0, 0.0, 1.0))), material);
}
