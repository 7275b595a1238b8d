#version 330 compatibility
// Terrain, entities, the opaque hand, particles, and every program that falls back here: drawn as the game draws it (lib/vanilla.glsl).
#define TEXTURED
#define LIT

out vec2 texUv;
out vec2 lightUv;
out vec4 tint;
out float viewDistance;

#include "/lib/vanilla_vertex.glsl"
