#version 120
#define FSH
#include "/program/terrain.glsl"
