#version 120
#include "/lib/fullscreen.glsl"
