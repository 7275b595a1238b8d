#version 330 compatibility
// Distant Horizons' opaque LODs, under Iris with the mod installed: drawn as the game draws its
// terrain (lib/vanilla.glsl), lit by the lightmap, with the vertex colour for a texture (LODs
// have none). Iris draws its generic objects (dh_generic) with this program too.
#define LIT

out vec2 texUv;
out vec2 lightUv;
out vec4 tint;
out float viewDistance;

#include "/lib/vanilla_vertex.glsl"
