#version 120
#define VSH
#include "/program/terrain.glsl"
