#version 130

#define VERTEX_SHADER
#define OVERWORLD

#include "/program/composite.glsl"
