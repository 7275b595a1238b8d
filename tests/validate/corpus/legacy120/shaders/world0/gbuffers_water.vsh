#version 120
#define OVERWORLD
#define VSH
#include "/program/gbuffers_water.glsl"
