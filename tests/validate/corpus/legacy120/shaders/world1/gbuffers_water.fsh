#version 120
#define END
#define FSH
#include "/program/gbuffers_water.glsl"
