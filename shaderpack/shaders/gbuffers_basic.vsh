#version 330 compatibility
// Lines, the block outline and the sky's colour, and every program that falls back here: drawn as the game draws it (lib/vanilla.glsl).

out vec2 texUv;
out vec2 lightUv;
out vec4 tint;
out float viewDistance;

#include "/lib/vanilla_vertex.glsl"
