#version 330 compatibility
// Translucent terrain. Water leaves colortex0 alone (composite shades it over the scene
// behind it); glass and ice blend into colortex0 as usual. For composite, every translucent
// writes its view normal and material to colortex4 and its tint and sky light to colortex5
// (both with blending off in shaders.properties). Water also writes its plain colour to
// colortex6 with blending on, where glass drawn later (alpha 0) leaves it intact: what
// composite shows of water seen through glass.
#include "/lib/common.glsl"

uniform sampler2D gtexture;
uniform sampler2D lightmap;

in vec2 texUv;
in vec2 lightUv;
in vec4 tint;
in vec3 viewNormal;
in float material;

/* RENDERTARGETS: 0,4,5,6 */
out vec4 outColor0;
out vec4 outColor1;
out vec4 outColor2;
out vec4 outColor3;

void main() {
    vec4 albedo = texture(gtexture, texUv) * tint;
    vec3 light = texture(lightmap, lightUv).rgb;
    bool water = isWaterMaterial(material);
    // Lightmap coordinates run from 1/32 (dark) to 31/32 (full sky light).
    float skyLight = clamp((lightUv.y - 1.0 / 32.0) * (16.0 / 15.0), 0.0, 1.0);
    outColor0 = water ? vec4(0.0) : vec4(albedo.rgb * light, albedo.a);
    // Interpolation can shorten the normal; re-normalise before encoding.
    outColor1 = vec4(encodeNormal(safeNormalize(viewNormal, vec3(0.0, 0.0, 1.0))), material);
    outColor2 = vec4(water ? tint.rgb : albedo.rgb, skyLight);
    outColor3 = water ? vec4(albedo.rgb * light, 1.0) : vec4(0.0);
}
