#version 130

#define FRAGMENT_SHADER
#define END

#include "/program/gbuffers_skybasic.glsl"
