#version 330 compatibility
// Distant Horizons' LODs in the Nether, water included (dh_water falls back here), drawn as the
// game draws its terrain, as the root's dh_terrain does: Iris loads only this folder's
// programs here, and without one it shades no LODs.
#define LIT

out vec2 texUv;
out vec2 lightUv;
out vec4 tint;
out float viewDistance;

#include "/lib/vanilla_vertex.glsl"
