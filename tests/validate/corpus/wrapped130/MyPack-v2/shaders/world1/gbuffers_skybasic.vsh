#version 130

#define VERTEX_SHADER
#define END

#include "/program/gbuffers_skybasic.glsl"
