#version 330 compatibility
// Clouds: drawn as the game draws it (lib/vanilla.glsl).
#define TEXTURED

out vec2 texUv;
out vec2 lightUv;
out vec4 tint;
out float viewDistance;

#include "/lib/vanilla_vertex.glsl"
