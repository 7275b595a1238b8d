#version 130

#define FRAGMENT_SHADER
#define END

#include "/program/composite.glsl"
