#version 330 compatibility
// Distant Horizons' translucent LODs (see dh_water.fsh). Iris declares dhMaterialId, the LOD's
// material (one of the DH_BLOCK_* values), and gives the lightmap coordinate, already in 0..1,
// as gl_MultiTexCoord1. The LOD water lies flat: the swell of gbuffers_water is below a pixel
// that far away.
#include "/lib/common.glsl"

out vec2 lightUv;
out vec4 tint;
// 1 on water, 0 on every other translucent LOD.
out float waterBlock;
out vec3 viewPosition;

void main() {
    vec4 viewPos = gl_ModelViewMatrix * gl_Vertex;
    gl_Position = gl_ProjectionMatrix * viewPos;
    viewPosition = viewPos.xyz;
    lightUv = (gl_TextureMatrix[1] * gl_MultiTexCoord1).xy;
    tint = gl_Color;
    waterBlock = dhMaterialId == DH_BLOCK_WATER ? 1.0 : 0.0;
}
