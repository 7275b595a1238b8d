#ifndef COMMON_GLSL
#define COMMON_GLSL
#include "/lib/settings.glsl"
#include "/lib/util/math.glsl"

uniform float frameTimeCounter;
uniform float rainStrength;
uniform int worldTime;
uniform vec3 cameraPosition;

vec3 toLinear(vec3 c) { return pow(c, vec3(2.2)); }
#endif
