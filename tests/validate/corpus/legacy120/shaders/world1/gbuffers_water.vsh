#version 120
#define END
#define VSH
#include "/program/gbuffers_water.glsl"
