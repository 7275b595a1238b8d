#version 330 compatibility
// The translucent hand (a held glass block, ice): drawn as the game draws it (lib/vanilla.glsl).
#define TEXTURED
#define LIT

out vec2 texUv;
out vec2 lightUv;
out vec4 tint;
out float viewDistance;

#include "/lib/vanilla_vertex.glsl"
