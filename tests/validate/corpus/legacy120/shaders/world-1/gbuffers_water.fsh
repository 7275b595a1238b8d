#version 120
#define NETHER
#define FSH
#include "/program/gbuffers_water.glsl"
