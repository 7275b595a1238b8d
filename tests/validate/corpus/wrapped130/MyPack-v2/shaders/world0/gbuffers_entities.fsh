#version 130

#define FRAGMENT_SHADER
#define OVERWORLD

#include "/program/gbuffers_entities.glsl"
