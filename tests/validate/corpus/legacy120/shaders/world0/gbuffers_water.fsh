#version 120
#define OVERWORLD
#define FSH
#include "/program/gbuffers_water.glsl"
