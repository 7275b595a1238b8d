#version 120
#define NETHER
#define VSH
#include "/program/gbuffers_water.glsl"
