#version 130

#define VERTEX_SHADER
#define OVERWORLD

#include "/program/gbuffers_entities.glsl"
