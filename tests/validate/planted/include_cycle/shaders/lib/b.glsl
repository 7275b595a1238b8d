float b = 1.0;
#include "/lib/a.glsl"
